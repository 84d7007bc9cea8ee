"""Teeth touching beyond the path of contact in the loaded contact (issue: tip contact).

The rigid geometry is tested in ``test_tip_contact.py``; the comparison with the
independent CalculiX contact model in ``test_reference_calculix.py``. Here: the switch
(``[contact] tip_contact``), the relief check of the issue (a tip relief longer and deeper
than the deflection keeps the corners apart, and the numbers are those of contact on the
nominal path), the local model of a corner (Hertz of its edge rounding, Johnson 1985, eq.
4.45, against the mate's involute), equilibrium through the lever factors, the record,
the warning and the figures. Pair: the assembly-error paper's z 50/50 (m 3 mm, b 20 mm),
analytical slices (fast), 340 N m.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
from gearsets import spur

from pipeline.contact.analysis import analytical_compliance
from pipeline.contact.hertz import HertzLineContact, LeverScaled, contact_modulus
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.options import ContactOptions
from pipeline.contact.separations import FlankModifications
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at, tip_contact
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError

PAIR = GearPair(spur(50, "pinion"), spur(50, "gear"))
TORQUE = 340.0
OP = OperatingPoint(torque=TORQUE)
LOAD = TORQUE / PAIR.pinion.base_radius


def _cycle(tip: bool, mods: FlankModifications | None = None, positions: int = 24):
    src = analytical_compliance(PAIR, OP, ContactOptions(tip_contact=tip))
    return loaded_mesh_cycle(src, LOAD, mods, "weber", positions)


def test_nominal_path_control_has_no_point_beyond_the_path():
    """``tip_contact = False``: every candidate point on the path (today's model), the tooth
    pairs of ``pair_indices(beyond=False)``; with it the pairs one further at each end."""
    off, on = _cycle(False), _cycle(True)
    assert np.all((off.point_s >= PAIR.s_start - 1e-12) & (off.point_s <= PAIR.s_end + 1e-12))
    assert np.all(off.point_corner == 0) and np.all(off.point_lever == 1.0)
    assert list(off.pair_index) == [0, 1, 2] and list(on.pair_index) == [-1, 0, 1, 2]
    assert (on.point_corner > 0).any() and (on.point_load[on.point_corner > 0] > 0).any()


def test_unmodified_pair_touches_at_the_tips_and_is_stiffer():
    """Without relief the leaving and approaching pairs stay loaded at their corners: the
    minimum mesh stiffness rises by more than 15 % and the TE peak-to-peak falls (the
    independent FE model of the issue: +20 % and -10 % on the demo pair)."""
    off, on = _cycle(False), _cycle(True)
    assert on.mesh_stiffness.min() > 1.15 * off.mesh_stiffness.min()
    p2p = [np.ptp(c.transmission_error) for c in (off, on)]
    assert p2p[1] < 0.95 * p2p[0]
    assert on.loaded_contact_ratio > off.loaded_contact_ratio + 0.1


def test_relief_longer_than_the_deflection_gives_the_nominal_numbers():
    """The issue's check: with a tip relief deeper (60 um) than the loaded deflection
    (about 20 um) and long (3 mm of roll) on both gears no corner closes, and every
    number equals contact confined to the path (to the solver's tolerance)."""
    mods = FlankModifications(tip_relief_pinion=60e-6, tip_relief_gear=60e-6,
                              relief_length_pinion=3e-3, relief_length_gear=3e-3)
    off, on = _cycle(False, mods), _cycle(True, mods)
    assert not (on.point_load[on.point_corner > 0] > 0).any()
    np.testing.assert_allclose(on.transmission_error, off.transmission_error, rtol=1e-9)
    np.testing.assert_allclose(on.mesh_stiffness, off.mesh_stiffness, rtol=1e-7)
    cols = np.searchsorted(on.pair_index, off.pair_index)
    np.testing.assert_allclose(on.pair_loads[:, cols], off.pair_loads, rtol=1e-7, atol=1e-6)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert on.physics_warnings() == []


def test_equilibrium_through_the_lever_factors():
    """Line-of-action loads add up to P at every position; a corner's normal force is its
    line-of-action load over its lever (the torque it puts on the turning pinion over
    r_b1 is a F_n), and its lever is the geometry's."""
    cyc = _cycle(True)
    per_position = np.bincount(cyc.point_position, weights=cyc.point_load)
    np.testing.assert_allclose(per_position, LOAD, rtol=1e-9)
    tip = cyc.point_corner > 0
    np.testing.assert_allclose(cyc.point_lever[tip],
                               tip_contact(PAIR, cyc.point_s[tip]).lever_pinion, rtol=1e-15)
    np.testing.assert_allclose(cyc.point_normal_load * cyc.point_lever, cyc.point_load,
                               rtol=1e-15)
    assert np.all(cyc.point_lever[cyc.point_corner == 1] < 1.0)
    assert np.all(cyc.point_lever[cyc.point_corner == 2] == pytest.approx(1.0, abs=1e-12))


def test_corner_pressure_is_hertz_of_the_corner_against_the_flank():
    """Johnson (1985), eq. 4.45 written out here: ``p0 = sqrt(w E* / (pi R))``, with the
    normal unit load ``w``, ``R = rho_c rho_2 / (rho_c + rho_2)`` of the pinion's local
    corner radius (0.05 m_n) and the gear's involute at the contact radius."""
    cyc = _cycle(True)
    i = int(np.argmax(np.where(cyc.point_corner == 1, cyc.point_load, 0.0)))
    s = cyc.point_s[i]
    r2 = contact_radii_at(PAIR, s)[1]
    rho2 = math.sqrt(r2**2 - PAIR.gear.base_radius**2)
    rho_e = 0.05 * 3e-3
    R = rho_e * rho2 / (rho_e + rho2)
    E = 2.0e11 / (1.0 - 0.3**2) / 2.0
    w = cyc.point_load[i] / cyc.point_lever[i] / cyc.point_width[i]
    assert cyc.point_unit_load[i] == pytest.approx(w, rel=1e-12)
    assert cyc.point_pressure[i] == pytest.approx(math.sqrt(w * E / (math.pi * R)), rel=1e-12)


def test_lever_scaled_local_model_is_a_consistent_convex_law():
    """``LeverScaled``: approach(0) = 0, the tangent is the derivative of the approach
    (central differences, 1e-6), increasing concave approach as the solver needs."""
    base = HertzLineContact(np.full(3, 0.02), np.full(3, 1e-3), np.full(3, 0.02),
                            np.full(3, 3e-3), np.full(3, 3e-3))
    a = np.array([1.0, 0.97, 0.9])
    model = LeverScaled(base, a)
    assert np.all(model.approach(np.zeros(3)) == 0.0)
    F = np.array([500.0, 1200.0, 3000.0])
    h = 1e-3 * F
    fd = (model.approach(F + h) - model.approach(F - h)) / (2 * h)
    np.testing.assert_allclose(model.tangent(F), fd, rtol=1e-6)
    np.testing.assert_allclose(model.approach(F), base.approach(F / a) / a, rtol=1e-15)
    assert np.all(model.tangent(2 * F) < model.tangent(F)) and np.all(model.tangent(F) > 0)


def test_warning_names_the_largest_corner_load_and_pressure():
    """One warning line: the corner, its largest normal force and share, its pressure; the
    same numbers as the record."""
    cyc = _cycle(True)
    peak = cyc.tip_contact_peak()
    lines = [x for x in cyc.physics_warnings() if x.startswith("tip contact")]
    assert len(lines) == 1 and "\n" not in lines[0]
    assert f"{peak['normal_load_N']:.4g} N" in lines[0]
    assert f"{peak['pressure_Pa'] * 1e-6:.4g} MPa" in lines[0]
    assert peak["corner"] in ("pinion", "gear") and 0.0 < peak["share"] < 0.5
    assert 1e9 < peak["pressure_Pa"] < 1e10  # an edge of 0.15 mm: GPa, edge loading
    assert _cycle(False).tip_contact_peak() is None


def test_contact_options_switch():
    """``[contact] tip_contact`` reaches the sources; a default analysis touches the tips."""
    assert ContactOptions().tip_contact is True
    src = analytical_compliance(PAIR, OP, dataclasses.replace(ContactOptions(),
                                                              tip_contact=False))
    assert src.tip_contact is False
    assert contact_modulus(PAIR.pinion.material, PAIR.gear.material) > 0


def test_figures_mark_tip_contact(tmp_path):
    """The contact-cycle figure circles the load shares carried at a tip corner; the 2D
    load map draws the pinion's tip corner as a band above the tip radius, labelled."""
    from pipeline.contact.loadmap import flank_load_map
    from pipeline.viz.contact import corner_shares, plot_contact_cycle
    from pipeline.viz.loadmap import plot_load_map_2d

    cyc = _cycle(True)
    shares = corner_shares(cyc)
    assert shares.max() > 0.05
    fig = plot_contact_cycle(cyc, cyc.mesh_stiffness, "t")
    labels = [t.get_text() for t in fig.axes[2].get_legend().get_texts()]
    assert "at a tip corner, beyond the path" in labels
    lm = flank_load_map(cyc, PAIR)
    assert lm.s[0] < PAIR.s_start and lm.s[-1] > PAIR.s_end
    assert lm.tip_corner_load("pinion").max() > 0
    ax = plot_load_map_2d(lm)
    texts = [t.get_text() for t in ax.texts]
    assert any(t.startswith("tip corner, beyond the path of contact") for t in texts)
    assert ax.get_ylim()[1] > PAIR.pinion.tip_radius_ * 1e3
    ax.figure.savefig(tmp_path / "map.png")
    off = flank_load_map(_cycle(False), PAIR)
    assert off.tip_corner_load("pinion").max() == 0.0


def test_ring_pair_planet_corner_touches_and_relief_removes_it():
    """The planet-ring example (``planet_ring_pair.toml``, 150 N m): the planet's tip corner
    touches the ring's concave flank past the end of the path (lever < 1), the ring's
    corner cannot reach the planet's involute (the path already starts below its form
    circle), loads add up to P, the minimum stiffness rises; a 60 um relief over 2 mm on
    both gears gives the nominal-path numbers."""
    from pipeline.config import load_gearbox

    box = load_gearbox(Path(__file__).resolve().parents[1] / "workflows" / "configs"
                       / "planet_ring_pair.toml")
    pair, op = box.pair, box.operation
    P = op.torque / pair.pinion.base_radius

    def run(tip, mods=None):
        src = analytical_compliance(pair, op, ContactOptions(tip_contact=tip))
        return loaded_mesh_cycle(src, P, mods, "weber", 36)

    off, on = run(False), run(True)
    loaded = (on.point_corner > 0) & (on.point_load > 0)
    assert loaded.any() and set(on.point_corner[loaded]) == {1}
    assert np.all(on.point_lever[loaded] < 1.0)
    np.testing.assert_allclose(np.bincount(on.point_position, weights=on.point_load), P,
                               rtol=1e-9)
    assert on.mesh_stiffness.min() > 1.3 * off.mesh_stiffness.min()
    mods = FlankModifications(tip_relief_pinion=60e-6, tip_relief_gear=60e-6,
                              relief_length_pinion=2e-3, relief_length_gear=2e-3)
    off, on = run(False, mods), run(True, mods)
    assert not (on.point_load[on.point_corner > 0] > 0).any()
    np.testing.assert_allclose(on.transmission_error, off.transmission_error, rtol=1e-9)


def test_3d_load_map_draws_the_tip_corner(tmp_path):
    """The pyvista load map: each flank whose tip corner touches beyond the path gets a tube
    along its tip edge (a mesh more than the tooth and the flank) and says so in its
    caption, with the corner's largest unit load."""
    from pipeline.contact.loadmap import flank_load_map
    from pipeline.viz import save
    from pipeline.viz.loadmap import render_load_map

    lm = flank_load_map(_cycle(True), PAIR)
    plotter = render_load_map(PAIR, lm, "t", window_width=600)
    texts = [a.GetInput() for r in plotter.renderers for a in r.actors.values()
             if hasattr(a, "GetInput") and isinstance(a.GetInput(), str)]
    tip = [x for x in texts if "tip corner touches beyond the path" in x]
    assert len(tip) == 2
    peak = lm.tip_corner_load("pinion").max() * 1e-3
    assert f"up to {peak:.0f} N/mm" in tip[0]
    assert all(len(r.actors) >= 3 for r in plotter.renderers)
    save(plotter, tmp_path / "map.png")
    off = render_load_map(PAIR, flank_load_map(_cycle(False), PAIR), "t", window_width=600)
    texts = [a.GetInput() for r in off.renderers for a in r.actors.values()
             if hasattr(a, "GetInput") and isinstance(a.GetInput(), str)]
    assert not any("tip corner" in x for x in texts)
    off.close()


def test_rounded_tips_touch_with_their_rounding():
    """Tips rounded by 0.3 mm on both gears: the path of contact ends where the roundings
    touch the involutes (transverse contact ratio 1.755 -> 1.663), the roundings carry load
    beyond it, and their pressure is Hertz of the rounding against the mate's involute
    (Johnson 1985, eq. 4.45, written out)."""
    rho = 0.3e-3
    pair = GearPair(spur(50, "pinion", tip_rounding=rho), spur(50, "gear", tip_rounding=rho))
    assert pair.transverse_contact_ratio == pytest.approx(1.6629, abs=1e-4)
    src = analytical_compliance(pair, OP, ContactOptions())
    cyc = loaded_mesh_cycle(src, LOAD, None, "weber", 24)
    tip = (cyc.point_corner == 1) & (cyc.point_load > 0)
    assert tip.any()
    i = int(np.flatnonzero(tip)[np.argmax(cyc.point_load[tip])])
    r2 = contact_radii_at(pair, cyc.point_s[i])[1]
    rho2 = math.sqrt(r2**2 - pair.gear.base_radius**2)
    R = rho * rho2 / (rho + rho2)
    E = 2.0e11 / (1.0 - 0.3**2) / 2.0
    w = cyc.point_unit_load[i]
    assert cyc.point_pressure[i] == pytest.approx(math.sqrt(w * E / (math.pi * R)), rel=1e-12)
    r1 = contact_radii_at(pair, cyc.point_s[i])[0]
    assert pair.pinion.active_tip_radius < r1 < pair.pinion.tip_radius_
    np.testing.assert_allclose(np.bincount(cyc.point_position, weights=cyc.point_load), LOAD,
                               rtol=1e-9)


def test_load_beyond_the_tip_zone_is_refused():
    """A load whose elastic approach passes the 200 um tip zone (the corners beyond it are
    not candidates) is refused in one line naming the position; the demo load is far
    inside it."""
    src = analytical_compliance(PAIR, OP, ContactOptions(tip_contact=True))
    one = loaded_mesh_cycle(src, LOAD, None, "weber", 1)
    approach = float(one.transmission_error[0])  # the loaded TE is the approach
    assert 0.0 < approach < 50e-6
    with pytest.raises(InputError, match=r"^mesh position 0 \(s0 = .* mm\): elastic approach "
                                         r".* um reaches the 200 um tip zone"):
        loaded_mesh_cycle(src, 300e-6 / approach * LOAD, None, "weber", 1)


def test_helical_pair_is_its_transverse_section_averaged_over_the_face():
    """Why tip contact doubles the traction helical pair's TE peak to peak (1.30 -> 2.74 um
    at 6031 N m, eps_alpha 2.05, overlap 0.39 base pitches): its transverse section made
    spur (``workflows/reference/hcr_spur_pair.toml``, checked against CalculiX in
    tests/test_reference_calculix.py) touches at its corners and stays three pairs longer
    around the change from three to two, which lowers the section's own TE peak to peak
    (7.26 -> 6.48 um) but widens the narrow three-pair dip that the face's overlap averaged
    away. The section's secant stiffness averaged over the overlap window (the helical
    pair's slices with independent slices) gives the helical pair's mean TE within 0.5 %
    (measured 0.13 %) with and without tip contact, and the same growth of the peak to
    peak (x 1.92 against the slice model's x 2.11)."""
    from pipeline.config import load_gearbox
    from pipeline.config.gearbox import gearbox_from_text

    root = Path(__file__).resolve().parents[1]
    hel = load_gearbox(root / "workflows/configs/traction_helical_pair.toml")
    text = (root / "workflows/reference/hcr_spur_pair.toml").read_text()
    sec = gearbox_from_text(text.replace('compliance = "fe2d"', 'compliance = "analytical"'),
                            name="section")
    window = hel.pair.face_width * math.tan(hel.pair.pinion.base_helix_angle) / hel.pair.base_pitch
    n = 240
    w = round(window * n)
    p2p, mean = {}, {}
    for tip in (False, True):
        src = analytical_compliance(sec.pair, sec.operation, ContactOptions(tip_contact=tip))
        P = sec.operation.torque / sec.pair.pinion.base_radius
        te = loaded_mesh_cycle(src, P, None, "weber", n).transmission_error
        k = np.tile(P / te, 2)
        averaged = P / np.array([k[i:i + w].mean() for i in range(n)])
        hsrc = analytical_compliance(hel.pair, hel.operation, hel.contact, hel.stiffness)
        hsrc = dataclasses.replace(hsrc, tip_contact=tip)
        Ph = hel.operation.torque / hel.pair.pinion.base_radius
        hte = loaded_mesh_cycle(hsrc, Ph, None, "weber", 60).transmission_error
        p2p[tip] = (np.ptp(te), np.ptp(averaged), np.ptp(hte))
        mean[tip] = (averaged.mean(), hte.mean())
        assert mean[tip][1] == pytest.approx(mean[tip][0], rel=5e-3)
    assert p2p[True][0] < p2p[False][0]  # the section: corners soften the change
    grow_avg, grow_hel = p2p[True][1] / p2p[False][1], p2p[True][2] / p2p[False][2]
    assert grow_avg > 1.7 and grow_hel > 1.7
    assert grow_hel == pytest.approx(grow_avg, rel=0.15)
