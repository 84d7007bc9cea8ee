"""Matplotlib figures for pair geometry and mesh stiffness (all axes labelled with units).

Every function returns the :class:`matplotlib.figure.Figure`; :func:`save` writes
it atomically as PNG.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path

import numpy as np

from pipeline.geometry.pair import GearPair
from pipeline.io import atomic_write


def _plt():
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    return plt


def save(fig, path: str | Path, dpi: int = 130) -> Path:
    """Save ``fig`` as PNG atomically and close it."""
    plt = _plt()
    out = atomic_write(path, lambda p: fig.savefig(p, dpi=dpi, bbox_inches="tight", format="png"))
    plt.close(fig)
    return out


def plot_line_of_action(pair: GearPair, title: str = ""):
    """Path of contact on the line of action: single/double contact zones and the pitch point."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(8, 2.8))
    pb = pair.base_pitch
    s_a, s_e, s_c = pair.s_start * 1e3, pair.s_end * 1e3, pair.s_pitch * 1e3
    ax.plot([0, pair.t1t2 * 1e3], [0, 0], color="0.6", lw=1, label="line of action T1-T2")
    ax.plot([s_a, s_e], [0, 0], color="C0", lw=6, solid_capstyle="butt", label="path of contact")
    # zones: double contact near both ends (length (eps-1) p_b each)
    n = math.floor(pair.transverse_contact_ratio)
    extra = pair.path_length - n * pb
    ax.axvspan(s_a, s_a + extra * 1e3, color="C1", alpha=0.25, label=f"{n + 1} pairs in contact")
    ax.axvspan(s_e - extra * 1e3, s_e, color="C1", alpha=0.25)
    ax.axvline(s_c, color="k", ls="--", lw=1, label="pitch point")
    for x, lab in ((0, "T1"), (pair.t1t2 * 1e3, "T2"), (s_a, "A"), (s_e, "E")):
        ax.annotate(lab, (x, 0), xytext=(0, 10), textcoords="offset points", ha="center")
    ax.set_xlabel("roll coordinate s along the line of action [mm]")
    ax.set_yticks([])
    ax.set_title(title or f"eps_alpha = {pair.transverse_contact_ratio:.3f}, "
                 f"eps_beta = {pair.overlap_ratio:.3f}, "
                 f"alpha_wt = {math.degrees(pair.operating_pressure_angle):.3f} deg")
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.35), ncol=4, fontsize=8)
    return fig


def plot_contact_lines(pair: GearPair, n_positions: int = 4):
    """Contact lines on the plane of action at a few positions over one mesh cycle."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6, 4))
    b = pair.face_width * 1e3
    ax.add_patch(plt.Rectangle((pair.s_start * 1e3, 0), pair.path_length * 1e3, b, fill=False,
                               ec="k", lw=1))
    for i, s0 in enumerate(pair.mesh_cycle(n_positions)):
        for j, seg in enumerate(pair.contact_lines(float(s0))):
            ax.plot(seg[:, 0] * 1e3, seg[:, 1] * 1e3, color=f"C{i}", lw=2,
                    label=f"t = {i}/{n_positions} T_m" if j == 0 else None)
    ax.axvline(pair.s_pitch * 1e3, color="k", ls="--", lw=1)
    ax.set_xlabel("roll coordinate s [mm]")
    ax.set_ylabel("face width position z [mm]")
    ax.set_title("Contact lines on the plane of action")
    ax.legend(fontsize=8)
    return fig


def plot_stiffness_curves(
    curves: Sequence[tuple[str, np.ndarray, np.ndarray]],
    xlabel: str = "pinion rotation over one mesh cycle [deg]",
    title: str = "",
    pairs: np.ndarray | None = None,
    pairs_x: np.ndarray | None = None,
):
    """Overlay stiffness curves ``(label, x, k [N/m])``; optional per-pair curves of the first."""
    plt = _plt()
    fig, ax = plt.subplots(figsize=(8, 4.2))
    for i, (label, x, k) in enumerate(curves):
        ax.plot(x, np.asarray(k) * 1e-8, lw=1.6, color=f"C{i}", label=label)
    if pairs is not None and pairs_x is not None:
        for j in range(pairs.shape[1]):
            kj = np.where(pairs[:, j] > 0, pairs[:, j], np.nan)
            if np.any(np.isfinite(kj)):
                ax.plot(pairs_x, kj * 1e-8, lw=0.8, ls=":", color="0.35",
                        label="single tooth pairs" if j == 0 else None)
    ax.set_xlabel(xlabel)
    ax.set_ylabel("mesh stiffness [1e8 N/m]")
    ax.grid(alpha=0.3)
    ax.set_title(title)
    ax.legend(fontsize=8)
    return fig


def plot_friction_coefficients(x: np.ndarray, kf: np.ndarray, kt1: np.ndarray, kt2: np.ndarray,
                               title: str = ""):
    """Friction stiffness (N/m) and friction torque coefficients (N) over a mesh cycle."""
    plt = _plt()
    fig, (a1, a2) = plt.subplots(1, 2, figsize=(10, 3.8))
    a1.plot(x, kf * 1e-6)
    a1.set_ylabel("friction stiffness K_f [1e6 N/m]")
    a2.plot(x, kt1 * 1e-3, label="driving gear")
    a2.plot(x, kt2 * 1e-3, label="driven gear")
    a2.set_ylabel("friction torque coefficient KT_f [kN]")
    a2.legend(fontsize=8)
    for a in (a1, a2):
        a.set_xlabel("pinion rotation over one mesh cycle [deg]")
        a.grid(alpha=0.3)
    fig.suptitle(title)
    return fig
