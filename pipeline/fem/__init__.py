"""Finite elements: Gmsh meshing (one session manager), scikit-fem elasticity, solvers.

* ``gmsh_session`` - the only place Gmsh is initialised; meshes leave as plain arrays.
* ``cache`` - meshes on disk keyed by a content hash, written atomically.
* ``tetmesh`` - arrays -> scikit-fem meshes with named surfaces; surface integrals.
* ``elasticity`` - 2D/3D linear elasticity stiffness (scikit-fem forms, fast batched path).
* ``solvers`` - factorise once (CHOLMOD via scikit-sparse or cholespy, else SuperLU), solve
  many; AMG-CG for one big solve.
* ``linear_static`` - assemble + clamp + solve all load cases from one factorisation.
* ``sector2d`` / ``flank`` / ``influence`` / ``hertz_separation`` - 2D tooth sectors,
  flank points, compliance matrices, half-plane near field.
* ``sector3d`` / ``flank3d`` / ``influence3d`` / ``halfspace_separation`` - the same in
  3D: helical (or spur, or herringbone-half) sectors, profile x face-width flank grids,
  compliance matrices in m/N, Boussinesq near field.
* ``groove`` - herringbone sun relief-groove stiffness (Xu et al. 2020).
"""
