"""The operating point in the dynamics: mesh frequency, speeds, sweep range, report.

* Exact: the mesh frequency of a pair is z_1 n_1 / 60 and of a planetary set (ring fixed,
  sun driving) z_s |n_s - n_c| / 60 with n_c = n_s z_s / (z_s + z_r) (Xu et al. 2020,
  eq. 7); every member's speed is 60 f / (its mesh order), exactly; the dynamic model's
  period is 1 / f_m.
* The default sweep range (``SweepOptions`` docstring: f_m / 4 to max(4 f_m, 1.25 f_n*))
  on hand-made spectra, and on the wind-turbine file, whose sweep holds its 27.7 Hz mesh
  frequency and harmonics 2-4; a given range is used as given, with one warning line when
  it leaves out f_m.
* The sweep figure puts its operating marker at f_m (read back from the Axes) and its top
  axis in rpm; the report lists the elastic modes up to the stated cut (no 0 Hz rows) and
  the mesh forces once per group of equal planets.
"""

from __future__ import annotations

import math
import warnings
from pathlib import Path

import numpy as np
import pytest

from pipeline.cache.folder import Cache
from pipeline.config import gearbox_from_text, load_gearbox
from pipeline.dynamics.operating import (
    elastic_modes,
    modes_that_matter,
    pair_operating_frequency,
    planetary_operating_frequency,
)
from pipeline.dynamics.options import SweepOptions, default_sweep_range
from pipeline.dynamics.sweep import SweepResult
from pipeline.report.dynamics_section import dynamics_meshes_section, dynamics_section
from pipeline.validation import InputError, PhysicsWarning

ROOT = Path(__file__).resolve().parents[1]
WIND = ROOT / "workflows/configs/wind_turbine_herringbone_planetary.toml"
RPM = 2 * math.pi / 60  # rad/s per rpm

# the wind-turbine set of Xu et al. (2020): sun 21, ring 95 teeth, sun 96.67 rpm (the file)
ZS, ZR, NS = 21, 95, 96.67
F_WIND = ZS * ZR * NS / (60 * (ZS + ZR))  # = z_s (n_s - n_c) / 60 = 27.70929 Hz


def test_planetary_mesh_frequency_and_speeds_are_exact():
    """f_m = z_s |n_s - n_c| / 60 with n_c = n_s z_s / (z_s + z_r) = 17.5006 rpm: 27.7093 Hz;
    the carrier turns at 60 f_m / z_r, the sun at 60 f_m (z_s + z_r) / (z_s z_r)."""
    op = planetary_operating_frequency(ZS, ZR, NS * RPM)
    n_c = NS * ZS / (ZS + ZR)
    assert op.mesh_frequency == pytest.approx(ZS * (NS - n_c) / 60, rel=1e-14)
    assert op.mesh_frequency == pytest.approx(F_WIND, rel=1e-14)
    assert round(op.mesh_frequency, 4) == 27.7093
    assert op.rpm("carrier") == pytest.approx(n_c, rel=1e-14)
    assert op.rpm("carrier") == pytest.approx(60 * F_WIND / ZR, rel=1e-14)
    assert op.rpm("sun") == pytest.approx(NS, rel=1e-14)
    assert op.rpm("sun", 100.0) == pytest.approx(60 * 100.0 * (ZS + ZR) / (ZS * ZR), rel=1e-14)
    assert op.speed("sun") == pytest.approx(NS * RPM, rel=1e-14)
    assert op.members == ("sun", "carrier")


def test_pair_mesh_frequency_and_speeds_are_exact():
    """The z 50/50 pair at 2340 rpm (the assembly-error paper's case): f_m = 50 x 2340 / 60
    = 1950 Hz; at 1000 Hz the pinion turns at 60 x 1000 / 50 = 1200 rpm, a 75-tooth gear at
    800 rpm."""
    op = pair_operating_frequency(50, 75, 2340 * RPM)
    assert op.mesh_frequency == pytest.approx(1950.0, rel=1e-14)
    assert op.rpm("pinion") == pytest.approx(2340.0, rel=1e-14)
    assert op.rpm("pinion", 1000.0) == pytest.approx(1200.0, rel=1e-14)
    assert op.rpm("gear", 1000.0) == pytest.approx(800.0, rel=1e-14)
    np.testing.assert_allclose(op.rpm("gear", np.array([750.0, 1500.0])), [600.0, 1200.0],
                               rtol=1e-14)
    with pytest.raises(KeyError, match="no speed for 'sun'"):
        op.rpm("sun")


@pytest.mark.parametrize(("modes", "expected"), [
    # f_m = 100 Hz: f_n* = the highest elastic mode up to 10 f_m = 1000 Hz -> 1.25 x 900
    ([0.0, 0.0, 150.0, 900.0, 1200.0], (25.0, 1125.0)),
    # none up to 1000 Hz: the lowest elastic mode, 1.25 x 5000
    ([0.0, 5000.0, 7000.0], (25.0, 6250.0)),
    # 1.25 x 60 < 4 f_m: the harmonics decide
    ([0.0, 60.0], (25.0, 400.0)),
    # rigid-body modes only (and round-off of one): 4 f_m
    ([0.0, 0.0], (25.0, 400.0)),
    ([], (25.0, 400.0)),
])
def test_default_sweep_range_rule(modes, expected):
    assert default_sweep_range(100.0, np.array(modes)) == pytest.approx(expected, rel=1e-15)


def test_given_range_is_kept_and_warned_about_once():
    """Xu et al.'s 200-3000 Hz, as the wind-turbine file had it: kept point for point, one
    warning line naming the range and the 27.7093 Hz mesh frequency."""
    opts = SweepOptions(f_min=200.0, f_max=3000.0, points_coarse=40)
    with pytest.warns(PhysicsWarning) as rec:
        f = opts.frequencies(False, F_WIND, [0.0, 160.0])
    np.testing.assert_array_equal(f, np.linspace(200.0, 3000.0, 40))
    assert len(rec) == 1
    text = str(rec[0].message)
    assert "\n" not in text and "200-3000 Hz" in text and "27.7093 Hz" in text
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        np.testing.assert_array_equal(
            SweepOptions(f_min=10.0, f_max=3000.0).frequencies(True, F_WIND),
            np.linspace(10.0, 3000.0, 500))


def test_one_given_end_and_the_default_other():
    """f_max_Hz alone: f_min = f_m / 4; an f_min_Hz above the default f_max is refused in one
    line naming the key."""
    lo, hi = SweepOptions(f_max=500.0).bounds(100.0, [0.0, 160.0])
    assert (lo, hi) == (25.0, 500.0)
    with pytest.raises(InputError, match=r"dynamics\.sweep\.f_min_Hz = 500 Hz"):
        SweepOptions(f_min=500.0).bounds(100.0, [0.0, 160.0])  # default f_max 400 Hz
    with pytest.raises(ValueError, match="operating mesh frequency"):
        SweepOptions().frequencies(False)


def test_file_without_a_range_gets_the_default():
    box = gearbox_from_text("[pinion]\nteeth = 20\nmodule_mm = 2.0\npressure_angle_deg = 20.0\n"
                            "face_width_mm = 20.0\n[gear]\nteeth = 40\nmodule_mm = 2.0\n"
                            "pressure_angle_deg = 20.0\nface_width_mm = 20.0\n"
                            "[operation]\ntorque_Nm = 100.0\nspeed_rpm = 3000.0\n"
                            "[dynamics.sweep]\npoints = 50\n")
    assert box.dynamics.sweep.f_min is None and box.dynamics.sweep.f_max is None
    assert not box.dynamics.sweep.given


def test_elastic_modes_and_the_listed_ones():
    """Rigid-body modes (0 and round-off) are not natural frequencies; the list stops at
    max(10 f_m, top of the sweep)."""
    f = np.array([0.0, 2e-9, 160.0, 181.0, 270.0, 400.0])
    np.testing.assert_array_equal(elastic_modes(f), [2, 3, 4, 5])
    idx, cut = modes_that_matter(f, 27.7, 200.0)
    assert cut == pytest.approx(277.0) and list(idx) == [2, 3, 4]
    idx, cut = modes_that_matter(f, 27.7, 450.0)
    assert cut == 450.0 and list(idx) == [2, 3, 4, 5]


@pytest.fixture(scope="module")
def wind_run(tmp_path_factory):
    """The wind-turbine file's run (analytical compliance, groove FE, contact excitation)."""
    from pipeline.run import RunOptions, run_pipeline

    box = load_gearbox(WIND)
    return box, run_pipeline(box, RunOptions(cache=Cache(tmp_path_factory.mktemp("cache")),
                                             show_progress=False))


def test_wind_turbine_default_sweep_holds_the_operating_point(wind_run):
    """The file gives no range: the sweep runs from f_m / 4 = 6.93 Hz to 1.25 x the highest
    natural frequency up to 10 f_m (271.0 Hz), past 4 f_m = 110.8 Hz; the model's mesh
    period is 1 / f_m; every listed mode is inside the sweep."""
    box, res = wind_run
    dyn = res.dynamics
    assert box.dynamics.sweep.f_min is None and not dyn.sweep_given
    f_m = dyn.operating.mesh_frequency
    assert f_m == pytest.approx(F_WIND, rel=1e-12)
    assert dyn.model.assembly().assemble().period == pytest.approx(1 / F_WIND, rel=1e-12)
    f = dyn.sweep.frequencies
    assert f[0] == pytest.approx(F_WIND / 4, rel=1e-14)
    assert f[0] < f_m and 4 * f_m < f[-1]
    fn = dyn.modes.frequencies
    f_star = fn[(fn > 1e-3) & (fn <= 10 * f_m)].max()
    assert 270.5 < f_star < 271.5
    assert f[-1] == pytest.approx(1.25 * f_star, rel=1e-14)
    s = dyn.summary()
    assert s["operating_point"]["speeds_rpm"]["sun"] == pytest.approx(NS, rel=1e-12)
    # one rigid-body mode: the whole set turning on its supports (the turning carrier's
    # gyroscopic problem counts it once)
    assert s["rigid_body_modes"] == 1 and min(s["natural_frequencies_Hz"]) > 100.0
    assert max(s["natural_frequencies_Hz"]) <= s["natural_frequency_cut_Hz"] == f[-1]
    listed = len(s["natural_frequencies_Hz"])
    assert listed > 6 and listed + s["elastic_modes_above_cut"] + s["rigid_body_modes"] == fn.size


def test_wind_turbine_report_sections(wind_run):
    """The sun-planet report: operating point and modes once, no 0 Hz row; the sun meshes
    only (both halves), planets 1, 3 and 2, 4 in one column each (sequential phasing with
    z_s = 21 over 4 planets: planet 3 runs half a mesh period after planet 1) - 10 rows
    where the run has 16 meshes x 4 quantities."""
    _, res = wind_run
    s = res.dynamics.summary()
    main = dynamics_section(s)
    q = {r.key: r for r in main.quantities}
    assert q["operating_mesh_frequency"].values[0] == pytest.approx(F_WIND, rel=1e-12)
    assert q["speed_sun"].unit == "rpm" and q["speed_sun"].values[0] == pytest.approx(NS)
    modes = [r for r in main.quantities if r.key.startswith("natural_frequency_mode")]
    assert all(r.values[0] > 100.0 and r.unit == "Hz" for r in modes)
    # 10 modes up to 317.6 Hz, modes 6 and 7 (292.114 Hz, to 1e-6) in one row (the loaded
    # contact's mean stiffness, the tip corners touching beyond the path, sets them)
    assert len(modes) == 9 and s["natural_frequencies_Hz"][5] == pytest.approx(292.1137, 1e-6)
    assert modes[5].label.startswith("modes 6, 7 (repeated)")
    # f_n / f_m once per row: 161.16 / 27.709 = 5.816, 181.51 / 27.709 = 6.551, ...
    ratios = main.notes[-1].split(": ")[1].split(". ")[0].split(", ")
    assert len(ratios) == 9 and ratios[:2] == ["5.82", "6.55"]
    meshes = dynamics_meshes_section(s, "sun_planet")
    assert meshes.columns == ("planets 1, 3", "planets 2, 4")
    assert len(meshes.quantities) == 10
    assert all(r.label.startswith(("half L", "half R")) for r in meshes.quantities)
    rows = {r.key: r.values for r in meshes.quantities}
    op = s["response_at_operating_speed"]["meshes"]
    assert rows["half_L_dynamic_factor"] == pytest.approx(
        (op["s-p1L"]["dynamic_factor"], op["s-p2L"]["dynamic_factor"]), rel=1e-15)
    assert rows["half_R_max_elastic_force"][0] == pytest.approx(
        op["s-p1R"]["max_elastic_force_N"] / 1e3)
    f_at = s["sweep"]["max_dynamic_factor_at_Hz"]["s-p1L"]
    assert rows["half_L_sweep_max_at_speed"][0] == pytest.approx(
        60 * f_at * (ZS + ZR) / (ZS * ZR), rel=1e-12)
    ring = dynamics_meshes_section(s, "planet_ring")
    assert all(c.startswith("planet") for c in ring.columns)


def _summary(planets: dict[int, float]) -> dict:
    meshes = {f"s-p{p}": {"dynamic_factor": v, "max_elastic_force_N": 1e3 * v} for p, v in
              planets.items()}
    meshes.update({f"r-p{p}": {"dynamic_factor": 9.0, "max_elastic_force_N": 9e3}
                   for p in planets})
    return {"operating_point": {"mesh_frequency_Hz": 100.0, "speeds_rpm": {}},
            "response_at_operating_speed": {"meshes": meshes},
            "sweep": {"f_min_Hz": 25.0, "f_max_Hz": 400.0,
                      "max_dynamic_factor": {m: 2.0 for m in meshes},
                      "max_dynamic_factor_at_Hz": {m: 300.0 for m in meshes}}}


def test_equal_planets_share_one_column():
    """Planets equal to 1e-4 share a column; all equal: "every planet"; the ring meshes stay
    out of the sun report."""
    sec = dynamics_meshes_section(_summary({1: 1.2, 2: 1.2 * (1 + 5e-5), 3: 1.2}), "sun_planet")
    assert sec.columns == ("every planet (1-3)",)
    assert [r.values for r in sec.quantities][:2] == [(1.2,), (1.2,)]  # -, kN
    sec = dynamics_meshes_section(_summary({1: 1.2, 2: 1.3, 3: 1.2}), "sun_planet")
    assert sec.columns == ("planets 1, 3", "planet 2")
    assert sec.quantities[0].values == (1.2, 1.3)


def test_sweep_figure_marks_the_operating_point():
    """The operating marker sits at f_m = 1950 Hz (the pair at 2340 rpm), harmonic 2 at
    3900 Hz, and the top axis reads pinion rpm = 60 f / 50."""
    from pipeline.viz.dynamics import plot_sweep

    f = np.linspace(500.0, 5000.0, 10)
    sw = SweepResult(f, np.ones((1, 10)), np.ones((1, 10)), np.ones((1, 10)),
                     np.ones((1, 10)), ("mesh",), "harmonic_balance")
    op = pair_operating_frequency(50, 50, 2340 * RPM)
    fig = plot_sweep([sw], ["x"], ["mesh"], operating=op, natural_frequencies=[0.0, 4488.0])
    ax = fig.axes[0]
    lines = {ln.get_gid(): ln for ln in ax.get_lines() if ln.get_gid()}
    assert lines["operating"].get_xdata()[0] == pytest.approx(1950.0, rel=1e-14)
    assert lines["harmonic_2"].get_xdata()[0] == pytest.approx(3900.0, rel=1e-14)
    assert "harmonic_3" not in lines  # 5850 Hz lies beyond the sweep
    assert "2340 rpm" in lines["operating"].get_label()
    fig.draw_without_rendering()
    (top,) = ax.child_axes
    assert top.get_xlim() == pytest.approx((60 * 500.0 / 50, 60 * 5000.0 / 50), rel=1e-12)
    assert top.get_xlabel() == "pinion speed [rpm]"


def test_operating_point_in_the_titles():
    """The response figures name the operating point: mesh frequency and driver speed."""
    from pipeline.cli.dynamics_files import operating_title
    from pipeline.dynamics.operating import system_operating_frequency

    op = planetary_operating_frequency(ZS, ZR, NS * RPM)
    assert operating_title(op) == "at f_m = 27.71 Hz (sun 96.67 rpm)"
    assert operating_title(None) == ""

    class _System:  # a lumped model with its carrier at rest: mesh frequency only
        period, carrier_speed = 1 / 1500.0, 0.0

    assert operating_title(system_operating_frequency(_System())) == "at f_m = 1500 Hz"
