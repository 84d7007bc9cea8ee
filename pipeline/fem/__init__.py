"""Finite elements: Gmsh meshing (one session manager), scikit-fem elasticity, solvers.

* ``gmsh_session`` - the only place Gmsh is initialised; meshes leave as plain arrays.
* ``cache`` - meshes on disk keyed by a content hash, written atomically.
* ``tetmesh`` - arrays -> scikit-fem meshes with named surfaces; surface integrals.
* ``elasticity`` - 2D/3D linear elasticity stiffness (scikit-fem forms, fast batched path).
* ``solvers`` - factorise once (CHOLMOD / SuperLU), solve many; AMG-CG for one big solve.
* ``linear_static`` - assemble + clamp + solve all load cases from one factorisation.
* ``groove`` - herringbone sun relief-groove stiffness (seed 002).
"""
