"""The ``gearpipe`` command line.

Every subcommand takes a gearbox file (TOML, units in the key names;
:mod:`pipeline.config`); everything inside is SI. Each writes CSV/JSON data, PNG
plots and a ``run.json`` record (:mod:`pipeline.provenance`) to
``results/<file stem>/<command>/`` unless ``--out`` says otherwise, as a unit
(:mod:`pipeline.output_folder`); ``--json`` prints the summary to stdout. An input error
is one line on stderr, ``gearpipe <command>: error: ...``, with exit status 2; an output
folder that cannot be written (a file in the way, a full or read-only disk) is one such
line with exit status 1, and the folder keeps its previous result; a solve that fails
(the contact iteration does not converge, a singular or too large model) is one such line
with exit status 1. Warnings (an unusable cache, a loaded contact ratio below 1, input
values that change nothing, ...) are one line each, ``gearpipe <command>: warning: ...``,
and the run goes on.

Layout: one module per command (``run``, ``report``, ``geometry``, ``stiffness``, ``fe``,
``groove``, ``contact``, ``dynamics`` for modes/response/sweep, ``study``, ``validate``)
with its file writers beside it (``dynamics_files``), and ``common`` for the shared
arguments, loading and records. Only this package reads files and writes results; the
stage packages below it form a one-way import graph, checked by the layers contract in
``pyproject.toml`` (``lint-imports``, run by ``./dev.sh test``).
"""

from __future__ import annotations

import argparse
import importlib
import sys
import time
import warnings
from collections.abc import Callable
from pathlib import Path
from typing import Any

from pipeline import __version__
from pipeline.output_folder import OutputError
from pipeline.validation import InputError

# name -> (module, add-arguments function, run function, help)
SUBCOMMANDS: dict[str, tuple[str, str, str, str]] = {
    "run": ("pipeline.cli.run", "add_arguments", "run",
            "the whole pipeline: geometry, stiffness, FE-enriched loaded contact, dynamics "
            "(modes, response, speed sweep), into one folder"),
    "report": ("pipeline.cli.report", "add_arguments", "run",
               "tooth load distribution report per gear mesh: HTML (self-contained), JSON, "
               "CSV"),
    "geometry": ("pipeline.cli.geometry", "add_arguments", "run",
                 "tooth profiles, contact ratios and line of action"),
    "stiffness": ("pipeline.cli.stiffness", "add_arguments", "run",
                  "analytical mesh stiffness over a mesh cycle"),
    "fe": ("pipeline.cli.fem", "add_arguments", "run",
           "2D sector FE of both gears: mesh, flank influence matrix, FE vs analytical "
           "tooth compliance"),
    "groove": ("pipeline.cli.groove", "add_arguments", "run",
               "herringbone sun relief groove: 3D FE torsional and coupling stiffness"),
    "contact": ("pipeline.cli.contact", "add_arguments", "run",
                "loaded tooth contact over a mesh cycle: load sharing, TE, mesh stiffness, "
                "load maps"),
    "modes": ("pipeline.cli.dynamics", "add_modes_arguments", "run_modes",
              "natural frequencies, mode types and mode shapes of the dynamic model"),
    "response": ("pipeline.cli.dynamics", "add_response_arguments", "run_response",
                 "steady dynamic response: DTE, mesh forces, spectrum"),
    "sweep": ("pipeline.cli.dynamics", "add_sweep_arguments", "run_sweep",
              "RMS dynamic mesh force against mesh frequency"),
    "study": ("pipeline.cli.study", "add_arguments", "run",
              "design study: a base gearbox file over design axes, KPIs per point, on Dask; "
              "kind = \"harris\" a Harris map, kind = \"optimise\" an optimisation "
              "(STUDY.toml instead of a gearbox file)"),
    "validate": ("pipeline.cli.validate", "add_arguments", "run",
                 "the verification cases (exact solutions, published values, an independent "
                 "FE model, convergence studies) in one report; exit status 1 when one "
                 "fails"),
}


def build_parser(available: dict[str, tuple[str, str, str, str]] | None = None, *,
                 command: str | None = None) -> argparse.ArgumentParser:
    """The parser of every subcommand; with ``command``, only that one's arguments are
    added (its module imported), the rest are listed for ``--help`` alone - importing all
    command modules costs a second or more that a single command does not need."""
    parser = argparse.ArgumentParser(prog="gearpipe", description=__doc__.split("\n\n")[0])
    parser.add_argument("--version", action="version", version=f"gearpipe {__version__}")
    sub = parser.add_subparsers(dest="command", required=True)
    for name, (mod, add, run, help_) in (available or SUBCOMMANDS).items():
        p = sub.add_parser(name, help=help_, description=help_)
        if command is None or name == command:
            module = importlib.import_module(mod)
            getattr(module, add)(p)
            p.set_defaults(_run=getattr(module, run))
    return parser


def _solve_errors() -> tuple[type[BaseException], ...]:
    """Failures of a computation on valid input, reported in one line (exit status 1)."""
    from numpy.linalg import LinAlgError

    from pipeline.contact.complementarity import ContactConvergenceError

    return (ContactConvergenceError, LinAlgError, MemoryError)


def _one_line(prefix: str, call: Callable[[], Any]) -> int:
    """``call()`` with warnings as one line each and its errors as one line with an exit
    status: 2 for an input error, 1 for an output folder that cannot be written or a
    failed solve; otherwise 0 (or ``call``'s own integer status)."""

    def one_line(message, category, filename, lineno, file=None, line=None) -> None:
        print(f"{prefix}: warning: {message}", file=sys.stderr, flush=True)

    with warnings.catch_warnings():
        warnings.showwarning = one_line
        try:
            status = call()
            return status if isinstance(status, int) and not isinstance(status, bool) else 0
        except InputError as exc:
            print(f"{prefix}: error: {exc}", file=sys.stderr)
            return 2
        except OutputError as exc:
            print(f"{prefix}: error: {exc}", file=sys.stderr)
            return 1
        except _solve_errors() as exc:
            what = "out of memory" if isinstance(exc, MemoryError) else str(exc).strip()
            print(f"{prefix}: error: the computation failed ({type(exc).__name__}: "
                  f"{what or 'no detail'})", file=sys.stderr)
            return 1


def main(argv: list[str] | None = None) -> int:
    """Run one command; exit status 0 on success, 2 on an input error, 1 when the results
    cannot be written or a solve fails (one line on stderr each); warnings are one line
    each."""
    started = time.time()
    argv = sys.argv[1:] if argv is None else list(argv)
    command = next((a for a in argv[:1] if a in SUBCOMMANDS), None)
    args = build_parser(command=command).parse_args(argv)
    args._argv, args._started = argv, started  # for the run record
    return _one_line(f"gearpipe {args.command}", lambda: args._run(args))


def run_workflow(script: str, main_function: Callable[[list[str]], Any],
                 argv: list[str] | None = None) -> int:
    """A workflow script's entry point: ``main_function(argv)`` under the commands' rules
    (warnings and errors one line each, prefixed by the script's file name; exit status 0,
    1 or 2 as :func:`main`). Use as ``sys.exit(run_workflow(__file__, main))``."""
    argv = sys.argv[1:] if argv is None else list(argv)
    return _one_line(Path(script).name, lambda: main_function(argv))
