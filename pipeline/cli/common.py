"""What every ``gearpipe`` command shares: its arguments, its output folder, its record,
its summary.

One rule for the output folder: ``results/<file stem>/<command>`` (the stem of the
gearbox file, never a name written inside it), or ``--out DIR``; it is checked before
the work starts and written as a unit (:func:`pipeline.output_folder.staged_output`).
Workflow scripts follow the same shape with ``workflow`` in the command's place,
``results/<script stem>/workflow`` (:func:`workflow_dir`): no command has that name, so a
workflow's folder and a command's folder are never the same, nor one inside the other,
even when a gearbox file and a script share a stem.
One record (``run.json``, :mod:`pipeline.provenance`). One summary format: a short
table on stdout, or one JSON object with ``--json``.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.cache.folder import CACHE_ENV, Cache
from pipeline.config import Gearbox, load_gearbox
from pipeline.config.signals import referenced_files
from pipeline.io import to_jsonable
from pipeline.output_folder import check_target
from pipeline.provenance import write_run_record
from pipeline.validation import InputError

# arguments that choose where and how results are shown or cached, not what they are
_NOT_NUMBERS = frozenset({"config", "out", "json", "command", "cache_dir", "no_cache"})


def add_common_arguments(parser: argparse.ArgumentParser) -> None:
    """CONFIG, --out and --json, the same for every subcommand."""
    parser.add_argument("config", type=Path, help="gearbox file (TOML, units in the key names)")
    parser.add_argument("--out", type=Path, default=None,
                        help="output folder (default: results/<file stem>/<command>)")
    parser.add_argument("--json", action="store_true",
                        help="print the result summary as JSON on stdout")


def add_cache_arguments(parser: argparse.ArgumentParser) -> None:
    """--cache-dir and --no-cache, the same for every command that meshes or solves."""
    parser.add_argument("--no-cache", action="store_true",
                        help="recompute meshes, FE tables and contact cycles (neither read "
                             "nor write the cache)")
    parser.add_argument("--cache-dir", type=Path, default=None,
                        help=f"cache folder (default: ${CACHE_ENV}, else meshes/ of a source "
                             "checkout, else $XDG_CACHE_HOME/gearpipe or ~/.cache/gearpipe)")


def command_cache(args: argparse.Namespace) -> Cache:
    """The cache of this run: off with ``--no-cache`` or when the folder cannot be written
    (one warning line, and the run goes on without it), else ``--cache-dir`` or the
    default folder."""
    return Cache.for_command(args.cache_dir, disabled=args.no_cache)


def output_dir(args: argparse.Namespace, command: str) -> Path:
    """The folder a command will write (``--out`` or the default rule), checked now so
    that a file in the way or a read-only parent is refused before any work
    (:class:`pipeline.output_folder.OutputError`); nothing is created."""
    out = args.out or Path("results") / Path(args.config).stem / command
    check_target(out)
    return out


WORKFLOW_FOLDER = "workflow"
"""The last part of a workflow script's default folder; never a command's name."""


def workflow_dir(script: str | os.PathLike, out: str | os.PathLike | None = None, *,
                 check: bool = True) -> Path:
    """The folder a workflow script writes: ``out`` (its ``--out``) or
    ``results/<script stem>/workflow``; with ``check``, checked now
    (:func:`pipeline.output_folder.check_target`), so that a folder holding other files is
    refused in one line before any work. ``check=False`` for a script that hands the
    folder to a command which checks it itself."""
    target = Path(out) if out is not None else \
        Path("results") / Path(script).stem / WORKFLOW_FOLDER
    if check:
        check_target(target)
    return target


def number_options(args: argparse.Namespace) -> dict[str, Any]:
    """The command-line options that change the numbers (all but output, cache, display)."""
    return {k: v for k, v in sorted(vars(args).items())
            if not k.startswith("_") and k not in _NOT_NUMBERS}


def record(out: Path, args: argparse.Namespace, box: Gearbox, files: list, *,
           inputs: Any = None) -> Path:
    """Write ``run.json`` of a command into ``out``: the gearbox file as written, the parsed
    ``inputs`` (default: the file's contents), the options that change the numbers and the
    SHA-256 of every file the gearbox file points to."""
    src = box.source
    base = src.path.parent if src is not None and src.path is not None else None
    return write_run_record(
        out, box.to_dict() if inputs is None else inputs, files,
        f"gearpipe {getattr(args, 'command', '')}".strip(),
        arguments=getattr(args, "_argv", None), options=number_options(args),
        sources=[] if src is None else [src],
        referenced={} if src is None else referenced_files(src.document, base),
        started=getattr(args, "_started", None))


COMMAND_KINDS: dict[str, tuple[str, ...]] = {
    "run": ("pair", "planetary", "lumped"),
    "report": ("pair", "planetary"),
    "geometry": ("pair",),
    "stiffness": ("pair",),
    "fe": ("pair",),
    "contact": ("pair",),
    "groove": ("gear", "planetary"),
    "modes": ("pair", "planetary", "lumped"),
    "response": ("pair", "planetary", "lumped"),
    "sweep": ("pair", "planetary", "lumped"),
}
"""The kinds of gearbox file (:attr:`pipeline.config.Gearbox.kind`) each command takes."""

_KIND_NAMES = {"pair": "a gear pair", "planetary": "a planetary set", "gear": "a single gear",
               "lumped": "a lumped dynamic model"}


def _either(words: list[str], last: str) -> str:
    return words[0] if len(words) == 1 else ", ".join(words[:-1]) + f" {last} " + words[-1]


def kind_mismatch(command: str, kind: str) -> str | None:
    """Why ``gearpipe command`` does not take a file of ``kind`` and which commands do, or
    ``None`` when it takes it (:data:`COMMAND_KINDS`)."""
    takes = COMMAND_KINDS.get(command)
    if takes is None or kind in takes:
        return None
    others = [f"gearpipe {c}" for c, kinds in COMMAND_KINDS.items() if kind in kinds]
    return (f"gearpipe {command} takes {_either([_KIND_NAMES[k] for k in takes], 'or')}; "
            f"this file describes {_KIND_NAMES[kind]}, which "
            f"{_either(others, 'and')} take{'s' if len(others) == 1 else ''}")


def load(args: argparse.Namespace) -> Gearbox:
    """The gearbox file named on the command line; an input error when the command does not
    take its kind (:func:`kind_mismatch`)."""
    box = load_gearbox(args.config)
    why = kind_mismatch(getattr(args, "command", ""), box.kind)
    if why is not None:
        raise InputError(f"{box.name}: {why}")
    return box


def emit(args: argparse.Namespace, summary: dict[str, Any], out: Path,
         lines: list[str] | None = None) -> None:
    """The one way a command reports on stdout: ``summary`` as JSON (``--json``), else
    ``lines`` (a command's own table) or the summary's scalars, then where the files are."""
    if args.json:
        json.dump(to_jsonable(summary), sys.stdout, indent=2)
        sys.stdout.write("\n")
        return
    if lines is None:
        _print_scalars(summary, "")
    else:
        print("\n".join(lines))
    print(f"written to {out}/")


def _print_scalars(summary: dict[str, Any], prefix: str) -> None:
    """Print the scalar entries of ``summary``, nested dictionaries as ``outer.inner``."""
    for key, value in summary.items():
        name = f"{prefix}{key}"
        if isinstance(value, dict):
            _print_scalars(value, f"{name}.")
        elif isinstance(value, float):
            print(f"  {name:40s} {value:.6g}")
        elif not isinstance(value, (list, tuple, np.ndarray)):
            print(f"  {name:40s} {value}")
