"""Files of the dynamics results: CSV tables and PNG figures (units in names and labels).

Shared by ``gearpipe modes|response|sweep`` and ``gearpipe run``.
"""

from __future__ import annotations

from pathlib import Path

from pipeline.dynamics.analysis import ResponseResult
from pipeline.dynamics.modal import ModalResult
from pipeline.dynamics.sweep import SweepResult
from pipeline.io import write_csv


def write_modes(res: ModalResult, out: Path, count: int = 8) -> list[Path]:
    """``modes.csv`` and ``mode_shapes.png`` (the first ``count`` modes)."""
    from pipeline.viz import save
    from pipeline.viz.dynamics import plot_mode_shapes

    return [write_csv(out / "modes.csv", res.columns()),
            save(plot_mode_shapes(res, count=count), out / "mode_shapes.png")]


def write_response(result: ResponseResult, out: Path, name: str) -> list[Path]:
    """Time history, DTE spectrum (CSV + PNG) and harmonic contributions (PNG)."""
    from pipeline.viz import save
    from pipeline.viz.dynamics import (
        plot_harmonic_contributions,
        plot_spectrum,
        plot_time_history,
    )

    resp, hr = result.response, result.harmonic
    files = [write_csv(out / "time_history.csv", result.columns())]
    f, a = resp.dte_spectrum(0)
    files.append(write_csv(out / "dte_spectrum.csv", {"frequency [Hz]": f, "amplitude [m]": a}))
    fig = plot_time_history([resp], [name], title=f"{name}: {resp.mesh_names[0]}")
    files.append(save(fig, out / "time_history.png"))
    files.append(save(plot_spectrum([resp], [name]), out / "dte_spectrum.png"))
    if hr is not None:
        files.append(save(plot_harmonic_contributions([hr], [name]), out / "harmonics.png"))
    return files


def shown_meshes(res: SweepResult) -> list[str]:
    """The meshes a sweep plot shows: the pair's mesh, or the first planet's sun mesh."""
    return [m for m in res.mesh_names if m.startswith("s-p1") or m == "mesh"] or list(
        res.mesh_names[:2])


def write_sweep(res: SweepResult, out: Path, name: str) -> list[Path]:
    """``sweep.csv`` and ``sweep.png``."""
    from pipeline.viz import save
    from pipeline.viz.dynamics import plot_sweep

    return [write_csv(out / "sweep.csv", res.columns()),
            save(plot_sweep([res], [name], shown_meshes(res), title=name), out / "sweep.png")]
