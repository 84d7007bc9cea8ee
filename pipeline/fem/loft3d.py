"""What the swept 3D models (sectors lofted in :mod:`pipeline.fem.sector3d`; whole gears
twisted in :mod:`pipeline.fem.whole3d`) are built from: the hand of each helical half,
the checked tooth count, bore radius, meshed width and twist rate, the outline pieces,
and the meshing options (Gmsh's curved P2 for the sectors, linear tetrahedra for the
whole gears, which place their own P2 nodes). Gmsh is passed in (the session lives in
:mod:`pipeline.fem.gmsh_session`). Lengths in m, angles in rad.
"""

from __future__ import annotations

import math

from pipeline.fem.mesh_settings import SectorSettings3D, meshed_width
from pipeline.fem.outline2d import inner_radius, outline_pieces
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError


def helix_sign(gear: GearSpec, half: int = 0) -> int:
    """+1 (right hand), -1 (left hand) or 0 (spur) for ``half`` of ``gear``."""
    s = {"right": 1, "left": -1, "none": 0}[gear.hand]
    return -s if (gear.herringbone and half == 1) else s


def generate_curved_tets(gmsh) -> None:
    """Mesh the synchronised model with curved P2 tetrahedra (sectors and whole gears).

    ``HighOrderOptimize`` untangles curved cells that come out inverted (found: one in a
    5-tooth sector at refinement 0.6, which a factorisation reports only as "not positive
    definite"; large cells on the fillets of a whole gear's coarse teeth).
    """
    gmsh.option.setNumber("Mesh.ElementOrder", 2)
    gmsh.option.setNumber("Mesh.SecondOrderLinear", 0)
    gmsh.option.setNumber("Mesh.HighOrderOptimize", 1)
    generate_linear_tets(gmsh)


def generate_linear_tets(gmsh) -> None:
    """Mesh the synchronised model with tetrahedra (Frontal-Delaunay surfaces, Delaunay
    volume, Gmsh's quality optimisation); linear unless ``Mesh.ElementOrder`` was set."""
    gmsh.option.setNumber("Mesh.Algorithm", 6)
    gmsh.option.setNumber("Mesh.Algorithm3D", 1)
    gmsh.option.setNumber("Mesh.Optimize", 1)
    gmsh.model.mesh.generate(3)


def check_sector_teeth(gear: GearSpec, settings: SectorSettings3D) -> None:
    """External gears only; ``teeth`` < z/2 (a sector) or = z (the whole gear)."""
    if gear.internal:
        raise InputError(f"{gear.name}: the 3D sector mesh supports external gears only")
    if 2 * settings.teeth >= gear.teeth and settings.teeth != gear.teeth:
        raise InputError(f"sector.teeth = {settings.teeth} must be < z/2 = {gear.teeth / 2:g} "
                         f"or = z (whole gear)")
    if settings.reach is not None and settings.teeth != gear.teeth:
        raise InputError(f"sector.reach = {settings.reach} applies to whole gears only "
                         f"(sector.teeth = {settings.teeth}, z = {gear.teeth})")


def loft_inputs(gear: GearSpec, settings: SectorSettings3D, teeth: int
                ) -> tuple[float, float, float, list]:
    """What a lofted 3D model of ``teeth`` teeth is built from, after checking the tooth
    count: bore radius (m), meshed width (m), twist rate along the face (rad/m, signed by
    the hand) and the outline pieces of :func:`pipeline.fem.outline2d.outline_pieces`."""
    check_sector_teeth(gear, settings)
    rate = helix_sign(gear, settings.half) * math.tan(gear.helix_angle) / gear.reference_radius
    return (inner_radius(gear, settings), meshed_width(gear), rate,
            outline_pieces(gear, teeth, settings.profile_points))
