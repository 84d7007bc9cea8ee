"""p-multigrid CG (scipy only) against SuperLU on a 3D P2 elasticity problem.

The two-level preconditioner interpolates vertex (P1) displacements to the P2
nodes; that interpolation must reproduce linear fields exactly, and CG with it
must give the direct solution to the requested residual on every right-hand side.
"""

from __future__ import annotations

import numpy as np
import pytest
from skfem import MeshTet

from pipeline.fem.linear_static import build_model
from pipeline.fem.pmultigrid import p1_prolongation, pmg_cg
from pipeline.fem.solvers import factorize_spd
from pipeline.geometry.gear import Material
from pipeline.validation import InputError


@pytest.fixture(scope="module")
def beam():
    """Clamped P2 bar 1 x 0.1 x 0.1 m, three tip load cases (x, y, z)."""
    mesh = MeshTet.init_tensor(np.linspace(0, 1, 11), np.linspace(0, 0.1, 3),
                               np.linspace(0, 0.1, 3))
    model = build_model(mesh, Material(), order=2)
    clamp = model.basis.get_dofs(lambda x: x[0] < 1e-12).flatten()
    free = np.setdiff1d(np.arange(model.n_dof), clamp)
    tip = model.basis.get_dofs(lambda x: x[0] > 1 - 1e-12).flatten()
    F = np.zeros((model.n_dof, 3))
    for k in range(3):
        F[tip[tip % 3 == k], k] = 1.0
    return model, free, F


def test_prolongation_reproduces_linear_fields(beam):
    """P (vertex values of u = A x + c) equals u at every P2 node, to round-off."""
    model, _, _ = beam
    P, nv = p1_prolongation(model.basis)
    nodes = model.basis.doflocs[:, ::3]
    A = np.array([[1.0, 2.0, -1.0], [0.5, -3.0, 2.0], [4.0, 1.0, 0.25]])
    u = (A @ nodes + np.array([[1.0], [2.0], [3.0]])).T.ravel()  # DOF 3 node + comp
    coarse = (A @ nodes[:, :nv] + np.array([[1.0], [2.0], [3.0]])).T.ravel()
    np.testing.assert_allclose(P @ coarse, u, atol=1e-12 * np.abs(u).max())


def test_pmg_cg_matches_superlu(beam):
    """All three load cases agree with SuperLU to 1e-8 relative (rtol 1e-11)."""
    model, free, F = beam
    A = model.stiffness[free][:, free]
    P, _ = p1_prolongation(model.basis)
    res = pmg_cg(A, F[free], P[free], rtol=1e-11)
    ref = factorize_spd(A, "splu").solve(F[free])
    assert res.residual <= 1e-11 and 0 < res.iterations < 100
    np.testing.assert_allclose(res.x, ref, atol=1e-8 * np.abs(ref).max())
    one = pmg_cg(A, F[free, 0], P[free], rtol=1e-11)  # 1D right-hand side keeps its shape
    assert one.x.shape == (free.size,)


def test_pmg_bad_inputs(beam):
    """A P1 basis has no edge nodes to prolongate to; rtol out of range is refused."""
    model, free, F = beam
    p1 = build_model(model.basis.mesh, Material(), order=1)
    with pytest.raises(InputError, match="P2"):
        p1_prolongation(p1.basis)
    P, _ = p1_prolongation(model.basis)
    with pytest.raises(InputError, match="pmg.rtol"):
        pmg_cg(model.stiffness[free][:, free], F[free], P[free], rtol=0.5)
