"""Frequency sweeps, executors, load-sharing factor, commands and the coarse workflows."""

import json
import os
import sys
import time
from functools import partial
from pathlib import Path

import numpy as np
import pytest

from pipeline.dynamics import sweep
from pipeline.dynamics.excitation import rectangular_mesh_stiffness
from pipeline.dynamics.harmonic_balance import harmonic_balance
from pipeline.dynamics.models.planetary import PlanetaryModel
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.dynamics.sweep import load_sharing_factor, mesh_force_sweep

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def pair():
    return SpurPairModel(rectangular_mesh_stiffness(2.0e8, 3.4e8, 1.65, 180)).assembly().assemble()


def test_sweep_methods_agree(pair):
    """HB (H = 30), exact Floquet and continued time integration give the same RMS force."""
    f = np.array([600.0, 1400.0, 2600.0])
    hb = mesh_force_sweep(pair, f, n_harmonics=30, executor=None)
    fl = mesh_force_sweep(pair, f, method="floquet", segments=720, executor=None)
    ti = mesh_force_sweep(
        pair, f[1:], method="time", segments=720, tol=1e-5, max_periods=20000, executor=None
    )
    np.testing.assert_allclose(hb.rms_force, fl.rms_force, rtol=0.01)
    np.testing.assert_allclose(ti.rms_force, fl.rms_force[:, 1:], rtol=1e-3)


def test_local_process_pool_matches_serial(pair, monkeypatch):
    """The same numbers bit for bit in this process and in the pool (forced: POOL_WORTH_S
    0), and from a local sweep too small for the pool."""
    f = np.linspace(100.0, 4000.0, 12)
    a = mesh_force_sweep(pair, f, n_harmonics=10, executor=None)
    b = mesh_force_sweep(pair, f, n_harmonics=10, executor="local")
    monkeypatch.setattr(sweep, "POOL_WORTH_S", 0.0)
    c = mesh_force_sweep(pair, f, n_harmonics=10, executor="local")
    np.testing.assert_array_equal(a.rms_force, b.rms_force)
    np.testing.assert_array_equal(a.rms_force, c.rms_force)


def _pid_after(seconds: float, item: int) -> int:
    del item
    time.sleep(seconds)
    return os.getpid()


@pytest.mark.parametrize("seconds, forked", [(0.0, False), (0.2, True)])
def test_local_map_forks_only_for_work_worth_it(seconds, forked):
    """A local map computes its first item here and forks the pool only when the rest would
    take longer than POOL_WORTH_S here (4 x 0.2 s = 0.8 s > 0.5 s; 4 x 0 s < 0.5 s)."""
    pids = sweep.map_chunks(partial(_pid_after, seconds), [0, 1, 2, 3, 4], "local")
    assert pids[0] == os.getpid()
    assert (set(pids[1:]) != {os.getpid()}) is forked


def test_sweep_plan_equals_harmonic_balance():
    """The sweep's precomputed plan (herringbone planetary, 56 DOF, 16 periodic terms, with
    transmission-error excitation) gives the statistics of a full harmonic balance per
    frequency, and the real-form Woodbury solve the complex one; the same for a spur pair
    excited by a transmission error (displacement excitation and its rate)."""
    from pipeline.dynamics.harmonic_balance import solve_coefficients
    from pipeline.dynamics.hb_sweep import plan_sweep, sweep_point
    from pipeline.dynamics.models.wind_turbine_planetary import wind_turbine_herringbone_model
    from pipeline.dynamics.reduction import reduce_rigid_body_modes
    from pipeline.dynamics.sweep import hb_samples

    red = reduce_rigid_body_modes(
        wind_turbine_herringbone_model(half_coupling=(5e10,) * 4).assembly().assemble())
    assert len(red.terms) == 16
    plan = plan_sweep(red, 12, hb_samples(12))
    for f in (120.0, 1436.0, 4100.0):
        s = red.with_mesh_frequency(f)
        r = harmonic_balance(s, 12, samples=hb_samples(12)).response
        F = r.mesh_force[:, :-1]
        ref = np.stack([np.sqrt((F**2).mean(1)), F.std(1), F.max(1), F.mean(1),
                        r.elastic_force[:, :-1].max(1)])
        np.testing.assert_allclose(sweep_point(plan, f), ref, rtol=1e-11, atol=1e-9)
        a = solve_coefficients(s, 12, method="woodbury")
        b = solve_coefficients(s, 12, method="woodbury_complex")
        assert np.abs(a - b).max() < 1e-12 * np.abs(b).max()
    from pipeline.signals import PeriodicSignal

    tau = np.arange(180) / 180
    te = PeriodicSignal(4e-6 * np.abs(np.sin(np.pi * tau)) + 1e-6 * np.cos(6 * np.pi * tau))
    k = rectangular_mesh_stiffness(2.0e8, 3.4e8, 1.65, 180)
    spur = reduce_rigid_body_modes(SpurPairModel(k, transmission_error=te).assembly().assemble())
    assert spur.meshes[0].transmission_error is not None
    plan = plan_sweep(spur, 20, hb_samples(20))
    for f in (900.0, 2500.0):
        r = harmonic_balance(spur.with_mesh_frequency(f), 20, samples=hb_samples(20)).response
        F = r.mesh_force[:, :-1]
        ref = np.stack([np.sqrt((F**2).mean(1)), F.std(1), F.max(1), F.mean(1),
                        r.elastic_force[:, :-1].max(1)])
        np.testing.assert_allclose(sweep_point(plan, f), ref, rtol=1e-11, atol=1e-9)


def test_sweep_peak_at_torsional_resonance():
    """Torsional pair with constant-ish stiffness: the force peak sits at the natural frequency."""
    k = rectangular_mesh_stiffness(3.0e8, 3.3e8, 1.5, 64)
    m = SpurPairModel(k, torsional_only=True, damping_ratio=0.02)
    s = m.assembly().assemble()
    fn = np.sqrt(3.15e8 * 2 * m.base_radius_pinion**2 / m.inertia_pinion) / (2 * np.pi)
    sw = mesh_force_sweep(s, np.linspace(0.8 * fn, 1.2 * fn, 201), n_harmonics=6, executor=None)
    assert sw.peaks("mesh", 1)[0] == pytest.approx(fn, rel=0.01)


def test_load_sharing_factor_is_one_for_in_phase_equal_planets():
    k = rectangular_mesh_stiffness(4e8, 6e8, 1.5, 64)
    m = PlanetaryModel(
        n_planets=3, k_sun_mesh=k, k_ring_mesh=k, sun_torque=100.0, damping_ratio=0.05
    )
    r = harmonic_balance(m.assembly().assemble(), 8).response
    L = load_sharing_factor(r, ["s-p1", "s-p2", "s-p3"])
    np.testing.assert_allclose(L, 1.0, atol=1e-9)
    assert r.mesh_force[0].mean() > 0


def _run(cmd, cfg, out, extra=()):
    from pipeline.cli import main

    return main([cmd, str(cfg), "--out", str(out), *extra])


def test_commands_write_outputs(tmp_path, capsys):
    cfg = ROOT / "workflows/configs/lin_parker_planetary.toml"
    assert _run("modes", cfg, tmp_path / "m", ["--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["frequencies_Hz"][1] == pytest.approx(727.0, rel=1e-3)  # Lin & Parker 1999
    assert (tmp_path / "m/mode_shapes.png").is_file() and (tmp_path / "m/run.json").is_file()
    spur = ROOT / "workflows/configs/spur_pair_assembly_errors.toml"
    assert _run("response", spur, tmp_path / "r") == 0
    for f in ("time_history.csv", "time_history.png", "dte_spectrum.png", "summary.json"):
        assert (tmp_path / "r" / f).is_file()


def test_command_reports_bad_config(tmp_path, capsys):
    bad = tmp_path / "bad.toml"
    bad.write_text(
        '[lumped_model]\nmodel = "spur_pair"\nmass_pinion_kg = -1\n'
        '[lumped_model.mesh_stiffness]\nkind = "constant"\nvalue_N_per_m = 1e8\n'
    )
    assert _run("modes", bad, tmp_path / "o") == 2
    assert "mass_pinion" in capsys.readouterr().err


def test_split_torque_workflow_coarse(tmp_path):
    """Workflow of Jin et al. (2018): confluence-stage DTE falls as the roughness rises (Jin et al.
    2018, sec. 5.3).

    The split (spur) stage of this model moves the other way by < 1 % (see the report);
    only the reproduced trend is asserted.
    """
    sys.path.insert(0, str(ROOT / "workflows"))
    import dynamics_split_torque as wf

    cols = wf.run(False, tmp_path)
    assert np.all(np.diff(cols["dte order-1 amplitude conf1R [m]"]) < 0)
    assert np.all(np.diff(cols["mean |K_f| split [N/m]"]) > 0)
    assert (tmp_path / "contribution_split.png").is_file()


def test_herringbone_sweep_workflow_coarse(tmp_path):
    """Workflow of Xu et al. (2020) (coarse, 100 points, H = 10): the trends of its sec. 4.

    * Softer groove (K_1 -> K_5 = 5.2e7 -> 4.0e7 N m^2) lowers the natural frequency of
      the sun-half twist (groove) mode monotonically, by about sqrt(K5/K1) on the
      groove-dominated part (measured 3043 -> 2823 Hz, -7.2 %; sqrt ratio -12 %).
    * Axial slide of the sun (0, +0.5, +1 mm at K_1) moves the left and right
      sun-planet mesh forces in opposite directions: peak and mean RMS force of
      s-p1L fall while those of s-p1R rise.
    * With the K_j-dependent left/right mesh stiffness of eq. 14 (Fig. 5), the main
      peak (near 1440 Hz) of both s-p1L and s-p1R falls monotonically from K_1 to
      K_5 (Fig. 9); it sits on the translational sun-mesh mode (measured: 80 % of
      its strain energy in the sun meshes, none in the groove).
    Not reproduced, so not asserted (see the workflow docstring): the peak values
    falling on both sides (L rises here), and the right side's 2500 Hz region
    falling (s-p1R near 2690 Hz rises by 2 Hz).
    """
    sys.path.insert(0, str(ROOT / "workflows"))
    import dynamics_herringbone_sweep as wf

    r = wf.run(False, tmp_path)
    cases = r["cases"]
    groove = [cases.index(f"K{j} slide 0") for j in range(1, 6)]
    fg = r["groove mode [Hz]"][groove]
    assert np.all(np.diff(fg) < 0)
    assert fg[-1] / fg[0] == pytest.approx(0.928, abs=0.01)  # regression of this model
    slide = [cases.index(c) for c in ("K1 slide 0", "K1 slide +0.5 mm", "K1 slide +1 mm")]
    for key, sign in (("force L [N]", -1), ("force R [N]", 1)):
        assert np.all(sign * np.diff(r[f"peak {key}"][slide]) > 0)
        assert np.all(sign * np.diff(r[f"mean {key}"][slide]) > 0)
    assert (tmp_path / "sweep_groove.png").is_file() and (tmp_path / "sweep_slide.png").is_file()
    t = r["groove_peaks"]
    assert np.all(np.diff(t["peak1 L [Hz]"]) < 0) and np.all(np.diff(t["peak1 R [Hz]"]) < 0)
    assert np.all(t["mesh mode sun-mesh energy [-]"] > 0.75)
    assert np.all(t["mesh mode groove energy [-]"] < 1e-6)
    assert (tmp_path / "sweep_groove_peak1.png").is_file()
    assert (tmp_path / "groove_peaks.csv").is_file()


def test_herringbone_hb_agrees_with_time_integration_at_the_main_peak():
    """Xu et al. (2020) model (56 DOF), 1440 Hz main peak: HB (H = 20) vs time integration < 1 %.

    Time integration: exact propagator on 360 segments per mesh period, run from the
    static state until the period-to-period change is below 1e-6. Measured here:
    2.5e-3 on the RMS force (the 360-segment h^2 error dominates; the benchmark's
    ladder shows it falling to 2e-4 at 720 segments). 1 % is the issue's requirement.
    """
    from pipeline.dynamics.models.wind_turbine_planetary import wind_turbine_herringbone_model

    model = wind_turbine_herringbone_model(half_coupling=(5e10, 5e10, 5e10, 5e10))
    s = model.assembly().assemble()
    f = np.array([1440.0])
    hb = mesh_force_sweep(s, f, n_harmonics=20, executor=None)
    ti = mesh_force_sweep(
        s, f, method="time", segments=360, tol=1e-6, max_periods=50000, executor=None
    )
    np.testing.assert_allclose(hb.rms_force, ti.rms_force, rtol=0.01)
    np.testing.assert_allclose(hb.max_force, ti.max_force, rtol=0.01)


def test_modes_command_on_the_herringbone_config(tmp_path, capsys):
    """gearpipe modes on configs/herringbone_planetary_lumped.toml: 8(N+3) DOF, mode types.

    Translational modes come in pairs and there is one rigid rotation. (Planet-type
    modes here have multiplicity 1 and 3 = N - 1: the axial planet motions add the
    N - 1 family; not asserted, the classification is the planar one.)
    """
    cfg = ROOT / "workflows/configs/herringbone_planetary_lumped.toml"
    assert _run("modes", cfg, tmp_path, ["--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert s["coordinates"] == 8 * (4 + 3) and s["independent_dofs"] == len(s["frequencies_Hz"])
    kinds, mult = np.array(s["kinds"]), np.array(s["multiplicity"])
    assert np.count_nonzero(kinds == "rigid") == 1
    assert np.all(mult[kinds == "translational"] == 2)
    assert (tmp_path / "mode_shapes.png").is_file()


def test_refined_peak_on_a_coarse_grid():
    """Parabola vertex: exact for a parabola; a damped resonance to << the grid step."""
    from pipeline.dynamics.peaks import refined_peak

    f = np.arange(1000.0, 1100.0, 4.0)
    p = refined_peak(f, 7.0 - (f - 1041.3) ** 2)
    assert p.frequency == pytest.approx(1041.3, abs=1e-9) and not p.at_edge
    fn, z = 1040.0, 0.05  # |H| of a single mode: peak at fn sqrt(1 - 2 z^2)
    y = 1.0 / np.sqrt((1 - (f / fn) ** 2) ** 2 + (2 * z * f / fn) ** 2)
    # measured error 0.008 Hz (4 Hz step, half-power band 104 Hz)
    assert refined_peak(f, y).frequency == pytest.approx(fn * np.sqrt(1 - 2 * z**2), abs=0.05)
    assert refined_peak(f, f).at_edge


def test_xu2020_main_peak_frequency_falls_with_groove_stiffness():
    """Xu et al. (2020), Fig. 9 trend: the main peak (near 1440 Hz) moves down as K_j falls.

    Coarse grid (4 Hz) around the peak, H = 10, parabola-refined peak of the RMS mesh
    force of s-p1L and s-p1R. With the K_j-dependent left/right mesh stiffness (eq. 14)
    both peaks fall monotonically (measured K_1 -> K_5: L 1436.4 -> 1430.0 Hz,
    R 1440.4 -> 1436.4 Hz); with equal sides (``groove_mesh=None``, groove spring and
    phase only) they barely move (L -0.5 Hz, R +0.3 Hz), so the trend comes from eq. 14.
    """
    from pipeline.dynamics.models.wind_turbine_planetary import K_J, wind_turbine_herringbone_model
    from pipeline.dynamics.peaks import refined_peak

    f = np.arange(1400.0, 1481.0, 4.0)

    def peaks(**kw):
        out = []
        for kj in K_J:
            sw = mesh_force_sweep(
                wind_turbine_herringbone_model(kj, **kw).assembly().assemble(),
                f,
                n_harmonics=10,
                executor=None,
            )
            pk = [
                refined_peak(f, sw.rms_force[sw.mesh_names.index(m)]) for m in ("s-p1L", "s-p1R")
            ]
            assert not any(p.at_edge for p in pk)
            out.append([p.frequency for p in pk])
        return np.array(out)  # (K, side)

    from pipeline.dynamics.models.groove_mesh import XU2020_GROOVE_MESH

    model = peaks(groove_mesh=XU2020_GROOVE_MESH)
    assert np.all(np.diff(model, axis=0) < 0)
    equal = peaks()
    shift_model, shift_equal = model[-1] - model[0], equal[-1] - equal[0]
    assert np.all(np.abs(shift_equal) < 0.2 * np.abs(shift_model))
