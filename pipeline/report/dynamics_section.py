"""The dynamics sections of a mesh report, from the run's dynamics summary
(:meth:`pipeline.run.dynamics.DynamicsStages.summary`).

Two sections:

* ``dynamics`` - the operating point (mesh frequency in Hz, the members' speeds in rpm),
  the sweep range (Hz and rpm, default or given) and the natural frequencies that matter
  at the operating point: every elastic mode up to max(10 f_m, top of the sweep), the cut
  stated, rigid-body modes counted but not listed;
* ``dynamics_meshes`` - the mesh forces of this report's meshes only (a planetary set's
  sun-planet report: the sun meshes; herringbone: both halves), one column per planet,
  and planets whose every value agrees to :data:`SAME_RTOL` share one column ("planets
  1, 3"; "every planet (1-4)") so that no block of rows repeats per planet.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

from pipeline.dynamics.mesh_names import planet_meshes
from pipeline.report.content import quantity
from pipeline.report.model import Figure, Quantity, Section

SAME_RTOL = 1e-4
"""Planets share a column when each of their values agrees to this relative tolerance
(the report prints 4 significant digits; sequentially phased planets give forces that are
time-shifted copies, equal up to the sampling of the steady period)."""

_HALF = {"": "", "L": "half L: ", "R": "half R: "}


def _mesh_values(summary: Mapping[str, Any], name: str, driver: str | None,
                 rpm_per_hz: float) -> list[float]:
    op = summary["response_at_operating_speed"]["meshes"][name]
    sw = summary["sweep"]
    f = sw["max_dynamic_factor_at_Hz"][name]
    values = [op["dynamic_factor"], op["max_elastic_force_N"] * 1e-3,
              sw["max_dynamic_factor"][name],
              f]
    if driver is not None:
        values.append(f * rpm_per_hz)
    return values


def _same(a: Sequence[float], b: Sequence[float]) -> bool:
    return all(abs(x - y) <= SAME_RTOL * max(abs(x), abs(y)) for x, y in zip(a, b, strict=True))


def _groups(columns: dict[int, list[float]]) -> list[list[int]]:
    """Planets grouped by equal values (first planet of a group first)."""
    groups: list[list[int]] = []
    for p, v in columns.items():
        g = next((g for g in groups if _same(columns[g[0]], v)), None)
        if g is None:
            groups.append([p])
        else:
            g.append(p)
    return groups


def _heading(group: list[int], planets: int) -> str:
    if planets == 1:
        return "value"
    if len(group) == planets:
        return f"every planet (1-{planets})"
    return ("planet " if len(group) == 1 else "planets ") + ", ".join(map(str, group))


def dynamics_meshes_section(summary: Mapping[str, Any], mesh: str,
                            figures: Sequence[Figure] = ()) -> Section:
    """Dynamic factor and largest force at the operating speed, largest dynamic factor
    over the sweep and where (Hz, rpm), for the meshes of report ``mesh`` (module
    docstring)."""
    op = summary["operating_point"]
    speeds = op["speeds_rpm"]
    driver = next(iter(speeds), None)
    rpm_per_hz = speeds[driver] / op["mesh_frequency_Hz"] if driver else 0.0
    names = list(summary["response_at_operating_speed"]["meshes"])
    by_half = planet_meshes(names, mesh)
    planets = sorted({p for d in by_half.values() for p in d})
    per_planet = {p: [v for half in sorted(by_half)
                      for v in _mesh_values(summary, by_half[half][p], driver, rpm_per_hz)]
                  for p in planets}
    groups = _groups(per_planet)
    sw = summary["sweep"]
    span = f"{sw['f_min_Hz']:.4g}-{sw['f_max_Hz']:.4g} Hz"
    rows: list[Quantity] = []
    for half in sorted(by_half):
        h = _HALF[half]
        key = f"half_{half}_" if half else ""
        vals = [_mesh_values(summary, by_half[half][g[0]], driver, rpm_per_hz)
                for g in groups]
        spec = [("dynamic_factor", "dynamic factor at the operating speed (max elastic mesh "
                 "force k (delta - e) / mean mesh force)", "-"),
                ("max_elastic_force", "largest elastic mesh force k (delta - e) at the "
                 "operating speed", "kN"),
                ("sweep_max_dynamic_factor", f"largest dynamic factor over the sweep ({span}; "
                 "max elastic / mean mesh force)",
                 "-"),
                ("sweep_max_at", "at mesh frequency", "Hz")]
        if driver is not None:
            spec.append(("sweep_max_at_speed", f"at {driver} speed", "rpm"))
        for j, (k, label, unit) in enumerate(spec):
            rows.append(quantity(key + k, h + label, unit, *(v[j] for v in vals)))
    notes = []
    if len(planets) > 1:
        notes.append(f"Columns: planets whose values all agree to {SAME_RTOL:g} (relative) "
                     "share one; sweep.csv and summary.json give every mesh of the model.")
    return Section("dynamics_meshes", "Dynamic mesh forces", tuple(rows),
                   columns=tuple(_heading(g, len(planets)) for g in groups),
                   figures=tuple(figures), notes=tuple(notes))


def _mode_rows(modes: Sequence[Mapping[str, Any]]) -> list[Quantity]:
    """One row per listed frequency; repeated frequencies (to 1e-6) share a row."""
    rows: list[Quantity] = []
    i = 0
    while i < len(modes):
        j = i + 1
        f = modes[i]["frequency_Hz"]
        while j < len(modes) and abs(modes[j]["frequency_Hz"] - f) <= 1e-6 * f:
            j += 1
        ks = [m["mode"] for m in modes[i:j]]
        kind = modes[i]["kind"]
        label = (f"mode {ks[0]}" if len(ks) == 1 else f"modes {', '.join(map(str, ks))} "
                 "(repeated)") + (f", {kind}" if kind else "")
        rows.append(quantity(f"natural_frequency_mode_{ks[0]}", label, "Hz", f))
        i = j
    return rows


def dynamics_section(summary: Mapping[str, Any]) -> Section:
    """Operating mesh frequency and speeds, sweep range, natural frequencies that matter
    (module docstring)."""
    op = summary["operating_point"]
    f_m = op["mesh_frequency_Hz"]
    speeds = op["speeds_rpm"]
    sw = summary["sweep"]
    rows = [quantity("excitation", "mesh excitation of the dynamic model", "",
                     summary["excitation"]),
            quantity("operating_mesh_frequency", "operating mesh frequency f_m", "Hz", f_m)]
    for member, n in speeds.items():
        rows.append(quantity(f"speed_{member}", f"{member} speed at f_m", "rpm", n))
    rows.append(quantity("sweep_range", "sweep range", "",
                         "as given in [dynamics.sweep] (an end left out: the default's)"
                         if sw["range"] == "given" else
                         ("default: f_m / 4 to max(4 f_m, 1.25 f_n*), f_n* the highest "
                          "natural frequency up to 10 f_m (else the lowest)")))
    for end, key in (("lowest", "f_min_Hz"), ("highest", "f_max_Hz")):
        rows.append(quantity(f"sweep_{end}", f"sweep: {end} mesh frequency", "Hz", sw[key]))
        for member, n in speeds.items():
            rows.append(quantity(f"sweep_{end}_{member}", f"sweep: {member} speed at the "
                                 f"{end} mesh frequency", "rpm", n * sw[key] / f_m))
    rows.append(quantity("model_size", "dynamic model", "",
                         f"{summary['coordinates']} coordinates, {summary['independent_dofs']} "
                         "independent DOF (one mode each)"))
    cut = summary["natural_frequency_cut_Hz"]
    rows.append(quantity("natural_frequency_cut", "natural frequencies listed up to "
                         "max(10 f_m, highest mesh frequency of the sweep)", "Hz", cut))
    listed = summary["modes_listed"]
    mode_rows = _mode_rows(listed)
    rows += mode_rows
    rows.append(quantity("elastic_modes_above_cut", "elastic modes above that (in modes.csv)",
                         "-", summary["elastic_modes_above_cut"]))
    rows.append(quantity("rigid_body_modes", "rigid-body modes (0 Hz, not listed)", "-",
                         summary["rigid_body_modes"]))
    notes = []
    if not sw["f_min_Hz"] <= f_m <= sw["f_max_Hz"]:
        notes.append(f"The sweep ({sw['f_min_Hz']:.4g}-{sw['f_max_Hz']:.4g} Hz, as given) "
                     f"leaves out the operating mesh frequency {f_m:.4g} Hz.")
    if listed:
        ratios = ", ".join(f"{r.values[0] / f_m:.3g}" for r in mode_rows)
        notes.append(f"f_n / f_m of the listed frequencies: {ratios}. A mode whose f_n / f_m "
                     "is near a whole number h resonates with mesh harmonic h at the "
                     "operating speed; sweep.png marks f_m, its harmonics and the natural "
                     "frequencies.")
    else:
        notes.append(f"No elastic mode below {cut:.4g} Hz: mesh harmonics 1-10 at the "
                     "operating speed excite no resonance.")
    return Section("dynamics", "Dynamics: operating point and natural frequencies",
                   tuple(rows), notes=tuple(notes))
