"""``gearpipe report CONFIG``: the tooth load distribution report of every gear mesh.

The same run as ``gearpipe run`` (:func:`pipeline.cli.run.run`: the stages the
gearbox file asks for, with the same cache, their tables and figures, then the reports of
:func:`pipeline.report.write_reports`), written to ``results/<file stem>/report/`` (or
``--out``): ``report.html`` per mesh (prefixed by the mesh name for a planetary set),
``report.json``, ``report.csv``, ``report_cycle.csv``, ``report_face.csv``, beside the
stage files, ``summary.json`` and ``run.json``. A file without gears in mesh (one gear, a
lumped model) is refused in one line before anything runs.
"""

from __future__ import annotations

import argparse

from pipeline.cli import run as run_commands
from pipeline.cli.common import load
from pipeline.validation import InputError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    run_commands.add_arguments(parser)


def run(args: argparse.Namespace) -> int:
    box = load(args)
    if box.kind not in ("pair", "planetary"):
        raise InputError(f"{box.name}: a load distribution report needs gears in mesh (a pair "
                         f"or a planetary set); this file describes a "
                         f"{box.kind.replace('gear', 'single gear')}")
    return run_commands.run(args, "report")
