"""``gearpipe study STUDY.toml``: a design study over a base gearbox file, on Dask.

Writes to ``results/<study file stem>/study/`` (or ``--out``): ``study.parquet`` and
``study.csv`` (one row per point: ``point``, the axes in the file's units, the KPIs with
their units in the names, ``error``), ``manifest.json`` and ``parts/`` (what resuming
reads), ``sensitivity.png``, ``tradeoff.png`` (with two KPIs or more; the summary's
``tradeoff`` says which, or why none), ``best_point/gearbox.toml`` with the best
point (with ``[best] mean_over``: the design best on average over that axis, at the
axis's reference value) and its ``gearpipe run`` results in ``best_point/run/``
(:func:`report_best_point`, the hook of the tooth load distribution report),
``summary.json`` and ``run.json``.

A Harris map (``kind = "harris"``, :mod:`pipeline.study.harris`) writes, beside the study
tables, ``harris_map.csv`` (variant, torque, unit load, the KPIs, units in the headers),
``harris_map.png`` and ``harris_map.html``; its summary gives each variant's load of
smallest TE peak-to-peak. An optimisation (``kind = "optimise"``,
:mod:`pipeline.study.optimise`) writes ``history.csv`` (one row per evaluation),
``convergence.png``, ``optimum/gearbox.toml`` (the base file with the optimum values, a
header saying what was optimised) with its ``gearpipe run`` folder ``optimum/run/``,
``summary.json`` and ``run.json``.

The folder follows every command's rule (:mod:`pipeline.output_folder`): checked before any
point is computed (new, empty, or an earlier result of the same study:
:func:`pipeline.study.store.study_folder`; anything else is refused in one line and left
as it was) and written as a unit. Where the points are computed depends on what the folder
holds: an unfinished study (the folder itself, new or killed part way) gets its part files
there, so that ``--resume`` continues it after a kill; the finished result is then
assembled in the staging folder (part files hard-linked) and swapped in. A rerun over a
finished result computes in the staging folder, so a kill leaves the earlier result whole.
"""

from __future__ import annotations

import argparse
import math
from pathlib import Path
from typing import Any

from pipeline.cli.common import emit
from pipeline.io import atomic_write_text, write_json
from pipeline.output_folder import staged_output
from pipeline.provenance import write_run_record
from pipeline.study.execute import CONNECT_TIMEOUT_S, StudyOptions, check_study, run_study
from pipeline.study.spec import StudySpec, read_study_file
from pipeline.study.store import is_complete, link_work_files, study_folder


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("config", type=Path, help="study file (TOML: base gearbox file + axes)")
    parser.add_argument("--out", type=Path, default=None,
                        help="output folder (default: results/<study file stem>/study)")
    parser.add_argument("--json", action="store_true", help="print the summary as JSON")
    parser.add_argument("--scheduler", default=None,
                        help="address of an existing Dask scheduler (tcp://host:8786), "
                             f"waited for {CONNECT_TIMEOUT_S:g} s at most; default: a "
                             "LocalCluster on this "
                             "machine")
    parser.add_argument("--workers", type=int, default=None,
                        help="LocalCluster worker processes (default: one per core); 0 runs "
                             "the points serially in this process")
    parser.add_argument("--resume", action="store_true",
                        help="continue the unfinished study in the output folder")
    parser.add_argument("--no-best-run", action="store_true",
                        help="write the best point's (an optimisation: the optimum's) gearbox "
                             "file but do not run it")


def best_row(table: dict[str, list], kpi: str, goal: str) -> int | None:
    """Row of the best finite value of ``kpi`` (lowest for "min"), or ``None``."""
    vals = [(v, i) for i, v in enumerate(table[kpi]) if v is not None and math.isfinite(v)]
    if not vals:
        return None
    return (min(vals) if goal == "min" else max(vals))[1]


def best_row_mean_over(table: dict[str, list], kpi: str, goal: str, over: str,
                       axes: list[str], reference: Any) -> tuple[int | None, float]:
    """The best design on average over the axis ``over``: group the rows by the other
    ``axes``' values, take the mean of ``kpi`` over each group (groups with a failed point
    left out), pick the lowest mean ("min") or highest; returns the group's row at
    ``reference`` (the value of ``over`` the best point is run at) and the mean, or
    ``(None, nan)``."""
    others = [a for a in axes if a != over]
    groups: dict[tuple, list[int]] = {}
    for i in range(len(table["point"])):
        groups.setdefault(tuple(table[a][i] for a in others), []).append(i)
    means = {}
    for key, rows in groups.items():
        vals = [table[kpi][i] for i in rows]
        if all(v is not None and math.isfinite(v) for v in vals):
            means[key] = sum(vals) / len(vals)
    if not means:
        return None, math.nan
    pick = (min if goal == "min" else max)(means, key=means.__getitem__)
    rows = groups[pick]
    row = next((i for i in rows if table[over][i] == reference), rows[len(rows) // 2])
    return row, means[pick]


def report_best_point(spec: StudySpec, values: dict[str, Any], out: Path, run: bool = True
                      ) -> list[Path]:
    """The best point as a gearbox file and, with ``run``, its ``gearpipe run`` folder.

    The run folder holds what ``gearpipe run`` writes, the load distribution report
    (``report.html``) included; the gearbox file's ``name`` says it is the best point, so
    the figures and the report carry that name, not the base file's.
    """
    doc = spec.point_document(values)
    # figure titles and the report name the best point, not the base file
    doc["name"] = f"{doc.get('name', spec.base_path.stem)}, best point of study {spec.name}"
    header = (f"# Best point of the study {spec.name} ({spec.path.name}): the base file "
              f"{spec.base_path.name} with\n" + "".join(f"#   {k} = {v!r}\n"
                                                       for k, v in values.items()))
    return write_gearbox_and_run(doc, header, out, run)


def write_gearbox_and_run(doc: dict[str, Any], header: str, out: Path, run: bool = True
                          ) -> list[Path]:
    """``out/gearbox.toml`` (``header`` comment lines, then ``doc``) and, with ``run``, its
    ``gearpipe run`` folder ``out/run/`` (report included)."""
    import tomli_w

    from pipeline.cli.run import figure_cache, write_run
    from pipeline.config import load_gearbox
    from pipeline.run.chain import RunOptions
    from pipeline.run.runner import run_pipeline

    path = atomic_write_text(out / "gearbox.toml", header + tomli_w.dumps(doc))
    files = [path]
    if run:
        box = load_gearbox(path)
        options = RunOptions(show_progress=False)
        result = run_pipeline(box, options)
        folder = out / "run"
        folder.mkdir(parents=True, exist_ok=True)
        written = write_run(result, folder, False, figure_cache(options))
        if result.meshes:  # the report embeds the figures written above: after them
            from pipeline.report import write_reports

            written += write_reports(result, folder, figure_cache(options),
                                     command=f"gearpipe run {path}", show_progress=False)
        written.append(write_json(folder / "summary.json", result.summary()))
        write_run_record(folder, {"gearbox": box.to_dict(), "options": options}, written,
                         f"gearpipe run {path}")
        files.append(folder)
    return files


def run(args: argparse.Namespace) -> int:
    spec = read_study_file(args.config)
    options = StudyOptions(scheduler=args.scheduler, workers=args.workers, resume=args.resume,
                           show_progress=not args.json)
    if spec.kind == "optimise":
        return _run_optimisation(args, spec, options)
    check_study(spec)  # the study file and options before the folder, all before any point
    target = args.out or Path("results") / Path(args.config).stem / "study"
    with staged_output(target, study_folder(spec)) as out:
        work = out if is_complete(target) and not args.resume else target
        table, facts = run_study(spec, work, options, tables=out)
        files = [out / "study.parquet", out / "study.csv"]
        if work != out:
            files += link_work_files(work, out)
        summary = _write_outputs(args, spec, table, facts, out, files)
    emit(args, summary, target)
    return 0


def _write_outputs(args: argparse.Namespace, spec: StudySpec, table: Any,
                   facts: dict[str, Any], out: Path, files: list[Path]) -> dict[str, Any]:
    """Figures, the best point, ``summary.json`` and ``run.json`` into ``out``; the
    summary."""
    from pipeline.study.plots import plot_sensitivity, plot_tradeoff
    from pipeline.viz import save

    cols = table.to_pydict()
    kpis = [n for n in table.column_names[1 + len(spec.axes):] if n != "error"]
    if spec.kind == "harris":
        return _write_harris(args, spec, cols, facts, out, files)
    trade = list(spec.tradeoff) or kpis[:2]  # checked before the points: check_study
    best_kpi = spec.best_kpi or kpis[0]
    mean = None
    if spec.best_mean_over:
        from pipeline.study.plots import reference_values

        ref = reference_values(spec, cols)[spec.best_mean_over]
        best, mean = best_row_mean_over(cols, best_kpi, spec.best_goal, spec.best_mean_over,
                                        [a.label for a in spec.axes], ref)
    else:
        best = best_row(cols, best_kpi, spec.best_goal)
    files.append(save(plot_sensitivity(spec, cols, kpis), out / "sensitivity.png"))
    if len(trade) == 2:
        files.append(save(plot_tradeoff(cols, trade[0], trade[1], best,
                                        f"{spec.name}: {len(cols['point'])} points"),
                          out / "tradeoff.png"))
        drawn = f"tradeoff.png: {trade[1]} against {trade[0]}"
    else:
        drawn = f"none: the study has one KPI ({kpis[0]}), a trade-off needs two"
    summary: dict[str, Any] = {"study": spec.name, **facts,
                               "failed_points": sum(1 for e in cols["error"] if e),
                               "tradeoff": drawn}
    if best is not None:
        values = {a.label: cols[a.label][best] for a in spec.axes}
        summary["best"] = {"point": cols["point"][best], "kpi": best_kpi,
                           "goal": spec.best_goal, "value": cols[best_kpi][best], **values}
        if mean is not None:
            summary["best"].update(mean_over=spec.best_mean_over, mean=mean)
        files += report_best_point(spec, values, out / "best_point", not args.no_best_run)
    files.append(write_json(out / "summary.json", summary))
    write_run_record(out, {"study": spec.document, "base": spec.base.document,
                           "base_sha256": spec.base.sha256}, files,
                     f"gearpipe study {args.config}")
    return summary


def _write_harris(args: argparse.Namespace, spec: StudySpec, cols: dict[str, list],
                  facts: dict[str, Any], out: Path, files: list[Path]) -> dict[str, Any]:
    """The Harris map's CSV, figure and page, ``summary.json`` and ``run.json``."""
    from pipeline.study.harris import harris_html, harris_map, plot_harris_map
    from pipeline.viz import save

    hmap = harris_map(spec, cols)
    files.append(_write_rows(out / "harris_map.csv", hmap.rows()))
    files.append(save(plot_harris_map(hmap), out / "harris_map.png"))
    page = harris_html(hmap, "harris_map.png", [f.name for f in files])
    files.append(atomic_write_text(out / "harris_map.html", page))
    summary: dict[str, Any] = {"study": spec.name, "kind": "harris", **facts,
                               "failed_points": sum(1 for e in cols["error"] if e),
                               **hmap.summary()}
    files.append(write_json(out / "summary.json", summary))
    write_run_record(out, {"study": spec.document, "base": spec.base.document,
                           "base_sha256": spec.base.sha256}, files,
                     f"gearpipe study {args.config}")
    return summary


def _run_optimisation(args: argparse.Namespace, spec: Any, options: StudyOptions) -> int:
    """``kind = "optimise"``: the optimiser, its record and figure, the optimum as a gearbox
    file with its run folder (module docstring)."""
    from pipeline.study.optimise import optimum_document, plot_convergence, run_optimisation
    from pipeline.viz import save

    if args.resume:
        from pipeline.validation import InputError

        raise InputError("--resume: an optimisation is not resumable; run it again")
    target = args.out or Path("results") / Path(args.config).stem / "optimise"
    with staged_output(target) as out:
        result = run_optimisation(spec, options)
        files = [_write_rows(out / "history.csv", result.history),
                 save(plot_convergence(result), out / "convergence.png")]
        doc, header = optimum_document(result)
        files += write_gearbox_and_run(doc, header, out / "optimum", not args.no_best_run)
        summary = {"kind": "optimise", **result.summary()}
        files.append(write_json(out / "summary.json", summary))
        write_run_record(out, {"study": spec.document, "base": spec.base.document,
                               "base_sha256": spec.base.sha256}, files,
                         f"gearpipe study {args.config}")
    emit(args, summary, target)
    return 0


def _write_rows(path: Path, rows: list[dict[str, Any]]) -> Path:
    """Rows of equal keys as a CSV (units in the keys; booleans as 1/0)."""
    from pipeline.io import write_csv

    cols = {k: [int(r[k]) if isinstance(r[k], bool) else r[k] for r in rows] for k in rows[0]}
    return write_csv(path, cols)
