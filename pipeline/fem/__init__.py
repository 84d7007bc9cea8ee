"""Finite elements: Gmsh meshing (one session manager), scikit-fem elasticity, solvers.

* ``gmsh_session`` - the only place Gmsh is initialised; meshes leave as plain arrays.
* ``cache`` - meshes on disk keyed by a content hash, written atomically.
* ``tetmesh`` - arrays -> scikit-fem meshes with named surfaces; surface integrals.
* ``elasticity`` - 2D/3D linear elasticity stiffness (scikit-fem forms, fast batched path).
* ``solvers`` / ``pmultigrid`` - solvers passed in (``DirectSolver``: factorise once with
  CHOLMOD via scikit-sparse or cholespy, else SuperLU; ``PMultigridCG``), AMG-CG for one
  big solve.
* ``linear_static`` - assemble + clamp + one solver set-up for all load cases.
* ``sector2d`` / ``sector3d`` - 2D sectors (or whole gears) and 3D helical (or spur, or
  herringbone-half) sectors: ``sector_mesh_2d`` / ``sector_mesh_3d``; ``teeth = z`` gives a
  whole gear in both (3D geometry in ``whole3d``, size grading in ``grading3d``).
* ``flank`` / ``flank_grid`` - ``FlankPoints`` of 2D profiles and 3D profile x face grids.
* ``patch_loads`` / ``influence`` - one influence routine for 2D and 3D: patch loads,
  constraints, one solver set-up, blocks of right-hand sides, minus the near field of
  ``nearfield_halfplane`` (2D) or ``nearfield_halfspace`` (3D Boussinesq).
* ``groove`` - herringbone sun relief-groove stiffness (Xu et al. (2020)).

The FE compliance sources of the contact solver are in :mod:`pipeline.contact`.
"""

from pipeline.fem.flank import FlankPoints, active_radii, flank_points
from pipeline.fem.flank_grid import face_positions, flank_grid
from pipeline.fem.influence import InfluenceMatrix, constrained_dofs, influence_matrix
from pipeline.fem.linear_static import build_model, load_compliance, solve_static
from pipeline.fem.options import SectorFEOptions
from pipeline.fem.patch_loads import patch_loads
from pipeline.fem.pmultigrid import PMultigridCG
from pipeline.fem.sector2d import SectorMesh2D, SectorSettings2D, sector_mesh_2d
from pipeline.fem.sector3d import SectorMesh3D, SectorSettings3D, sector_mesh_3d
from pipeline.fem.sector_analysis import SectorResult, analyse_sector
from pipeline.fem.solvers import DirectSolver, solver_named

__all__ = [
    "DirectSolver", "FlankPoints", "InfluenceMatrix", "PMultigridCG", "SectorMesh2D",
    "SectorMesh3D", "SectorSettings2D", "SectorSettings3D", "active_radii", "build_model",
    "constrained_dofs", "face_positions", "flank_grid", "flank_points", "influence_matrix",
    "load_compliance", "patch_loads", "sector_mesh_2d", "sector_mesh_3d", "solve_static",
    "solver_named", "SectorFEOptions", "SectorResult", "analyse_sector",
]
