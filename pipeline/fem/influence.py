"""Influence coefficients of a 2D gear sector: the normal compliance matrix between flank points.

``G_ij`` is the approach (displacement into the tooth along the normal) at flank
point ``i`` per unit normal load at flank point ``j``, for points on all loaded
teeth of the sector, so the coupling of neighbouring teeth through the rim is
in the matrix. Loads are consistent nodal forces of a smooth pressure patch
(``cos^2`` over the arc coordinate, fixed half-width ``c``, pressing along the
local inward normal); the approach at ``i`` is measured with the *same* patch
weights, which makes ``G_FE`` exactly ``F^T K^-1 F`` - symmetric (Maxwell-Betti)
to solver round-off. All patches are solved from one factorisation
(:func:`pipeline.fem.linear_static.solve_static`). The local Hertzian near
field is then removed analytically (:mod:`pipeline.fem.hertz_separation`), so
the result is the *structural* compliance to which the contact solver adds
Yang et al. (2026), eq. (24).

2D models are per unit face width: ``G`` is in m^2/N (m per N/m);
:meth:`InfluenceMatrix.matrix` divides by a face width for m/N.

Boundary conditions. The sector is clamped on its bore (external gear) or outer
rim (internal gear). Its radial cut faces are clamped too by default: with free
cut faces a narrow sector rotates as a wedge about the bore, which a full gear
cannot do (the assembly-error paper's gear, bore 21 mm under a 71 mm root circle: 13x the
analytical compliance with 5 free-cut teeth). Clamped cuts approach the full-gear
value from the stiff side as teeth are added, free cuts from the flexible side;
z 30, bore 30 mm, plane stress, middle tooth vs the analytical compliance:
3 teeth -25 % / +12 %, 7 teeth -18 % / -15 %, 11 teeth -17 % / -16 % (clamped /
free, lowest point on the flank). Use >= 5 teeth (more for deep bodies) when the
body compliance matters.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from skfem import ElementTriP2, FacetBasis

from pipeline.fem.flank import FlankPoints
from pipeline.fem.hertz_separation import patch_halfplane_compliance
from pipeline.fem.linear_static import ElasticModel, build_model, solve_static
from pipeline.fem.sector2d import SectorMesh2D
from pipeline.validation import InputError, check_choice, check_positive

CUTS = ("clamped", "free")


@dataclass(frozen=True, eq=False)
class InfluenceMatrix:
    """Flank compliance matrix of a sector (per unit face width).

    Attributes
    ----------
    points : the ``n`` flank points.
    fe : (n, n) FE patch-to-patch compliance, m^2/N (symmetric).
    local : (n, n) analytical half-plane near field removed from it, m^2/N.
    patch_half_width : c, m.
    kind : "plane_strain" or "plane_stress".
    n_dof : DOFs of the FE model; n_free : unknowns after clamping.
    method : sparse solver used; timings : dict of wall times, s.
    """

    points: FlankPoints
    fe: np.ndarray
    local: np.ndarray
    patch_half_width: float
    kind: str
    n_dof: int
    n_free: int
    method: str
    timings: dict

    @property
    def structural(self) -> np.ndarray:
        """(n, n) structural compliance ``fe - local``, m^2/N, without the Hertz approach."""
        return self.fe - self.local

    def matrix(self, face_width: float) -> np.ndarray:
        """(n, n) structural compliance in m/N for a tooth of ``face_width`` (m)."""
        return self.structural / check_positive("face_width", face_width, unit="m")

    def symmetry_error(self) -> float:
        """max |G - G^T| / max |G| of the FE matrix (Maxwell-Betti check)."""
        return float(np.abs(self.fe - self.fe.T).max() / np.abs(self.fe).max())


def patch_loads(sector: SectorMesh2D, points: FlankPoints, half_width: float,
                intorder: int = 12) -> sp.csc_matrix:
    """Consistent nodal forces (2 N_nodes, n) of unit cos^2 pressure patches, N per (N/m).

    Column ``j``: the pressure ``q_j(t) = cos^2(pi t / 2c) / c`` (t: distance from the
    patch centre along the flank tangent, |t| < c) acting along the inward normal on
    the facets of the flank of point ``j``; its resultant is a unit load (N/m).
    """
    c = check_positive("influence.patch_half_width", half_width, unit="m")
    mesh = sector.mesh
    n_scalar = mesh.doflocs.shape[1]
    cols = []
    for j in range(len(points)):
        side = "right" if points.side[j] > 0 else "left"
        name = f"{side}{int(points.tooth[j])}"
        if name not in sector.facets:
            raise InputError(f"flank {name!r} is not in the sector mesh")
        cols.append(name)
    rows_all, cols_all, vals_all = [], [], []
    for name in sorted(set(cols)):
        idx = [j for j, nm in enumerate(cols) if nm == name]
        fb = FacetBasis(mesh, ElementTriP2(), facets=sector.facets[name], intorder=intorder)
        X = np.asarray(fb.global_coordinates())  # (2, nf, nq)
        nrm = fb.normals  # outward (2, nf, nq)
        phi = np.stack([np.asarray(fb.basis[a][0]) for a in range(fb.Nbfun)])  # (a, nf, nq)
        dofs = fb.element_dofs  # (a, nf)
        for j in idx:
            t = ((X[0] - points.position[j, 0]) * points.tangent[j, 0]
                 + (X[1] - points.position[j, 1]) * points.tangent[j, 1])
            # same-flank facets far along the profile are excluded by |t| < c; facets of
            # the flank bending away (tip land) by requiring the normal to agree.
            agree = (nrm[0] * points.normal[j, 0] + nrm[1] * points.normal[j, 1]) > 0.5
            q = np.where((np.abs(t) < c) & agree, np.cos(0.5 * np.pi * t / c) ** 2 / c, 0.0)
            w = q * fb.dx
            for comp in range(2):
                f = np.einsum("afq,fq->af", phi, -nrm[comp] * w)
                rows_all.append((2 * dofs + comp).ravel())
                cols_all.append(np.full(dofs.size, j))
                vals_all.append(f.ravel())
    F = sp.coo_matrix((np.concatenate(vals_all), (np.concatenate(rows_all),
                                                 np.concatenate(cols_all))),
                      shape=(2 * n_scalar, len(points))).tocsc()
    total = np.asarray(F.sum(axis=0)).ravel()
    if np.any(np.abs(total) < 1e-12):
        raise InputError("a load patch missed its flank (is the point on the meshed involute?)")
    return F


def clamped_dofs(sector: SectorMesh2D, model: ElasticModel, cuts: str = "clamped") -> np.ndarray:
    """All DOFs on the bore (external) or outer rim (internal), and on the cut faces
    unless ``cuts`` is "free"."""
    check_choice("influence.cuts", cuts, CUTS)
    names = ["bore"] + ([n for n in ("cut_left", "cut_right") if n in sector.facets]
                        if cuts == "clamped" else [])
    return np.unique(np.concatenate([model.basis.get_dofs(sector.facets[n]).all()
                                     for n in names]))


def influence_matrix(
    sector: SectorMesh2D, points: FlankPoints, patch_half_width: float | None = None,
    kind: str = "plane_strain", method: str = "auto", model: ElasticModel | None = None,
    cuts: str = "clamped",
) -> InfluenceMatrix:
    """Structural flank compliance matrix of ``points`` on ``sector`` (one factorisation).

    Parameters
    ----------
    sector : the sector mesh (:func:`pipeline.fem.sector2d.sector_mesh`).
    points : flank points (:func:`pipeline.fem.flank.flank_points`, same ``teeth``).
    patch_half_width : c, m; default 0.1 m_n (mesh-independent, so the FE part converges).
    kind : "plane_strain" (default) or "plane_stress".
    method : sparse solver ("auto", "cholmod", "cholespy", "splu").
    model : a prebuilt model of ``sector`` (reuse across calls), else assembled here.
    cuts : "clamped" (default) or "free" cut faces (module docstring).
    """
    check_choice("influence.kind", kind, ("plane_strain", "plane_stress"))
    gear = sector.gear
    c = 0.1 * gear.module if patch_half_width is None else patch_half_width
    rb = gear.base_radius
    arc_tip = (gear.tip_radius_**2 - rb**2) / (2 * rb)
    room = np.abs(arc_tip - points.arc)  # internal gears: the tip is the small radius
    if np.any(room < c):
        raise InputError(f"flank point(s) closer than the patch half-width {c:.4g} m to the end "
                         f"of the involute (arc room {room.min():.4g} m)")
    t0 = time.perf_counter()
    if model is None:
        model = build_model(sector.mesh, gear.material, order=2, kind=kind)
    elif model.kind != kind:
        raise InputError(f"model kind {model.kind!r} differs from influence.kind {kind!r}")
    t1 = time.perf_counter()
    F = patch_loads(sector, points, c)
    t2 = time.perf_counter()
    sol = solve_static(model, F.toarray(), clamped_dofs(sector, model, cuts), method)
    fe = np.asarray(F.T @ sol.displacements)
    t3 = time.perf_counter()
    same = points.same_flank()
    local = np.zeros_like(fe)
    ii, jj = np.nonzero(same)
    h = np.sqrt(points.depth[ii] * points.depth[jj])
    local[ii, jj] = patch_halfplane_compliance(points.arc[ii] - points.arc[jj], h, c,
                                               gear.material, kind)
    t4 = time.perf_counter()
    timings = {"assembly": t1 - t0, "loads": t2 - t1, "factor": sol.factor_seconds,
               "solve": sol.solve_seconds, "fe_total": t3 - t2, "halfplane": t4 - t3,
               "total": t4 - t0}
    return InfluenceMatrix(points, fe, local, c, kind, model.n_dof, sol.n_free, sol.method,
                           timings)
