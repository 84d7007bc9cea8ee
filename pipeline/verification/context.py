"""What a case may use besides its own inputs: the cache of FE tables and where the
committed reference data lie."""

from __future__ import annotations

import importlib.util
import sys
from dataclasses import dataclass, field
from pathlib import Path
from types import ModuleType

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


def checkout_script(path: Path, name: str, where: str) -> ModuleType:
    """The script at ``path`` as a module registered under the private ``name`` (as an
    import would, so that its dataclasses resolve their module); a missing file is one
    line saying it is in a source checkout's ``where``."""
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing (it is in a source checkout's {where})")
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    sys.modules[name] = module
    spec.loader.exec_module(module)
    return module
