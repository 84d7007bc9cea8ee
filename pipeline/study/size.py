"""The size of a study, known before any point is built: its point count, and a bound.

:func:`point_count` multiplies the axis lengths of a grid (or takes the Latin hypercube's
sample count) without building a point, so a study of 10^10 points is refused in one
line (:func:`check_size`) instead of filling the memory. The line gives the count and
what the study would cost, from two figures measured on the example spur pair
(``workflows/configs/spur_pair_assembly_errors.toml``, contact defaults, the contact
KPIs), one run on a 2-core machine shared with other jobs (load average 1.7):

* :data:`SECONDS_PER_POINT` - one point of the analytical chain (geometry, analytical
  stiffness, loaded contact on the analytical slices) on one BLAS thread: median 0.058 s
  over 20 points (0.056-0.067 s). FE compliance, FE root stress and a speed sweep cost
  more, so the estimate is a lower bound;
* :data:`BYTES_PER_POINT` - what the study holds per point before the first one runs
  (the point's gearbox document, its design values and FE geometry key): 3.5 kB per point
  of resident memory at 10 000 points, 4.5 kB at 1000.

:data:`MAX_POINTS` = 100 000 points is then at least 1.6 h on one worker and 0.45 GB
before the first point (checking every point's gearbox first adds 0.5 ms per point).
"""

from __future__ import annotations

import math

from pipeline.study.points import axis_values
from pipeline.study.spec import StudySpec
from pipeline.validation import InputError

MAX_POINTS = 100_000
"""Largest study (points) that is run."""

SECONDS_PER_POINT = 0.06
"""Lower bound of one point's time on one worker, s (module docstring)."""

BYTES_PER_POINT = 4_500
"""Memory held per point before the first one runs, bytes (module docstring)."""


def point_count(spec: StudySpec) -> int:
    """Number of points of ``spec``: the product of the grid's axis lengths, or the Latin
    hypercube's ``samples`` (no point is built)."""
    if spec.method != "grid":
        return spec.samples
    return math.prod(len(axis_values(a)) for a in spec.axes)


def _duration(seconds: float) -> str:
    for unit, size in (("years", 365.25 * 86400), ("days", 86400), ("h", 3600),
                       ("min", 60)):
        if seconds >= size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"


def _amount(nbytes: float) -> str:
    for unit, size in (("PB", 1e15), ("TB", 1e12), ("GB", 1e9), ("MB", 1e6)):
        if nbytes >= size:
            return f"{nbytes / size:.3g} {unit}"
    return f"{nbytes / 1e3:.3g} kB"


def check_size(spec: StudySpec) -> int:
    """The point count of ``spec``; :class:`InputError` (one line: the count, the time
    and memory it would take) above :data:`MAX_POINTS`."""
    n = point_count(spec)
    if n <= MAX_POINTS:
        return n
    if spec.method == "grid":
        how = " x ".join(str(len(axis_values(a))) for a in spec.axes)
        how, fix = f"grid {how}", "give the axes fewer points or values"
    else:
        how, fix = f"sampling.samples = {n}", "lower sampling.samples"
    raise InputError(
        f"{spec.path}: the study has {n} points ({how}); at most {MAX_POINTS} are run: at "
        f"{SECONDS_PER_POINT:g} s a point (the analytical chain; FE and dynamics cost more) "
        f"it would take at least {_duration(n * SECONDS_PER_POINT)} on one worker and "
        f"{_amount(n * BYTES_PER_POINT)} of memory before its first point; {fix}, or "
        "split the study")
