"""Size of a 3D P2 tetrahedral model before meshing: estimate, warn, refuse.

A mesh size that looks harmless in a file (``groove.mesh_size_mm = 0.5`` on a 280 mm
sun) can ask for billions of cells: Gmsh then runs for hours and the solver for ever.
The callers (:func:`pipeline.fem.groove.study.analyse_groove`,
:func:`pipeline.fem.sector3d.sector_mesh_3d`) estimate the cells from the volumes and
the size field before Gmsh runs, and :func:`check_size_3d` refuses a model above
:data:`MAX_DOF` (one line: the estimate, the limit and the key to change) or warns
above :data:`WARN_DOF`.

Cells. A region of volume ``V`` meshed at edge ``h`` holds ``V / (c h^3)`` tetrahedra,
``c`` = :data:`TET_FILL`; a layer graded linearly from
``h0`` to ``hb`` over the distance ``d`` adds per unit area
``d (1/h0^2 - 1/hb^2) / (2 c (hb - h0))`` (:func:`graded_layer_cells`). A P2 mesh has
about :data:`NODES_PER_TET` nodes per tetrahedron (vertices and mid-edge nodes), three
unknowns each. The constants were measured
on real meshes (tests/test_fem_size3d.py states the ratio estimate / actual).

Limits: 800 thousand unknowns refused (about 16 GiB with CHOLMOD), 250 thousand warned
about; 2D sectors (:mod:`pipeline.fem.sector2d_size`) are refused above 4 million. The
estimate names the memory and the key to change: ``groove.mesh_size_mm = 0.5`` (which ran
for ever) is 8.2 billion unknowns. Estimated over actual unknowns, measured on real meshes:
0.80-1.20 for groove bodies (40k-293k unknowns), 0.82-1.15 for 3- and 5-tooth sectors and
whole z 50 gears (18k-352k); ``tests/test_fem_size3d.py`` holds it to 0.7-1.3.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass

from pipeline.validation import InputError

TET_FILL = 0.19
"""Mean volume of a Gmsh tetrahedron meshed at edge ``h``, over ``h^3`` (measured on the
groove bodies: 0.17-0.21; a regular tetrahedron has ``1 / (6 sqrt 2) = 0.118``)."""
NODES_PER_TET = 1.6
"""P2 nodes per tetrahedron (vertices + edges; 1.46-1.74 measured, more on coarse meshes
where the surface holds a larger share)."""
BYTES_PER_DOF = 21_000
"""Peak memory per unknown of a 3D P2 model factorised by CHOLMOD (10.3 GB at 494k
unknowns, measured); the iterative groove solver needs less."""
WARN_DOF = 250_000
"""Above this many unknowns a run takes minutes and gigabytes: say so."""
MAX_DOF = 800_000
"""Largest 3D model accepted (about 16 GiB with CHOLMOD on a 24 GiB machine)."""


class SizeWarning(UserWarning):
    """A model is large enough to take minutes and gigabytes (the estimate is given)."""


@dataclass(frozen=True)
class SizeEstimate:
    """Estimated size of a 3D P2 model.

    Attributes
    ----------
    cells : tetrahedra.
    dof : unknowns (three per P2 node).
    memory : peak memory of assembly and factorisation in bytes.
    """

    cells: float

    @property
    def dof(self) -> int:
        return int(3 * NODES_PER_TET * self.cells)

    @property
    def memory(self) -> float:
        return self.dof * BYTES_PER_DOF


def uniform_cells(volume: float, size: float) -> float:
    """Tetrahedra in ``volume`` (m^3) meshed at edge ``size`` (m)."""
    return volume / (TET_FILL * size**3)


def graded_layer_cells(area: float, h0: float, hb: float, d_fine: float,
                       d_grade: float) -> float:
    """Tetrahedra *added* to a body meshed at ``hb`` by a layer over ``area`` (m^2): edge
    ``h0`` up to the distance ``d_fine`` from the surface, growing linearly to ``hb`` at
    ``d_fine + d_grade`` (m)."""
    if hb <= h0:
        return 0.0
    fine = d_fine * (1.0 / h0**3 - 1.0 / hb**3)
    grown = d_grade * (0.5 * (1.0 / h0**2 - 1.0 / hb**2) / (hb - h0) - 1.0 / hb**3)
    return area * (fine + max(grown, 0.0)) / TET_FILL


def check_size_3d(what: str, estimate: SizeEstimate, change: str, *,
                  max_dof: int = MAX_DOF, warn_dof: int = WARN_DOF) -> SizeEstimate:
    """Refuse (InputError) a model above ``max_dof`` unknowns, warn (:class:`SizeWarning`)
    above ``warn_dof``; ``what`` names the model, ``change`` says which key to change."""
    dof, gib = estimate.dof, estimate.memory / 2**30
    text = (f"the 3D mesh of {what} would have about {_count(dof)} unknowns and need about "
            f"{gib:.2g} GiB")
    if dof > max_dof:
        raise InputError(f"{text}; the limit is {_count(max_dof)} unknowns: {change}")
    if dof > warn_dof:
        warnings.warn(f"{text} (minutes of meshing and solving; above {_count(warn_dof)} "
                      f"unknowns: {change} for a quicker run)", SizeWarning, stacklevel=2)
    return estimate


def _count(n: float) -> str:
    for scale, word in ((1e9, "billion"), (1e6, "million"), (1e3, "thousand")):
        if n >= scale:
            return f"{n / scale:.3g} {word}"
    return f"{n:.0f}"
