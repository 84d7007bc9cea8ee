"""A study file: a base gearbox file, fixed changes to it and the design axes.

::

    name = "tip_relief"                       # optional label
    base = "spur_pair_assembly_errors.toml"   # gearbox file, relative to the study file

    [set]                                     # the same change on every point (file units)
    "contact.compliance" = "fe2d"

    [[axes]]                                  # one axis per table; keys as in the base file
    keys = ["contact.tip_relief_pinion_um", "contact.tip_relief_gear_um"]  # moved together
    range = [0.0, 30.0]                       # with points = N (grid) or sampled (LHS)
    points = 16
    # values = [0.0, 5.0, 10.0]               # or an explicit list

    [sampling]
    method = "grid"                           # or "latin_hypercube" (ranges only)
    samples = 50                              # latin_hypercube: number of points
    seed = 1

    [kpis]
    names = ["te_peak_to_peak_um", ...]       # default: every KPI the points can give
    speed_range_rpm = [500.0, 6000.0]         # peak dynamic factor over this driver speed range
    speed_points = 40

    [plots]
    tradeoff = ["te_peak_to_peak_um", "mesh_stiffness_mean_N_per_um"]

    [best]
    kpi = "te_peak_to_peak_um"
    goal = "min"                              # or "max"
    mean_over = "operation.torque_Nm"         # optional: the design best on average over
                                              # this axis (a load range), not one point

    [execution]
    batch_points = 16                         # points per task (and per result part file)

Axis keys are dotted paths into the base file, written with their unit suffix as there
(``pinion.face_width_mm``, ``operation.torque_Nm``): values are in the file's units. A
range of two integers samples integers (``pinion.teeth``). Every point is built into a
:class:`~pipeline.config.Gearbox` before any work starts, so an unknown key or a value
out of range is one line naming the key as written and the point's value.

``kind`` names what the file asks for: ``"study"`` (default, above), ``"harris"`` (a Harris
map: ``[[variants]]`` of labelled key changes x a ``[torque]`` range, read here into the
two axes ``variant`` and ``operation.torque_Nm``; :mod:`pipeline.study.harris`) or
``"optimise"`` (:mod:`pipeline.study.optimise`, its own tables). Each kind accepts only its
own tables.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from pipeline.config.schema import unknown
from pipeline.config.toml_file import InputFile, read_input_file
from pipeline.validation import InputError

TOP = ("name", "description", "base", "kind")
KINDS = ("study", "harris", "optimise")
KIND_TABLES = {
    "study": ("set", "axes", "sampling", "kpis", "plots", "best", "execution"),
    "harris": ("set", "variants", "torque", "kpis", "execution"),
    "optimise": ("set", "parameters", "load", "objective", "constraints", "kpis",
                 "optimiser", "execution"),
}
TABLES = KIND_TABLES["study"]
VARIANT_AXIS = "variant"
"""Column name of a Harris map's variant axis (its labels)."""
TORQUE_KEY = "operation.torque_Nm"
AXIS_KEYS = ("keys", "key", "values", "range", "points")
SAMPLING_METHODS = ("grid", "latin_hypercube")


@dataclass(frozen=True)
class Axis:
    """One design axis.

    Attributes
    ----------
    keys : dotted keys of the gearbox file that take the axis value (moved together).
    values : explicit values (file units), or ``None`` when given as a range.
    range : (low, high) in file units, or ``None``.
    points : grid points on the range.
    integer : the range samples integers (both ends written as integers).
    variants : a Harris map's variant axis: ``(label, {dotted key: value})`` per variant
        (file units), its ``values`` being the labels; ``None`` for a key axis.
    """

    keys: tuple[str, ...]
    values: tuple[Any, ...] | None = None
    range: tuple[float, float] | None = None
    points: int = 0
    integer: bool = False
    variants: tuple[tuple[str, Mapping[str, Any]], ...] | None = None

    @property
    def label(self) -> str:
        """The first key: the column name of the axis in the results table."""
        return self.keys[0]


@dataclass(frozen=True)
class StudySpec:
    """A parsed study file.

    Attributes
    ----------
    name : label (``name`` or the file stem).
    path : the study file.
    base_path : the base gearbox file.
    base : the base gearbox file as read (document and SHA-256 of its bytes).
    fixed : dotted key -> value set on every point (file units).
    axes : the design axes.
    method : "grid" or "latin_hypercube".
    samples, seed : Latin hypercube size and random seed.
    kpis : KPI names asked for (empty: all the points can give).
    speed_range_rpm, speed_points : speed range (driver, rpm) and points of the
        peak-dynamic-factor KPI, or ``None``.
    tradeoff : the two KPIs of the trade-off plot (empty: the first two).
    best_kpi, best_goal : the KPI that picks the best point and "min" / "max".
    best_mean_over : an axis label: the best design is the one whose KPI averaged over
        that axis is best (``""``: the best single point).
    batch_points : points per task and per result part file (0: chosen from the size).
    document : the study file as parsed (for the resume check and records).
    kind : "study" or "harris" (the optimiser's file is :class:`~.optimise.OptimiseSpec`).
    design_torque_Nm : a Harris map's design torque (marked on the map), N m.
    """

    name: str
    path: Path
    base_path: Path
    base: InputFile
    fixed: Mapping[str, Any]
    axes: tuple[Axis, ...]
    method: str = "grid"
    samples: int = 0
    seed: int = 0
    kpis: tuple[str, ...] = ()
    speed_range_rpm: tuple[float, float] | None = None
    speed_points: int = 40
    tradeoff: tuple[str, ...] = ()
    best_kpi: str = ""
    best_goal: str = "min"
    best_mean_over: str = ""
    batch_points: int = 0
    document: Mapping[str, Any] = field(default_factory=dict, repr=False)
    kind: str = "study"
    design_torque_Nm: float | None = None

    def point_document(self, values: Mapping[str, Any]) -> dict[str, Any]:
        """The base document with the fixed changes and one point's ``{axis label: value}``."""
        doc = copy.deepcopy(dict(self.base.document))
        for key, v in self.fixed.items():
            set_key(doc, key, v)
        for axis in self.axes:
            if axis.variants is not None:
                for key, v in dict(axis.variants)[values[axis.label]].items():
                    set_key(doc, key, v)
                continue
            for key in axis.keys:
                set_key(doc, key, values[axis.label])
        return doc


def set_key(doc: dict[str, Any], dotted: str, value: Any) -> None:
    """Set ``a.b.c = value`` in a nested document, creating missing tables."""
    *tables, last = dotted.split(".")
    node = doc
    for i, t in enumerate(tables):
        nxt = node.setdefault(t, {})
        if not isinstance(nxt, dict):
            raise InputError(f"{'.'.join(tables[:i + 1])} is a value in the base file, not a "
                             f"table: {dotted!r} cannot be set")
        node = nxt
    node[last] = value


def check_table_keys(table: Mapping[str, Any], allowed: tuple[str, ...], where: str) -> None:
    """``table`` is a table holding only ``allowed`` keys; else one line naming ``where``."""
    if not isinstance(table, Mapping):
        raise InputError(f"{where}: expected a table [{where}]")
    for k in table:
        if k not in allowed:
            raise unknown(k, allowed, f"[{where}] key")


def _flatten(table: Mapping[str, Any], prefix: str = "") -> dict[str, Any]:
    """``{"contact": {"compliance": x}}`` or ``{"contact.compliance": x}`` -> dotted keys."""
    out: dict[str, Any] = {}
    for k, v in table.items():
        if isinstance(v, Mapping):
            out.update(_flatten(v, f"{prefix}{k}."))
        else:
            out[f"{prefix}{k}"] = v
    return out


def number(v: Any, where: str) -> float:
    """``v`` as a float; a non-number is one line naming ``where``."""
    if isinstance(v, bool) or not isinstance(v, int | float):
        raise InputError(f"{where} = {v!r}: expected a number")
    return float(v)


def gearbox_keys(table: Any, where: str) -> list[str]:
    """The dotted gearbox keys a table names by ``key = "..."`` or ``keys = [...]`` (one of
    the two), refused in one line naming ``where`` otherwise."""
    if ("key" in table) == ("keys" in table):
        raise InputError(f"{where}: give the gearbox key(s) as key = \"table.key_unit\" or "
                         "keys = [...]")
    keys = table.get("keys", [table.get("key")])
    if (not isinstance(keys, list) or not keys
            or not all(isinstance(k, str) and k for k in keys)):
        raise InputError(f"{where}.keys = {keys!r}: expected a list of dotted gearbox keys")
    return keys


def _axis(table: Any, i: int) -> Axis:
    where = f"axes[{i}]"
    check_table_keys(table, AXIS_KEYS, where)
    keys = gearbox_keys(table, where)
    if ("values" in table) == ("range" in table):
        raise InputError(f"{where} ({keys[0]}): give either values = [...] or range = [lo, hi]")
    if "values" in table:
        vals = table["values"]
        if not isinstance(vals, list) or not vals:
            raise InputError(f"{where}.values = {vals!r}: expected a non-empty list")
        if "points" in table:
            raise InputError(f"{where}.points applies to a range, not to a list of values")
        return Axis(tuple(keys), values=tuple(vals))
    rng = table["range"]
    if not isinstance(rng, list) or len(rng) != 2:
        raise InputError(f"{where}.range = {rng!r}: expected [low, high]")
    lo, hi = (number(v, f"{where}.range") for v in rng)
    if not lo < hi:
        raise InputError(f"{where}.range = {rng!r}: low must be below high")
    points = table.get("points", 0)
    if isinstance(points, bool) or not isinstance(points, int) or not 0 <= points <= 100_000:
        raise InputError(f"{where}.points = {points!r}: expected an integer in [2, 100000]")
    integer = all(isinstance(v, int) and not isinstance(v, bool) for v in rng)
    return Axis(tuple(keys), range=(lo, hi), points=points, integer=integer)


def read_header(path: str | Path) -> tuple[dict[str, Any], Path, str, Path, InputFile]:
    """The parts every kind of study file shares: its document, path and kind, the base
    file's path and the base file as read (top-level keys and tables checked by kind)."""
    src = read_input_file(path)
    doc, path = src.document, Path(path)
    kind = doc.get("kind", "study")
    if kind not in KINDS:
        raise unknown(str(kind), KINDS, "kind")
    tables = KIND_TABLES[kind]
    for k, v in doc.items():
        if k not in TOP + tables:
            where = "study file key or table" + (f" of kind = \"{kind}\"" if kind != "study"
                                                 else "")
            raise unknown(k, TOP + tables, where)
        if k in TOP and not isinstance(v, str):
            raise InputError(f"{k} = {v!r}: expected a string in quotes")
    if "base" not in doc:
        raise InputError(f"{path}: a study file needs base = \"<gearbox file>\"")
    base_path = (path.parent / doc["base"]).resolve()
    return doc, path, kind, base_path, read_input_file(base_path)


def fixed_changes(doc: Mapping[str, Any]) -> dict[str, Any]:
    """The ``[set]`` table as dotted keys."""
    fixed_t = doc.get("set", {})
    check_table_keys(fixed_t, tuple(fixed_t) if isinstance(fixed_t, Mapping) else (), "set")
    return _flatten(fixed_t)


def read_study_file(path: str | Path) -> Any:
    """A study file of any kind: :class:`StudySpec` (``"study"``, ``"harris"``) or
    :class:`~pipeline.study.optimise.OptimiseSpec` (``"optimise"``)."""
    kind = read_input_file(path).document.get("kind", "study")
    if kind == "optimise":
        from pipeline.study.optimise import optimise_from_file

        return optimise_from_file(path)
    return study_from_file(path)


def study_from_file(path: str | Path) -> StudySpec:
    """Read and check a study file of kind ``"study"`` or ``"harris"`` (module docstring);
    the base file is read too."""
    doc, path, kind, base_path, base = read_header(path)
    if kind == "optimise":
        raise InputError(f"{path}: kind = \"optimise\" is an optimisation, not a study of "
                         "points (pipeline.study.optimise.optimise_from_file reads it)")
    if kind == "harris":
        return _harris_spec(doc, path, base_path, base)
    axes_t = doc.get("axes", [])
    if not isinstance(axes_t, list) or not axes_t:
        raise InputError(f"{path}: a study needs at least one [[axes]] table")
    axes = tuple(_axis(t, i) for i, t in enumerate(axes_t))
    labels = [k for a in axes for k in a.keys]
    dup = {k for k in labels if labels.count(k) > 1}
    if dup:
        raise InputError(f"axes: {sorted(dup)[0]!r} is on more than one axis")
    fixed = fixed_changes(doc)
    both = set(fixed) & set(labels)
    if both:
        raise InputError(f"set: {sorted(both)[0]!r} is also an axis; give it in one place")
    sampling = doc.get("sampling", {})
    check_table_keys(sampling, ("method", "samples", "seed"), "sampling")
    method = sampling.get("method", "grid")
    if method not in SAMPLING_METHODS:
        raise unknown(str(method), SAMPLING_METHODS, "sampling.method")
    samples, seed = sampling.get("samples", 0), sampling.get("seed", 0)
    # the number of samples is bounded with the study's size (pipeline.study.size)
    for name, v, lo, hi in (("samples", samples, 1 if method != "grid" else 0, None),
                            ("seed", seed, 0, 10**6)):
        if (isinstance(v, bool) or not isinstance(v, int) or v < lo
                or (hi is not None and v > hi)):
            rng = f"in [{lo}, {hi}]" if hi is not None else f">= {lo}"
            raise InputError(f"sampling.{name} = {v!r}: expected an integer {rng}")
    if method == "grid":
        ignored = [k for k in ("samples", "seed") if k in sampling]
        if ignored:
            raise InputError(f"sampling.{ignored[0]} applies to method = "
                             "\"latin_hypercube\", not to a grid (its points are the axes')")
        for i, a in enumerate(axes):
            if a.range is not None and a.points < 2:
                raise InputError(f"axes[{i}] ({a.label}): a grid over a range needs "
                                 "points >= 2")
    else:
        for i, a in enumerate(axes):
            if a.range is None:
                raise InputError(f"axes[{i}] ({a.label}): a Latin hypercube samples ranges; "
                                 "give range = [lo, hi] instead of values")
    return StudySpec(name=str(doc.get("name", path.stem)), path=path, base_path=base_path,
                     base=base, fixed=dict(fixed), axes=axes, method=method, samples=samples,
                     seed=seed, document=doc, **output_tables(doc))


HARRIS_KPIS = ("te_peak_to_peak_um", "te_order1_um", "te_order2_um")
"""The KPIs of a Harris map unless ``[kpis] names`` says otherwise."""


def _variant(table: Any, i: int) -> tuple[str, dict[str, Any]]:
    where = f"variants[{i}]"
    check_table_keys(table, ("label", "set"), where)
    label = table.get("label")
    if not isinstance(label, str) or not label.strip():
        raise InputError(f"{where}.label = {label!r}: expected a non-empty string in quotes")
    changes = table.get("set", {})
    if not isinstance(changes, Mapping):
        raise InputError(f"{where}.set = {changes!r}: expected a table of gearbox keys")
    changes = _flatten(changes)
    if TORQUE_KEY in changes:
        raise InputError(f"{where}.set: {TORQUE_KEY!r} is the map's [torque] axis; a variant "
                         "changes the gears, not the load")
    return label, changes


def _torque_axis(table: Any) -> tuple[Axis, float | None]:
    check_table_keys(table, ("range", "points", "values", "design_Nm"), "torque")
    if not table:
        raise InputError("a Harris map needs a [torque] table: range = [low, high] (N m) and "
                         "points, or values = [...]")
    sub = {k: v for k, v in table.items() if k != "design_Nm"}
    axis = _axis({"key": TORQUE_KEY, **sub}, 0)
    vals = axis.values if axis.values is not None else axis.range
    for v in vals:
        if number(v, "torque") <= 0.0:
            raise InputError(f"torque: {v!r} N m: expected torques > 0 N m")
    if axis.range is not None and axis.points < 2:
        raise InputError("torque.points: a Harris map over a range needs points >= 2")
    design = table.get("design_Nm")
    if design is not None and number(design, "torque.design_Nm") <= 0.0:
        raise InputError(f"torque.design_Nm = {design!r} N m: expected > 0 N m")
    return Axis(axis.keys, values=axis.values, range=axis.range, points=axis.points), design


def _harris_spec(doc: dict[str, Any], path: Path, base_path: Path, base: InputFile
                 ) -> StudySpec:
    """A Harris map's file: ``[[variants]]`` x ``[torque]`` as the study's two axes."""
    vt = doc.get("variants", [])
    if not isinstance(vt, list) or not vt:
        raise InputError(f"{path}: a Harris map needs at least one [[variants]] table "
                         "(label = \"...\" and its set = {{gearbox key = value}})")
    variants = tuple(_variant(t, i) for i, t in enumerate(vt))
    labels = [v[0] for v in variants]
    dup = [x for x in labels if labels.count(x) > 1]
    if dup:
        raise InputError(f"variants: label {dup[0]!r} is given more than once")
    fixed = fixed_changes(doc)
    if TORQUE_KEY in fixed:
        raise InputError(f"set: {TORQUE_KEY!r} is the map's [torque] axis; give it there")
    torque, design = _torque_axis(doc.get("torque", {}))
    if design is None:
        op = base.document.get("operation", {})
        design = op.get("torque_Nm") if isinstance(op, Mapping) else None
    outputs = output_tables(doc)
    outputs["kpis"] = outputs["kpis"] or HARRIS_KPIS
    axes = (Axis((VARIANT_AXIS,), values=tuple(labels), variants=variants), torque)
    return StudySpec(name=str(doc.get("name", path.stem)), path=path, base_path=base_path,
                     base=base, fixed=fixed, axes=axes, document=doc, kind="harris",
                     design_torque_Nm=None if design is None else float(design), **outputs)


def output_tables(doc: Mapping[str, Any]) -> dict[str, Any]:
    """The [kpis], [plots], [best] and [execution] tables (those present)."""
    out: dict[str, Any] = {}
    kp = doc.get("kpis", {})
    check_table_keys(kp, ("names", "speed_range_rpm", "speed_points"), "kpis")
    names = kp.get("names", [])
    if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
        raise InputError(f"kpis.names = {names!r}: expected a list of KPI names")
    out["kpis"] = tuple(names)
    if "speed_range_rpm" in kp:
        rng = kp["speed_range_rpm"]
        if not isinstance(rng, list) or len(rng) != 2:
            raise InputError(f"kpis.speed_range_rpm = {rng!r}: expected [low, high] in rpm")
        lo, hi = (number(v, "kpis.speed_range_rpm") for v in rng)
        if not 0 < lo < hi:
            raise InputError(f"kpis.speed_range_rpm = {rng!r} rpm: expected 0 < low < high")
        out["speed_range_rpm"] = (lo, hi)
    sp = kp.get("speed_points", 40)
    if isinstance(sp, bool) or not isinstance(sp, int) or not 2 <= sp <= 100_000:
        raise InputError(f"kpis.speed_points = {sp!r}: expected an integer in [2, 100000]")
    out["speed_points"] = sp
    pl = doc.get("plots", {})
    check_table_keys(pl, ("tradeoff",), "plots")
    trade = pl.get("tradeoff", [])
    if not isinstance(trade, list) or len(trade) not in (0, 2):
        raise InputError(f"plots.tradeoff = {trade!r}: expected two KPI names")
    out["tradeoff"] = tuple(trade)
    best = doc.get("best", {})
    check_table_keys(best, ("kpi", "goal", "mean_over"), "best")
    out["best_kpi"] = str(best.get("kpi", ""))
    if "mean_over" in best:
        out["best_mean_over"] = str(best["mean_over"])
    goal = best.get("goal", "min")
    if goal not in ("min", "max"):
        raise unknown(str(goal), ("min", "max"), "best.goal")
    out["best_goal"] = goal
    ex = doc.get("execution", {})
    check_table_keys(ex, ("batch_points",), "execution")
    bp = ex.get("batch_points", 0)
    if isinstance(bp, bool) or not isinstance(bp, int) or not 0 <= bp <= 100_000:
        raise InputError(f"execution.batch_points = {bp!r}: expected an integer in [0, 100000] "
                         "(0: chosen from the study size)")
    out["batch_points"] = bp
    return out
