"""Figures of the tooth load distribution report: stiffness, transmission error, line load,
contact pressure over both flanks, root stress along the fillets.

Every function draws a new matplotlib :class:`~matplotlib.figure.Figure` (no pyplot, no
backend chosen) with its axes labelled in the report's units: mesh stiffness N/um,
transmission error um, line load and unit load N/mm, pressures and stresses MPa, lengths
mm, angles deg.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pipeline.contact.distribution import LoadDistribution
from pipeline.contact.pressure_envelope import pressure_envelope
from pipeline.contact.results import LoadedMeshCycle, pairs_in_order_of_entry
from pipeline.geometry.pair import GearPair
from pipeline.viz.canvas import TITLE_Y, Margins, new_figure, panels_with_colorbar

if TYPE_CHECKING:
    from matplotlib.figure import Figure

N_PER_UM = 1e-6  # N/m -> N/um
N_PER_MM = 1e-3  # N/m -> N/mm


def _cycle_fraction(pair: GearPair, s0: np.ndarray) -> np.ndarray:
    return (np.asarray(s0) - pair.s_start) / pair.base_pitch


def plot_stiffness_comparison(pair: GearPair, s0_analytical: np.ndarray,
                              k_analytical: np.ndarray, cycle: LoadedMeshCycle,
                              k_iso: float, compliance: str, title: str) -> Figure:
    """Analytical k(t), the LTCA tangent k(t) on ``compliance`` and ISO 6336-1's
    c_gamma_alpha b over one mesh cycle (N/m in, N/um drawn)."""
    fig = new_figure((7.0, 3.6), Margins())
    ax = fig.add_subplot()
    ax.plot(_cycle_fraction(pair, s0_analytical), np.asarray(k_analytical) * N_PER_UM,
            label="analytical (potential energy)")
    ax.plot(_cycle_fraction(pair, cycle.s0), cycle.mesh_stiffness * N_PER_UM, "o-", ms=3,
            label=f"loaded contact (LTCA, {compliance} compliance)")
    ax.axhline(k_iso * N_PER_UM, color="k", ls="--", lw=1.0,
               label="ISO 6336-1 c_gamma_alpha b (mean)")
    ax.set_xlabel("mesh cycle [-] (roll of the leading pair over the base pitch)")
    ax.set_ylabel("mesh stiffness [N/um]")
    ax.set_ylim(0.0, None)
    ax.set_xlim(0.0, 1.0)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(title, fontsize=9, y=TITLE_Y)
    return fig


def plot_transmission_error(pair: GearPair, dist: LoadDistribution, s0: np.ndarray,
                            title: str) -> Figure:
    """Loaded static TE over the cycle (um), the amplitudes of mesh orders 1-10 (um) and the
    load share of every tooth pair."""
    # the legend beside the last panel: 1.25 in on the right
    fig = new_figure((10.0, 3.4), Margins(top=0.5, right=1.25, wspace=0.8))
    a1, a2, a3 = fig.subplots(1, 3, width_ratios=(1.3, 1.0, 1.3))
    x = _cycle_fraction(pair, s0)
    a1.plot(x, dist.transmission_error * 1e6, "o-", ms=3)
    a1.set_xlabel("mesh cycle [-]")
    a1.set_ylabel("loaded static TE [um]")
    a1.set_xlim(0.0, 1.0)
    a1.grid(alpha=0.3)
    orders = np.arange(1, dist.te_orders.size + 1)
    a2.bar(orders, np.nan_to_num(dist.te_orders) * 1e6, color="C1")
    a2.set_xticks(orders)
    a2.set_xlabel("mesh order [-]")
    a2.set_ylabel("TE amplitude [um]")
    a2.grid(alpha=0.3, axis="y")
    for n, j in enumerate(pairs_in_order_of_entry(dist.load_share), start=1):
        a3.plot(x, dist.load_share[:, j], label=f"tooth pair {n}")
    a3.set_title("pairs numbered as they take load", fontsize=8, y=TITLE_Y)
    a3.set_xlabel("mesh cycle [-]")
    a3.set_ylabel("load share [-]")
    a3.set_ylim(0.0, 1.05)
    a3.set_xlim(0.0, 1.0)
    a3.grid(alpha=0.3)
    a3.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))  # outside: no overlap
    fig.suptitle(title, fontsize=9)
    return fig


def plot_line_load(dist: LoadDistribution, title: str) -> Figure:
    """Line load over the face width at every position (grey), its envelope and its mean over
    the cycle, with the mean P/b (N/mm against mm)."""
    fig = new_figure((7.0, 3.6), Margins())
    ax = fig.add_subplot()
    z, w, env, mean = dist.z * 1e3, dist.line_load, dist.envelope, dist.cycle_mean
    if z.size == 1:  # one slice stands for the whole face
        z = np.array([0.0, dist.face_width * 1e3])
        w, env, mean = np.repeat(w, 2, axis=1), np.repeat(env, 2), np.repeat(mean, 2)
    for i, row in enumerate(w):
        ax.plot(z, row * N_PER_MM, color="0.7", lw=0.7,
                label="each mesh position" if i == 0 else None)
    ax.plot(z, env * N_PER_MM, "C3", lw=2.0, label="envelope over the cycle")
    ax.plot(z, mean * N_PER_MM, "C0", lw=2.0, ls="--",
            label=f"mean over the cycle (K_Hbeta = {dist.k_hbeta:.3f})")
    ax.axhline(dist.mean_line_load * N_PER_MM, color="k", ls=":", lw=1.0, label="P / b")
    ax.set_xlabel("face position b_z [mm]")
    ax.set_ylabel("line load w [N/mm]")
    ax.set_xlim(0.0, dist.face_width * 1e3)
    ax.set_ylim(0.0, max(dist.envelope.max() * N_PER_MM * 1.15, 1e-9))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower right")
    ax.set_title(title, fontsize=9, y=TITLE_Y)
    return fig


def _with_margin(lo: float, hi: float, share: float = 0.05) -> tuple[float, float]:
    """``(lo, hi)`` widened by ``share`` of its length on both sides (pcolormesh keeps no
    margin of its own, and a marker at the edge would be cut in half)."""
    pad = share * (hi - lo)
    return lo - pad, hi + pad


def flank_axis_label(name: str, internal: bool) -> str:
    """x label of a flank drawn over its diameter, growing to the right: an external gear's
    root is its smallest diameter (left), an internal gear's (ring's) its largest (right)."""
    if internal:
        return f"{name} (internal) diameter [mm], root side right"
    return f"{name} diameter [mm], root side left"


def plot_contact_pressure(cycle: LoadedMeshCycle, dist: LoadDistribution, pair: GearPair,
                          title: str, profile_points: int = 80) -> Figure:
    """Hertz pressure envelope over the cycle on the pinion and the gear flank (MPa), drawn
    over the diameter of each flank (mm, growing to the right; the x label says on which
    side the root is) and the whole face width 0..b (mm,
    :func:`~pipeline.contact.pressure_envelope.to_face_ends`); the maximum
    is marked, inside a margin of 5 % of each axis so that a maximum at the end of the path
    or the face is not cut."""
    grid = pressure_envelope(cycle, dist, pair, profile_points)
    s, z, env = grid.s, grid.z, grid.pressure
    r1, r2 = pair.contact_radii(s)
    # a two-line suptitle above the panels' titles, the colour bar's label on the right
    fig = new_figure((10.0, 3.8), Margins(top=0.8, right=0.75, wspace=0.3))
    axes, bar = panels_with_colorbar(fig)
    vmax = max(env.max() * 1e-6, 1e-9)
    zz = z * 1e3
    h = dist.hertz_max
    for ax, r, rmax, name, internal in (
            (axes[0], r1, h.pinion_radius, "pinion", False),
            (axes[1], r2, h.gear_radius, "gear", pair.gear.internal)):
        d = 2e3 * r
        order = np.argsort(d)
        m = ax.pcolormesh(d[order], zz, env[order].T * 1e-6, shading="gouraud",
                          cmap="inferno", vmin=0.0, vmax=vmax)
        ax.plot(2e3 * rmax, h.z * 1e3, "P", ms=11, mfc="w", mec="k", mew=1.0)
        ax.set_xlabel(flank_axis_label(name, internal))
        ax.set_title(f"{name} flank: max {h.value * 1e-6:.0f} MPa at +", fontsize=9, y=TITLE_Y)
        ax.set_xlim(*_with_margin(d.min(), d.max()))
    axes[0].set_ylim(*_with_margin(zz.min(), zz.max()))
    axes[0].set_ylabel("face position b_z [mm]")
    fig.colorbar(m, cax=bar, label="Hertz pressure p_H, envelope over the cycle [MPa]")
    c = dist.tip_corner_max
    fig.suptitle(title if c is None else (
        f"{title}\ntip corners beyond the path of contact, not drawn: up to "
        f"{c.value * 1e-6:.0f} MPa (edge loading)"), fontsize=9)
    return fig


def plot_root_stress(curves: list[tuple[str, np.ndarray, np.ndarray, float | None]],
                     title: str) -> Figure:
    """Largest principal stress along the fillet, envelope over the cycle, per gear.

    ``curves`` : (name, arc length from the middle of the tooth space in mm, stress in MPa,
    ISO 6336-3 nominal stress in MPa or None) per gear.
    """
    fig = new_figure((7.0, 3.6), Margins())
    ax = fig.add_subplot()
    for i, (name, arc, sigma, iso) in enumerate(curves):
        ax.plot(arc, sigma, color=f"C{i}", label=f"{name}: FE 2D, envelope over the cycle")
        k = int(np.argmax(sigma))
        ax.plot(arc[k], sigma[k], "o", color=f"C{i}")
        if iso is not None and math.isfinite(iso):
            ax.axhline(iso, color=f"C{i}", ls="--", lw=1.0,
                       label=f"{name}: ISO 6336-3 sigma_F0")
    ax.set_xlabel("arc length along the loaded-side root, from the middle of the tooth "
                  "space [mm]")
    ax.set_ylabel("largest principal stress [MPa]")
    ax.set_ylim(0.0, None)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9, y=TITLE_Y)
    return fig
