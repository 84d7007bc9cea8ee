"""What a case may use besides its own inputs: the cache of FE tables and where the
committed reference data lie."""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from pipeline.cache.folder import Cache

REFERENCE_DIR = Path(__file__).resolve().parents[2] / "workflows" / "reference"
"""The committed reference data of a source checkout (``workflows/reference/``: the
CalculiX contact model's results); an installed package has none, and the cases that need
them fail with a one-line message naming the missing file."""


@dataclass(frozen=True)
class Context:
    """The run's shared resources.

    Attributes
    ----------
    cache : the FE table cache (:class:`pipeline.cache.folder.Cache`; ``Cache.off()``
        computes everything afresh).
    reference_dir : the folder of the committed reference data.
    """

    cache: Cache = field(default_factory=Cache.off)
    reference_dir: Path = REFERENCE_DIR
