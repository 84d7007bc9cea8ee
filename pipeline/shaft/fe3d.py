"""The 3D shaft model (``model = "fe3d"``): Gmsh + scikit-fem, condensed to a superelement.

The shaft with its shoulders is meshed in Gmsh with curved P2 tetrahedra
(:mod:`pipeline.fem.shaft_mesh`), assembled with the project's elasticity
(:func:`pipeline.fem.linear_static.build_model`) and condensed to a few reference nodes on
the axis (:mod:`pipeline.fem.superelement`): the gear's seat, one node per bearing, the
torque point. Bearings, the torque point and the loads act on these nodes only, so the
supports are applied to a matrix of some 6 x 10 rows, and the FE model is solved once per
layout and cached (:func:`pipeline.cache.entries.cached_file`, kind ``shaftfe3d``) like the
FE tooth tables.

Modelling choices
-----------------
* Bearings: a distributing (RBE3-like) coupling of a reference node at the bearing's
  position to the shaft's outer surface over a band ``band_factor`` times the local
  diameter wide (clipped at the shaft's ends, at the seat and half-way to a neighbouring
  bearing): the node moves with the band's least-squares rigid motion and its reaction is
  spread as a traction varying like a rigid motion - a bearing ring that does not stiffen
  the shaft. The bearing's radial stiffness (u_x, u_y), its tilting stiffness (theta_x,
  theta_y; 0 lets the shaft tilt, as a ball bearing does) and, for the locating bearing,
  a rigid axial support act between that node and the ground; an infinite stiffness holds
  the DOF. The bearings are not part of the cached superelement: a changed stiffness reuses
  the cache.
* The torque point: theta_z held at a reference node tied the same way to a band of the
  surface (a coupling's hub); a torque point inside a bearing's band shares its node. One
  on the seat is refused (the seat would not turn).
* The seat, ``hub = "rigid"``: the gear's hub is a rigid ring; every node of the shaft's
  outer surface over the seat follows the seat node at the gear's mid-face (RBE2) - the
  stiff bound of a shrink fit. ``hub = "integral"`` (a pinion cut on its shaft): the seat
  is shaft material of its segment's diameter, loaded through ``seat_stations`` reference
  nodes, each tied (RBE3) to a thin ring of the seat's surface (the seat split into equal
  rings); a load at ``z`` is shared between the two neighbouring stations with linear
  (hat) weights moved rigidly to the stations, and the motion at ``z`` is read with the
  same weights, so ``flexibility(z)`` is symmetric and exact for rigid motions.
* Condensation: one solver set-up, ``6 (n - 1)`` balanced load cases (``n`` nodes), the
  motions of the nodes relative to the anchor (the seat node, or the first seat station),
  ``K = A^T C^-1 A`` (:class:`~pipeline.fem.superelement.Superelement`). The deflection
  line is read on the cross-sections at every cut of the mesh (ends, steps, seat and band
  edges - not the rings inside a disc seat -, bearings, torque point, and at most
  ``section_spacing`` diameters apart) as their least-squares rigid motion: the beam's
  section kinematics.
* Mesh: edge ``min(d / 4, wall, l / 2) / refinement`` in each segment (``d`` its outer
  diameter, ``wall`` its wall thickness, ``l`` its length: a short, wide segment - a
  pinion's body - bends and shears as a plate through its length: loaded at its rim it
  is not rigid; an edge growing from 10 mm at the core to 30 mm at the rim of the example
  below lost 1.1 % of its axial and tilting compliance), ``shoulder_factor``
  times that at every shoulder circle and at the edges of a rigid hub, growing 0.5 m per
  m away from them (:mod:`pipeline.fem.shaft_mesh`). At a large step (outer diameters at
  least :data:`~pipeline.shaft.fe3d_plan.LARGE_STEP_RATIO` apart) ``large_step_factor``
  (0.08) growing 1 m per m: its re-entrant corner is a stronger singularity, whose zone
  holds much of the shaft's flexibility, and a uniform mesh converges there only like
  h^1. An integral seat on a disc (its segment shorter than its diameter) is not cut at
  its stations: their edges split only its surface (rings,
  :attr:`~pipeline.fem.shaft_mesh.ShaftMeshSpec.rings`), so the disc is one solid meshed
  by its own size instead of ten thin slabs across its whole diameter. At the default
  refinement the seat's bending compliance is 0.06 % (integral seat) and 1.4 % (rigid
  hub) below its extrapolated value on a plain shaft. On the straddle-mounted example
  (35 mm journals, 142.5 mm body) the seat's 6 x 6 diagonal lies within 0.25 % (the
  5-point seat flexibility within 0.35 % of its largest diagonal) of the earlier sizing
  (slabs, shoulder circles at 0.35 growing 0.5 m/m) refined to 2 (121k unknowns).

Cache: the key holds everything of the layout that changes the superelement (the pieces
with their radii and mesh sizes, the hub, the nodes and their bands, E and nu) and the
source of :data:`FE3D_CODE`; bearing stiffnesses, names and the solver are not in it.

Checks (``tests/test_shaft_fe3d.py``): between the Saint-Venant zones of the supports and
the seat, the sections' curvature is M / (E I), their shear strain V / (kappa G A) with
Cowper's kappa and their twist per length T / (G J) - exact 3D elasticity - to 1.4e-4, 5e-3
(of the shear part) and 4e-4 on the coarsest mesh, solid and bored. A plain shaft with a
central load on an integral seat converges (rate h^2.2) to 0.27 % above the Timoshenko
beam (the bands are not points); a rigid hub converges more slowly (h^1.4: the hub's edges
are corner singularities) to 7 % above the beam with a rigid segment over the seat: the
hub holds the shaft's surface, not its sections, as if the beam's built-in points lay
0.06 d inside the hub. A stepped shaft (30/45 mm) is 2.0-2.4 % more flexible in bending
and 4.8-5.5 % in torsion than the beam: each shoulder acts like 0.16-0.2 d (bending) and
0.07-0.08 d (torsion) of extra small shaft - the large section next to a step is not
fully effective (a Saint-Venant zone of the order of the step height, which beam theory
lacks). The condensed flexibility is symmetric to 1e-15 before symmetrising. Timing
(``workflows/benchmarks/bench_shaft_fe3d.py``; 2 cores shared with other jobs; the
factorisation MKL PARDISO's, :mod:`pipeline.fem.solvers`): the straddle-mounted example
(integral seat on the 142.5 mm body) 64k unknowns, 6.3-10.2 s cold at a load average of
2-4 (mesh 0.7-1.0, assembly 0.9-3.7, factorisation 2.9-3.2 with MKL's loading, solves
0.7-0.8 s) and 12.3-16.4 s at 5, against 14.9-20.8 s and 22.6-27.5 s with cholespy's
CHOLMOD on the reference BLAS in the same runs (factorisation 9.5-18.4 s; the seat's
compliance agrees to 2.5e-12; with the earlier sizing 51k unknowns in 38-41 s, 34 s of
them factorising the slabs); a straddle-mounted pinion shaft (35-45 mm, bearings 200 mm
apart, rigid hub) 35k unknowns, 2.6-3.5 s cold at load 2-4 (mesh 0.3-0.5, assembly
0.6-0.8, factorisation 0.9-1.2, solves 0.2-0.3 s); 2-7 ms warm.
"""

from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field

import numpy as np

from pipeline.cache.entries import cached_file
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.groove.coupling import transfer_matrix
from pipeline.fem.mesh_cache import MESH_CODE
from pipeline.fem.superelement import Superelement
from pipeline.shaft.fe3d_plan import TOL, Fe3dPlan, Fe3dSettings, plan_fe3d
from pipeline.shaft.layout import ShaftLayout
from pipeline.shaft.model import PointLoad, ShaftSolution
from pipeline.validation import InputError

FE3D_CODE = (*MESH_CODE, "pipeline.shaft.fe3d", "pipeline.shaft.fe3d_plan")
"""The code a shaft superelement depends on (part of its cache key)."""
def _build(plan: Fe3dPlan, layout: ShaftLayout, settings: Fe3dSettings) -> dict:
    """Mesh, assemble and condense (the cache's build)."""
    from pipeline.fem.linear_static import build_model
    from pipeline.fem.shaft_mesh import mesh_shaft
    from pipeline.fem.size3d import check_size_3d
    from pipeline.fem.solvers import solver_named
    from pipeline.fem.superelement import Patch, condense
    from pipeline.fem.tetmesh import to_skfem

    check_size_3d(f"the shaft {layout.name}", plan.mesh.estimated_size(),
                  f"lower fe3d.refinement (now {settings.refinement:g})")
    t0 = time.perf_counter()
    sk = to_skfem(mesh_shaft(plan.mesh))
    t_mesh = time.perf_counter() - t0
    model = build_model(sk.mesh, layout.material, order=2, kind="3d")
    piece_z = [(p.z0, p.z1) for p in plan.mesh.pieces]

    def patch(z: float, band: tuple[float, float]) -> Patch:
        ids = [i for i, (a, b) in enumerate(piece_z)
               if a >= band[0] - TOL and b <= band[1] + TOL]
        tri = np.hstack([sk.triangles[f"outer:{i}"] for i in ids])
        return Patch(tri, np.array([0.0, 0.0, z]))

    patches = [patch(z, b) for z, b in zip(plan.nodes_z, plan.bands, strict=True)]
    cuts = plan.mesh.section_cuts
    sections = [Patch(sk.triangles[f"section:{k}"], np.array([0.0, 0.0, c]))
                for k, c in enumerate(cuts)]
    se = condense(model, patches[0], patches[1:], sections, anchor_rigid=plan.rigid,
                  solver=solver_named(settings.solver, dim=3))
    timings = {"mesh": t_mesh, "assembly": model.assembly_seconds, **se.timings,
               "total": time.perf_counter() - t0}
    return {"positions": se.positions, "flexibility": se.flexibility,
            "section_positions": se.section_positions,
            "section_flexibility": se.section_flexibility, "asymmetry": se.asymmetry,
            "n_dof": se.n_dof, "method": se.method,
            "timing_names": np.array(list(timings)),
            "timing_values": np.array(list(timings.values()))}


def _superelement(v: dict) -> Superelement:
    timings = {str(k): float(t) for k, t in zip(v["timing_names"], v["timing_values"],
                                                strict=True)}
    return Superelement(v["positions"], v["flexibility"], v["section_positions"],
                        v["section_flexibility"], float(v["asymmetry"]), int(v["n_dof"]),
                        str(v["method"]), timings)


def _supported_compliance(K: np.ndarray, layout: ShaftLayout, plan: Fe3dPlan) -> np.ndarray:
    """(6n, 6n) nodal motions per unit nodal load with the bearings (springs between their
    nodes and the ground; an infinite stiffness and the axial location hold the DOF) and
    the torque point (theta_z held) as supports; zero on held DOFs."""
    K = K.copy()
    held = np.zeros(K.shape[0], dtype=bool)
    for b, j in zip(layout.bearings, plan.bearing_nodes, strict=True):
        for dofs, k in (((0, 1), b.radial_stiffness), ((3, 4), b.tilting_stiffness)):
            for d in dofs:
                if math.isinf(k):
                    held[6 * j + d] = True
                else:
                    K[6 * j + d, 6 * j + d] += k
        held[6 * j + 2] |= b.axial
    held[6 * plan.torque_node + 5] = True
    free = np.flatnonzero(~held)
    C = np.zeros_like(K)
    C[np.ix_(free, free)] = np.linalg.inv(K[np.ix_(free, free)])
    return 0.5 * (C + C.T)


@dataclass(frozen=True, eq=False)
class Fe3dShaft:
    """The 3D FE shaft model of ``layout`` (module docstring); a
    :class:`~pipeline.shaft.model.ShaftModel`.

    Construction builds (or reads from ``cache``) the superelement.

    Attributes
    ----------
    layout : the shaft.
    settings : mesh and coupling controls.
    cache : where superelements are kept (:class:`~pipeline.cache.folder.Cache`).
    superelement : the condensed body (nodes: seat, bearings, torque point).
    cached : True when the superelement was read from the cache.
    seconds : wall time of the construction, s.
    """

    layout: ShaftLayout
    settings: Fe3dSettings = field(default_factory=Fe3dSettings)
    cache: Cache = DEFAULT_CACHE
    superelement: Superelement = field(init=False)
    cached: bool = field(init=False)
    seconds: float = field(init=False)
    _plan: Fe3dPlan = field(init=False, repr=False)
    _stiffness: np.ndarray = field(init=False, repr=False)
    _compliance: np.ndarray = field(init=False, repr=False)

    def __post_init__(self) -> None:
        t0 = time.perf_counter()
        plan = plan_fe3d(self.layout, self.settings)
        mat = self.layout.material
        # everything of the layout that changes the superelement (bearing stiffnesses do not)
        key = {"pieces": [asdict(p) for p in plan.mesh.pieces],
               "shoulder_factor": plan.mesh.shoulder_factor, "grading": plan.mesh.grading,
               "large_step": [plan.mesh.large_step_ratio, plan.mesh.large_step_factor,
                              plan.mesh.large_step_grading],
               "edges": plan.mesh.edges, "rings": plan.mesh.rings, "rigid": plan.rigid,
               "nodes_z": plan.nodes_z,
               "bands": plan.bands, "material": [mat.youngs_modulus, mat.poisson_ratio]}
        v, _, hit = cached_file("shaftfe3d", key,
                                lambda: _build(plan, self.layout, self.settings),
                                lambda d: d, dict, code=FE3D_CODE, cache=self.cache)
        se = _superelement(v)
        K = se.stiffness()
        for name, value in (("superelement", se), ("cached", hit), ("_plan", plan),
                            ("_stiffness", K), ("_compliance", _supported_compliance(
                                K, self.layout, plan)),
                            ("seconds", time.perf_counter() - t0)):
            object.__setattr__(self, name, value)

    # -- the interface -------------------------------------------------------------------

    def flexibility(self, z: np.ndarray) -> np.ndarray:
        """(6m, 6m): generalised displacements at the seat points ``z`` (m,) per unit
        generalised load at each of them, bearings and torque point as supports
        (m/N, rad/(N m), ...; symmetric)."""
        W = self._seat_weights(np.atleast_1d(np.asarray(z, dtype=float)))
        C = W @ self._compliance @ W.T
        return 0.5 * (C + C.T)

    def seat_stiffness(self) -> np.ndarray:
        """(6, 6) stiffness at the seat's centre (bearings and shaft in series; torsion to
        the torque point), the inverse of ``flexibility([gear_position])``: N/m, N,
        N m/rad."""
        K = np.linalg.inv(self.flexibility(np.array([self.layout.gear_position])))
        return 0.5 * (K + K.T)

    def solve(self, loads: Sequence[PointLoad]) -> ShaftSolution:
        """The deflection line (on the mesh's cross-sections) and the reactions under
        ``loads`` on the seat."""
        se, plan = self.superelement, self._plan
        F = np.zeros(self._compliance.shape[0])
        for ld in loads:
            W = self._seat_weights(np.array([ld.z]))
            F += W.T @ np.concatenate([ld.force, ld.moment])
        U = self._compliance @ F
        on_body = self._stiffness @ U  # loads at the nodes: applied and supports'
        support = (on_body - F).reshape(-1, 6)
        torque = float(support[plan.torque_node, 5])
        support[plan.torque_node, 5] = 0.0
        reactions = np.array([support[j] for j in plan.bearing_nodes])
        Un = U.reshape(-1, 6)
        loads_rel = on_body[6:]
        rel0 = np.array([transfer_matrix(p - se.positions[0]) @ Un[0]
                         for p in se.section_positions])
        line = (se.section_flexibility @ loads_rel).reshape(-1, 6) + rel0
        return ShaftSolution(se.section_positions[:, 2].copy(), line[:, :3], line[:, 3:],
                             reactions, torque)

    # -- helpers -------------------------------------------------------------------------

    def _seat_weights(self, z: np.ndarray) -> np.ndarray:
        """W (6m, 6n): the motion at seat points ``z`` from the nodes' motions (rigid
        transfer from the seat node, or hat weights between seat stations)."""
        s0, s1 = self.layout.seat
        bad = (z < s0 - TOL) | (z > s1 + TOL)
        if np.any(bad):
            raise InputError(f"{self.layout.name}: a seat point at z = "
                             f"{z[bad][0] * 1e3:.6g} mm lies off the gear's seat "
                             f"({s0 * 1e3:.6g} to {s1 * 1e3:.6g} mm)")
        nodes = np.array(self._plan.seat_nodes)
        zs = np.array([self._plan.nodes_z[j] for j in nodes])
        W = np.zeros((6 * z.size, self._compliance.shape[0]))
        for i, zi in enumerate(z):
            if nodes.size == 1:
                weights = {0: 1.0}
            else:
                k = int(np.clip(np.searchsorted(zs, zi) - 1, 0, zs.size - 2))
                t = float(np.clip((zi - zs[k]) / (zs[k + 1] - zs[k]), 0.0, 1.0))
                weights = {k: 1.0 - t, k + 1: t}
            for k, w in weights.items():
                j = nodes[k]
                W[6 * i:6 * i + 6, 6 * j:6 * j + 6] += w * transfer_matrix(
                    np.array([0.0, 0.0, zi - zs[k]]))
        return W
