"""Package attributes imported on first use.

A package whose names live in modules that pull in scikit-fem, Gmsh or SciPy's larger
parts (seconds of import) exports them lazily, so that a run which finds its FE results
in the cache, or a command that never needs them, does not pay for the import.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from typing import Any


def lazy_exports(package: str, exports: Mapping[str, str]) -> Callable[[str], Any]:
    """A module-level ``__getattr__`` for ``package``: ``name`` -> ``exports[name]``'s
    attribute of that name, imported when first asked for."""

    def __getattr__(name: str) -> Any:
        module = exports.get(name)
        if module is None:
            raise AttributeError(f"module {package!r} has no attribute {name!r}")
        return getattr(importlib.import_module(module), name)

    return __getattr__
