"""Optimised flank modifications: gearbox keys within bounds minimising a KPI over a load range.

The study file (``kind = "optimise"``)::

    kind = "optimise"
    name = "relief_over_load"
    base = "spur_pair_assembly_errors.toml"

    [set]                                       # on every evaluation (file units)
    "contact.tip_relief_length_pinion_mm" = 6.2

    [[parameters]]                              # dotted gearbox keys, moved together
    keys = ["contact.tip_relief_pinion_um", "contact.tip_relief_gear_um"]
    bounds = [0.0, 30.0]                        # file units

    [load]                                      # the torques (N m, driving gear) ...
    torques_Nm = [170.0, 255.0, 340.0, 425.0]
    weights = [0.1, 0.3, 0.4, 0.2]              # ... and their duty-cycle weights (default equal)

    [objective]
    kpi = "te_peak_to_peak_um"                  # any KPI of pipeline.study.kpis

    [[constraints]]                             # at every torque of [load]
    kpi = "contact_pressure_max_MPa"
    max = 1500.0                                # or min = ...

    [optimiser]
    method = "differential_evolution"           # scipy.optimize
    popsize = 6                                 # population = popsize x parameters
    maxiter = 20
    tol = 0.01
    seed = 1

The objective is the weighted mean J(x) = sum_i w_i K(x, T_i) / sum_i w_i of the KPI over
the torques T_i. Constraints are met at every torque; the optimiser minimises the penalised
f(x) = J(x) + 1000 max(1, |J(x)|) v(x), v the sum over constraints and torques of the
relative violations max(0, (K - limit) / |limit|) (``max``) or max(0, (limit - K) / |limit|)
(``min``; the limit itself when it is 0), and the reported optimum is the evaluation of
smallest J among those that meet every constraint (the smallest f when none does, flagged).

Why differential evolution (:func:`scipy.optimize.differential_evolution`): TE
peak-to-peak over relief parameters is a V with kinks (contact lost and regained) and
plateaus, where gradient methods stall; DE needs no gradient, respects box bounds and
evaluates a whole population at once, here as one call (``vectorized=True``) whose
population x torques points run as batches on the Dask cluster (the FE tables built once per
geometry and shipped to the workers, as in a study). No polishing step: a gradient polish of
a kinked objective would spend evaluations for nothing.

Every bound is checked at entry by building the gearbox with the parameter at that bound
(the others at their midpoints), so a bound outside a key's allowed range is one line naming
the parameter, the key and the gearbox file's own message - for every key the gearbox file
knows, now or later.

Measured (``workflows/benchmarks/bench_optimise.py``, the example
``tip_relief_optimise.toml``: 4 parameters x 5 torques, FE 2D, 20 positions, 20 designs per
generation, 10 generations = 220 evaluations = 1100 points, 2 LocalCluster workers; the 2
cores shared with other jobs): 53.5 s at load average 3.5 (46 ms per point, 52 ms
serially in one process; LocalCluster start 2.6 s), 127 s at load average 6.7 (111 ms per
point). ``gearpipe study`` on the same file: 59.2 s for the optimisation, the optimum's
``gearpipe run`` after it. Nearly all of a point's time is the loaded contact solve
(``pipeline.contact.ltca``: 95 % in a profile). The record of the run reached 1.51 um
(3 % above the final 1.468 um) after 100 evaluations.
"""

from __future__ import annotations

import copy
import math
import time
import uuid
import warnings
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.config.schema import unknown
from pipeline.config.toml_file import InputFile
from pipeline.study.spec import (
    TORQUE_KEY,
    check_table_keys,
    fixed_changes,
    gearbox_keys,
    number,
    read_header,
    set_key,
)
from pipeline.validation import InputError, PhysicsWarning

PENALTY = 1000.0
"""Weight of the relative constraint violation in the penalised objective (module
docstring)."""

METHODS = ("differential_evolution",)


@dataclass(frozen=True)
class Parameter:
    """One parameter: gearbox ``keys`` moved together (dotted, file units) within
    [``low``, ``high``]."""

    keys: tuple[str, ...]
    low: float
    high: float

    @property
    def label(self) -> str:
        """The first key: the parameter's column in the records."""
        return self.keys[0]


@dataclass(frozen=True)
class Constraint:
    """``kpi`` at most (``sense = "max"``) or at least (``"min"``) ``limit`` (the KPI's
    unit) at every torque."""

    kpi: str
    limit: float
    sense: str

    def violation(self, value: float) -> float:
        """Relative violation (0 when met; NaN values count as violated by 1)."""
        if not math.isfinite(value):
            return 1.0
        gap = value - self.limit if self.sense == "max" else self.limit - value
        return max(0.0, gap) / (abs(self.limit) or 1.0)


@dataclass(frozen=True)
class OptimiseSpec:
    """A parsed optimisation file (module docstring).

    Attributes
    ----------
    name, path, base_path, base : label, the file, the base gearbox file and it as read.
    fixed : dotted key -> value on every evaluation (file units).
    parameters : the parameters with their bounds.
    torques_Nm : shape (T,), driving gear torques of the load cases, N m.
    weights : shape (T,), their weights, normalised to sum 1.
    objective : the KPI whose weighted mean over the torques is minimised.
    constraints : the constraints, met at every torque.
    speed_range_rpm, speed_points : the dynamic KPIs' speed range (rpm), or ``None``.
    method, popsize, maxiter, tol, seed : the optimiser and its settings.
    batch_points : points per task (0: chosen from the population).
    document : the file as parsed.
    """

    name: str
    path: Path
    base_path: Path
    base: InputFile
    fixed: Mapping[str, Any]
    parameters: tuple[Parameter, ...]
    torques_Nm: tuple[float, ...]
    weights: tuple[float, ...]
    objective: str
    constraints: tuple[Constraint, ...] = ()
    speed_range_rpm: tuple[float, float] | None = None
    speed_points: int = 40
    method: str = "differential_evolution"
    popsize: int = 6
    maxiter: int = 20
    tol: float = 0.01
    seed: int = 0
    batch_points: int = 0
    document: Mapping[str, Any] = field(default_factory=dict, repr=False)
    kind: str = "optimise"

    @property
    def kpi_names(self) -> tuple[str, ...]:
        """The objective's KPI and the constraints', each once."""
        return tuple(dict.fromkeys((self.objective, *(c.kpi for c in self.constraints))))

    def gearbox_document(self, x: Mapping[str, float]) -> dict[str, Any]:
        """The base document with ``[set]`` and the parameters ``{label: value}`` (file
        units); the torque is the base file's."""
        doc = copy.deepcopy(dict(self.base.document))
        for key, v in self.fixed.items():
            set_key(doc, key, v)
        for p in self.parameters:
            for key in p.keys:
                set_key(doc, key, float(x[p.label]))
        return doc

    def point_document(self, x: Mapping[str, float], torque_Nm: float) -> dict[str, Any]:
        """:meth:`gearbox_document` at the driving torque ``torque_Nm`` (N m)."""
        doc = self.gearbox_document(x)
        set_key(doc, TORQUE_KEY, float(torque_Nm))
        return doc

    def values(self, x: np.ndarray) -> dict[str, float]:
        """``{parameter label: value}`` of a parameter vector (file units)."""
        return {p.label: float(v) for p, v in zip(self.parameters, x, strict=True)}


def _positive_int(v: Any, where: str, lo: int, hi: int) -> int:
    if isinstance(v, bool) or not isinstance(v, int) or not lo <= v <= hi:
        raise InputError(f"{where} = {v!r}: expected an integer in [{lo}, {hi}]")
    return v


def _parameter(table: Any, i: int) -> Parameter:
    where = f"parameters[{i}]"
    check_table_keys(table, ("keys", "key", "bounds"), where)
    keys = gearbox_keys(table, where)
    b = table.get("bounds")
    if not isinstance(b, list) or len(b) != 2:
        raise InputError(f"{where}.bounds = {b!r} ({keys[0]}): expected [low, high] in the "
                         "key's unit")
    lo, hi = (number(v, f"{where}.bounds") for v in b)
    if not lo < hi:
        raise InputError(f"{where}.bounds = {b!r} ({keys[0]}): low must be below high")
    if TORQUE_KEY in keys:
        raise InputError(f"{where}: {TORQUE_KEY!r} is the load, given in [load]")
    return Parameter(tuple(keys), lo, hi)


def _load(table: Any) -> tuple[tuple[float, ...], tuple[float, ...]]:
    check_table_keys(table, ("torques_Nm", "weights"), "load")
    t = table.get("torques_Nm") if isinstance(table, Mapping) else None
    if not isinstance(t, list) or not t:
        raise InputError(f"load.torques_Nm = {t!r}: expected a list of driving torques in N m")
    torques = tuple(number(v, "load.torques_Nm") for v in t)
    if min(torques) <= 0.0:
        raise InputError(f"load.torques_Nm = {t!r} N m: expected torques > 0 N m")
    if len(set(torques)) != len(torques):
        raise InputError(f"load.torques_Nm = {t!r}: a torque is given twice; weight it instead")
    w = table.get("weights", [1.0] * len(torques))
    if not isinstance(w, list) or len(w) != len(torques):
        raise InputError(f"load.weights = {w!r}: expected {len(torques)} weights, one per "
                         "torque")
    weights = tuple(number(v, "load.weights") for v in w)
    if min(weights) < 0.0 or sum(weights) <= 0.0:
        raise InputError(f"load.weights = {w!r}: expected weights >= 0 with a positive sum")
    total = sum(weights)
    return torques, tuple(v / total for v in weights)


def _constraint(table: Any, i: int, names: list[str]) -> Constraint:
    where = f"constraints[{i}]"
    check_table_keys(table, ("kpi", "max", "min"), where)
    kpi = table.get("kpi")
    if kpi not in names:
        raise unknown(str(kpi), names, f"{where}.kpi: KPI")
    if ("max" in table) == ("min" in table):
        raise InputError(f"{where} ({kpi}): give either max = ... or min = ...")
    sense = "max" if "max" in table else "min"
    return Constraint(kpi, number(table[sense], f"{where}.{sense}"), sense)


def _optimiser(table: Any) -> dict[str, Any]:
    check_table_keys(table, ("method", "popsize", "maxiter", "tol", "seed"), "optimiser")
    method = table.get("method", "differential_evolution")
    if method not in METHODS:
        raise unknown(str(method), METHODS, "optimiser.method")
    tol = number(table.get("tol", 0.01), "optimiser.tol")
    if not 0.0 < tol < 1.0:
        raise InputError(f"optimiser.tol = {tol!r}: expected a relative tolerance in (0, 1)")
    return {"method": method, "tol": tol,
            "popsize": _positive_int(table.get("popsize", 6), "optimiser.popsize", 2, 1000),
            "maxiter": _positive_int(table.get("maxiter", 20), "optimiser.maxiter", 1, 10_000),
            "seed": _positive_int(table.get("seed", 0), "optimiser.seed", 0, 10**6)}


def optimise_from_file(path: str | Path) -> OptimiseSpec:
    """Read and check an optimisation file (module docstring): every table, then every
    parameter bound by building the gearbox there (:func:`check_bounds`).

    Raises :class:`InputError` (one line naming the key) for the first thing wrong.
    """
    from pipeline.study.kpis import KPI_BY_NAME, select_kpis
    from pipeline.study.spec import output_tables

    doc, path, kind, base_path, base = read_header(path)
    if kind != "optimise":
        raise InputError(f"{path}: kind = {kind!r}; an optimisation file has kind = "
                         "\"optimise\"")
    pt = doc.get("parameters", [])
    if not isinstance(pt, list) or not pt:
        raise InputError(f"{path}: an optimisation needs at least one [[parameters]] table "
                         "(keys and bounds)")
    params = tuple(_parameter(t, i) for i, t in enumerate(pt))
    keys = [k for p in params for k in p.keys]
    dup = [k for k in keys if keys.count(k) > 1]
    if dup:
        raise InputError(f"parameters: {dup[0]!r} is in more than one parameter")
    fixed = fixed_changes(doc)
    both = sorted((set(fixed) & set(keys)) | ({TORQUE_KEY} & set(fixed)))
    if both:
        raise InputError(f"set: {both[0]!r} is also a parameter or the load; give it in one "
                         "place")
    torques, weights = _load(doc.get("load", {}))
    kp = doc.get("kpis", {})
    check_table_keys(kp, ("speed_range_rpm", "speed_points"), "kpis")
    outs = output_tables({"kpis": kp, "execution": doc.get("execution", {})})
    dynamics = outs.get("speed_range_rpm") is not None
    if dynamics and "dynamics" not in base.document:
        raise InputError(f"{path}: kpis.speed_range_rpm needs a [dynamics] table in the base "
                         f"file {base_path.name}")
    obj = doc.get("objective", {})
    check_table_keys(obj, ("kpi",), "objective")
    if "kpi" not in obj:
        raise InputError(f"{path}: [objective] needs kpi = \"<KPI name>\" (e.g. "
                         "\"te_peak_to_peak_um\")")
    names = list(KPI_BY_NAME)
    if obj["kpi"] not in names:
        raise unknown(str(obj["kpi"]), names, "objective.kpi: KPI")
    ct = doc.get("constraints", [])
    if not isinstance(ct, list):
        raise InputError("constraints: expected [[constraints]] tables (kpi and max or min)")
    constraints = tuple(_constraint(t, i, names) for i, t in enumerate(ct))
    spec = OptimiseSpec(
        name=str(doc.get("name", path.stem)), path=path, base_path=base_path, base=base,
        fixed=fixed, parameters=params, torques_Nm=torques, weights=weights,
        objective=obj["kpi"], constraints=constraints,
        speed_range_rpm=outs.get("speed_range_rpm"), speed_points=outs["speed_points"],
        batch_points=outs["batch_points"], document=doc, **_optimiser(doc.get("optimiser", {})))
    select_kpis(spec.kpi_names, dynamics, "rating" in base.document)  # needs checked here
    check_bounds(spec)
    return spec


def check_bounds(spec: OptimiseSpec) -> None:
    """Build the gearbox with each parameter at each bound (the others at their midpoints,
    the first and the last torque); the first refused value is one line naming the
    parameter and its key."""
    from pipeline.study.evaluate import point_gearbox

    mid = {p.label: 0.5 * (p.low + p.high) for p in spec.parameters}
    for i, p in enumerate(spec.parameters):
        for bound in (p.low, p.high):
            for torque in dict.fromkeys((spec.torques_Nm[0], spec.torques_Nm[-1])):
                try:
                    point_gearbox(spec.point_document({**mid, p.label: bound}, torque),
                                  spec.name)
                except InputError as exc:
                    raise InputError(
                        f"{spec.path}: parameters[{i}].bounds = [{p.low:g}, {p.high:g}] "
                        f"({p.label}): at {bound:g} the gearbox is refused: {exc}") from None


@dataclass(frozen=True)
class OptimiseResult:
    """An optimisation's outcome.

    Attributes
    ----------
    spec : what was optimised.
    best : ``{parameter label: value}`` of the optimum (file units).
    objective : J at the optimum (the objective KPI's unit).
    feasible : the optimum meets every constraint.
    per_torque : shape (T,), the objective KPI at each torque of the optimum.
    history : one row per evaluation (:func:`history_columns`).
    evaluations, generations : counts; ``message``: the optimiser's stop reason.
    seconds : wall time, s.
    """

    spec: OptimiseSpec
    best: dict[str, float]
    objective: float
    feasible: bool
    per_torque: np.ndarray
    history: list[dict[str, Any]]
    evaluations: int
    generations: int
    message: str
    seconds: float

    def summary(self) -> dict[str, Any]:
        """The optimum, its objective and what produced it (units in the keys)."""
        s = self.spec
        return {"optimisation": s.name, "objective_kpi": s.objective,
                f"objective_{s.objective}": self.objective, "feasible": self.feasible,
                "optimum": self.best,
                "per_torque": {f"{t:g} N m": float(v)
                               for t, v in zip(s.torques_Nm, self.per_torque, strict=True)},
                "torques_Nm": list(s.torques_Nm), "weights": list(s.weights),
                "constraints": [f"{c.kpi} {'<=' if c.sense == 'max' else '>='} {c.limit:g}"
                                for c in s.constraints],
                "evaluations": self.evaluations, "generations": self.generations,
                "points_evaluated": self.evaluations * len(s.torques_Nm),
                "optimiser": f"scipy.optimize.{s.method}", "stop": self.message,
                "seconds": self.seconds}


def kpi_column(kpi: str, torque: float) -> str:
    """Record column of a KPI at one torque, e.g. ``te_peak_to_peak_um_at_340Nm``."""
    return f"{kpi}_at_{torque:g}Nm"


def history_columns(spec: OptimiseSpec) -> list[str]:
    """Columns of the evaluation record: ``evaluation``, ``generation``, the parameters
    (file units), ``objective_<kpi>`` (J, the KPI's unit), ``violation`` (-), ``feasible``
    (meets every constraint), ``penalised_objective`` (f), each KPI at each torque (its
    unit), ``error``."""
    cols = ["evaluation", "generation", *(p.label for p in spec.parameters),
            f"objective_{spec.objective}", "violation", "feasible", "penalised_objective"]
    cols += [kpi_column(k, t) for k in spec.kpi_names for t in spec.torques_Nm]
    return cols + ["error"]


def score(spec: OptimiseSpec, rows: list[Mapping[str, float]]) -> tuple[float, float]:
    """(J, v) of one parameter vector from its KPI rows, one per torque of ``spec``."""
    vals = np.array([r[spec.objective] for r in rows], dtype=float)
    j = float(np.dot(spec.weights, vals)) if np.all(np.isfinite(vals)) else math.inf
    v = sum(c.violation(float(r[c.kpi])) for c in spec.constraints for r in rows)
    return j, float(v)


def penalised(j: float, v: float) -> float:
    """f = J + PENALTY max(1, |J|) v (module docstring)."""
    if not math.isfinite(j):
        return math.inf
    return j + PENALTY * max(1.0, abs(j)) * v


class _Evaluator:
    """The vectorised objective handed to the optimiser: one call evaluates a population
    (every member at every torque) as batches on the executor and records each member."""

    def __init__(self, spec: OptimiseSpec, run_batches: Any) -> None:
        self.spec, self.run_batches = spec, run_batches
        self.history: list[dict[str, Any]] = []
        self.generation = 0

    def __call__(self, xt: np.ndarray) -> np.ndarray:
        xs = np.atleast_2d(np.asarray(xt, dtype=float).T)  # (S, N)
        s = self.spec
        docs = [s.point_document(s.values(x), t) for x in xs for t in s.torques_Nm]
        rows = self.run_batches(docs)
        nt = len(s.torques_Nm)
        out = np.empty(len(xs))
        for m, x in enumerate(xs):
            mine = rows[m * nt:(m + 1) * nt]
            j, v = score(s, mine)
            out[m] = penalised(j, v)
            rec = {"evaluation": len(self.history), "generation": self.generation,
                   **s.values(x), f"objective_{s.objective}": j, "violation": v,
                   "feasible": bool(v == 0.0 and math.isfinite(j)),
                   "penalised_objective": float(out[m])}
            rec.update({kpi_column(k, t): float(r[k]) for k in s.kpi_names
                        for t, r in zip(s.torques_Nm, mine, strict=True)})
            rec["error"] = "; ".join(sorted({r["error"] for r in mine if r["error"]}))
            self.history.append(rec)
        return out

    def next_generation(self, *_: Any) -> bool:
        self.generation += 1
        return False


def _batch_runner(spec: OptimiseSpec, client: Any, job: Any, workers: int) -> Any:
    """``docs -> KPI rows`` (in order): serially here (``client`` None) or as batches on
    the Dask client, the FE tables of each geometry one task shared by its batches."""
    from pipeline.study.evaluate import fe_geometry_key, point_gearbox
    from pipeline.study.execute import evaluate_batch, fe_tables_task

    fe: dict[Any, Any] = {}

    def run(docs: list[dict]) -> list[dict]:
        keys = [fe_geometry_key(point_gearbox(d)) for d in docs]
        groups: dict[Any, list[int]] = {}
        for i, k in enumerate(keys):
            groups.setdefault(k, []).append(i)
        size = spec.batch_points or max(1, math.ceil(len(docs) / max(2 * workers, 1)))
        batches = [(g, ids[j:j + size]) for g, ids in groups.items()
                   for j in range(0, len(ids), size)]
        rows: list[dict] = [{}] * len(docs)
        if client is None:
            # hundreds of evaluations would repeat their physics warnings; the constraints
            # (tip_contact_share_percent, loaded_contact_ratio) are how a design rules them out
            with warnings.catch_warnings():
                warnings.simplefilter("ignore", PhysicsWarning)
                for g, ids in batches:
                    if g is not None and g not in fe:
                        fe[g] = fe_tables_task(docs[ids[0]], job)
                    for r in evaluate_batch([(i, docs[i]) for i in ids], fe.get(g), job):
                        rows[r["point"]] = r
            return rows
        for g, ids in batches:
            if g is not None and g not in fe:
                fe[g] = client.submit(fe_tables_task, docs[ids[0]], job, key=f"fe-tables-{g}")
        futures = [client.submit(evaluate_batch, [(i, docs[i]) for i in ids], fe.get(g), job,
                                 pure=False) for g, ids in batches]
        for part in client.gather(futures):
            for r in part:
                rows[r["point"]] = r
        return rows

    return run


def run_optimisation(spec: OptimiseSpec, options: Any = None) -> OptimiseResult:
    """Minimise the spec's objective (module docstring) with its optimiser; evaluations on
    the Dask cluster of ``options`` (:class:`pipeline.study.execute.StudyOptions`: a
    LocalCluster by default, ``scheduler``, or ``workers = 0`` serially here)."""
    import os
    from contextlib import ExitStack

    from scipy.optimize import differential_evolution

    from pipeline.study.execute import BatchJob, StudyOptions, dask_client
    from pipeline.study.kpis import select_kpis

    options = options or StudyOptions()
    kpis = select_kpis(spec.kpi_names, spec.speed_range_rpm is not None,
                       "rating" in spec.base.document)
    job = BatchJob(kpis, spec.speed_range_rpm, spec.speed_points, options.cache, None,
                   uuid.uuid4().hex[:8])
    t0 = time.perf_counter()
    with ExitStack() as stack:
        client = None
        workers = 1
        if options.workers != 0:
            client = stack.enter_context(dask_client(options.scheduler, options.workers))
            workers = len(client.scheduler_info().get("workers", {})) or (
                options.workers or os.cpu_count() or 1)
        ev = _Evaluator(spec, _batch_runner(spec, client, job, workers))
        res = differential_evolution(
            ev, [(p.low, p.high) for p in spec.parameters], popsize=spec.popsize,
            maxiter=spec.maxiter, tol=spec.tol, seed=spec.seed, polish=False,
            vectorized=True, updating="deferred", callback=ev.next_generation)
    hist = ev.history
    col = f"objective_{spec.objective}"
    feasible = [h for h in hist if h["feasible"]]
    best = (min(feasible, key=lambda h: h[col]) if feasible
            else min(hist, key=lambda h: h["penalised_objective"]))
    per = np.array([best[kpi_column(spec.objective, t)] for t in spec.torques_Nm])
    return OptimiseResult(spec, {p.label: best[p.label] for p in spec.parameters},
                          float(best[col]), bool(feasible), per, hist, len(hist),
                          ev.generation, str(res.message), time.perf_counter() - t0)


def optimum_document(result: OptimiseResult) -> tuple[dict[str, Any], str]:
    """The optimum as a gearbox document (base file, ``[set]``, the optimum values; the
    base file's torque) and its header comment (what was optimised, how, the result)."""
    s = result.spec
    doc = s.gearbox_document(result.best)
    doc["name"] = f"{doc.get('name', s.base_path.stem)}, optimum of {s.name}"
    lines = [f"Optimum of {s.name} ({s.path.name}): the base file {s.base_path.name} with",
             *(f"  {k} = {v!r}" for k, v in result.best.items()),
             f"minimising the weighted mean of {s.objective} over the driving torques",
             "  " + ", ".join(f"{t:g} N m (weight {w:.4g})"
                              for t, w in zip(s.torques_Nm, s.weights, strict=True)),
             f"= {result.objective:.10g}"
             + ("" if result.feasible else " (NO evaluation met every constraint)"),
             *(f"subject to {c.kpi} {'<=' if c.sense == 'max' else '>='} {c.limit:g} at "
               "every torque" for c in s.constraints),
             "bounds: " + "; ".join(f"{p.label} in [{p.low:g}, {p.high:g}]"
                                    + (f" (+{len(p.keys) - 1} tied)" if len(p.keys) > 1
                                       else "") for p in s.parameters),
             f"scipy.optimize.{s.method}: {result.evaluations} evaluations x "
             f"{len(s.torques_Nm)} torques, {result.generations} generations "
             f"({result.message})"]
    return doc, "".join(f"# {line}\n" for line in lines)


def plot_convergence(result: OptimiseResult) -> Any:
    """Objective J of every evaluation (constraint-violating ones as crosses) and the best
    feasible so far, over the evaluation number."""
    from pipeline.study.kpis import KPI_BY_NAME, kpi_label
    from pipeline.viz.canvas import new_figure

    s = result.spec
    unit = KPI_BY_NAME[s.objective].unit
    col = f"objective_{s.objective}"
    n = np.array([h["evaluation"] for h in result.history])
    j = np.array([h[col] for h in result.history], dtype=float)
    ok = np.array([h["feasible"] for h in result.history])
    best = np.minimum.accumulate(np.where(ok, j, np.inf))
    fig = new_figure((6.4, 4.0), "constrained")
    ax = fig.subplots()
    ax.plot(n[ok], j[ok], "o", ms=3, alpha=0.6, label="evaluation")
    if (~ok).any():
        ax.plot(n[~ok], j[~ok], "x", ms=4, color="0.5", label="violates a constraint")
    ax.plot(n[np.isfinite(best)], best[np.isfinite(best)], "-", color="C3", lw=1.6,
            label="best feasible so far")
    ax.set_xlabel("evaluation (each at every torque of the load cases)")
    ax.set_ylabel(f"weighted mean {kpi_label(s.objective)}")
    ax.grid(alpha=0.3)
    fig.legend(*ax.get_legend_handles_labels(), loc="outside lower center", ncol=3,
               fontsize=8)
    ax.set_title(f"{s.name}: {result.evaluations} evaluations, {result.generations} "
                 f"generations; optimum {result.objective:.4g}"
                 + ("" if unit == "-" else f" {unit}"), fontsize=9)
    return fig
