"""CLI entry points: ``gearpipe modes|response|sweep CONFIG [--out DIR] [--json] [--full]``.

Each ``run_*`` reads a dynamics TOML (:mod:`pipeline.dynamics.config`), writes
CSV/PNG/JSON plus ``run.json`` to ``--out`` (default ``results/<name>/<command>``)
and prints a short table, or one JSON object with ``--json``. ``--full`` uses the
fine settings (more harmonics/segments, all sweep points); the default is coarse.
Exit code 0 on success, 2 on an input error (the message names the field).
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from pipeline.dynamics.config import DynamicsConfig, load_dynamics_config
from pipeline.io import to_jsonable, write_csv, write_json, write_run_record
from pipeline.validation import InputError


def _common(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("config", help="dynamics study TOML file")
    parser.add_argument("--out", default=None, help="output folder (default results/<name>/<cmd>)")
    parser.add_argument("--json", action="store_true", help="print one JSON summary on stdout")
    parser.add_argument("--full", action="store_true", help="fine settings instead of coarse")


add_modes_arguments = _common
add_response_arguments = _common
add_sweep_arguments = _common


def _setup(args, command: str) -> tuple[DynamicsConfig, Path]:
    cfg = load_dynamics_config(args.config)
    out = Path(args.out) if args.out else Path("results") / cfg.name / command
    out.mkdir(parents=True, exist_ok=True)
    return cfg, out


def _emit(args, summary: dict, lines: list[str]) -> None:
    if args.json:
        print(json.dumps(to_jsonable(summary)))
    else:
        print("\n".join(lines))


def _guard(func):
    def wrapper(args) -> int:
        try:
            return func(args)
        except InputError as exc:
            print(f"error: {exc}", file=sys.stderr)
            return 2

    wrapper.__name__ = func.__name__
    wrapper.__doc__ = func.__doc__
    return wrapper


@_guard
def run_modes(args) -> int:
    """Natural frequencies, mode types and mode-shape plots of the configured model."""
    from pipeline.dynamics.modal import modal_analysis
    from pipeline.viz import save
    from pipeline.viz.dynamics import plot_mode_shapes

    cfg, out = _setup(args, "modes")
    system = cfg.model.assembly().assemble()
    res = modal_analysis(system, gyroscopic=system.carrier_speed != 0.0)
    if hasattr(cfg.model, "classify"):
        res = cfg.model.classify(res)
    kinds = np.array(
        [
            {"": 0, "rigid": 1, "rotational": 2, "translational": 3, "planet": 4, "mixed": 5}[k]
            for k in res.kinds
        ]
    )
    files = [
        write_csv(
            out / "modes.csv",
            {
                "frequency [Hz]": res.frequencies,
                "multiplicity [-]": res.multiplicity,
                "kind [0 none,1 rigid,2 rot,3 trans,4 planet,5 mixed]": kinds,
            },
        ),
        save(plot_mode_shapes(res, count=16 if args.full else 8), out / "mode_shapes.png"),
    ]
    summary = {
        "frequencies_Hz": res.frequencies,
        "kinds": res.kinds,
        "multiplicity": res.multiplicity,
        "dofs": len(res.dof_names),
        "out": str(out),
    }
    write_run_record(out, cfg.raw, files, f"gearpipe modes {args.config}")
    lines = [
        f"{len(res.dof_names)} DOF ({system.n} independent), results in {out}",
        "  #   f [Hz]      kind           mult",
    ]
    lines += [
        f"{k:3d} {f:10.2f}  {kd:14s} {m}"
        for k, (f, kd, m) in enumerate(
            zip(res.frequencies, res.kinds, res.multiplicity, strict=True)
        )
    ]
    _emit(args, summary, lines)
    return 0


def solve_response(cfg: DynamicsConfig, full: bool):
    """Steady response by the configured method; returns (Response, HarmonicResponse | None)."""
    from pipeline.dynamics.harmonic_balance import harmonic_balance
    from pipeline.dynamics.integrate import integrate, steady_state

    system = cfg.model.assembly().assemble()
    s = cfg.solver
    segments = None if s.segments is None else int(s.segments) * (4 if full else 1)
    if s.method == "harmonic_balance":
        hr = harmonic_balance(system, int(s.n_harmonics) * (2 if full else 1))
        return hr.response, hr
    if s.method == "floquet":
        return steady_state(system, segments), None
    return integrate(system, int(s.periods), segments=segments), None


@_guard
def run_response(args) -> int:
    """Steady dynamic response: DTE and mesh forces in time, DTE spectrum."""
    from pipeline.viz import save
    from pipeline.viz.dynamics import (
        plot_harmonic_contributions,
        plot_spectrum,
        plot_time_history,
    )

    cfg, out = _setup(args, "response")
    resp, hr = solve_response(cfg, args.full)
    cols = {"time [s]": resp.time}
    for i, m in enumerate(resp.mesh_names):
        cols[f"dte {m} [m]"] = resp.dte[i]
        cols[f"force {m} [N]"] = resp.mesh_force[i]
    files = [write_csv(out / "time_history.csv", cols)]
    f, a = resp.dte_spectrum(0)
    files.append(write_csv(out / "dte_spectrum.csv", {"frequency [Hz]": f, "amplitude [m]": a}))
    fig = plot_time_history([resp], [cfg.name], title=f"{cfg.name}: {resp.mesh_names[0]}")
    files.append(save(fig, out / "time_history.png"))
    files.append(save(plot_spectrum([resp], [cfg.name]), out / "dte_spectrum.png"))
    if hr is not None:
        files.append(save(plot_harmonic_contributions([hr], [cfg.name]), out / "harmonics.png"))
    summary = {
        "method": resp.method,
        "period_s": resp.period,
        "meshes": {
            m: {
                "rms_force_N": resp.rms_mesh_force()[i],
                "dte_peak_to_peak_m": resp.peak_to_peak_dte()[i],
                "dte_mean_m": float(resp.dte[i, resp.steady_slice()].mean()),
            }
            for i, m in enumerate(resp.mesh_names)
        },
        "out": str(out),
    }
    write_json(out / "summary.json", summary)
    files.append(out / "summary.json")
    write_run_record(out, cfg.raw, files, f"gearpipe response {args.config}")
    lines = [
        f"{cfg.name}: {resp.method}, mesh period {resp.period * 1e3:.4f} ms, results in {out}",
        "mesh            RMS force [N]   DTE p-p [um]",
    ]
    lines += [
        f"{m:14s} {v['rms_force_N']:14.1f} {v['dte_peak_to_peak_m'] * 1e6:14.4f}"
        for m, v in summary["meshes"].items()
    ]
    _emit(args, summary, lines)
    return 0


@_guard
def run_sweep(args) -> int:
    """RMS dynamic mesh force against mesh frequency."""
    from pipeline.dynamics.sweep import mesh_force_sweep
    from pipeline.viz import save
    from pipeline.viz.dynamics import plot_sweep

    cfg, out = _setup(args, "sweep")
    system = cfg.model.assembly().assemble()
    sw = cfg.sweep
    freqs = sw.frequencies(args.full)
    res = mesh_force_sweep(
        system,
        freqs,
        sw.method,
        int(sw.n_harmonics),
        executor="local" if freqs.size >= 50 else None,
        show_progress=not args.json,
    )
    cols = {"mesh frequency [Hz]": res.frequencies}
    for i, m in enumerate(res.mesh_names):
        cols[f"rms force {m} [N]"] = res.rms_force[i]
        cols[f"max force {m} [N]"] = res.max_force[i]
    files = [write_csv(out / "sweep.csv", cols)]
    shown = [m for m in res.mesh_names if m.startswith("s-p1") or m == "mesh"] or list(
        res.mesh_names[:2]
    )
    files.append(save(plot_sweep([res], [cfg.name], shown, title=cfg.name), out / "sweep.png"))
    peaks = {m: res.peaks(m) for m in shown}
    write_run_record(out, cfg.raw, files, f"gearpipe sweep {args.config}")
    summary = {"points": int(freqs.size), "peaks_Hz": peaks, "out": str(out)}
    lines = [
        f"{cfg.name}: {freqs.size} points {freqs[0]:.0f}-{freqs[-1]:.0f} Hz, results in {out}"
    ]
    lines += [f"  {m}: peaks at {', '.join(f'{p:.0f}' for p in v)} Hz" for m, v in peaks.items()]
    _emit(args, summary, lines)
    return 0
