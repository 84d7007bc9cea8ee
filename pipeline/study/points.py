"""The design points of a study: a grid over the axes or a Latin hypercube.

Points are numbered in a fixed order (grid: the first axis varies slowest; Latin
hypercube: sample order of :class:`scipy.stats.qmc.LatinHypercube` with the study's
seed), so a point's number names the same design in every run of the same study file,
which is what resuming relies on.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.study.spec import Axis, StudySpec


@dataclass(frozen=True)
class DesignPoint:
    """One point: its number and ``{axis label: value}`` in the file's units."""

    index: int
    values: dict[str, Any]


def axis_values(axis: Axis) -> list[Any]:
    """Grid values of an axis (file units)."""
    if axis.values is not None:
        return list(axis.values)
    lo, hi = axis.range
    v = np.linspace(lo, hi, axis.points)
    if axis.integer:
        return sorted({int(round(x)) for x in v})
    return [float(x) for x in v]


def design_points(spec: StudySpec) -> list[DesignPoint]:
    """Every point of the study, numbered from 0."""
    labels = [a.label for a in spec.axes]
    if spec.method == "grid":
        grid = itertools.product(*(axis_values(a) for a in spec.axes))
        return [DesignPoint(i, dict(zip(labels, vals, strict=True)))
                for i, vals in enumerate(grid)]
    from scipy.stats import qmc

    u = qmc.LatinHypercube(d=len(spec.axes), seed=spec.seed).random(spec.samples)
    out = []
    for i, row in enumerate(u):
        vals = {}
        for a, x in zip(spec.axes, row, strict=True):
            lo, hi = a.range
            v = lo + x * (hi - lo)
            # an integer axis: each integer of [lo, hi] gets an equal share of the unit interval
            vals[a.label] = int(min(np.floor(lo + x * (hi - lo + 1)), hi)) if a.integer \
                else float(v)
        out.append(DesignPoint(i, vals))
    return out
