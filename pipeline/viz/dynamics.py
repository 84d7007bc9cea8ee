"""Dynamic results: time histories, spectra, harmonic contributions, sweeps, mode shapes.

Units on the axes: time in mesh periods, DTE in um, forces in kN, frequencies in
Hz. Every function draws into ``ax`` (or ``fig`` for several panels) when given
one, otherwise into a new :class:`~matplotlib.figure.Figure`, and returns it.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from matplotlib.axes import Axes
from matplotlib.figure import Figure

from pipeline.dynamics.results import HarmonicResponse, ModalResult, Response


def _panels(fig: Figure | None, rows: int, cols: int, size) -> tuple[Figure, np.ndarray]:
    """``rows x cols`` axes (always 2D) on ``fig`` or on a new constrained-layout figure."""
    if fig is None:
        fig = Figure(figsize=size, constrained_layout=True)
    return fig, fig.subplots(rows, cols, squeeze=False)


def _axes(ax: Axes | None, size=(8, 4.5)) -> Axes:
    return Figure(figsize=size, constrained_layout=True).subplots() if ax is None else ax


def plot_time_history(
    responses: Sequence[Response],
    labels: Sequence[str],
    mesh: str | None = None,
    title: str = "",
    fig: Figure | None = None,
) -> Figure:
    """DTE (um) and mesh force (kN) of one mesh over the steady part of each response."""
    fig, ax = _panels(fig, 2, 1, (8, 6))
    for r, lab in zip(responses, labels, strict=True):
        i = 0 if mesh is None else r.mesh(mesh)
        s = r.steady_from
        t = (r.time[s:] - r.time[s]) / r.period
        ax[0, 0].plot(t, r.dte[i, s:] * 1e6, label=lab)
        ax[1, 0].plot(t, r.mesh_force[i, s:] / 1e3, label=lab)
    ax[0, 0].set_ylabel("DTE [um]")
    ax[1, 0].set_ylabel("mesh force [kN]")
    ax[1, 0].set_xlabel("time [mesh periods]")
    ax[0, 0].legend(fontsize=8)
    ax[0, 0].set_title(title or (mesh or "mesh"))
    for a in ax[:, 0]:
        a.grid(alpha=0.3)
    return fig


def plot_spectrum(
    responses: Sequence[Response],
    labels: Sequence[str],
    mesh: str | None = None,
    max_order: int = 8,
    title: str = "",
    ax: Axes | None = None,
) -> Axes:
    """DTE amplitude spectrum (um) against frequency in multiples of the mesh frequency."""
    ax = _axes(ax)
    width = 0.8 / max(len(responses), 1)
    for j, (r, lab) in enumerate(zip(responses, labels, strict=True)):
        i = 0 if mesh is None else r.mesh(mesh)
        f, a = r.dte_spectrum(i)
        order = f * r.period
        keep = (order > 0.5) & (order <= max_order + 0.5)
        ax.bar(
            order[keep] + (j - (len(responses) - 1) / 2) * width,
            a[keep] * 1e6,
            width=width,
            label=lab,
        )
    ax.set_xlabel("frequency / mesh frequency")
    ax.set_ylabel("DTE amplitude [um]")
    ax.set_title(title or "DTE spectrum")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def plot_harmonic_contributions(
    results: Sequence[HarmonicResponse],
    labels: Sequence[str],
    mesh: int = 0,
    max_order: int = 6,
    title: str = "",
    ax: Axes | None = None,
) -> Axes:
    """Share of each harmonic order in the DTE (the "contribution proportion" of
    Jin et al. 2018)."""
    ax = _axes(ax)
    width = 0.8 / max(len(results), 1)
    for j, (hr, lab) in enumerate(zip(results, labels, strict=True)):
        o = np.arange(1, min(max_order, hr.dte_contribution.shape[1]) + 1)
        ax.bar(
            o + (j - (len(results) - 1) / 2) * width,
            hr.dte_contribution[mesh, : o.size],
            width=width,
            label=lab,
        )
    ax.set_xlabel("harmonic order")
    ax.set_ylabel("contribution to DTE [-]")
    ax.set_title(title)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def plot_sweep(
    sweeps: Sequence, labels: Sequence[str], meshes: Sequence[str], title: str = "",
    fig: Figure | None = None,
) -> Figure:
    """RMS dynamic mesh force (kN) against mesh frequency, one panel per mesh."""
    fig, ax = _panels(fig, len(meshes), 1, (8, 3.2 * len(meshes)))
    for k, m in enumerate(meshes):
        for sw, lab in zip(sweeps, labels, strict=True):
            ax[k, 0].plot(
                sw.frequencies, sw.rms_force[sw.mesh_names.index(m)] / 1e3, label=lab, lw=1
            )
        ax[k, 0].set_ylabel(f"RMS force {m} [kN]")
        ax[k, 0].grid(alpha=0.3)
    ax[-1, 0].set_xlabel("mesh frequency [Hz]")
    ax[0, 0].legend(fontsize=8)
    ax[0, 0].set_title(title)
    return fig


def plot_mode_shapes(
    result: ModalResult, count: int = 8, skip_rigid: bool = True, fig: Figure | None = None
) -> Figure:
    """Bar charts of the first ``count`` mode shapes.

    Each coordinate is shown as its kinetic-energy amplitude ``sqrt(m_i) phi_i`` (so
    rotations and translations compare), normalised to the largest entry.
    """
    idx = [
        k
        for k in range(result.frequencies.size)
        if not (skip_rigid and result.frequencies[k] == 0.0)
    ][:count]
    cols = 2
    rows = max(1, (len(idx) + 1) // cols)
    n = len(result.dof_names)
    fig, ax = _panels(fig, rows, cols, (12, 2.6 * rows))
    for j, k in enumerate(idx):
        a = ax[j // cols, j % cols]
        phi = result.shapes[:, k].real
        if result.weights is not None:
            phi = phi * result.weights
        a.bar(np.arange(n), phi / np.abs(phi).max(), color="tab:blue")
        kind = result.kinds[k] if result.kinds[k] else ""
        a.set_title(
            f"{result.frequencies[k]:.1f} Hz {kind} (x{result.multiplicity[k]})", fontsize=9
        )
        a.set_xticks(np.arange(n))
        a.set_xticklabels(result.dof_names, rotation=90, fontsize=5 if n > 30 else 7)
        a.set_ylim(-1.05, 1.05)
        if j % cols == 0:
            a.set_ylabel("sqrt(m) phi, normalised [-]", fontsize=8)
        a.grid(alpha=0.3)
    for j in range(len(idx), rows * cols):
        ax[j // cols, j % cols].axis("off")
    return fig
