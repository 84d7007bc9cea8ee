"""``gearpipe validate``: the catalogue of verification cases (exact solutions, published
values, an independent FE model, convergence studies; :mod:`pipeline.verification`) in
one run and one report.

Writes ``validate.html`` (self-contained), ``validate.json``, ``validate.csv`` and
``run.json`` to ``results/validate/fast`` (``--full``: ``results/validate/full``; with
``--case``: ``results/validate/selected``) or ``--out``. A line per case on stderr as it
ends (status, time, its largest error against the tolerance), then the totals. Exit
status 1 when a case fails or raises, 0 when every case passes; an unknown ``--case`` id
is an input error (status 2) that lists the valid ones. ``--list`` prints the catalogue
and runs nothing.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from pipeline.cli.common import add_cache_arguments, command_cache, emit
from pipeline.output_folder import check_target, staged_output
from pipeline.provenance import write_run_record


def add_arguments(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--full", action="store_true",
                        help="run every case (the fast set and the slow ones)")
    parser.add_argument("--case", nargs="+", default=None, metavar="ID",
                        help="run only these cases (any set; --list shows the ids)")
    parser.add_argument("--list", action="store_true",
                        help="list the cases (id, set, kind, what is compared) and exit")
    parser.add_argument("--out", type=Path, default=None,
                        help="output folder (default: results/validate/fast, "
                             "results/validate/full with --full, results/validate/selected "
                             "with --case)")
    parser.add_argument("--json", action="store_true",
                        help="print the summary as JSON on stdout")
    add_cache_arguments(parser)


def _stderr(line: str) -> None:
    print(f"gearpipe validate: {line}", file=sys.stderr, flush=True)


def _reference_files(context) -> dict[str, Path]:
    """The committed reference data and model the cases read (their SHA-256 goes into the
    record)."""
    from pipeline.verification.cases_calculix import HCR_FILE, REFERENCE_FILE
    from pipeline.verification.cases_calculix_rerun import SCRIPT

    folder = Path(context.reference_dir)
    return {name: folder / name for name in (REFERENCE_FILE, HCR_FILE, SCRIPT)
            if (folder / name).is_file()}


def run(args: argparse.Namespace) -> int:
    from pipeline import __version__
    from pipeline.verification import CATALOGUE, Context, run_cases, select
    from pipeline.verification.writers import write_validation

    if args.list:
        width = max(len(c.id) for c in CATALOGUE)
        for c in CATALOGUE:
            print(f"{c.id:{width}s}  {c.tier:4s}  {c.kind:14s}  {c.title}")
        return 0
    cases = select(args.case, args.full)  # an unknown id: one line, before any work
    name = "selected" if args.case else ("full" if args.full else "fast")
    target = args.out or Path("results") / "validate" / name
    check_target(target)
    started = getattr(args, "_started", None)
    context = Context(cache=command_cache(args))
    result = run_cases(cases, context, report=_stderr)
    counts = result.counts
    _stderr(f"{len(result.results)} cases: {counts['pass']} passed, {counts['fail']} failed, "
            f"{counts['error']} raised ({result.seconds:.1f} s)")
    facts = {"command": " ".join(["gearpipe", *(getattr(args, "_argv", None) or ["validate"])]),
             "gearpipe": __version__, "set": name}
    with staged_output(target) as out:
        files = write_validation(result, out, facts)
        write_run_record(out, {"cases": [c.id for c in cases]}, files,
                         "gearpipe validate", arguments=getattr(args, "_argv", None),
                         options={"full": args.full, "case": args.case}, started=started,
                         referenced=_reference_files(context))
    summary = {k: v for k, v in result.summary().items() if k != "results"}
    emit(args, {**summary, "failed_cases": [r.id for r in result.results if not r.passed]},
         target, [f"{counts['pass']} of {len(result.results)} cases passed"])
    return 0 if result.passed else 1
