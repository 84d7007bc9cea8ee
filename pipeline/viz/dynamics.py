"""Dynamic results: time histories, spectra, harmonic contributions, sweeps (mode shapes:
:mod:`pipeline.viz.modes`).

Units on the axes: time in mesh periods, DTE in um, forces in kN, frequencies in
Hz. Every function draws into ``ax`` (or ``fig`` for several panels) when given
one, otherwise into a new :class:`~matplotlib.figure.Figure`, and returns it.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from pipeline.dynamics.operating import OperatingFrequency
from pipeline.dynamics.options import SWEEP_HARMONICS
from pipeline.dynamics.results import HarmonicResponse, Response
from pipeline.viz.canvas import TITLE_Y, Margins, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


def mesh_title(what: str, meshes: Sequence[str]) -> str:
    """``what`` followed by the meshes it shows: ``"DTE spectrum, mesh s-p1"``. A pair's
    only mesh is named "mesh" and goes unnamed (``"DTE spectrum"``), not "mesh mesh"."""
    named = [m for m in meshes if m != "mesh"]
    return f"{what}, mesh {', '.join(named)}" if named else what


def _panels(fig: Figure | None, rows: int, cols: int, size,
            layout: str | Margins = "constrained") -> tuple[Figure, np.ndarray]:
    """``rows x cols`` axes (always 2D) on ``fig`` or on a new figure laid out by
    ``layout`` (:func:`~pipeline.viz.canvas.new_figure`)."""
    if fig is None:
        fig = new_figure(size, layout)
    return fig, fig.subplots(rows, cols, squeeze=False)


def _axes(ax: Axes | None, size=(8, 4.5)) -> Axes:
    return new_figure(size, Margins()).subplots() if ax is None else ax


def plot_time_history(
    responses: Sequence[Response],
    labels: Sequence[str],
    mesh: str | None = None,
    title: str = "",
    fig: Figure | None = None,
) -> Figure:
    """DTE (um) and elastic mesh force k (delta - e) (kN) of one mesh over the steady part
    of each response.

    The elastic force is the one the dynamic factor is read from
    (:meth:`pipeline.dynamics.results.Response.dynamic_factor`); the damping force
    c (delta' - e') is left out because e' of a sampled static transmission error is a
    pulse one contact sample wide at each tooth entry, drawn by a truncated Fourier series
    as a ripple that belongs to the sampling, not to the gears (``time_history.csv`` keeps
    the total force)."""
    fig, ax = _panels(fig, 2, 1, (8, 6), Margins(hspace=0.45))
    for r, lab in zip(responses, labels, strict=True):
        i = 0 if mesh is None else r.mesh(mesh)
        s = r.steady_from
        t = (r.time[s:] - r.time[s]) / r.period
        ax[0, 0].plot(t, r.dte[i, s:] * 1e6, label=lab)
        ax[1, 0].plot(t, r.elastic_mesh_force()[i, s:] / 1e3, label=lab)
    ax[0, 0].set_ylabel("DTE [um]")
    ax[1, 0].set_ylabel("elastic mesh force k (delta - e) [kN]")
    ax[1, 0].set_xlabel("time [mesh periods]")
    ax[0, 0].legend(fontsize=8)
    names = sorted({r.mesh_names[0] if mesh is None else mesh for r in responses})
    ax[0, 0].set_title(title or mesh_title("DTE and elastic mesh force", names), y=TITLE_Y)
    for a in ax[:, 0]:
        a.grid(alpha=0.3)
    return fig


def shown_orders(amplitudes: np.ndarray, threshold: float = 0.01, at_least: int = 10) -> int:
    """Highest harmonic order a spectrum plot shows.

    Parameters
    ----------
    amplitudes : shape (..., H), amplitudes (any unit) of orders 1..H; leading axes are
        several curves (meshes, cases), all judged together.
    threshold : orders whose amplitude is at least ``threshold`` times the largest one are
        all shown, wherever they lie (a planetary set's order 7 can be as large as order 1).
    at_least : the plot shows orders 1..``at_least`` in any case (within 1..H).

    Returns
    -------
    The highest order shown, in [1, H].
    """
    a = np.abs(np.atleast_2d(np.asarray(amplitudes, dtype=float)))
    h = a.shape[-1]
    big = np.flatnonzero((a >= threshold * a.max()).any(axis=tuple(range(a.ndim - 1))))
    last = int(big[-1]) + 1 if a.max() > 0 and big.size else 0
    return max(1, min(h, max(at_least, last)))


def _order_axis(ax: Axes, max_order: int) -> None:
    """x from order 1 to ``max_order``: a tick at every order (every 2nd, 5th, ... when many)."""
    step = next(s for s in (1, 2, 5, 10, 20, 50, 100, 10**9) if max_order / s <= 20)
    ax.set_xticks(np.r_[1, np.arange(step, max_order + 1, step)] if step > 1
                  else np.arange(1, max_order + 1))
    ax.set_xlim(0.4, max_order + 0.6)


def plot_spectrum(
    responses: Sequence[Response],
    labels: Sequence[str],
    mesh: str | None = None,
    max_order: int | None = None,
    title: str = "",
    ax: Axes | None = None,
) -> Axes:
    """DTE amplitude spectrum (um) against frequency in multiples of the mesh frequency.

    ``mesh`` names the mesh (default: the first of each response); ``max_order`` the
    highest order drawn (default: :func:`shown_orders` over all responses, so every
    component of at least 1 % of the largest is shown, and at least orders 1-10). The
    title names the mesh.
    """
    ax = _axes(ax)
    width = 0.8 / max(len(responses), 1)
    spectra = []
    for r in responses:
        i = 0 if mesh is None else r.mesh(mesh)
        f, a = r.dte_spectrum(i)
        spectra.append((f * r.period, a))
    if max_order is None:
        top = max(int(np.floor(o.max() + 0.5)) for o, _ in spectra)
        binned = np.zeros((len(spectra), max(top, 1)))
        for j, (o, a) in enumerate(spectra):
            k = np.floor(o + 0.5).astype(int)
            ok = (k >= 1) & (k <= binned.shape[1])
            np.maximum.at(binned[j], k[ok] - 1, a[ok])
        max_order = shown_orders(binned)
    for j, ((order, a), lab) in enumerate(zip(spectra, labels, strict=True)):
        keep = (order > 0.5) & (order <= max_order + 0.5)
        ax.bar(
            order[keep] + (j - (len(responses) - 1) / 2) * width,
            a[keep] * 1e6,
            width=width,
            label=lab,
        )
    names = sorted({r.mesh_names[0] if mesh is None else mesh for r in responses})
    ax.set_xlabel("frequency / mesh frequency (mesh order) [-]")
    ax.set_ylabel("DTE amplitude [um]")
    ax.set_title(title or mesh_title("DTE spectrum", names), y=TITLE_Y)
    _order_axis(ax, max_order)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def plot_harmonic_contributions(
    results: Sequence[HarmonicResponse],
    labels: Sequence[str],
    mesh: int = 0,
    max_order: int | None = None,
    title: str = "",
    ax: Axes | None = None,
) -> Axes:
    """Share of each harmonic order in the DTE of mesh row ``mesh`` (the "contribution
    proportion" of Jin et al. 2018).

    ``max_order`` is the highest order drawn (default: :func:`shown_orders`, every order
    with at least 1 % of the largest share, and at least orders 1-10). The title names
    the mesh.
    """
    ax = _axes(ax)
    width = 0.8 / max(len(results), 1)
    if max_order is None:
        h = min(hr.dte_contribution.shape[1] for hr in results)
        max_order = shown_orders(np.array([hr.dte_contribution[mesh, :h] for hr in results]))
    for j, (hr, lab) in enumerate(zip(results, labels, strict=True)):
        o = np.arange(1, min(max_order, hr.dte_contribution.shape[1]) + 1)
        ax.bar(
            o + (j - (len(results) - 1) / 2) * width,
            hr.dte_contribution[mesh, : o.size],
            width=width,
            label=lab,
        )
    names = sorted({hr.response.mesh_names[mesh] for hr in results})
    ax.set_xlabel("harmonic order (multiple of the mesh frequency) [-]")
    ax.set_ylabel("contribution to DTE [-]")
    ax.set_title(title or mesh_title("harmonic contributions to the DTE", names), y=TITLE_Y)
    _order_axis(ax, max_order)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return ax


def _mark_operating(a: Axes, operating: OperatingFrequency, fmin: float, fmax: float,
                    first: bool) -> None:
    """The operating mesh frequency f_m (solid) and its harmonics 2 f_m .. 4 f_m
    (dash-dotted) inside ``[fmin, fmax]``; a note on the panel when f_m lies outside."""
    f_m = operating.mesh_frequency
    text = f"operating mesh frequency f_m = {f_m:.4g} Hz"
    if operating.members:
        m = operating.members[0]
        text += f" ({m} {operating.rpm(m):.4g} rpm)"
    if fmin <= f_m <= fmax:
        a.axvline(f_m, color="C3", lw=1.4, label=text if first else None, gid="operating")
    else:
        a.text(0.01 if f_m < fmin else 0.99, 0.04, f"{text}: {'below' if f_m < fmin else 'above'}"
               " the sweep", transform=a.transAxes, fontsize=8, color="C3",
               ha="left" if f_m < fmin else "right")
    h = [k for k in range(2, SWEEP_HARMONICS + 1) if fmin <= k * f_m <= fmax]
    for j, k in enumerate(h):
        a.axvline(k * f_m, color="C3", lw=0.9, ls="-.", gid=f"harmonic_{k}",
                  label=(f"harmonics {h[0]}-{h[-1]} f_m (excitation at the operating speed)"
                         if len(h) > 1 else f"harmonic {k} f_m (excitation at the operating "
                         "speed)")
                  if first and j == 0 else None)


def _speed_axis(a: Axes, operating: OperatingFrequency) -> None:
    """A top x axis with the driver's speed (rpm) at each mesh frequency."""
    m = operating.members[0]
    per_hz = operating.rpm(m, 1.0)
    top = a.secondary_xaxis("top", functions=(lambda f: f * per_hz, lambda n: n / per_hz))
    top.set_xlabel(f"{m} speed [rpm]")


def plot_sweep(
    sweeps: Sequence, labels: Sequence[str], meshes: Sequence[str], title: str = "",
    natural_frequencies: np.ndarray | None = None, fig: Figure | None = None,
    operating: OperatingFrequency | None = None,
) -> Figure:
    """RMS dynamic mesh force (kN, solid) and its alternating part (RMS of the force minus
    its mean, dashed) against mesh frequency (Hz), one panel per mesh.

    Every y axis starts at 0. ``natural_frequencies`` (Hz, the undamped modes of the
    model) are marked as vertical lines where the mesh frequency equals them (first-order
    resonance). ``operating`` marks the operating mesh frequency f_m (solid, with the
    driver's speed in rpm in the legend), its harmonics 2 f_m .. 4 f_m (where one meets
    a natural frequency, that mode resonates at the operating speed) and adds the
    driver's speed (rpm) as a top axis. A panel whose curves equal those of an earlier
    panel to 1e-9 says so (the left and right halves of a symmetric herringbone set carry
    equal forces).
    """
    fig, ax = _panels(fig, len(meshes), 1, (8, 3.2 * len(meshes) + 0.4))
    fmin = min(float(sw.frequencies[0]) for sw in sweeps)
    fmax = max(float(sw.frequencies[-1]) for sw in sweeps)
    fn = np.asarray([] if natural_frequencies is None else natural_frequencies, dtype=float)
    fn = np.unique(np.round(fn[(fn > 0) & (fn >= fmin) & (fn <= fmax)], 6))
    curves: list[np.ndarray] = []
    for k, m in enumerate(meshes):
        a = ax[k, 0]
        for j, f in enumerate(fn):
            a.axvline(f, color="0.55", ls=":", lw=0.8,
                      label="natural frequencies (undamped)" if j == 0 else None)
        if operating is not None:
            _mark_operating(a, operating, fmin, fmax, k == 0)
        y = np.concatenate([sw.rms_force[sw.mesh_names.index(m)] for sw in sweeps])
        for c, (sw, lab) in enumerate(zip(sweeps, labels, strict=True)):
            i = sw.mesh_names.index(m)
            a.plot(sw.frequencies, sw.rms_force[i] / 1e3, color=f"C{c}", lw=1.2,
                   label=f"{lab}: RMS")
            a.plot(sw.frequencies, sw.rms_alternating[i] / 1e3, color=f"C{c}", lw=1, ls="--",
                   label=f"{lab}: alternating RMS (mean removed)")
        same = [meshes[i] for i, c in enumerate(curves)
                if np.allclose(c, y, rtol=1e-9, atol=1e-9 * np.abs(y).max())]
        curves.append(y)
        a.set_ylabel(f"{mesh_title('RMS mesh force', [m])} [kN]")
        if same:
            a.set_title(f"{m}: equal to {same[0]} (symmetric model)", fontsize=9)
        a.set_ylim(bottom=0.0, top=1.08 * float(y.max()) / 1e3)
        a.set_xlim(fmin, fmax)
        a.grid(alpha=0.3)
    if operating is not None and operating.members:
        _speed_axis(ax[0, 0], operating)
    ax[-1, 0].set_xlabel("mesh frequency [Hz]")
    handles, names = ax[0, 0].get_legend_handles_labels()
    fig.legend(handles, names, loc="outside lower center", fontsize=8,
               ncol=2 if len(names) > 3 else len(names))
    fig.suptitle(title)
    return fig
