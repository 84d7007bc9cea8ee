"""The loaded contact through a revolution with per-tooth errors (pipeline.contact.revolution).

Checks against exact solutions of the contact problem:

* without errors every mesh cycle is the same problem: the revolution repeats the mesh
  cycle of :func:`pipeline.contact.ltca.loaded_mesh_cycle`;
* a runout is a rigid translation of one gear's teeth: at an instant every pair on the line
  of action gets the same gap, which the KKT conditions of Yang et al. (2026) eqs. 27-29
  carry into the approach unchanged (``x_s + d`` solves ``eps + d``) with the same loads,
  and the pair has another centre distance and a turned line of centres: each mesh cycle
  of the revolution is the mesh cycle of that pair plus the gap, and its sidebands at the
  mesh orders +- 1 are the linear estimate's (derived in the test's docstring);
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
from pipeline.contact.revolution import at_centre_distance, loaded_revolution, revolution_size
from pipeline.contact.revolution_results import revolution_arrays, revolution_from_arrays
from pipeline.contact.separations import FlankModifications
from pipeline.contact.tooth_errors import (
    GearErrors,
    ToothErrors,
    centre_distance_change,
    centre_line_turn,
    pair_teeth,
    roll_shift,
)
from pipeline.geometry import GearPair
from pipeline.geometry.assembly_errors import AssembledPair, AssemblyErrors
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError
from pipeline.verification.cases_revolution import rebuilt_runout_cycles

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


def test_centre_distance_change_and_roll_shift_of_an_eccentricity():
    """The eccentricity's share along the line of centres (pipeline.contact.tooth_errors):
    teeth moved e behind along the line of action (phi = 90 deg) move the centre e
    sin(alpha_wt) away from the mate (the line of action makes 90 deg - alpha_wt with the
    line of centres); phi = 0 moves it e cos(alpha_wt) away (pinion) or towards the mate
    (gear: u_2 points from the gear's centre towards the pinion's side). The roll shift of a
    pure centre-distance change is AssembledPair.roll_offset (the assembly-error geometry)
    with the gear moved along the line of centres (no rotation of it). Teeth moved e across
    the line of centres (the pinion's at phi = 90 deg + alpha_wt, towards T1's side) leave
    the centre distance and turn the line of centres by e / a away from that side."""
    pair = GearPair(spur(50, "pinion"), spur(50, "gear"))
    alpha, e = pair.operating_pressure_angle, 10e-6
    for who, sign0 in (("pinion", 1.0), ("gear", -1.0)):
        behind = _errors(**{f"eccentricity_{who}": e,
                            f"eccentricity_phase_{who}": math.pi / 2})
        assert centre_distance_change(pair, behind, 0.0) == pytest.approx(
            e * math.sin(alpha), rel=1e-12)
        across = _errors(**{f"eccentricity_{who}": e})
        assert centre_distance_change(pair, across, 0.0) == pytest.approx(
            sign0 * e * math.cos(alpha), rel=1e-12)
    across = _errors(eccentricity_pinion=e, eccentricity_phase_pinion=math.pi / 2 + alpha)
    assert abs(centre_distance_change(pair, across, 0.0)) < 1e-15 * e
    assert centre_line_turn(pair, across, 0.0) == pytest.approx(-e / 0.15, rel=1e-12)
    da = 10e-6
    phi = pair.operating_pressure_angle  # the assembly-error frame's centre line
    moved = AssembledPair(pair, AssemblyErrors(gear=(da * math.sin(phi), da * math.cos(phi))))
    assert moved.centre_distance - 0.15 == pytest.approx(da, rel=1e-6)
    assert roll_shift(pair, moved.actual) == pytest.approx(moved.roll_offset, rel=1e-6)
    assert roll_shift(pair, moved.actual) == pytest.approx(12.905e-6, rel=1e-3)


@pytest.mark.parametrize("load_share", [0.01, 1.0])
def test_pinion_runout_is_the_mesh_cycle_at_each_centre_distance_plus_e_sin(load_share):
    """A pinion runout e (phase phi) is a common gap e sin(phi + theta_1) plus, once per
    revolution, the centre distance a + e cos(phi + theta_1 - alpha_wt). Each mesh cycle of
    the revolution is therefore the mesh-cycle contact of the pair at its cycle's centre
    distance (positions moved by the roll shift) plus the gap, to the solvers' round-off;
    the centre-line part of the difference from the nominal mesh cycle plus the gap is
    linear in e (it vanishes as delta_a -> 0): a tenth of e leaves a tenth of it, to 2 %
    (the quadratic term: 0.9 % at e = 10 um, full load). Position j = 0 is left out of that:
    it lies exactly at the start of the path of contact, and the contact model's TE steps
    there (corner contact before s_start, path contact from it: 0.54 um at full load without
    relief, 5.6 nm at 1 %), so however small delta_a, the path's start moving past that
    sample shows the whole step. The spectrum: order 1 carries e, plus the mean TE's change
    with a and that step's share (measured 1.4e-5 of e at 1 % load, 1.8e-3 at full load)."""
    src = _source()
    load = line_of_action_load(src.pair, OPERATION) * load_share
    e, phi = 10e-6, 0.3
    errors = _errors(eccentricity_pinion=e, eccentricity_phase_pinion=phi)
    rev = loaded_revolution(src, load, errors, positions=12)
    theta = rev.contact.pinion_angle
    assert np.allclose(theta[12], 2 * math.pi / 50, rtol=1e-12)
    te = rev.transmission_error.reshape(50, 12)
    cycles = (0, 13, 37)
    ref = rebuilt_runout_cycles(src, load, errors, 12, cycles)
    assert np.abs(te[list(cycles)] - ref).max() < ROUND_OFF
    cyc = _cycle(src, load, 12)
    rest = rev.transmission_error - np.tile(cyc.transmission_error, 50) - e * np.sin(phi + theta)
    small = loaded_revolution(src, load, _errors(eccentricity_pinion=e / 10,
                                                 eccentricity_phase_pinion=phi), positions=12)
    rest_small = (small.transmission_error - np.tile(cyc.transmission_error, 50)
                  - e / 10 * np.sin(phi + theta))
    inner = np.abs(rest.reshape(50, 12)[:, 1:]).max()
    assert inner > 1e-10 * load_share  # the centre distance acts
    assert np.abs(rest_small.reshape(50, 12)[:, 1:]).max() == pytest.approx(inner / 10,
                                                                            rel=0.02)
    sp = rev.spectrum()
    assert sp.at(0.0) == pytest.approx(rev.transmission_error.mean(), rel=1e-12)
    assert sp.at(1.0) == pytest.approx(e, rel=3e-3)
    assert sp.at(49.0) > 0 and sp.at(51.0) > 0


def test_gear_runout_turns_with_the_gear():
    """A gear runout on a 20/30 pair: order z1 / z2 = 2/3 per pinion revolution (the gear
    turns by theta_1 r_b1 / r_b2), amplitude e, over the hunting cycle of LCM(20, 30) = 60
    mesh cycles (3 pinion revolutions, 2 gear revolutions); every mesh cycle is the one of
    the pair at its centre distance a - e cos(phi + theta_2 + alpha_wt), its line of centres
    turned, plus the gap. Contact
    on the path only (no tip corners: there the gear's turn acts through its lever, not as
    a common gap, and position j = 0, at the path's start, reaches a corner whenever the
    path's start moves past it)."""
    src = _source(20, 30, tip_contact=False)
    load = line_of_action_load(src.pair, OPERATION) * 0.1
    e, phi = 6e-6, -1.0
    errors = _errors("hunting", eccentricity_gear=e, eccentricity_phase_gear=phi)
    rev = loaded_revolution(src, load, errors, positions=6)
    assert rev.mesh_cycles == 60 and rev.pinion_revolutions == 3.0
    ref = rebuilt_runout_cycles(src, load, errors, 6, range(60))
    assert np.abs(rev.transmission_error.reshape(60, 6) - ref).max() < ROUND_OFF
    # order 2/3: e of the common gap, plus the once-per-gear-revolution change of the mean of
    # the 6 samples of each cycle with its centre distance and turn (measured +2.1 %)
    assert rev.spectrum().at(2.0 / 3.0) == pytest.approx(e, rel=0.03)


@pytest.mark.parametrize("driver", ["pinion", "gear"])
def test_helical_pair_repeats_its_mesh_cycle(driver):
    """A helical 19/21 pair (beta 15 deg, 10 slices: pairs k = -2 .. 3 touch, those behind
    through the far face end) driven by either gear: without errors one pinion revolution
    repeats the mesh cycle; with a runout of the driving gear each mesh cycle is the one of
    the pair at its centre distance plus the common gap (tip corners included: the driver's
    turn is the approach)."""
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
    errors = _errors(**{f"eccentricity_{driver}": 5e-6})
    rev = loaded_revolution(src, load, errors, positions=4, driver=driver)
    ref = rebuilt_runout_cycles(src, load, errors, 4, (0, 9), driver=driver)
    assert np.abs(rev.transmission_error.reshape(19, 4)[[0, 9]] - ref).max() < ROUND_OFF


def test_runout_sidebands_match_the_linear_estimate_at_light_load():
    """Sidebands of a pinion runout (e = 10 um) on the demo pair with tip reliefs (15 um over
    2.5 mm on both gears) at 20 % of the demo load, where the reliefs (15 um) far exceed the
    teeth's deflection (about 1.7 um) and the TE's mesh harmonic is set by where each pair's
    relief starts on the path of contact, hence by the centre distance.

    Linear estimate. Mesh cycle c is solved at a_c = a + e cos(x_c) (x_c = phi + theta_c -
    alpha_wt at the cycle's middle, N = z1 = 50 cycles of m positions) at positions moved by
    r_b1 (delta_c + alpha'_c - alpha_wt), delta_c = -e sin(x_c) / a the turn of the line of
    centres (pipeline.contact.tooth_errors). To first order its TE is TE_j + D_j (a_c - a) +
    S_j r_b1 delta_c, with D_j = dTE_j / da (central difference of two mesh cycles at a +- 1
    um, positions moved by r_b1 (alpha' - alpha_wt)) and S_j = dTE_j / ds0 (two mesh cycles at
    positions +- 1 um). With a_c - a = Re(e exp(i x_c)) and delta_c = Re(i (e / a)
    exp(i x_c)), the sample (c, j) at pinion order q = z1 +- 1 carries exp(-+ 2 pi i c / N)
    exp(-2 pi i j (1 +- 1/N) / m), the sum over c keeps N / 2 times the coefficient of
    exp(+- i x_c), and the one-sided amplitude is

        A(z1 +- 1) = e |sum_j (D_j +- i r_b1 S_j / a) exp(-2 pi i j (1 +- 1/N) / m)| / m.

    For a smooth modulation (N -> infinity) that is |dC_1/da +- i r_b1 dC_1/ds0 / a| e / 2 =
    |dC_1/da -+ z1 C_1 / a| e / 2 (C_1 the complex first mesh-order harmonic, dC_1/ds0 =
    2 pi i C_1 / p_bt): the centre distance modulates the harmonic's amplitude and phase,
    the turning line of centres its phase (z1 delta), so the two sidebands differ. Higher
    terms of the Taylor series put nothing at z1 +- 1 below third order, and the solves'
    round-off is 1e-15 m against sidebands of nanometres: the estimate must hold to 1e-3.
    The staircase of N steps moves each sideband off the smooth value (measured +0.9 % at
    z1 + 1, -0.2 % at z1 - 1; checked to 3 %). Without the line of centres' turn the
    sidebands would be about equal (|dC_1/da| e / 2 = 4.4 nm); with it they are 6.2 and
    2.7 nm."""
    pair = GearPair(spur(50, "pinion"), spur(50, "gear"))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        src = analytical_compliance(pair, OPERATION, ContactOptions(tip_contact=True))
    mods = FlankModifications(tip_relief_pinion=15e-6, relief_length_pinion=2.5e-3,
                              tip_relief_gear=15e-6, relief_length_gear=2.5e-3)
    load = line_of_action_load(pair, OPERATION) * 0.2
    m, n, e, d, a = 20, 50, 10e-6, 1e-6, 0.15
    s0 = pair.mesh_cycle(m)

    def mesh_te(da, ds=0.0):
        moved = GearPair(pair.pinion, pair.gear, centre_distance=a + da)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return loaded_mesh_cycle(at_centre_distance(src, moved), load, mods, "weber",
                                     s0 + ds + roll_shift(pair, moved)).transmission_error

    te0 = mesh_te(0.0)
    dte = (mesh_te(d) - mesh_te(-d)) / (2 * d)
    ste = (mesh_te(0.0, d) - mesh_te(0.0, -d)) / (2 * d) * pair.pinion.base_radius / a
    j = np.arange(m)
    estimate = {s: e * abs(np.sum((dte + s * 1j * ste)
                                  * np.exp(-2j * np.pi * j * (1 + s / n) / m))) / m
                for s in (1, -1)}
    c1 = np.fft.fft(te0)[1] * 2 / m
    smooth = {s: abs(np.fft.fft(dte)[1] * 2 / m - s * n * c1 / a) * e / 2 for s in (1, -1)}
    rev = loaded_revolution(src, load, _errors(eccentricity_pinion=e,
                                               eccentricity_phase_pinion=0.3), mods,
                            positions=m)
    sp = rev.spectrum()
    assert sp.at(50.0) == pytest.approx(abs(c1), rel=1e-3)
    for s in (1, -1):
        side = sp.at(50.0 + s)
        assert side > 2e-3 * abs(c1)  # a real sideband: nm against A_1 = 1.05 um
        assert side == pytest.approx(estimate[s], rel=1e-3), s
        assert side == pytest.approx(smooth[s], rel=0.03), s


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
