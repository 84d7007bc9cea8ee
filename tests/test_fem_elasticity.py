"""Fast batched elasticity assembly against scikit-fem's generic form (the reference).

Both assemble the same bilinear form on the same quadrature, so they must agree
to round-off (relative 1e-12) on 2D and 3D, P1 and P2, affine and curved cells.
"""

from __future__ import annotations

import numpy as np
import pytest
from skfem import MeshTet, MeshTet2, MeshTri

from pipeline.fem.elasticity import (
    assemble_fast,
    assemble_generic,
    assemble_stiffness,
    lame_constants,
    vector_basis,
)
from pipeline.geometry.gear import Material
from pipeline.validation import InputError

MESHES = {
    "tri": lambda: MeshTri.init_symmetric().refined(3),
    "tet": lambda: MeshTet.init_tensor(*(np.linspace(0, 1, 4),) * 2, np.linspace(0, 2, 5)),
    "tet2-curved": lambda: MeshTet2.init_ball(1),
}


@pytest.mark.parametrize("name", list(MESHES))
@pytest.mark.parametrize("order", [1, 2])
def test_fast_matches_generic(name, order):
    mesh = MESHES[name]()
    # Distort affine meshes so that every element has a different Jacobian.
    if mesh.affine:
        rng = np.random.default_rng(1)
        mesh = type(mesh)(mesh.p + 0.02 * rng.standard_normal(mesh.p.shape), mesh.t)
    basis = vector_basis(mesh, order)
    lam, mu = 1.7e11, 0.8e11
    A = assemble_generic(basis, lam, mu)
    # Small chunks to exercise the chunked accumulation.
    B = assemble_fast(mesh, lam, mu, order, chunk=17, quadrature=(basis.X, basis.W))
    assert A.shape == B.shape
    assert abs(A - B).max() <= 1e-12 * abs(A).max()
    C = assemble_stiffness(basis, lam, mu, "fast")
    assert abs(A - C).max() <= 1e-12 * abs(A).max()


def test_rigid_modes_in_null_space():
    """K times a rigid motion is zero (the form only sees symmetric gradients)."""
    from pipeline.fem.linear_static import rigid_body_modes

    mesh = MeshTet2.init_ball(1)
    basis = vector_basis(mesh, 2)
    K = assemble_fast(mesh, 1.0, 1.0, 2)
    R = rigid_body_modes(basis.doflocs[:, ::3])
    assert np.abs(K @ R).max() < 1e-11 * abs(K).max()


def test_lame_plane_stress():
    """lambda* = E nu / (1 - nu^2) for plane stress; mu = E / 2(1 + nu) always."""
    m = Material(youngs_modulus=2.0e11, poisson_ratio=0.25)
    lam3, mu3 = lame_constants(m, "3d")
    lam_s, mu_s = lame_constants(m, "plane_stress")
    assert lam3 == pytest.approx(2e11 * 0.25 / (1.25 * 0.5))
    assert lam_s == pytest.approx(2e11 * 0.25 / (1 - 0.0625))
    assert mu3 == mu_s == pytest.approx(2e11 / 2.5)
    with pytest.raises(InputError, match="elasticity.kind"):
        lame_constants(m, "axisymmetric")
