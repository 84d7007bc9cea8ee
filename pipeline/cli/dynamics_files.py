"""Files of the dynamics results: CSV tables and PNG figures (units in names and labels).

Shared by ``gearpipe modes|response|sweep`` and ``gearpipe run``; figures go through a
:class:`~pipeline.viz.figure_cache.FigureCache` (none by default).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipeline.dynamics.analysis import ResponseResult
from pipeline.dynamics.layout import ModelLayout
from pipeline.dynamics.modal import ModalResult
from pipeline.dynamics.operating import OperatingFrequency
from pipeline.dynamics.sweep import SweepResult
from pipeline.io import write_csv
from pipeline.viz.figure_cache import NO_CACHE, FigureCache


def write_modes(res: ModalResult, out: Path, layout: ModelLayout,
                figures: FigureCache = NO_CACHE, title: str = "") -> list[Path]:
    """``modes.csv`` (frequencies, multiplicities, kinds), ``mode_shapes.csv`` (the
    eigenvectors, one row per coordinate with its unit) and the mode shapes drawn on
    ``layout``: every elastic mode, 12 per page, ``mode_shapes.png`` then
    ``mode_shapes_2.png``, ... (:func:`pipeline.viz.modes.mode_pages`)."""
    from pipeline.viz.modes import mode_pages, plot_mode_shapes

    files = [write_csv(out / "modes.csv", res.columns()),
             write_csv(out / "mode_shapes.csv", res.shape_columns())]
    pages = mode_pages(res)
    for n, page in enumerate(pages, start=1):
        name = "mode_shapes.png" if n == 1 else f"mode_shapes_{n}.png"
        head = f"{title}: " if title else ""
        files.append(figures.save(out / name, plot_mode_shapes, res, layout, page,
                                  title=f"{head}mode shapes, page {n} of {len(pages)}"))
    return files


def operating_title(operating: OperatingFrequency | None) -> str:
    """``"at f_m = 27.71 Hz (sun 96.67 rpm)"``: the operating point a figure is drawn at
    (mesh frequency, the driver's speed), or "" without one."""
    if operating is None:
        return ""
    text = f"at f_m = {operating.mesh_frequency:.4g} Hz"
    if operating.members:
        m = operating.members[0]
        text += f" ({m} {operating.rpm(m):.4g} rpm)"
    return text


def write_response(result: ResponseResult, out: Path, name: str,
                   figures: FigureCache = NO_CACHE,
                   operating: OperatingFrequency | None = None) -> list[Path]:
    """Time history, DTE spectrum (CSV + PNG) and harmonic contributions (PNG); the
    titles name the ``operating`` mesh frequency (Hz) and driver speed (rpm) when given."""
    from pipeline.viz.dynamics import (
        mesh_title,
        plot_harmonic_contributions,
        plot_spectrum,
        plot_time_history,
    )

    resp, hr = result.response, result.harmonic
    meshes = resp.mesh_names[:1]
    at = f" {operating_title(operating)}".rstrip()
    files = [write_csv(out / "time_history.csv", result.columns())]
    files.append(write_csv(out / "dte_spectrum.csv", resp.dte_spectrum_columns(0)))
    files.append(figures.save(out / "time_history.png", plot_time_history, [resp], [name],
                              title=f"{name}: " + mesh_title("DTE and elastic mesh force",
                                                             meshes) + at))
    files.append(figures.save(out / "dte_spectrum.png", plot_spectrum, [resp], [name],
                              title=mesh_title("DTE spectrum", meshes) + at if at else ""))
    if hr is not None:
        files.append(figures.save(
            out / "harmonics.png", plot_harmonic_contributions, [hr], [name],
            title=mesh_title("harmonic contributions to the DTE", meshes) + at if at else ""))
    return files


def shown_meshes(res: SweepResult) -> list[str]:
    """The meshes a sweep plot shows: the pair's mesh, or the first planet's sun mesh (both
    halves of a herringbone set)."""
    first = ("mesh", "s-p1", "s-p1L", "s-p1R")
    return [m for m in res.mesh_names if m in first] or list(res.mesh_names[:2])


def write_sweep(res: SweepResult, out: Path, name: str,
                figures: FigureCache = NO_CACHE,
                natural_frequencies: np.ndarray | None = None,
                operating: OperatingFrequency | None = None) -> list[Path]:
    """``sweep.csv`` (every mesh: RMS, max, mean and alternating RMS force in N, dynamic
    factor) and ``sweep.png`` (RMS force of :func:`shown_meshes`, with the model's
    ``natural_frequencies`` in Hz, the ``operating`` mesh frequency and its harmonics
    marked, the driver's speed in rpm on the top axis)."""
    from pipeline.viz.dynamics import plot_sweep

    return [write_csv(out / "sweep.csv", res.columns()),
            figures.save(out / "sweep.png", plot_sweep, [res], [name], shown_meshes(res),
                         title=name, natural_frequencies=natural_frequencies,
                         operating=operating)]
