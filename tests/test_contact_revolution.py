"""The loaded contact through a revolution with per-tooth errors (pipeline.contact.revolution).

Checks against exact solutions of the contact problem:

* without errors every mesh cycle is the same problem: the revolution repeats the mesh
  cycle of :func:`pipeline.contact.ltca.loaded_mesh_cycle`;
* a runout is a rigid translation of one gear's teeth: at an instant every pair on the line
  of action gets the same gap, which the KKT conditions of Yang et al. (2026) eqs. 27-29
  carry into the approach unchanged (``x_s + d`` solves ``eps + d``) with the same loads;
* a tooth's pitch deviation is a rigid offset of the pairs it meshes in; at light load the
  approach is the smallest gap of the pairs in contact (the unloaded transmission error,
  Harris 1958 / Welbourn 1979's rigid-body TE), so the TE moves by that offset exactly
  where the tooth meshes.
"""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from gearsets import spur

from pipeline.contact.analysis import analytical_compliance, line_of_action_load
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.options import ContactOptions
from pipeline.contact.revolution import loaded_revolution, revolution_size
from pipeline.contact.revolution_results import revolution_arrays, revolution_from_arrays
from pipeline.contact.separations import FlankModifications
from pipeline.contact.tooth_errors import GearErrors, ToothErrors, pair_teeth
from pipeline.geometry import GearPair
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError

OPERATION = OperatingPoint(torque=340.0, speed=2340.0 * math.pi / 30.0)
ROUND_OFF = 1e-14  # m: each solve meets its residual bound 1e-10 x an approach of ~1e-5 m


def _source(z1=50, z2=50, tip_contact=True):
    pair = GearPair(spur(z1, "pinion"), spur(z2, "gear"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return analytical_compliance(pair, OPERATION, ContactOptions(tip_contact=tip_contact))


def _cycle(source, load, positions, mods=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return loaded_mesh_cycle(source, load, mods, "weber", positions)


def _errors(span="pinion", **kw) -> ToothErrors:
    pinion = GearErrors(name="pinion", **{k[:-7]: v for k, v in kw.items()
                                          if k.endswith("_pinion")})
    gear = GearErrors(name="gear", **{k[:-5]: v for k, v in kw.items() if k.endswith("_gear")})
    return ToothErrors(pinion, gear, span)


def test_without_errors_the_revolution_repeats_the_mesh_cycle():
    """No errors: the N mesh cycles are the same problem, so the TE over the revolution is the
    mesh cycle's repeated, to the solver's residual bound (the warm starts differ)."""
    src = _source()
    load = line_of_action_load(src.pair, OPERATION)
    rev = loaded_revolution(src, load, ToothErrors(), positions=12)
    cyc = _cycle(src, load, 12)
    assert rev.mesh_cycles == 50 and len(rev) == 600
    te = rev.transmission_error.reshape(50, 12)
    assert np.abs(te - cyc.transmission_error).max() < ROUND_OFF
    assert np.abs(rev.contact.pair_loads.reshape(50, 12, -1) - cyc.pair_loads).max() < 1e-6


@pytest.mark.parametrize("load_share", [0.01, 1.0])
def test_pinion_runout_adds_e_sin_and_no_sidebands(load_share):
    """A pinion runout e (phase phi) opens the gap e sin(phi + theta_1) on every pair on the
    line of action (its projection on the line of action, pipeline.contact.tooth_errors).

    Linear estimate of the modulation: the loaded TE is ``x(theta) = x_0(s0) + g(theta)``
    because a gap common to all points leaves the loads of eqs. 27-29 unchanged, so the mesh
    harmonics are not modulated: ``A(n z1 +- 1) = 0`` at first order, the spectrum is the
    mesh cycle's lines at ``n z1`` plus one line of amplitude e at order 1 (exact for a
    sinusoid sampled over whole revolutions). Tested at 1 % and 100 % of the demo load."""
    src = _source()
    load = line_of_action_load(src.pair, OPERATION) * load_share
    e, phi = 10e-6, 0.3
    rev = loaded_revolution(src, load, _errors(eccentricity_pinion=e,
                                               eccentricity_phase_pinion=phi), positions=12)
    cyc = _cycle(src, load, 12)
    theta = rev.contact.pinion_angle
    assert np.allclose(theta[12], 2 * math.pi / 50, rtol=1e-12)
    d = rev.transmission_error - np.tile(cyc.transmission_error, 50)
    assert np.abs(d - e * np.sin(phi + theta)).max() < ROUND_OFF
    sp = rev.spectrum()
    assert sp.at(0.0) == pytest.approx(rev.transmission_error.mean(), rel=1e-12)
    assert sp.at(1.0) == pytest.approx(e, rel=1e-9)
    mesh = sp.at(50.0)
    assert mesh > 1e-8
    for order in (49.0, 51.0, 99.0, 101.0):
        assert sp.at(order) < 1e-9 * mesh
    assert rev.summary()["largest_sideband_amplitude_m"] < 1e-9 * mesh


def test_gear_runout_turns_with_the_gear():
    """A gear runout on a 20/30 pair: order z1 / z2 = 2/3 per pinion revolution (the gear
    turns by theta_1 r_b1 / r_b2), amplitude e, over the hunting cycle of LCM(20, 30) = 60
    mesh cycles (3 pinion revolutions, 2 gear revolutions). At 10 % load no tip corner
    carries load (there the gear's turn would act through its lever, not as a common gap)."""
    src = _source(20, 30)
    load = line_of_action_load(src.pair, OPERATION) * 0.1
    e, phi = 6e-6, -1.0
    rev = loaded_revolution(src, load, _errors("hunting", eccentricity_gear=e,
                                               eccentricity_phase_gear=phi), positions=6)
    assert rev.mesh_cycles == 60 and rev.pinion_revolutions == 3.0
    assert rev.contact.tip_contact_peak() is None
    cyc = _cycle(src, load, 6)
    d = rev.transmission_error - np.tile(cyc.transmission_error, 60)
    theta2 = rev.contact.pinion_angle * 20 / 30
    assert np.abs(d - e * np.sin(phi + theta2)).max() < ROUND_OFF
    assert rev.spectrum().at(2.0 / 3.0) == pytest.approx(e, rel=1e-9)


@pytest.mark.parametrize("driver", ["pinion", "gear"])
def test_helical_pair_repeats_its_mesh_cycle(driver):
    """A helical 19/21 pair (beta 15 deg, 10 slices: pairs k = -2 .. 3 touch, those behind
    through the far face end) driven by either gear: without errors one pinion revolution
    repeats the mesh cycle; a runout of the driving gear is a common gap, so it adds exactly
    e sin(phi + theta) of that gear (tip corners included: the driver's turn is the
    approach)."""
    op = OperatingPoint(torque=340.0, speed=100.0, driver=driver)
    pair = GearPair(spur(19, "pinion", helix_angle=math.radians(15), hand="right"),
                    spur(21, "gear", helix_angle=math.radians(15), hand="left"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        src = analytical_compliance(pair, op, ContactOptions(slices=10))
        load = line_of_action_load(pair, op)
        cyc = loaded_mesh_cycle(src, load, None, "weber", 4, driver=driver)
    rev = loaded_revolution(src, load, ToothErrors(span="pinion"), positions=4, driver=driver)
    assert np.abs(rev.transmission_error.reshape(19, 4) - cyc.transmission_error).max() \
        < ROUND_OFF
    key = f"eccentricity_{driver}"
    rev = loaded_revolution(src, load, _errors(**{key: 5e-6}), positions=4, driver=driver)
    theta = rev.contact.pinion_angle * (1.0 if driver == "pinion" else 19 / 21)
    d = rev.transmission_error - np.tile(cyc.transmission_error, 19)
    assert np.abs(d - 5e-6 * np.sin(theta)).max() < ROUND_OFF


def _on_path(pair, s0, k):
    s = s0 + k * pair.base_pitch
    return (s >= pair.s_start - 1e-12) & (s <= pair.s_end + 1e-12)


def test_a_proud_tooth_shows_once_per_revolution_by_its_offset_at_light_load():
    """Pinion tooth 3 stands 4 um proud (f_pt,3 = -4 um, f_pt,4 = +4 um: F_p,3 = -4 um on the
    reference circle, -4 cos(alpha_t) um along the line of action). At light load (1 N) the
    approach is the smallest gap of the pairs on the path (contact confined to the path):
    wherever the pair of tooth 3 is on the path the TE drops by 4 cos(alpha_t) um, elsewhere
    it is the error-free TE; the elastic part differs by P / k, a few nm."""
    src = _source(tip_contact=False)
    pair, m = src.pair, 10
    f = np.zeros(50)
    f[3], f[4] = -4e-6, 4e-6
    rev = loaded_revolution(src, 1.0, _errors(pitch_deviations_pinion=tuple(f)), positions=m)
    cyc = _cycle(src, 1.0, m)
    d = rev.transmission_error - np.tile(cyc.transmission_error, 50)
    offset = -4e-6 * pair.pinion.base_radius / pair.pinion.reference_radius
    s0 = pair.mesh_cycle(m)
    meshing = np.zeros((50, m), bool)
    for c in range(50):
        for k in pair.pair_indices(False):
            t1, _ = pair_teeth(pair, c, k)
            if t1 == 3:
                meshing[c] |= _on_path(pair, s0, k)
    meshing = meshing.ravel()
    assert 10 <= meshing.sum() <= 20  # one passage: epsilon_alpha = 1.7 mesh cycles
    assert np.ptp(np.flatnonzero(meshing)) < 2 * m  # once per revolution, in one passage
    assert np.abs(d[meshing] - offset).max() < 0.01 * abs(offset)
    assert np.abs(d[~meshing]).max() < 0.01 * abs(offset)
    # a spur pair's points lie at its roll coordinate s0_j + k p_bt
    assert rev.base_pitch == pytest.approx(pair.base_pitch, rel=1e-12)
    assert np.allclose(rev.pair_roll(), rev.contact.point_s, rtol=0, atol=1e-12)
    # its passage: the points of that tooth pair only, each position's share of the 1 N
    one = rev.pair_cycle(3, 3)
    assert set(np.unique(rev.point_teeth()[0][rev.pair_points(3, 3)])) == {3}
    loaded = np.unique(one.point_position[one.point_load > 0])
    assert np.array_equal(loaded, np.flatnonzero(meshing))


def test_a_low_gear_tooth_shows_only_where_its_pair_meshes_alone():
    """Gear tooth 5 lies 4 um back (f_pt,5 = +4 um, f_pt,6 = -4 um: material removed). At
    light load its pair carries load only where no other pair is on the path (single
    contact): there the TE rises by 4 cos(alpha_t) um, in double contact the other pair
    takes the 1 N and the TE is the error-free one (to P / k, a few nm)."""
    src = _source(tip_contact=False)
    pair, m = src.pair, 10
    f = np.zeros(50)
    f[5], f[6] = 4e-6, -4e-6
    rev = loaded_revolution(src, 1.0, _errors(pitch_deviations_gear=tuple(f)), positions=m)
    cyc = _cycle(src, 1.0, m)
    d = rev.transmission_error - np.tile(cyc.transmission_error, 50)
    offset = 4e-6 * pair.gear.base_radius / pair.gear.reference_radius
    s0 = pair.mesh_cycle(m)
    mine, others = np.zeros((50, m), bool), np.zeros((50, m), int)
    for c in range(50):
        for k in pair.pair_indices(False):
            on = _on_path(pair, s0, k)
            if pair_teeth(pair, c, k)[1] == 5:
                mine[c] |= on
            else:
                others[c] += on
    alone = (mine & (others == 0)).ravel()
    assert 2 <= alone.sum() <= 8  # single contact: (2 - epsilon_alpha) of a cycle
    assert np.abs(d[alone] - offset).max() < 0.01 * offset
    assert np.abs(d[~alone]).max() < 0.01 * offset


def test_sinusoidal_pitch_deviation_sidebands_match_the_rigid_body_estimate():
    """A once-per-revolution cumulative pitch deviation of the pinion (an index error of the
    cutting machine: F_p,i = A sin(2 pi i / z1), A = 8 um) changes the spacing of
    neighbouring teeth, so neighbouring pairs carry different offsets and the load sharing,
    hence the mesh harmonics, are modulated once per revolution: sidebands at n z1 +- 1.

    Estimate at light load (1 N, contact confined to the path): the approach is the smallest
    gap of the pairs on the path, ``x(c, j) = min_k o(c - k)`` with ``o(n) = F_p,(n mod
    z1) cos(alpha_t)`` (the rigid-body TE), plus the error-free elastic TE of the mesh cycle
    (``P / k``, nm); its spectrum at z1 +- 1 and 2 z1 +- 1 is what the revolution must
    give, within 2 %: the estimate leaves out how the elastic part changes where one pair
    carries the load alone (|TE - estimate| <= 4 nm against sidebands of 36-130 nm;
    measured 0.25-0.31 %)."""
    src = _source(tip_contact=False)
    pair, m, z = src.pair, 12, 50
    fp = 8e-6 * np.sin(2 * np.pi * np.arange(z) / z)
    f = np.diff(np.concatenate(([fp[-1]], fp)))
    rev = loaded_revolution(src, 1.0, _errors(pitch_deviations_pinion=tuple(f)), positions=m)
    cyc = _cycle(src, 1.0, m)
    cos_at = pair.pinion.base_radius / pair.pinion.reference_radius
    s0 = pair.mesh_cycle(m)
    rigid = np.full((z, m), np.inf)
    for c in range(z):
        for k in pair.pair_indices(False):
            o = fp[(c - k) % z] * cos_at
            rigid[c] = np.where(_on_path(pair, s0, k), np.minimum(rigid[c], o), rigid[c])
    estimate = rigid.ravel() + np.tile(cyc.transmission_error, z)
    amp = 2 * np.abs(np.fft.rfft(estimate - estimate.mean())) / estimate.size
    sp = rev.spectrum()
    for order in (49, 51, 99, 101):
        assert amp[order] > 1e-8  # a real sideband, tens of nm
        assert sp.at(order) == pytest.approx(amp[order], rel=0.02), order
    side_order, side_amp = sp.largest_sideband()
    assert side_amp == pytest.approx(amp[int(side_order)], rel=0.02)


def test_errors_are_refused_when_they_cannot_act():
    src = _source()
    with pytest.raises(InputError, match="has 3 entries; the pinion has 50 teeth"):
        loaded_revolution(src, 1.0, _errors(pitch_deviations_pinion=(1e-6, -1e-6, 0.0)),
                          positions=4)
    with pytest.raises(InputError, match="offsets the tooth pairs of one mesh cycle"):
        loaded_revolution(src, 1.0, _errors(eccentricity_gear=1e-6), positions=4,
                          modifications=FlankModifications(pitch_errors=(1e-6,)))
    with pytest.raises(InputError, match="sums to 2 um"):
        GearErrors((1e-6, 1e-6), name="gear")
    big = GearPair(spur(97, "pinion"), spur(101, "gear"))
    assert ToothErrors(span="hunting").mesh_cycles(big) == 9797
    with pytest.raises(InputError, match=r"9797 mesh cycles x contact.positions = 60"):
        revolution_size(ToothErrors(span="hunting"), big, 60)
    assert revolution_size(ToothErrors(span="gear"), big, 60) == (101, 6060)
    helical = GearPair(spur(97, "pinion", helix_angle=0.3, hand="right"),
                       spur(101, "gear", helix_angle=0.3, hand="left"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        fine = analytical_compliance(helical, OPERATION, ContactOptions(slices=100))
    with pytest.raises(InputError, match=r"keep about \d+ point records, more than 10000000"):
        loaded_revolution(fine, 1.0, ToothErrors(span="gear"), positions=400)


def test_cache_arrays_round_trip_exactly():
    src = _source()
    rev = loaded_revolution(src, 1000.0, _errors(eccentricity_pinion=3e-6), positions=3)
    back = revolution_from_arrays(revolution_arrays(rev))
    assert np.array_equal(back.transmission_error, rev.transmission_error)
    assert np.array_equal(back.contact.point_pressure, rev.contact.point_pressure)
    assert back.summary() == rev.summary()
