"""Options of the FE stage (``[fe]`` table, ``gearpipe fe``) and the names and defaults the
FE settings take (kept here, free of scikit-fem and Gmsh imports, for the gearbox file)."""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.validation import InputError, check_choice, check_int_range, check_range

PLANE_KINDS = ("plane_strain", "plane_stress")
CUTS = ("clamped", "free")  # sector cut faces
ENDS = ("free", "sliding")  # 3D end faces: traction-free or u_z = 0
FACTOR_METHODS = ("auto", "cholmod", "cholespy", "splu")
SOLVERS = FACTOR_METHODS + ("pmg-cg",)  # what configuration files may name
# graded 2D meshes: element size on unloaded teeth and largest body size (m_n), growth
GRADED_TOOTH = 0.6
GRADED_BODY = 4.0
GRADED_GROWTH = 0.5


MAX_TABLE_POINTS = 8000
"""Most flank points in one influence matrix: its dense ``n x n`` matrices (FE, near
field, structural) take 3 x 8 n^2 bytes (1.4 GiB at 8000) and each point is one solve
(7 ms on a 32k-unknown 2D sector, seconds in 3D)."""


def check_table_points(n: int, what: str, change: str) -> int:
    """Refuse (InputError) an influence matrix of more than :data:`MAX_TABLE_POINTS` flank
    points; ``what`` says how ``n`` was counted (keys as written), ``change`` what to do."""
    if n > MAX_TABLE_POINTS:
        gib = 3 * 8 * n * n / 2**30
        raise InputError(f"{what} = {n} flank points: the influence matrices would need about "
                         f"{gib:.3g} GiB; the limit is {MAX_TABLE_POINTS} points: {change}")
    return n


@dataclass(frozen=True)
class SectorFEOptions:
    """2D sector FE of each gear of a pair.

    Attributes
    ----------
    teeth : teeth in the sector, in [1, 99].
    points : flank points per tooth of the influence matrix, in [2, 1000].
    refinement : mesh refinement (flank element size m_n / (12 refinement)), in [0.1, 20].
    kind : "plane_strain" or "plane_stress".
    """

    teeth: int = 5
    points: int = 40
    refinement: float = 2.0
    kind: str = "plane_strain"

    def __post_init__(self) -> None:
        check_int_range("fe.teeth", self.teeth, 1, 99)
        check_int_range("fe.points", self.points, 2, 1000)
        check_range("fe.refinement", self.refinement, 0.1, 20.0)
        check_choice("fe.kind", self.kind, PLANE_KINDS)
        check_table_points(self.points * self.teeth,
                           f"fe.points x fe.teeth = {self.points} x {self.teeth}",
                           "lower fe.points or fe.teeth")
