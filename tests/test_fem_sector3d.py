"""3D helical tooth sectors: mesh, flank grid, influence coefficients, Boussinesq separation.

Ladder of checks:
* geometry: the mesh volume equals the section area times the width (a helical twist
  turns sections rigidly, so the exact volume is the extruded one); flank groups sit
  on the right side of the right tooth; grid points lie on the meshed flank with the
  meshed normal;
* half-space kernel: its integral along a line is the 2D plane-strain kernel
  (exact identity); the patch autocorrelation against a numerical convolution;
  the polar quadrature against brute force; H -> Delta for distant patches;
* FE: Maxwell-Betti symmetry, positive definiteness, rim coupling, solver agreement;
* 3D vs 2D: a spur sector with sliding end faces (u_z = 0) under a load uniform across
  the face is a plane-strain problem, so the 3D compliance per unit width must equal
  the 2D plane-strain one up to discretisation; with free end faces mid-face lies
  between plane strain and plane stress.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.integrate import quad
from skfem.quadrature import get_quadrature
from skfem.refdom import RefTri

from pipeline.cache.folder import Cache
from pipeline.fem.flank import active_radii, flank_points
from pipeline.fem.flank_grid import face_positions, flank_grid
from pipeline.fem.influence import influence_matrix
from pipeline.fem.loft3d import helix_sign
from pipeline.fem.mesh_settings import SectorSettings, SectorSettings3D
from pipeline.fem.nearfield_halfplane import halfplane_kernel
from pipeline.fem.nearfield_halfspace import (
    halfspace_kernel,
    patch_autocorrelation_1d,
    patch_halfspace_compliance,
    singular_integral,
)
from pipeline.fem.pmultigrid import PMultigridCG
from pipeline.fem.sector2d import sector_mesh_2d
from pipeline.fem.sector3d import section_area, sector_mesh_3d
from pipeline.fem.solvers import DirectSolver, solver_named
from pipeline.fem.tetmesh import tri_shape
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError

KW = dict(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.03)
SPUR = GearSpec(face_width=6e-3, **KW)
HELICAL = GearSpec(face_width=6e-3, helix_angle=math.radians(15), hand="right", **KW)
C = 0.3 * KW["module"]  # default patch half-width


@pytest.fixture(scope="module")
def cache(tmp_path_factory):
    return tmp_path_factory.mktemp("meshes3d")


@pytest.fixture(scope="module")
def helical(cache):
    return sector_mesh_3d(HELICAL, SectorSettings3D.for_gear(HELICAL, 3, 0.6), cache=Cache(cache))


# ---- geometry -----------------------------------------------------------------------------
@pytest.mark.parametrize("gear", [SPUR, HELICAL], ids=["spur", "helical"])
def test_volume_is_extruded_section(gear, cache):
    """|V_mesh / (A b) - 1| < 5e-4. Measured 4e-5 (spur) and 6e-6 (helical): the splines
    through the section points vs its polyline, and the loft between sections; the
    tolerance is 10x that, far below a lost tooth (~4 % of the volume) or a wrong width."""
    s = SectorSettings3D.for_gear(gear, 3, 0.6)
    sec = sector_mesh_3d(gear, s, cache=Cache(cache))
    exact = section_area(gear, 3, s.profile_points, sec.inner_radius) * gear.face_width
    assert sec.volume() == pytest.approx(exact, rel=5e-4)


def test_herringbone_half_has_opposite_twist(cache):
    """Half 1 of a herringbone gear twists the other way, half as wide as the face."""
    g = GearSpec(face_width=12e-3, helix_angle=math.radians(20), hand="left", herringbone=True,
                 groove_width=5e-3, **KW)
    assert helix_sign(g, 0) == -1 and helix_sign(g, 1) == 1
    s = SectorSettings3D.for_gear(g, 1, 0.5, half=1)
    sec = sector_mesh_3d(g, s, cache=Cache(cache))
    assert sec.width == pytest.approx(6e-3)
    assert sec.twist_rate == pytest.approx(math.tan(g.helix_angle) / g.reference_radius)
    exact = section_area(g, 1, s.profile_points, sec.inner_radius) * 6e-3
    assert sec.volume() == pytest.approx(exact, rel=5e-4)
    with pytest.raises(InputError, match="half"):
        sector_mesh_3d(HELICAL, SectorSettings3D(half=1), cache=Cache.off())


def test_flank_groups_lie_on_their_tooth_side(helical):
    """Every node of ``right{k}`` (``left{k}``), turned back to mid-face, lies within half a
    pitch clockwise (counter-clockwise) of tooth k's centre line; all groups present.
    Tolerance 1e-5 rad (0.5 um at the tip): the loft between sections strays from the
    exact helix by ~3e-7 rad (measured) at the tip-land and tooth-space middles."""
    z = HELICAL.teeth
    mesh = helical.mesh
    for name in ("bore", "cut_left", "cut_right", "end0", "end1"):
        assert helical.facets[name].size > 0
    for k in range(3):
        centre = math.pi / 2 + (k - 1) * 2 * math.pi / z
        for side, sgn in (("right", -1), ("left", 1)):
            nodes = np.unique(helical.tets.triangles[f"{side}{k}"])
            x, y, zz = mesh.doflocs[:, nodes]
            ang = np.arctan2(y, x) - helical.twist(zz) - centre
            assert np.all(sgn * ang > -1e-5)
            assert np.all(sgn * ang < math.pi / z + 1e-5)


def test_grid_points_on_meshed_flank_with_its_normal(helical):
    """Grid points lie on the meshed flank (distance to the tangent plane of the nearest
    surface quadrature point < 10 um, the loft + P2 geometric error at this coarse mesh)
    and their analytical normal (with its axial tilt) matches the meshed one within 3 deg
    (the nearest quadrature point is < 0.3 mm away on a flank of curvature radius > 8 mm)."""
    pts = flank_grid(helical, [1], active_radii(HELICAL, 5, margin=1.5 * C),
                     face_positions(helical.width, 4, 1.5 * C))
    tri = helical.tets.triangles["right1"]
    X, _ = get_quadrature(RefTri, 8)
    N, dN = tri_shape(X, 6)
    xe = helical.mesh.doflocs[:, tri]
    q = np.einsum("cnf,nq->cfq", xe, N).reshape(3, -1).T
    tang = np.einsum("cnf,ndq->cdfq", xe, dN)
    n = np.cross(tang[:, 0], tang[:, 1], axis=0).reshape(3, -1).T
    n /= np.linalg.norm(n, axis=1)[:, None]
    near = np.argmin(((q[None] - pts.position[:, None]) ** 2).sum(-1), axis=1)
    d = pts.position - q[near]
    assert np.abs(np.einsum("ij,ij->i", d, n[near])).max() < 1e-5
    cosang = np.abs(np.einsum("ij,ij->i", pts.normal, n[near]))
    assert cosang.min() > math.cos(math.radians(3))
    # the helical flank normal leans out of the transverse plane
    assert np.all(np.abs(pts.normal[:, 2]) > 0.1)


# ---- half-space near field ------------------------------------------------------------------
def test_halfspace_kernel_integrates_to_plane_strain_kernel():
    """int Delta(sqrt(u^2 + y^2), h) dy over all y = the 2D plane-strain kernel (exact)."""
    mat = SPUR.material
    for u, h in ((0.3e-3, 2e-3), (2e-3, 1e-3)):
        val = 2 * quad(lambda y, u=u, h=h: halfspace_kernel(math.hypot(u, y), h, mat), 0, np.inf,
                       limit=200, epsabs=0)[0]
        assert val == pytest.approx(float(halfplane_kernel(u, h, mat)), rel=1e-7)


def test_patch_autocorrelation_and_polar_quadrature():
    """Closed-form R_1 vs a numerical convolution (1e-6 of its peak); the polar singular
    integral vs a brute-force midpoint sum (converges like 1/N: 0.3 % at N = 800)."""
    c = 1.0
    t = np.linspace(-c, c, 4001)
    qv = np.cos(np.pi * t / (2 * c)) ** 2 / c
    R = np.convolve(qv, qv[::-1]) * (t[1] - t[0])
    v = (np.arange(R.size) - 4000) * (t[1] - t[0])
    assert np.abs(patch_autocorrelation_1d(v, c) - R).max() < 1e-6 * R.max()
    x = (np.arange(800) + 0.5) / 800 * 4 - 2
    vt, vw = np.meshgrid(x, x, indexing="ij")
    Rv = patch_autocorrelation_1d(vt, 1.0) * patch_autocorrelation_1d(vw, 1.0) * (4 / 800) ** 2
    for st, sw in ((0.0, 0.0), (0.7, 0.3), (3.0, 1.0)):
        brute = np.sum(Rv / np.hypot(st - vt + 1e-9, sw - vw))
        assert singular_integral(st, sw) == pytest.approx(brute, rel=3e-3)


def test_patch_compliance_tends_to_point_kernel():
    """Patches far apart act like point loads: |H(s) / Delta(s) - 1| < 3 (c/s)^2 at s = 15 c,
    and H is continuous where the tabulated part hands over to the Gauss rule (8 c)."""
    mat, c, h = SPUR.material, 0.5e-3, 1e-3
    s = 15 * c
    H = patch_halfspace_compliance(s, 0.0, h, c, mat)
    assert H / halfspace_kernel(s, h, mat) == pytest.approx(1.0, abs=3 * (c / s) ** 2)
    e = np.array([7.999, 8.001]) * c
    Hs = patch_halfspace_compliance(e, 0.5 * c, h, c, mat)
    assert Hs[0] == pytest.approx(Hs[1], rel=1e-3)


# ---- FE influence matrix ----------------------------------------------------------------------
@pytest.fixture(scope="module")
def helical_G(helical):
    pts = flank_grid(helical, [0, 1, 2], active_radii(HELICAL, 4, margin=1.5 * C),
                     face_positions(helical.width, 3, 1.5 * C))
    return influence_matrix(helical, pts, solver=DirectSolver("splu"))


def test_symmetric_positive_definite_with_rim_coupling(helical_G):
    """3 teeth x 3 face x 4 profile points: |G - G^T| < 1e-12 |G|; G_FE positive definite
    (Cholesky); the structural diagonal positive; the tip point of the middle tooth at
    mid-face moves both neighbours (rim coupling) by a positive amount below its own."""
    G = helical_G
    assert G.symmetry_error() < 1e-12
    np.linalg.cholesky(0.5 * (G.fe + G.fe.T))
    S = G.structural
    assert np.all(np.diag(S) > 0)
    i = 12 + 4 + 3  # tooth 1, mid-face, highest point
    for other in (slice(0, 12), slice(24, 36)):
        cross = S[i, other].max() / S[i, i]
        assert 1e-3 < cross < 0.5


def test_pmg_cg_agrees_with_direct(helical, helical_G):
    """The default solver without CHOLMOD (p-multigrid CG, rtol 1e-9, blocks of 10
    right-hand sides) gives the SuperLU matrix to 1e-7 of its largest entry."""
    G = influence_matrix(helical, helical_G.points, solver=PMultigridCG(rtol=1e-9), block=10)
    assert G.method == "pmg-cg" and G.iterations > 0
    assert np.abs(G.fe - helical_G.fe).max() < 1e-7 * np.abs(helical_G.fe).max()
    with pytest.raises(InputError, match="solver.method"):
        influence_matrix(helical, helical_G.points, solver=solver_named("mumps"))


def _line_load_compliance(gear: GearSpec, refinement: float, ends: str, radius: float,
                          cache) -> tuple[float, float]:
    """(FE, structural) approach at mid-face per unit line load (m^2/N) of a spur sector.

    A row of patches at ``radius`` spaced by their half-width c, from end face to end
    face, with trapezoidal weights, sums to a uniform line load of 1/c N/m (cos^2
    patches spaced by c are a partition of unity; the end patches are cut in half).
    """
    b = gear.face_width
    nz = 7
    cz = b / (nz - 1)
    sec = sector_mesh_3d(gear, SectorSettings3D.for_gear(gear, 3, refinement), cache=Cache(cache))
    pts = flank_grid(sec, [1], [radius], np.linspace(0.0, b, nz))
    G = influence_matrix(sec, pts, patch_half_width=cz, solver=DirectSolver("splu"), ends=ends)
    w = np.full(nz, cz)
    w[[0, -1]] *= 0.5
    return float(G.fe[nz // 2] @ w), float(G.structural[nz // 2] @ w)


@pytest.fixture(scope="module")
def plane_2d():
    """2D plane-strain and plane-stress compliances (m^2/N) at the pitch point, c = 1 mm."""
    sec = sector_mesh_2d(SPUR, SectorSettings.for_gear(SPUR, 3, 1.0), cache=Cache.off())
    pts = flank_points(SPUR, 3, [1], [SPUR.reference_radius])
    return {k: influence_matrix(sec, pts, patch_half_width=1e-3, kind=k)
            for k in ("plane_strain", "plane_stress")}


def test_spur_sector_with_sliding_ends_is_plane_strain(plane_2d, cache):
    """Spur sector, u_z = 0 on the end faces, uniform line load: 3D per unit width vs the
    2D plane-strain matrix at the pitch point. Measured 0.980 (FE) and 0.972 (structural)
    at refinement 1 (0.948 / 0.933 at 0.6): the coarse 3D mesh is stiffer, as a displacement
    FE model must be. Band: [0.95, 1.005]."""
    fe, st = _line_load_compliance(SPUR, 1.0, "sliding", SPUR.reference_radius, cache)
    ref = plane_2d["plane_strain"]
    assert 0.95 < fe / ref.fe[0, 0] < 1.005
    assert 0.95 < st / ref.structural[0, 0] < 1.005


def test_spur_mid_face_between_plane_strain_and_plane_stress(plane_2d, cache):
    """Free end faces: mid-face of a 2 m_n wide tooth is more compliant than plane strain
    (measured +5.9 % structural) and less than plane stress (the ends' limit)."""
    _, st = _line_load_compliance(SPUR, 1.0, "free", SPUR.reference_radius, cache)
    assert plane_2d["plane_strain"].structural[0, 0] < st
    assert st < plane_2d["plane_stress"].structural[0, 0]


# ---- slow: convergence ----------------------------------------------------------------------
@pytest.mark.slow
def test_plane_strain_limit_converges(cache):
    """Spur sector with sliding ends vs 2D plane strain (refinement 2, converged to 0.02 %
    against refinement 1) at refinements 1, 1.5, 2 (18k-65k DOF, ~20 s in all): the gap
    shrinks monotonically, at a fitted rate > 1.2 in the flank element size (measured
    2.1 for the FE value, 1.6 for the structural one) and is < 1.5 % at the finest
    (measured 0.5 % FE, 0.9 % structural)."""
    sec = sector_mesh_2d(SPUR, SectorSettings.for_gear(SPUR, 3, 2.0), cache=Cache.off())
    ref = influence_matrix(sec, flank_points(SPUR, 3, [1], [SPUR.reference_radius]),
                           patch_half_width=1e-3)
    refinements = np.array([1.0, 1.5, 2.0])
    gaps = []
    for r in refinements:
        fe, st = _line_load_compliance(SPUR, r, "sliding", SPUR.reference_radius, cache)
        gaps.append((1 - fe / ref.fe[0, 0], 1 - st / ref.structural[0, 0]))
    gaps = np.array(gaps)
    assert np.all(gaps > 0)  # the 3D mesh is stiffer
    assert np.all(np.diff(gaps, axis=0) < 0)
    for col in range(2):
        rate = np.polyfit(np.log(1 / refinements), np.log(gaps[:, col]), 1)[0]
        assert rate > 1.2
    assert gaps[-1].max() < 0.015


@pytest.mark.slow
def test_structural_compliance_independent_of_patch_width(cache):
    """Helical sector, pitch point at mid-face, c = 0.9 and 1.2 mm: the structural self
    compliance changes < 2.5 % while the raw FE one changes > 8 % (measured at refinement
    2, 66k DOF: 1.0 % vs 12 %); refinement 1 -> 2 shrinks the structural spread between
    c = 0.6 and 0.9 mm (measured 25 % -> 5.6 %: the smallest patch needs a finer mesh)."""
    spread = {}
    for r in (1.0, 2.0):
        sec = sector_mesh_3d(HELICAL, SectorSettings3D.for_gear(HELICAL, 3, r), cache=Cache(cache))
        pts = flank_grid(sec, [1], [HELICAL.reference_radius], [0.5 * sec.width])
        vals = np.array([[g.fe[0, 0], g.structural[0, 0]] for g in
                         (influence_matrix(sec, pts, patch_half_width=c)
                          for c in (0.6e-3, 0.9e-3, 1.2e-3))])
        spread[r] = vals / vals[1]
    fine = spread[2.0]
    assert abs(fine[2, 1] - 1) < 0.025
    assert abs(fine[2, 0] - 1) > 0.08
    assert abs(fine[0, 1] - 1) < abs(spread[1.0][0, 1] - 1)


def test_fast_assembly_matches_skfem_form_on_sector(helical):
    """On the curved lofted sector mesh the batched assembly used by the influence
    matrix equals scikit-fem's own ``linear_elasticity`` form to round-off."""
    from pipeline.fem.elasticity import assemble_stiffness, lame_constants, vector_basis

    lam, mu = lame_constants(HELICAL.material, "3d")
    basis = vector_basis(helical.mesh, 2)
    fast = assemble_stiffness(basis, lam, mu, "fast")
    ref = assemble_stiffness(basis, lam, mu, "generic")
    assert abs(fast - ref).max() < 1e-12 * abs(ref).max()
