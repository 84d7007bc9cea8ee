"""What every ``gearpipe`` command shares: its arguments, its output folder, its summary.

One rule for the output folder: ``results/<file stem>/<command>`` (the stem of the
gearbox file, never a name written inside it), or ``--out DIR``. One summary
format: a short table on stdout, or one JSON object with ``--json``.
"""

from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path
from typing import Any

import numpy as np

from pipeline.config import Gearbox, load_gearbox
from pipeline.fem.cache_dir import CACHE_ENV, writable_cache_dir
from pipeline.io import to_jsonable


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


def cache_folder(args: argparse.Namespace) -> Path | None:
    """The cache folder of this run, or None for no cache (``--no-cache``, or a folder that
    cannot be written: one warning line, and the run goes on without it)."""
    if args.no_cache:
        return None
    return writable_cache_dir(args.cache_dir)


def output_dir(args: argparse.Namespace, command: str) -> Path:
    """The folder a command writes to (created)."""
    out = args.out or Path("results") / Path(args.config).stem / command
    out.mkdir(parents=True, exist_ok=True)
    return out


def load(args: argparse.Namespace) -> Gearbox:
    """The gearbox file named on the command line."""
    return load_gearbox(args.config)


def emit(args: argparse.Namespace, summary: dict[str, Any], out: Path) -> None:
    """Print ``summary`` as JSON (``--json``) or a short human-readable report."""
    if args.json:
        json.dump(to_jsonable(summary), sys.stdout, indent=2)
        sys.stdout.write("\n")
        return
    _print_scalars(summary, "")
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
