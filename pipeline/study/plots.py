"""Figures of a study: one-at-a-time sensitivity and the trade-off of two KPIs."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from pipeline.config.units import key_label
from pipeline.study.kpis import kpi_label
from pipeline.study.spec import StudySpec
from pipeline.viz.canvas import new_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure


def _numeric(col: list[Any]) -> bool:
    return all(isinstance(v, int | float) and not isinstance(v, bool) for v in col)


def reference_values(spec: StudySpec, table: dict[str, list]) -> dict[str, Any]:
    """Per axis the grid value nearest the base file's value (the middle one if the base
    file does not give it): the point the one-at-a-time lines pass through."""
    from pipeline.study.points import axis_values

    ref = {}
    for a in spec.axes:
        vals = axis_values(a)
        node: Any = spec.base.document
        for part in a.label.split("."):
            node = node.get(part) if isinstance(node, dict) else None
        if _numeric(vals) and isinstance(node, int | float):
            ref[a.label] = min(vals, key=lambda v: abs(v - node))
        else:
            ref[a.label] = node if node in vals else vals[len(vals) // 2]
    return ref


def plot_sensitivity(spec: StudySpec, table: dict[str, list], kpis: list[str]) -> Figure:
    """KPIs (rows) against each axis (columns). A grid: one-at-a-time lines through the
    reference point (:func:`reference_values`); a Latin hypercube: every point."""
    axes_l = spec.axes
    fig = new_figure((3.6 * len(axes_l) + 0.8, 2.3 * len(kpis) + 0.6), "constrained")
    axs = fig.subplots(len(kpis), len(axes_l), squeeze=False)
    ref = reference_values(spec, table) if spec.method == "grid" else None
    n = len(table["point"])
    for j, a in enumerate(axes_l):
        x = np.array(table[a.label], dtype=object)
        if ref is not None:
            mask = np.array([all(table[b.label][i] == ref[b.label] for b in axes_l
                                 if b is not a) for i in range(n)])
        else:
            mask = np.ones(n, dtype=bool)
        for i, k in enumerate(kpis):
            ax = axs[i, j]
            y = np.array(table[k], dtype=float)
            xs, ys = x[mask], y[mask]
            if _numeric(list(xs)):
                order = np.argsort(xs.astype(float))
                ax.plot(xs.astype(float)[order], ys[order], "o-" if ref else "o", ms=3)
            else:
                ax.plot(range(len(xs)), ys, "o")
                ax.set_xticks(range(len(xs)), [str(v) for v in xs])
            if i == len(kpis) - 1:
                ax.set_xlabel(key_label(a.label) + _more(a.keys), fontsize=8)
            # every panel: the columns have their own y scales
            ax.set_ylabel(kpi_label(k), fontsize=8)
            ax.grid(alpha=0.3)
    title = "one-at-a-time sensitivity" if ref is not None else "sensitivity (all points)"
    if ref is not None:
        title += " through " + ", ".join(f"{k.rsplit('.', 1)[-1]} = {v:g}" if isinstance(
            v, int | float) else f"{k} = {v}" for k, v in ref.items())
    fig.suptitle(f"{spec.name}: {title}", fontsize=9)
    return fig


def _more(keys: tuple[str, ...]) -> str:
    return f" (+{len(keys) - 1} tied)" if len(keys) > 1 else ""


def plot_tradeoff(table: dict[str, list], kx: str, ky: str, best: int | None,
                  title: str) -> Figure:
    """KPI ``ky`` against ``kx`` over all points, the Pareto front (both minimised) and the
    best point."""
    x, y = np.array(table[kx], dtype=float), np.array(table[ky], dtype=float)
    fig = new_figure((5.5, 4.2), "constrained")
    ax = fig.subplots()
    ax.plot(x, y, "o", ms=4, alpha=0.6, label="design points")
    ok = np.flatnonzero(np.isfinite(x) & np.isfinite(y))
    front = [i for i in ok if not np.any((x[ok] <= x[i]) & (y[ok] <= y[i])
                                         & ((x[ok] < x[i]) | (y[ok] < y[i])))]
    front = sorted(front, key=lambda i: x[i])
    ax.plot(x[front], y[front], "-", color="C1", label="Pareto front (both minimised)")
    if best is not None:
        ax.plot(x[best], y[best], "*", ms=14, color="C3", label=f"best point ({best})")
    ax.set_xlabel(kpi_label(kx))
    ax.set_ylabel(kpi_label(ky))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    ax.set_title(title, fontsize=9)
    return fig
