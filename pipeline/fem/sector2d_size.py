"""Size of a 2D sector model before meshing: estimate, and refusal of models too big.

:func:`check_size` is called by :func:`pipeline.fem.sector2d.sector_mesh_2d` before Gmsh
runs, so a refinement too fine for the machine is refused in one line with the
estimated unknowns and memory, instead of running out of memory in Gmsh or the solver.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pipeline.fem.outline2d import inner_radius, outline_pieces
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError

if TYPE_CHECKING:
    from pipeline.fem.mesh_settings import SectorSettings

# FE memory per unknown of a 2D P2 model (stiffness, CHOLMOD factor, loads; peak RSS of
# whole-gear builds of 97k-526k unknowns rose by 2.8 kB per unknown), and the largest
# model accepted (about 14 GiB on a 24 GiB machine)
BYTES_PER_DOF = 3500
MAX_DOF = 4_000_000


def estimated_size(gear: GearSpec, settings: SectorSettings) -> tuple[int, float]:
    """(unknowns, memory in bytes) of the FE model of the mesh ``settings`` would give,
    estimated before meshing (within about 30 %, see :data:`BYTES_PER_DOF`).

    Triangles: the band within ``size/2`` of the outline at its size, the band over which
    the size grows linearly (``int dd / (A_eq h(d)^2)`` per unit outline length), the rest
    of the area at ``size_body``; ``A_eq = sqrt(3)/4 h^2``; two P2 nodes and four unknowns
    per triangle.
    """
    pieces = outline_pieces(gear, settings.teeth, settings.profile_points)
    keep = (None if settings.loaded is None
            else {f"{side}{k}" for k in settings.loaded for side in ("right", "left")})
    length = {True: 0.0, False: 0.0}
    for name, seg in pieces:
        length[keep is None or name in keep] += float(np.hypot(*np.diff(seg, axis=0).T).sum())
    h0, hb = settings.size_flank, settings.size_body
    rate = (hb - h0) / max(settings.grading - 0.5 * h0, 1e-12)
    a_eq = math.sqrt(3.0) / 4.0
    r_in = inner_radius(gear, settings)
    area = math.pi * abs(gear.tip_radius_**2 - r_in**2) * settings.teeth / gear.teeth
    tri = area / (a_eq * hb * hb)
    for fine, size in ((True, h0), (False, settings.size_tooth or h0)):
        band = 0.5 / (a_eq * size) + (1.0 / size - 1.0 / hb) / (a_eq * max(rate, 1e-12))
        tri += length[fine] * band
    tri = min(tri, area / (a_eq * h0 * h0))
    dof = int(4 * tri)
    return dof, dof * BYTES_PER_DOF


def check_size(gear: GearSpec, settings: SectorSettings, max_dof: int = MAX_DOF) -> int:
    """Refuse (InputError) a mesh whose FE model would exceed ``max_dof`` unknowns; returns
    the estimate."""
    dof, mem = estimated_size(gear, settings)
    if dof > max_dof:
        raise InputError(
            f"the 2D mesh of {gear.name or 'the gear'} (flank elements "
            f"{settings.size_flank:.3g} m, "
            f"{settings.teeth} teeth) would have about {dof / 1e6:.1f} million unknowns and "
            f"need about {mem / 2**30:.0f} GiB; the limit is {max_dof / 1e6:.1f} million "
            f"unknowns: use a smaller refinement (or fewer teeth)")
    return dof
