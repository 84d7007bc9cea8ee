"""Progress reporting for long runs (wraps tqdm; silent when not a terminal or disabled)."""

from __future__ import annotations

import sys
from collections.abc import Iterable, Iterator
from typing import TypeVar

T = TypeVar("T")


def progress(
    items: Iterable[T], desc: str, total: int | None = None, enabled: bool = True
) -> Iterator[T]:
    """Iterate over ``items`` showing a progress bar on stderr.

    The bar appears only when ``enabled`` and stderr is a terminal, or when the
    run is long enough for tqdm to print (``mininterval``); it never writes to
    stdout, so ``--json`` output stays clean.
    """
    if not enabled:
        yield from items
        return
    from tqdm import tqdm

    yield from tqdm(items, desc=desc, total=total, file=sys.stderr, mininterval=1.0, leave=False)
