"""Exact static condensation of a body's far part (pipeline.fem.condensation) and the Schur
complement it rests on (pipeline.fem.solvers.schur_complement).

Ladder of checks:
* exact: the Schur complement of every factorisation method equals the dense formula
  ``K_gg - K_gi K_ii^-1 K_ig`` (a random sparse SPD matrix, to round-off);
* exact: a condensed system solves, on the unknowns it keeps, exactly what the whole
  system solves for loads on them (a 3D P2 elasticity model of a clamped bar, the far
  end eliminated);
* the whole 3D gear: its flank compliances with the far body condensed equal those of one
  factorisation of the whole (same matrix, another elimination order), and fewer unknowns
  are factorised;
* the far part by angle: the span of the near points is measured from their circular
  mean, so a span across +-pi is whole; bad masks and requests are refused.
"""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest
import scipy.sparse as sp
from skfem import MeshTet

from pipeline.cache.folder import Cache
from pipeline.fem.condensation import condense, far_by_angle
from pipeline.fem.flank_grid import flank_grid
from pipeline.fem.influence import influence_matrix
from pipeline.fem.linear_static import build_model, compliance_blocks, free_system
from pipeline.fem.mesh_settings import SectorSettings, SectorSettings3D
from pipeline.fem.pmultigrid import PMultigridCG
from pipeline.fem.sector2d import sector_mesh_2d
from pipeline.fem.sector3d import sector_mesh_3d
from pipeline.fem.solvers import (
    DirectSolver,
    pardiso_available,
    schur_complement,
)
from pipeline.geometry.gear import GearSpec, Material
from pipeline.validation import InputError

METHODS = ["splu", "cholespy"] + (["pardiso"] if pardiso_available() else [])


def _random_spd(n: int, seed: int) -> sp.csr_matrix:
    A = sp.random(n, n, density=0.02, random_state=seed)
    return (A @ A.T + 5.0 * sp.eye(n)).tocsr()


@pytest.mark.parametrize("method", METHODS)
def test_schur_complement_is_the_dense_formula(method):
    K = _random_spd(300, 2)
    g = np.zeros(300, dtype=bool)
    g[np.random.default_rng(1).choice(300, 40, replace=False)] = True
    D, i = K.toarray(), ~g
    exact = D[np.ix_(g, g)] - D[np.ix_(g, i)] @ np.linalg.solve(D[np.ix_(i, i)],
                                                                D[np.ix_(i, g)])
    S = schur_complement(sp.triu(K, format="csr"), g, method)
    assert np.abs(S - exact).max() < 1e-12 * np.abs(exact).max()


def test_schur_complement_refuses_an_empty_or_full_interface():
    U = sp.triu(_random_spd(20, 3), format="csr")
    for g in (np.zeros(20, bool), np.ones(20, bool), np.ones(19, bool)):
        with pytest.raises(InputError, match="interface"):
            schur_complement(U, g)


@pytest.fixture(scope="module")
def bar():
    """A 3D P2 steel bar 0.1 x 0.02 x 0.02 m clamped at x = 0: (model, clamped DOFs)."""
    mesh = MeshTet.init_tensor(np.linspace(0, 0.1, 11), np.linspace(0, 0.02, 3),
                               np.linspace(0, 0.02, 3))
    model = build_model(mesh, Material(), order=2, kind="3d")
    clamped = np.flatnonzero(model.dofs.doflocs[0] < 1e-12)
    return model, clamped


@pytest.mark.parametrize("method", METHODS)
def test_a_condensed_system_solves_exactly_what_the_whole_does(bar, method):
    model, clamped = bar
    x = model.dofs.doflocs[0]
    far = x < 0.045  # the clamped half, eliminated; the loads and reading at the tip
    tip = np.flatnonzero(x > 0.1 - 1e-12)
    F = sp.csc_matrix((np.ones(tip.size), (tip, np.arange(tip.size) % 3)),
                      shape=(model.n_dof, 3))
    whole = compliance_blocks(*_set_up(model, clamped, method, None), F)
    cond = compliance_blocks(*_set_up(model, clamped, method, far), F)
    assert cond.n_free < 0.7 * whole.n_free
    assert np.abs(cond.matrix - whole.matrix).max() < 1e-10 * np.abs(whole.matrix).max()
    # a transverse tip load bends the bar (L / h = 5): (L / h)^2 4 = 100 times the axial
    # compliance in beam theory, so the compliances compared are not round-off
    assert 50 * whole.matrix[0, 0] < whole.matrix[1, 1] < 150 * whole.matrix[0, 0]


def _set_up(model, clamped, method, far):
    free, factorize = free_system(model, clamped, DirectSolver(method), far)
    return factorize(), free


def test_condensation_refuses_bad_masks_and_iterative_solvers(bar):
    model, clamped = bar
    U = sp.triu(_random_spd(20, 4), format="csr")
    for far in (np.zeros(20, bool), np.ones(20, bool)):
        with pytest.raises(InputError, match="far"):
            condense(U, far)
    with pytest.raises(InputError, match="direct solver"):
        free_system(model, clamped, PMultigridCG(), model.dofs.doflocs[0] < 0.05)


def test_the_condensed_matrix_is_the_schur_complement_in_place():
    K = _random_spd(200, 5)
    far = np.arange(200) >= 120
    c = condense(sp.triu(K, format="csr"), far)
    full = (c.upper + sp.triu(c.upper, k=1).T).toarray()
    D = K.toarray()
    kept = ~far
    exact = D[np.ix_(kept, kept)] - D[np.ix_(kept, far)] @ np.linalg.solve(
        D[np.ix_(far, far)], D[np.ix_(far, kept)])
    assert np.array_equal(c.kept, np.flatnonzero(kept))
    assert c.n_far == 80 and 0 < c.n_interface <= 120
    assert np.abs(full - exact).max() < 1e-12 * np.abs(exact).max()


def test_far_by_angle_measures_the_span_across_pi():
    angle = np.radians(np.arange(-180, 180, 5.0))
    points = np.vstack([np.cos(angle), np.sin(angle), np.zeros_like(angle)])
    near = np.abs(np.abs(np.degrees(angle)) - 180) <= 10.01  # 170 .. 180 .. -170 deg
    far = far_by_angle(points, near, np.radians(7))
    assert not far[near].any()
    off = 180 - np.abs(np.degrees(angle))  # angle from 180 deg
    assert np.array_equal(far, off > 17.01)


KW = dict(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.015)
HELICAL = GearSpec(face_width=6e-3, helix_angle=math.radians(15), hand="right", **KW)


def test_whole_gear_compliances_with_the_far_body_condensed():
    loaded = (14, 15, 16)
    s = replace(SectorSettings3D.whole_gear(HELICAL, loaded, 0.6), reach=None)
    sec = sector_mesh_3d(HELICAL, s, cache=Cache.off())
    pts = flank_grid(sec, loaded, [HELICAL.reference_radius], np.linspace(0, 6e-3, 3))
    # the default leaves a model this small whole (CONDENSE_MIN_DOFS)
    whole = influence_matrix(sec, pts, solver=DirectSolver())
    cond = influence_matrix(sec, pts, condense=True, solver=DirectSolver())
    assert whole.n_condensed == 0 and whole.n_free == cond.n_free
    assert cond.n_condensed > 0.4 * cond.n_free  # most of the body is far from 3 teeth
    assert np.abs(cond.fe - whole.fe).max() < 1e-9 * np.abs(whole.fe).max()


def test_condensation_needs_a_whole_3d_gear():
    gear = replace(HELICAL, helix_angle=0.0, hand="none")
    sec = sector_mesh_2d(gear, SectorSettings.for_gear(gear, 5, 0.5), cache=Cache.off())
    from pipeline.fem.flank import flank_points

    pts = flank_points(gear, 5, [2], [gear.reference_radius])
    with pytest.raises(InputError, match="condense"):
        influence_matrix(sec, pts, condense=True)
