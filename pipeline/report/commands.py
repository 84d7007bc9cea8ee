"""``gearpipe report CONFIG``: the tooth load distribution report of every gear mesh.

Runs the stages the gearbox file asks for (:func:`pipeline.run.run_pipeline`, with the
same cache as ``gearpipe run``), writes their tables and figures
(:func:`pipeline.run.commands.write_run`) and then the reports
(:func:`pipeline.report.write_reports`) to ``results/<file stem>/report/`` (or
``--out``): ``report.html`` per mesh (prefixed by the mesh name for a planetary set),
``report.json``, ``report.csv``, ``report_cycle.csv``, ``report_face.csv``, beside
``summary.json`` and ``run.json``. ``gearpipe run`` writes the same reports as its last
step.
"""

from __future__ import annotations

import argparse

from pipeline.commands_common import emit, load, output_dir
from pipeline.io import write_json, write_run_record
from pipeline.run.chain import RunOptions, run_pipeline
from pipeline.run.commands import add_arguments as add_run_arguments
from pipeline.run.commands import figure_cache, write_run
from pipeline.validation import InputError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_run_arguments(parser)


def run(args: argparse.Namespace) -> int:
    from pipeline.report.writer import write_reports

    box = load(args)
    if box.kind not in ("pair", "planetary"):
        raise InputError(f"{box.name}: a load distribution report needs gears in mesh (a pair "
                         f"or a planetary set); this file describes a "
                         f"{box.kind.replace('gear', 'single gear')}")
    options = RunOptions(full=args.full, cache=not args.no_cache, cache_dir=args.cache_dir,
                         show_progress=not args.json)
    result = run_pipeline(box, options)
    out = output_dir(args, "report")
    figures = figure_cache(options)
    with result.log.step("writing tables and figures", long=True):
        files = write_run(result, out, args.full, figures)
    with result.log.step("load distribution reports", long=True):
        files += write_reports(result, out, figures, command=f"gearpipe report {args.config}",
                               show_progress=options.show_progress)
    summary = result.summary()
    summary["reports"] = [f.name for f in files if f.suffix == ".html"]
    files.append(write_json(out / "summary.json", summary))
    write_run_record(out, {"gearbox": box.to_dict(), "options": options}, files,
                     f"gearpipe report {args.config}")
    emit(args, summary, out)
    return 0
