"""Matplotlib figures of dynamic results: time histories, spectra, sweeps, mode shapes.

Every function writes one PNG atomically and returns its path. Units on the
axes: time in ms, DTE in um, forces in kN, frequencies in Hz.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

import numpy as np

from pipeline.dynamics.results import HarmonicResponse, ModalResult, Response
from pipeline.io import atomic_write


def _save(fig, path: Path) -> Path:
    atomic_write(path, lambda p: fig.savefig(p, dpi=120, format="png"))
    import matplotlib.pyplot as plt

    plt.close(fig)
    return Path(path)


def _figure(rows: int = 1, cols: int = 1, size=(8, 4.5)):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt.subplots(rows, cols, figsize=size, squeeze=False, constrained_layout=True)


def plot_time_history(
    responses: Sequence[Response],
    labels: Sequence[str],
    path: Path,
    mesh: str | None = None,
    title: str = "",
) -> Path:
    """DTE (um) and mesh force (kN) of one mesh over the steady part of each response."""
    fig, ax = _figure(2, 1, (8, 6))
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
    return _save(fig, path)


def dte_spectrum(response: Response, mesh: int = 0) -> tuple[np.ndarray, np.ndarray]:
    """Single-sided amplitude spectrum of the steady DTE: (frequency Hz, amplitude m)."""
    s = response.steady_from
    d = response.dte[mesh, s:-1] if response.dte.shape[1] - s > 1 else response.dte[mesh, s:]
    dt = response.time[1] - response.time[0]
    a = np.abs(np.fft.rfft(d - d.mean())) / d.size
    a[1:] *= 2.0
    return np.fft.rfftfreq(d.size, dt), a


def plot_spectrum(
    responses: Sequence[Response],
    labels: Sequence[str],
    path: Path,
    mesh: str | None = None,
    max_order: int = 8,
    title: str = "",
) -> Path:
    """DTE amplitude spectrum (um) against frequency in multiples of the mesh frequency."""
    fig, ax = _figure()
    width = 0.8 / max(len(responses), 1)
    for j, (r, lab) in enumerate(zip(responses, labels, strict=True)):
        i = 0 if mesh is None else r.mesh(mesh)
        f, a = dte_spectrum(r, i)
        order = f * r.period
        keep = (order > 0.5) & (order <= max_order + 0.5)
        ax[0, 0].bar(
            order[keep] + (j - (len(responses) - 1) / 2) * width,
            a[keep] * 1e6,
            width=width,
            label=lab,
        )
    ax[0, 0].set_xlabel("frequency / mesh frequency")
    ax[0, 0].set_ylabel("DTE amplitude [um]")
    ax[0, 0].set_title(title or "DTE spectrum")
    ax[0, 0].legend(fontsize=8)
    ax[0, 0].grid(alpha=0.3)
    return _save(fig, path)


def plot_harmonic_contributions(
    results: Sequence[HarmonicResponse],
    labels: Sequence[str],
    path: Path,
    mesh: int = 0,
    max_order: int = 6,
    title: str = "",
) -> Path:
    """Share of each harmonic order in the DTE (seed 000 "contribution proportion")."""
    fig, ax = _figure()
    width = 0.8 / max(len(results), 1)
    for j, (hr, lab) in enumerate(zip(results, labels, strict=True)):
        o = np.arange(1, min(max_order, hr.dte_contribution.shape[1]) + 1)
        ax[0, 0].bar(
            o + (j - (len(results) - 1) / 2) * width,
            hr.dte_contribution[mesh, : o.size],
            width=width,
            label=lab,
        )
    ax[0, 0].set_xlabel("harmonic order")
    ax[0, 0].set_ylabel("contribution to DTE [-]")
    ax[0, 0].set_title(title)
    ax[0, 0].legend(fontsize=8)
    ax[0, 0].grid(alpha=0.3)
    return _save(fig, path)


def plot_sweep(
    sweeps: Sequence, labels: Sequence[str], meshes: Sequence[str], path: Path, title: str = ""
) -> Path:
    """RMS dynamic mesh force (kN) against mesh frequency, one panel per mesh."""
    fig, ax = _figure(len(meshes), 1, (8, 3.2 * len(meshes)))
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
    return _save(fig, path)


def plot_mode_shapes(
    result: ModalResult, path: Path, count: int = 8, skip_rigid: bool = True
) -> Path:
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
    fig, ax = _figure(rows, cols, (12, 2.6 * rows))
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
    return _save(fig, path)
