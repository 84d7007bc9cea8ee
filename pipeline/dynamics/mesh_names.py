"""The names of a dynamic model's gear meshes and what they belong to.

A pair's model has one mesh, ``"mesh"``; a planetary set's has one sun mesh and one ring
mesh per planet, ``s-p1``, ``r-p2`` (:mod:`pipeline.dynamics.models.planetary`), each split
into its halves ``s-p1L``, ``s-p1R`` for a herringbone set
(:mod:`pipeline.dynamics.models.herringbone_planetary`).
"""

from __future__ import annotations

import re
from collections.abc import Sequence

MESH_KIND = {"sun_planet": "s", "planet_ring": "r"}
"""A run's mesh name -> the prefix of its meshes in the dynamic model."""

_PLANETARY = re.compile(r"^([sr])-p(\d+)([LR]?)$")


def planet_meshes(names: Sequence[str], mesh: str) -> dict[str, dict[int, str]]:
    """``{half: {planet: model mesh name}}`` of a run's ``mesh`` among the model's mesh
    ``names``: a planetary set's sun or ring meshes by half ("", "L", "R") and planet; a
    pair's mesh as planet 0 of half ""."""
    kind = MESH_KIND.get(mesh)
    if kind is None:
        return {"": {0: mesh}} if mesh in names else {}
    out: dict[str, dict[int, str]] = {}
    for n in names:
        m = _PLANETARY.match(n)
        if m is not None and m.group(1) == kind:
            out.setdefault(m.group(3), {})[int(m.group(2))] = n
    return out
