"""Files of the dynamics results: CSV tables and PNG figures (units in names and labels).

Shared by ``gearpipe modes|response|sweep`` and ``gearpipe run``; figures go through a
:class:`~pipeline.viz.figure_cache.FigureCache` (none by default).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipeline.dynamics.analysis import ResponseResult
from pipeline.dynamics.modal import ModalResult
from pipeline.dynamics.sweep import SweepResult
from pipeline.io import write_csv
from pipeline.viz.figure_cache import NO_CACHE, FigureCache


def write_modes(res: ModalResult, out: Path, count: int = 8,
                figures: FigureCache = NO_CACHE) -> list[Path]:
    """``modes.csv`` and ``mode_shapes.png`` (the first ``count`` modes)."""
    from pipeline.viz.dynamics import plot_mode_shapes

    return [write_csv(out / "modes.csv", res.columns()),
            figures.save(out / "mode_shapes.png", plot_mode_shapes, res, count=count)]


def write_response(result: ResponseResult, out: Path, name: str,
                   figures: FigureCache = NO_CACHE) -> list[Path]:
    """Time history, DTE spectrum (CSV + PNG) and harmonic contributions (PNG)."""
    from pipeline.viz.dynamics import (
        plot_harmonic_contributions,
        plot_spectrum,
        plot_time_history,
    )

    resp, hr = result.response, result.harmonic
    files = [write_csv(out / "time_history.csv", result.columns())]
    f, a = resp.dte_spectrum(0)
    files.append(write_csv(out / "dte_spectrum.csv", {"frequency [Hz]": f, "amplitude [m]": a}))
    files.append(figures.save(out / "time_history.png", plot_time_history, [resp], [name],
                              title=f"{name}: {resp.mesh_names[0]}"))
    files.append(figures.save(out / "dte_spectrum.png", plot_spectrum, [resp], [name]))
    if hr is not None:
        files.append(figures.save(out / "harmonics.png", plot_harmonic_contributions, [hr],
                                  [name]))
    return files


def shown_meshes(res: SweepResult) -> list[str]:
    """The meshes a sweep plot shows: the pair's mesh, or the first planet's sun mesh (both
    halves of a herringbone set)."""
    first = ("mesh", "s-p1", "s-p1L", "s-p1R")
    return [m for m in res.mesh_names if m in first] or list(res.mesh_names[:2])


def write_sweep(res: SweepResult, out: Path, name: str,
                figures: FigureCache = NO_CACHE,
                natural_frequencies: np.ndarray | None = None) -> list[Path]:
    """``sweep.csv`` (every mesh: RMS, max, mean and alternating RMS force in N, dynamic
    factor) and ``sweep.png`` (RMS force of :func:`shown_meshes`, with the model's
    ``natural_frequencies`` in Hz marked)."""
    from pipeline.viz.dynamics import plot_sweep

    return [write_csv(out / "sweep.csv", res.columns()),
            figures.save(out / "sweep.png", plot_sweep, [res], [name], shown_meshes(res),
                         title=name, natural_frequencies=natural_frequencies)]
