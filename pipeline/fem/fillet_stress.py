"""Stress along the root fillet of a 2D gear under unit flank loads (stress influence table).

The 2D model is the whole gear (:func:`pipeline.fem.sector2d.sector_mesh_2d`, graded from
the loaded teeth like the FE compliance tables), P2 triangles, plane strain or plane
stress, clamped on its bore (a ring: on its rim circle). Unit line loads (1 N/m, the cos^2
pressure patches of :mod:`pipeline.fem.patch_loads`, half-width 0.1 m_n) act on the right
flank of the middle tooth ``mid`` and its neighbours ``mid +- 1 .. mid +- offsets`` at
``radii`` points of the involute. One factorisation solves all of them, for the free DOFs
only (no full displacement or reaction arrays: the recovery reads a few hundred DOFs). The
demo's gear (z 50, 7 loaded teeth, 44k unknowns, 140 load cases) takes 1.0-1.14 s of CPU:
Gmsh 0.4 s, assembly 0.1 s, factorisation 0.2 s, solves 0.3-0.45 s (2 cores shared with
other work, load average 6-9; 1.2-1.4 s through a full static solution, the same table bit
for bit).

Stress recovery: the stress tensor of each load case is evaluated at the P2 nodes of the
boundary edges of the middle tooth's right root - from the middle of the tooth space to
the form circle (the loaded side, in tension under a load on the right flank) - from the
displacement gradient of the triangle owning each edge, and averaged where two edges
meet. Plane strain and plane stress give the same in-plane stresses for loads on a body
clamped on one boundary up to the (small) Poisson effect of the clamp.

The table is linear in the loads, so the stress of any load pattern on those flanks is the
superposition of its columns; the largest principal stress is taken after superposing
(:func:`principal_stress`).

Tables are cached by content hash (``meshes/filletstress-<hash>.npz``).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from functools import partial

import numpy as np

from pipeline.cache.entries import cached_file, same_arrays, unlabelled
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.flank import table_radii
from pipeline.fem.mesh_cache import MESH_CODE
from pipeline.fem.mesh_settings import SectorSettings
from pipeline.fem.sector2d import SectorMesh2D, sector_mesh_2d
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.profile import tooth_profile
from pipeline.validation import check_choice, check_int_range, check_range

KINDS = ("plane_strain", "plane_stress")


@dataclass(frozen=True)
class FilletStressSettings:
    """Settings of a fillet stress table.

    Attributes
    ----------
    refinement : flank and fillet element size m_n / (12 refinement) on the loaded teeth
        (0.25..20); the default 2 is within 1 % of the refined limit (tests).
    radii : flank points per loaded tooth (4..200).
    offsets : neighbouring teeth loaded on each side of the middle tooth (0..3).
    kind : "plane_strain" or "plane_stress".
    """

    refinement: float = 2.0
    radii: int = 20
    offsets: int = 1
    kind: str = "plane_strain"

    def __post_init__(self) -> None:
        check_range("root_stress.refinement", self.refinement, 0.25, 20.0)
        check_int_range("root_stress.radii", self.radii, 4, 200)
        check_int_range("root_stress.offsets", self.offsets, 0, 3)
        check_choice("root_stress.kind", self.kind, KINDS)


@dataclass(frozen=True, eq=False)
class FilletStressTable:
    """Stress along the loaded-side root of the middle tooth per unit flank line load.

    Attributes
    ----------
    gear : the gear.
    settings : how the table was made.
    load_offsets : (n_t,) tooth offsets from the middle tooth of the loaded teeth.
    load_radii : (n_r,) radii of the flank points (the same on every tooth), m.
    load_arc : (n_r,) their arc coordinate on the involute, (r^2 - r_b^2) / (2 r_b), m.
    arc : (n_f,) arc length of the root nodes along the profile from the middle of the
        tooth space, m (ascending).
    radius : (n_f,) radius of the root nodes, m.
    stress : (3, n_f, n_t, n_r) stress components (xx, yy, xy) in the middle tooth's frame
        (y along its centre line) per unit line load, Pa per N/m.
    n_dof : unknowns of the model; timings : s (mesh, assembly, loads, solve, recovery).
    """

    gear: GearSpec
    settings: FilletStressSettings
    load_offsets: np.ndarray
    load_radii: np.ndarray
    load_arc: np.ndarray
    arc: np.ndarray
    radius: np.ndarray
    stress: np.ndarray
    n_dof: int
    timings: dict = field(default_factory=dict)


def principal_stress(sxx: np.ndarray, syy: np.ndarray, sxy: np.ndarray) -> np.ndarray:
    """Largest in-plane principal stress (same unit and shape as the inputs)."""
    c = 0.5 * (sxx + syy)
    return c + np.sqrt((0.5 * (sxx - syy)) ** 2 + sxy**2)


def _root_facets(sector: SectorMesh2D, tooth: int) -> np.ndarray:
    """Facets of the right root of ``tooth`` (between the form and the root circle)."""
    mesh = sector.mesh
    f = sector.facets[f"right{tooth}"]
    nodes = np.vstack([mesh.facets[:, f], mesh.nvertices + f])
    r = np.hypot(*mesh.doflocs[:, nodes])  # (2, 3, nf) -> (3, nf)
    form = tooth_profile(sector.gear).form_radius
    if sector.gear.internal:  # the ring's root is outside its form circle
        return f[r.min(axis=0) >= form * (1.0 - 1e-9)]
    return f[r.max(axis=0) <= form * (1.0 + 1e-9)]


def _recover(sector: SectorMesh2D, u: Callable[[np.ndarray], np.ndarray], lam: float,
             mu: float, tooth: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Root nodes (their scalar DOF ids), their coordinates (2, n_f) and the stress (3, n_f,
    n_cases) in the global frame, averaged over the owning triangles; ``u`` gives the
    displacements (..., n_cases) of an array of vector DOF ids."""
    from skfem import Basis, ElementTriP2

    mesh = sector.mesh
    facets = _root_facets(sector, tooth)
    tri = mesh.f2t[0, facets]
    elem = ElementTriP2()
    ref = np.asarray(elem.doflocs, dtype=float).T  # (2, 6) reference nodes
    sb = Basis(mesh, elem, elements=tri, quadrature=(ref, np.full(6, 1.0 / 6.0)))
    dofs = sb.element_dofs  # (6, n_el) scalar P2 DOFs of each owning triangle
    # gradient of each local shape function at each local node: (a, j, e, q)
    G = np.stack([sb.basis[a][0].grad for a in range(6)], axis=0)
    ux = u(2 * dofs)  # (6, n_el, n_cases)
    uy = u(2 * dofs + 1)
    # displacement gradients at the 6 nodes of every owning triangle: (e, q, cases)
    dux_dx = np.einsum("aeq,aec->eqc", G[:, 0], ux)
    dux_dy = np.einsum("aeq,aec->eqc", G[:, 1], ux)
    duy_dx = np.einsum("aeq,aec->eqc", G[:, 0], uy)
    duy_dy = np.einsum("aeq,aec->eqc", G[:, 1], uy)
    sxx = (lam + 2 * mu) * dux_dx + lam * duy_dy
    syy = lam * dux_dx + (lam + 2 * mu) * duy_dy
    sxy = mu * (dux_dy + duy_dx)
    facet_nodes = np.vstack([mesh.facets[:, facets], mesh.nvertices + facets])  # (3, nf)
    nodes = np.unique(facet_nodes)
    acc = np.zeros((3, nodes.size, ux.shape[-1]))
    count = np.zeros(nodes.size)
    for k in range(facets.size):  # a few hundred root edges: the loop is cheap
        for node in facet_nodes[:, k]:
            q = int(np.flatnonzero(dofs[:, k] == node)[0])
            i = int(np.searchsorted(nodes, node))
            acc[:, i] += np.stack([sxx[k, q], syy[k, q], sxy[k, q]])
            count[i] += 1
    return nodes, mesh.doflocs[:, nodes], acc / count[None, :, None]


def _free_rows(U: np.ndarray, free: np.ndarray, dofs: np.ndarray) -> np.ndarray:
    """Rows of the displacements ``dofs`` (any shape) from ``U`` (n_free, n_cases), the
    solution on the ``free`` DOFs (ascending); zero on clamped DOFs."""
    pos = np.minimum(np.searchsorted(free, dofs), free.size - 1)
    return np.where((free[pos] == dofs)[..., None], U[pos], 0.0)


def _to_tooth_frame(xy: np.ndarray, s: np.ndarray, angle: float
                    ) -> tuple[np.ndarray, np.ndarray]:
    """Coordinates and stress components rotated into the frame of a tooth whose centre line
    is at polar angle ``angle`` (its centre line becomes +y)."""
    phi = np.pi / 2 - angle
    c, si = np.cos(phi), np.sin(phi)
    R = np.array([[c, -si], [si, c]])
    p = R @ xy
    sxx, syy, sxy = s
    rxx = c * c * sxx + si * si * syy - 2 * c * si * sxy
    ryy = si * si * sxx + c * c * syy + 2 * c * si * sxy
    rxy = c * si * (sxx - syy) + (c * c - si * si) * sxy
    return p, np.stack([rxx, ryy, rxy])


def _profile_arc(gear: GearSpec, xy: np.ndarray) -> np.ndarray:
    """Arc length along the exact right profile from the middle of the tooth space of the
    points ``xy`` (2, n) (tooth frame), m: the nearest profile point's arc length."""
    prof = tooth_profile(gear, 400)
    px, py = prof.x, prof.y
    cum = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(px), np.diff(py)))])
    d = (xy[0][:, None] - px[None]) ** 2 + (xy[1][:, None] - py[None]) ** 2
    return cum[np.argmin(d, axis=1)]


def _table_inputs(gear: GearSpec, settings: FilletStressSettings
                  ) -> tuple[dict, np.ndarray, np.ndarray, SectorSettings]:
    """The cache key data of a table (every input it depends on), the tooth offsets, the
    flank radii (m) and the mesh settings."""
    z = gear.teeth
    offsets = np.arange(-settings.offsets, settings.offsets + 1)
    ss = SectorSettings.graded(gear, z, tuple(int(t) for t in z // 2 + offsets),
                               settings.refinement)
    r = table_radii(gear, settings.radii)
    inputs = {"gear": unlabelled(gear), "sector": asdict(ss), "settings": asdict(settings),
              "radii": r.tolist()}
    return inputs, offsets, r, ss


def build_fillet_stress(gear: GearSpec, settings: FilletStressSettings, *,
                        cache: Cache = DEFAULT_CACHE
                        ) -> FilletStressTable:
    """The fillet stress table of ``gear`` (module docstring), from the cache or solved."""
    z = gear.teeth
    mid = z // 2
    inputs, offsets, r, ss = _table_inputs(gear, settings)
    teeth = mid + offsets

    def build() -> dict[str, np.ndarray]:
        # the solver side is imported on a cache miss only (a second of imports)
        from pipeline.fem.elasticity import lame_constants
        from pipeline.fem.flank import flank_points
        from pipeline.fem.influence import constrained_dofs
        from pipeline.fem.linear_static import build_model, free_system
        from pipeline.fem.patch_loads import patch_loads

        t0 = time.perf_counter()
        sec = sector_mesh_2d(gear, ss, cache=cache)
        t1 = time.perf_counter()
        model = build_model(sec.mesh, gear.material, order=2, kind=settings.kind)
        t2 = time.perf_counter()
        pts = flank_points(gear, z, np.repeat(teeth, r.size), np.tile(r, teeth.size))
        free, factorize = free_system(model, constrained_dofs(sec, model))
        # the free rows only, already in the column order the factor's solve takes
        F = patch_loads(sec, pts, 0.1 * gear.module)[free].toarray(order="F")
        t3 = time.perf_counter()
        # the displacements of the free DOFs only: the recovery reads a few hundred of them
        U = factorize().solve(F)
        t4 = time.perf_counter()
        lam, mu = lame_constants(gear.material, settings.kind)
        _, xy, s = _recover(sec, partial(_free_rows, U, free), lam, mu, mid)
        xy, s = _to_tooth_frame(xy, s, sec.tooth_angle(mid))
        arc = _profile_arc(gear, xy)
        order = np.argsort(arc)
        t5 = time.perf_counter()
        return {"arc": arc[order], "radius": np.hypot(*xy)[order],
                "stress": s[:, order].reshape(3, order.size, teeth.size, r.size),
                "n_dof": np.array(model.n_dof),
                "timings": np.array([t1 - t0, t2 - t1, t3 - t2, t4 - t3, t5 - t4])}

    data, _, _ = cached_file("filletstress", inputs, build, same_arrays, same_arrays,
                             code=MESH_CODE, cache=cache)
    rb = gear.base_radius
    names = ("mesh", "assembly", "loads", "solve", "recovery")
    return FilletStressTable(gear, settings, offsets, r, (r * r - rb * rb) / (2 * rb),
                             np.asarray(data["arc"]), np.asarray(data["radius"]),
                             np.asarray(data["stress"]), int(data["n_dof"]),
                             dict(zip(names, np.asarray(data["timings"]).tolist(),
                                      strict=True)))
