"""Finite elements: Gmsh meshing (one session manager), scikit-fem elasticity, solvers.

* ``settings`` / ``mesh_settings`` - the FE model of a gear (``[fe]``: ``FE2DSettings``,
  ``FE3DSettings``) and the mesh of a sector or whole gear (``SectorSettings``, its 3D
  extension ``SectorSettings3D``); no scikit-fem or Gmsh imports.
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
* ``shaft_mesh`` / ``superelement`` - stepped shafts cut into pieces (Gmsh), and a body
  condensed to reference nodes tied to its surfaces (the 3D shaft model of
  :mod:`pipeline.shaft.fe3d`).

The FE compliance sources of the contact solver are in :mod:`pipeline.contact`.
"""

from pipeline._lazy import lazy_exports

# name -> module: imported on first use (the FE modules pull in scikit-fem, Gmsh and
# SciPy, seconds that a run which finds its FE tables in the cache does not need)
_EXPORTS = {
    "FlankPoints": "pipeline.fem.flank",
    "active_radii": "pipeline.fem.flank",
    "flank_points": "pipeline.fem.flank",
    "face_positions": "pipeline.fem.flank_grid",
    "flank_grid": "pipeline.fem.flank_grid",
    "InfluenceMatrix": "pipeline.fem.influence",
    "constrained_dofs": "pipeline.fem.influence",
    "influence_matrix": "pipeline.fem.influence",
    "build_model": "pipeline.fem.linear_static",
    "load_compliance": "pipeline.fem.linear_static",
    "solve_static": "pipeline.fem.linear_static",
    "FE2DSettings": "pipeline.fem.settings",
    "FE3DSettings": "pipeline.fem.settings",
    "patch_loads": "pipeline.fem.patch_loads",
    "PMultigridCG": "pipeline.fem.pmultigrid",
    "SectorMesh2D": "pipeline.fem.sector2d",
    "SectorSettings": "pipeline.fem.mesh_settings",
    "sector_mesh_2d": "pipeline.fem.sector2d",
    "SectorMesh3D": "pipeline.fem.sector3d",
    "SectorSettings3D": "pipeline.fem.mesh_settings",
    "sector_mesh_3d": "pipeline.fem.sector3d",
    "SectorResult": "pipeline.fem.sector_analysis",
    "analyse_sector": "pipeline.fem.sector_analysis",
    "DirectSolver": "pipeline.fem.solvers",
    "solver_named": "pipeline.fem.solvers",
}


__getattr__ = lazy_exports(__name__, _EXPORTS)

__all__ = sorted(_EXPORTS)
