"""Mode kinds from the kinetic-energy shares (pipeline.dynamics.modal.classify_modes).

* Rule: a mode is "axial" exactly when its axial kinetic-energy share is at least
  AXIAL_SHARE = 1/2, in modes.csv, in the summary and in the mode-shape panels; the other
  elastic modes keep Lin and Parker (1999)'s in-plane types.
* Exact: with spur halves (no helix) the axial coordinates of a herringbone planetary set
  decouple, so its N + 3 axial modes are those of the axial subsystem written out by hand
  (sun, ring on their axial bearings; carrier and planets joined by the planet bearings),
  purely axial, and the other modes are Lin and Parker (1999)'s Table 2 with their types
  and multiplicities (rotational 1, translational 2, planet N - 3).
* Exact count with a helix: mirror symmetry of the halves and the mass-orthogonality of
  the modes make the axial shares add up to the number of axial coordinates (N + 3), and
  leave at most one of the N + 4 antisymmetric modes (the sun halves' twist) below 1/2.
* Exact: a rotating-frame body on an isotropic support k has the frequencies
  sqrt(k/m) -+ Omega in the carrier frame, and a free rotation one rigid-body mode.
"""

from __future__ import annotations

import csv
import math
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
from gearsets import LIN_PARKER_1999

from pipeline.dynamics.analysis import analyse_modes
from pipeline.dynamics.assembly import Assembly
from pipeline.dynamics.bodies import Body
from pipeline.dynamics.couplings import Bearing
from pipeline.dynamics.modal import AXIAL_SHARE, modal_analysis
from pipeline.dynamics.models.herringbone_planetary import HerringbonePlanetaryModel

ROOT = Path(__file__).resolve().parents[1]
LUMPED = ROOT / "workflows/configs/herringbone_planetary_lumped.toml"


def _lumped_model():
    from pipeline.config import load_gearbox

    return load_gearbox(LUMPED).lumped


def _axial_iff_share(res) -> None:
    """Every elastic mode is "axial" exactly when its axial share is >= AXIAL_SHARE."""
    share = res.energy_shares()["axial"]
    elastic = res.frequencies > 0.0
    axial = np.array([k == "axial" for k in res.kinds])
    np.testing.assert_array_equal(axial[elastic], share[elastic] >= AXIAL_SHARE)
    assert not axial[~elastic].any()


def test_axial_share_threshold_is_one_half():
    assert AXIAL_SHARE == 0.5


def test_lumped_herringbone_set_labels_axial_modes_by_their_share():
    """herringbone_planetary_lumped.toml (4 planets, 8 deg helix, groove 3e6 N m/rad): the
    7 = N + 3 modes holding more than 99.9 % of their energy axially are "axial" and every
    other mode holds less than 0.1 % (measured 0.99914 and 0.00088)."""
    res = analyse_modes(_lumped_model())
    _axial_iff_share(res)
    share = res.energy_shares()["axial"]
    assert np.count_nonzero(share >= AXIAL_SHARE) == 7
    assert np.all((share > 0.999) | (share < 0.001))
    assert {"rotational", "translational", "planet"} <= set(res.kinds)


def test_flexible_halves_give_shares_on_both_sides_of_the_threshold():
    """Planet, ring and carrier halves on springs (1e9 N/m, 1e7 N m/rad) instead of ties:
    left and right halves move axially against each other, coupled with the plane through
    the 8 deg helix, so shares between 5 % and 95 % occur; the label follows the majority."""
    model = HerringbonePlanetaryModel(base_helix_angle=math.radians(8.0), groove=3e6,
                                      half_coupling=(1e9, 1e9, 1e9, 1e7))
    res = model.classify(modal_analysis(model.assembly().assemble()))
    _axial_iff_share(res)
    share = res.energy_shares()["axial"]
    assert np.any((share > 0.5) & (share < 0.95))  # measured 0.739 and 0.918: "axial"
    assert np.any((share > 0.05) & (share < 0.5))  # measured 0.083 and 0.259: not axial


def test_kinetic_energy_amplitudes_are_mass_normalised_over_the_named_coordinates():
    """sum_i (weights_i phi_ik)^2 = phi^T M phi = 1 for every mode, also where the halves
    are tied (each half keeps its own half mass) and the shares add up to 1."""
    res = analyse_modes(_lumped_model())
    e = (res.weights[:, None] * res.shapes) ** 2
    np.testing.assert_allclose(e.sum(axis=0), 1.0, rtol=1e-10)
    total = sum(res.energy_shares().values())
    np.testing.assert_allclose(total, 1.0, rtol=1e-12)


def _axial_subsystem(m: HerringbonePlanetaryModel) -> np.ndarray:
    """Axial frequencies (Hz) by hand: sun and ring alone on kz; carrier with the N planets
    (N - 1 planet modes sqrt(kz_p / m_p), and the carrier against all planets in phase)."""
    N = m.n_planets
    mass = np.diag([m.mass_carrier, N * m.mass_planet])
    stiff = np.array([[m.kz_carrier + N * m.kz_planet, -N * m.kz_planet],
                      [-N * m.kz_planet, N * m.kz_planet]])
    w2 = np.concatenate([[m.kz_sun / m.mass_sun, m.kz_ring / m.mass_ring],
                         np.full(N - 1, m.kz_planet / m.mass_planet),
                         np.linalg.eigvals(np.linalg.solve(mass, stiff)).real])
    return np.sort(np.sqrt(w2)) / (2 * math.pi)


@pytest.mark.parametrize("n_planets", [3, 4, 5])
def test_spur_halves_axial_modes_are_the_axial_subsystem_and_the_rest_lin_parker(n_planets):
    """Spur halves tied together (Lin and Parker's Table 1 set with kz = 1e8 N/m): N + 3
    purely axial modes at the hand-derived frequencies (N = 4: 1038.2, 1959.1 x 3,
    2516.5 Hz and the carrier pair), and Table 2 with its types for every other mode."""
    m = HerringbonePlanetaryModel(n_planets=n_planets)
    res = m.classify(modal_analysis(m.assembly().assemble()))
    share = res.energy_shares()["axial"]
    kinds = np.array(res.kinds)
    axial = kinds == "axial"
    assert axial.sum() == n_planets + 3
    np.testing.assert_allclose(share[axial], 1.0, atol=1e-12)
    assert np.all(share[~axial] < 1e-12)
    np.testing.assert_allclose(res.frequencies[axial], _axial_subsystem(m), rtol=1e-9)
    ref = LIN_PARKER_1999[n_planets]
    for kind, values, mult in (("rotational", ref["rot"][1:], 1),
                               ("translational", ref["trans"], 2),
                               ("planet", ref["planet"], n_planets - 3)):
        got = res.frequencies[kinds == kind]
        np.testing.assert_allclose(np.sort(got), np.sort(np.repeat(values, mult)), rtol=5e-4)
        assert np.all(res.multiplicity[kinds == kind] == mult)
    assert np.count_nonzero(kinds == "rigid") == 1


@pytest.mark.parametrize("helix_deg", [8.0, 30.0])
def test_helix_couples_the_axial_modes_only_with_the_sun_twist(helix_deg):
    """Mirror-symmetric halves (tied, groove 3e6 N m/rad), N = 4: 3 (N + 3) = 21 modes
    without axial motion (< 1e-12); over the N + 4 = 8 others the axial shares add up to
    the N + 3 = 7 axial coordinates (to 1e-9), so exactly 7 are "axial" and one, the
    twist of the sun halves on the groove, is "rotational" (measured axial share 0.001 at
    8 deg, 0.010 at 30 deg)."""
    m = HerringbonePlanetaryModel(base_helix_angle=math.radians(helix_deg), groove=3e6)
    res = m.classify(modal_analysis(m.assembly().assemble()))
    share = res.energy_shares()["axial"]
    assert np.count_nonzero(share < 1e-12) == 21
    assert share.sum() == pytest.approx(7.0, abs=1e-9)
    kinds = np.array(res.kinds)
    assert np.count_nonzero(kinds == "axial") == 7
    twist = np.flatnonzero((share > 1e-12) & (kinds != "axial"))
    assert twist.size == 1 and kinds[twist[0]] == "rotational"
    sl, sr = res.dof_names.index("sL.theta"), res.dof_names.index("sR.theta")
    assert res.shapes[sl, twist[0]] == pytest.approx(-res.shapes[sr, twist[0]], rel=1e-9)


def test_modes_csv_kind_agrees_with_the_shares_it_prints(tmp_path):
    """modes.csv of the lumped herringbone set: kind code 6 (axial) exactly on the rows whose
    axial energy share column is >= 0.5; the three share columns add up to 1."""
    from pipeline.cli.dynamics_files import write_modes
    from pipeline.dynamics.layout import model_layout

    model = _lumped_model()
    res = analyse_modes(model)
    write_modes(res, tmp_path, model_layout(model))
    with open(tmp_path / "modes.csv", newline="", encoding="utf-8") as fh:
        rows = list(csv.DictReader(fh))
    kind = np.array([int(r["kind [0 none,1 rigid,2 rot,3 trans,4 planet,5 mixed,6 axial]"])
                     for r in rows])
    cols = ["in-plane translation energy share [-]", "rotation energy share [-]",
            "axial translation energy share [-]"]
    shares = np.array([[float(r[c]) for c in cols] for r in rows])
    np.testing.assert_allclose(shares.sum(axis=1), 1.0, rtol=1e-9)
    np.testing.assert_array_equal(kind == 6, shares[:, 2] >= 0.5)
    assert np.count_nonzero(kind == 6) == 7


def test_gyroscopic_modes_of_a_spinning_support_keep_one_rigid_mode():
    """A body in the carrier frame on an isotropic support k (x, y) with a free rotation:
    sqrt(k/m) -+ Omega (m = 2 kg, k = 8e6 N/m: 2000 rad/s; Omega = 300 rad/s), and the free
    rotation once at 0 Hz (its double zero state-space eigenvalue counted once)."""
    body = Body("b", 2.0, 0.01, ("x", "y", "theta"), rotating_frame=True)
    system = Assembly([body], [Bearing("b", {"x": 8e6, "y": 8e6})], [], period=1e-3,
                      carrier_speed=300.0).assemble()
    res = modal_analysis(system, gyroscopic=True)
    np.testing.assert_allclose(res.frequencies, np.array([0.0, 1700.0, 2300.0]) / (2 * math.pi),
                               rtol=1e-10, atol=1e-9)


def test_gyroscopic_modes_of_a_herringbone_set_are_the_undamped_ones_at_rest():
    """At a carrier speed of 1e-3 rad/s the gyroscopic modes are the undamped ones (N = 4,
    8 deg helix): same count, one rigid mode, frequencies within 1e-6, same kinds."""
    m = HerringbonePlanetaryModel(base_helix_angle=math.radians(8.0), groove=3e6)
    rest = m.classify(modal_analysis(m.assembly().assemble()))
    spin = replace(m, carrier_speed=1e-3)
    gyro = spin.classify(modal_analysis(spin.assembly().assemble(), gyroscopic=True))
    assert gyro.frequencies.size == rest.frequencies.size == 29
    np.testing.assert_allclose(gyro.frequencies, rest.frequencies, rtol=1e-6, atol=1e-9)
    assert gyro.kinds == rest.kinds


def _axial_marks(ax) -> list:
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Circle

    green = {to_rgba("tab:green"), to_rgba("tab:olive")}
    return [p for p in ax.patches if isinstance(p, Circle) and not p.get_fill()
            and to_rgba(p.get_edgecolor()) in green]


def test_axial_mode_is_drawn_as_circles_of_diameter_z():
    """Spur halves, N = 4: the sun's axial mode (2516.5 Hz, sqrt(kz_s / m_s)) draws two
    circles (left and right half) of diameter 0.9 r_b,sun (the largest motion on the common
    scale), at -+ r_b,sun / 2 beside the sun's centre, and no arrow; a translational mode
    draws no circle."""
    from pipeline.dynamics.layout import model_layout
    from pipeline.viz.canvas import new_figure
    from pipeline.viz.modes import plot_mode_on_layout

    m = HerringbonePlanetaryModel()
    res = m.classify(modal_analysis(m.assembly().assemble()))
    layout = model_layout(m)
    k = int(np.argmin(np.abs(res.frequencies - math.sqrt(m.kz_sun / m.mass_sun) / (2 * math.pi))))
    assert res.kinds[k] == "axial"
    ax = plot_mode_on_layout(res, layout, k, ax=new_figure((4, 4)).subplots())
    marks = _axial_marks(ax)
    rs = m.base_radius_sun
    assert len(marks) == 2
    assert sorted(c.center[0] for c in marks) == pytest.approx([-0.5 * rs, 0.5 * rs])
    assert all(c.radius == pytest.approx(0.45 * rs) for c in marks)
    assert "axial 100 %" in ax.get_title() and " axial (x1)" in ax.get_title()
    trans = int(np.flatnonzero(np.array(res.kinds) == "translational")[0])
    ax2 = plot_mode_on_layout(res, layout, trans, ax=new_figure((4, 4)).subplots())
    assert _axial_marks(ax2) == []
