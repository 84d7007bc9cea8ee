"""Harris maps: loaded transmission error against load for a set of modification variants.

The study file::

    kind = "harris"
    name = "harris_map"
    base = "spur_pair_assembly_errors.toml"

    [set]                                   # on every point (file units)
    "contact.compliance" = "fe2d"

    [[variants]]                            # a label and its gearbox key changes
    label = "C_a 11 um"
    set = {"pinion.modifications.tip_relief_um" = 11.0, "gear.modifications.tip_relief_um" = 11.0}

    [torque]                                # driving torque, N m
    range = [30.0, 600.0]                   # with points, or values = [...]
    points = 20
    design_Nm = 340.0                       # marked on the map (default: the base file's)

    [kpis]
    names = ["te_peak_to_peak_um", "te_order1_um", "te_order2_um"]   # the default

    [execution]
    batch_points = 16

A Harris map is a study (``kind = "harris"`` in the study file, :mod:`pipeline.study.spec`)
whose points are every ``[[variants]]`` entry (a label and its gearbox key changes, any
dotted key of the base file in the file's units) at every torque of ``[torque]``: the
study's two axes ``variant`` x ``operation.torque_Nm``. It runs as any study
(:func:`pipeline.study.execute.run_study`): the points checked first, the FE tables built
once per geometry (modifications and load do not change the geometry, so all variants share
them), batches on the Dask cluster, finished parts kept for ``--resume``.

:func:`harris_map` turns the study table into the map: per variant and torque the KPIs
asked for (by default TE peak-to-peak and the amplitudes of mesh orders 1 and 2, um), the
unit load along the line of action per face width w = T / (r_b b) (N/mm; T the driving
gear's torque, r_b its base radius, b the smaller face width of the main mesh) and, per
variant, the load of its smallest TE peak-to-peak (a parabola through the lowest grid
point and its two neighbours).

The classic result (Harris 1958, "Dynamic loads on the teeth of spur gears", Proc. IMechE
172; the "Harris map"; see also Tavakoli & Houser 1986, J. Mech. Trans. Autom. Des.
108(1) 86-94, on optimum profile modifications): with a linear tip relief on both gears
spanning the double-contact zones, C_a at the tip, and a tooth pair of constant stiffness
k, the two loaded pairs of a double-contact position carry reliefs C_a (1 - t) and C_a t
(t in [0, 1] across the zone), so that

* both pairs loaded (F >= k C_a): delta = (F / k + C_a) / 2 in the double zone, F / k in
  the single zone, peak-to-peak TE |F / k - C_a| / 2;
* F < k C_a: the relieved pair is lifted off where C_a (1 - t) > delta and the TE rises
  to (F / k + C_a) / 2 in the double zone: peak-to-peak again (C_a - F / k) / 2.

The TE peak-to-peak is then a V over the load with its zero where the single-pair
deflection F / k equals the relief: the design load. ``tests/test_harris.py`` checks the
minimum of the pipeline's map against the deflection of its own single pair, and that a
larger relief moves it to a higher load.

Measured (``workflows/benchmarks/bench_harris.py``, the example ``harris_map.toml``: FE 2D,
20 positions, 5 variants x 20 torques, 2 LocalCluster workers, the FE tables in the cache;
the 2 cores shared with other jobs): at load average 4.2, 9.6 s and 11.0 s for two runs
in a row (LocalCluster start and close 1.7 s, the 100 points 6.3-8.7 s at 63-87 ms per
point against 68 ms serially in one process, the figure 0.5-1.4 s, checking every point
0.2 s); at load average 4.9, 14.8 s. The target of 10 s is met only when the two cores
are not shared (a point costs 45-60 ms on an idle core, ``bench_study.py``).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.study.spec import TORQUE_KEY, VARIANT_AXIS, StudySpec

TE_PP = "te_peak_to_peak_um"


@dataclass(frozen=True)
class HarrisMap:
    """A Harris map.

    Attributes
    ----------
    name : the study's name.
    variants : shape (V,), the variant labels in file order.
    torque_Nm : shape (T,), driving gear torques, N m (ascending).
    unit_load_N_per_mm : shape (T,), load along the line of action per face width, N/mm.
    kpis : KPI name -> shape (V, T) values (units in the names; NaN where a point failed).
    design_torque_Nm : the design torque marked on the map, N m (or ``None``).
    newtons_per_mm_per_Nm : w / T, the unit load of 1 N m, N/mm.
    """

    name: str
    variants: tuple[str, ...]
    torque_Nm: np.ndarray
    unit_load_N_per_mm: np.ndarray
    kpis: Mapping[str, np.ndarray]
    design_torque_Nm: float | None
    newtons_per_mm_per_Nm: float

    def minimum_torque_Nm(self, kpi: str = TE_PP) -> np.ndarray:
        """Shape (V,): per variant the torque of the smallest ``kpi`` (N m): the vertex of the
        parabola through the lowest grid point and its neighbours (the grid point itself at
        either end of the range, or when the three points do not bend upwards)."""
        out = np.full(len(self.variants), np.nan)
        x = self.torque_Nm
        for v, y in enumerate(self.kpis[kpi]):
            ok = np.isfinite(y)
            if not ok.any():
                continue
            i = int(np.nanargmin(np.where(ok, y, np.nan)))
            out[v] = x[i]
            if 0 < i < x.size - 1 and ok[i - 1:i + 2].all():
                c = np.polyfit(x[i - 1:i + 2], y[i - 1:i + 2], 2)
                if c[0] > 0:
                    out[v] = float(np.clip(-c[1] / (2 * c[0]), x[i - 1], x[i + 1]))
        return out

    def rows(self) -> list[dict[str, Any]]:
        """One row per variant and torque: ``variant``, ``torque_Nm``,
        ``unit_load_N_per_mm`` and the KPIs (units in the column names)."""
        out = []
        for v, label in enumerate(self.variants):
            for t, torque in enumerate(self.torque_Nm):
                out.append({"variant": label, "torque_Nm": float(torque),
                            "unit_load_N_per_mm": float(self.unit_load_N_per_mm[t]),
                            **{k: float(a[v, t]) for k, a in self.kpis.items()}})
        return out

    def summary(self) -> dict[str, Any]:
        """Per variant the torque (N m) and unit load (N/mm) of its smallest TE
        peak-to-peak, that value (um) and whether it lies at an end of the torque range
        (then the minimum may lie beyond it), with the design torque."""
        out: dict[str, Any] = {"design_torque_Nm": self.design_torque_Nm}
        if TE_PP in self.kpis:
            tmin = self.minimum_torque_Nm()
            out["minimum_te_peak_to_peak"] = {
                label: {"torque_Nm": float(tmin[v]),
                        "unit_load_N_per_mm": float(tmin[v] * self.newtons_per_mm_per_Nm),
                        "te_peak_to_peak_um": float(np.nanmin(self.kpis[TE_PP][v])),
                        "at_range_end": bool(tmin[v] in (self.torque_Nm[0],
                                                         self.torque_Nm[-1]))}
                for v, label in enumerate(self.variants)}
        return out


def newtons_per_mm_per_Nm(spec: StudySpec) -> float:
    """Unit load per N m of driving torque of the base file's main mesh, N/mm:
    1 / (r_b b) with r_b the driving gear's base radius and b the smaller face width."""
    from pipeline.run.chain import mesh_cases
    from pipeline.study.evaluate import point_gearbox

    variant = spec.axes[0].values[0]
    torque = (spec.axes[1].values or spec.axes[1].range)[0]
    box = point_gearbox(spec.point_document({VARIANT_AXIS: variant, TORQUE_KEY: torque}))
    case = mesh_cases(box)[0]
    driver = getattr(case.pair, case.operation.driver)
    # the main mesh's torque per N m of the file's torque (a planetary set splits it)
    per = case.operation.torque / box.operation.torque
    return per / (driver.base_radius * case.pair.face_width) * 1e-3


def harris_map(spec: StudySpec, table: Mapping[str, list]) -> HarrisMap:
    """The map of a finished Harris study's table (columns ``variant``,
    ``operation.torque_Nm``, the KPIs)."""
    labels = tuple(spec.axes[0].values)
    torques = np.array(sorted(set(float(t) for t in table[TORQUE_KEY])))
    kpi_names = [c for c in table if c not in ("point", VARIANT_AXIS, TORQUE_KEY, "error")]
    kpis = {k: np.full((len(labels), torques.size), np.nan) for k in kpi_names}
    col = {lab: i for i, lab in enumerate(labels)}
    for r in range(len(table["point"])):
        v = col[table[VARIANT_AXIS][r]]
        t = int(np.searchsorted(torques, float(table[TORQUE_KEY][r])))
        for k in kpi_names:
            val = table[k][r]
            kpis[k][v, t] = np.nan if val is None else float(val)
    per = newtons_per_mm_per_Nm(spec)
    return HarrisMap(spec.name, labels, torques, torques * per, kpis, spec.design_torque_Nm,
                     per)


def plot_harris_map(hmap: HarrisMap, kpis: tuple[str, ...] | None = None) -> Any:
    """The classic map: one panel per KPI (TE peak-to-peak first) over the driving torque
    (N m; the unit load per face width, N/mm, on the top axis), one curve per variant, the
    design torque marked and each variant's smallest TE peak-to-peak starred (when inside
    the torque range)."""
    from pipeline.study.kpis import kpi_label
    from pipeline.viz.canvas import new_figure

    names = list(kpis or hmap.kpis)
    fig = new_figure((6.4, 2.9 * len(names) + 0.9), "constrained")
    axs = fig.subplots(len(names), 1, squeeze=False, sharex=True)[:, 0]
    tmin = hmap.minimum_torque_Nm() if TE_PP in hmap.kpis else None
    for i, (ax, k) in enumerate(zip(axs, names, strict=True)):
        for v, label in enumerate(hmap.variants):
            ax.plot(hmap.torque_Nm, hmap.kpis[k][v], "o-", ms=3, lw=1.4, color=f"C{v}",
                    label=label)
            inside = tmin is not None and hmap.torque_Nm[0] < tmin[v] < hmap.torque_Nm[-1]
            if k == TE_PP and inside:  # a minimum at a range end may lie beyond it: no star
                y = np.interp(tmin[v], hmap.torque_Nm, hmap.kpis[k][v])
                ax.plot(tmin[v], y, "*", ms=11, color=f"C{v}", mec="k", mew=0.5)
        if hmap.design_torque_Nm is not None:
            ax.axvline(hmap.design_torque_Nm, color="0.3", ls="--", lw=1,
                       label=f"design load {hmap.design_torque_Nm:g} N m" if i == 0 else None)
        ax.set_ylabel(kpi_label(k))
        ax.set_ylim(bottom=0.0)
        ax.grid(alpha=0.3)
    axs[-1].set_xlabel("driving torque T (N m)")
    top = axs[0].secondary_xaxis("top", functions=(
        lambda t: t * hmap.newtons_per_mm_per_Nm, lambda w: w / hmap.newtons_per_mm_per_Nm))
    top.set_xlabel("unit load along the line of action w = T / (r_b b) (N/mm)")
    fig.legend(*axs[0].get_legend_handles_labels(), loc="outside lower center", fontsize=8,
               ncol=min(3, len(hmap.variants) + 1))
    fig.suptitle(f"{hmap.name}: Harris map (loaded static TE; * smallest TE p-p)",
                 fontsize=10)
    return fig


def harris_html(hmap: HarrisMap, figure: str, files: list[str]) -> str:
    """A short self-describing HTML page: the map figure (a file name beside the page),
    the smallest TE peak-to-peak per variant and the files written."""
    from html import escape

    s = hmap.summary()
    rows = "".join(
        f"<tr><td>{escape(lab)}</td><td>{m['torque_Nm']:.4g}</td>"
        f"<td>{m['unit_load_N_per_mm']:.4g}</td><td>{m['te_peak_to_peak_um']:.4g}</td></tr>"
        for lab, m in s.get("minimum_te_peak_to_peak", {}).items())
    design = ("" if hmap.design_torque_Nm is None else
              f"<p>Design load: {hmap.design_torque_Nm:g} N m "
              f"({hmap.design_torque_Nm * hmap.newtons_per_mm_per_Nm:.4g} N/mm).</p>")
    listed = "".join(f"<li>{escape(f)}</li>" for f in files)
    return (f"<!doctype html><html><head><meta charset='utf-8'><title>Harris map "
            f"{escape(hmap.name)}</title></head><body><h1>Harris map: {escape(hmap.name)}"
            f"</h1><p>Loaded static transmission error (along the line of action) of each "
            f"modification variant over the driving torque.</p>{design}"
            f"<img src='{escape(figure)}' style='max-width:100%'>"
            "<h2>Smallest TE peak to peak per variant</h2><table border='1' "
            "cellpadding='4'><tr><th>variant</th><th>torque (N m)</th><th>unit load "
            f"(N/mm)</th><th>TE p-p (um)</th></tr>{rows}</table><h2>Files</h2><ul>{listed}"
            "</ul></body></html>")
