"""Relief-groove stiffness: mesh (cached) -> P2 elasticity -> two-node condensation.

:func:`analyse_groove` runs the whole chain for one :class:`GrooveSpec` and keeps
the finite-element objects (for pictures); :func:`groove_stiffness` returns only
the small :class:`GrooveStiffness` the dynamic models need.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass

import numpy as np

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.groove.coupling import TwoNodeCoupling, couple_two_surfaces
from pipeline.fem.groove.mesh import mesh_coaxial_body
from pipeline.fem.groove.result import GrooveStiffness
from pipeline.fem.groove.size import estimated_size
from pipeline.fem.groove.spec import GrooveSpec
from pipeline.fem.groove.toothload import planet_mesh_loads
from pipeline.fem.linear_static import ElasticModel, build_model
from pipeline.fem.mesh_cache import cached_tet_mesh
from pipeline.fem.size3d import check_size_3d
from pipeline.fem.tetmesh import SkfemTetMesh, to_skfem
from pipeline.progress import Steps


@dataclass(frozen=True, eq=False)
class GrooveAnalysis:
    """Everything one groove run produced.

    Attributes
    ----------
    spec : the input.
    result : the stiffness for the dynamic models.
    mesh : scikit-fem mesh (m) with its named surfaces.
    model : assembled elastic body; coupling : condensation with its unit fields.
    mesh_cached : True if the mesh came from the on-disk cache.
    """

    spec: GrooveSpec
    result: GrooveStiffness
    mesh: SkfemTetMesh
    model: ElasticModel
    coupling: TwoNodeCoupling
    mesh_cached: bool

    def torque_displacement(self, torque: float) -> np.ndarray:
        """(n_dof,) displacement (m) under relative torque ``torque`` (N m) at O_L vs O_R.

        Distributed coupling: the load case itself; tooth forces: the tooth-force
        case. Rigid coupling: the unit twist field scaled by torque / k_t (other
        relative motions free).
        """
        U = self.coupling.displacements
        if self.coupling.coupling == "distributed":
            return U[:, 5] * torque
        if self.coupling.coupling == "tooth_forces":
            return U[:, 6] * torque
        motion = self.coupling.relative_flexibility[:, 5] * torque
        return U @ motion


def analyse_groove(
    spec: GrooveSpec, cache: Cache = DEFAULT_CACHE, solver: str = "auto", progress: bool = False,
) -> GrooveAnalysis:
    """Run the FE model of ``spec`` (see module doc). ``progress``: its phases (meshing,
    assembly, factorisation and solves) on stderr when one takes over a second
    (:class:`pipeline.progress.Steps`)."""
    t_start = time.perf_counter()
    steps = Steps(f"groove FE of {spec.gear.name}", enabled=progress)
    body = spec.body()
    settings = spec.mesh_settings()
    check_size_3d(f"the groove body of {spec.gear.name}", estimated_size(body, settings),
                  f"raise groove.mesh_size_mm (now {spec.mesh_size * 1e3:g} mm)")
    with steps.step("meshing the body (Gmsh)"):
        data, _, hit = cached_tet_mesh(
            "groove", {"body": asdict(body), "mesh": asdict(settings)},
            lambda: mesh_coaxial_body(body, settings), cache=cache)
        sk = to_skfem(data)
    t_mesh = time.perf_counter() - t_start
    with steps.step("assembling the stiffness (P2 tetrahedra)"):
        model = build_model(sk.mesh, spec.gear.material, order=2, kind="3d")
    zl, zr = spec.node_z
    left_loads = None
    if spec.coupling == "tooth_forces":
        seg = body.segment("left_gear")
        sign, z_ref = (seg.teeth.sign, seg.teeth.z_reference) if seg.teeth else (-1, seg.z1)
        left_loads = planet_mesh_loads(model, sk.triangles["left_gear:outer"], spec.gear, sign,
                                       z_ref, spec.planets, toothed=seg.teeth is not None)
    with steps.step(f"factorising and solving the coupling cases ({model.n_dof} DOF)"):
        cpl = couple_two_surfaces(model, sk.triangles["left_gear:outer"],
                                  sk.triangles["right_gear:outer"],
                                  np.array([0.0, 0.0, zl]), np.array([0.0, 0.0, zr]),
                                  spec.coupling, solver, left_loads)
    kt = cpl.torsional_stiffness
    total = time.perf_counter() - t_start
    result = GrooveStiffness(
        torsional_stiffness=kt,
        equivalent_Kj=kt * spec.l_LR,
        l_LR=spec.l_LR,
        coupling_matrix=cpl.matrix,
        node_z=(zl, zr),
        sun_teeth=spec.gear.teeth,
        teeth_model=spec.teeth_model,
        coupling=spec.coupling,
        n_dof=model.n_dof,
        solver=cpl.solver,
        mesh_size=spec.mesh_size,
        section_Kj={
            "root": spec.section_torsional_rigidity(2 * spec.gear.root_radius),
            "groove": spec.section_torsional_rigidity(spec.groove_bottom_diameter),
        },
        timings={"mesh": t_mesh, "assembly": model.assembly_seconds,
                 "factor": cpl.factor_seconds, "solve": cpl.solve_seconds, "total": total},
    )
    return GrooveAnalysis(spec, result, sk, model, cpl, hit)


def groove_stiffness(spec: GrooveSpec, **kwargs) -> GrooveStiffness:
    """The :class:`GrooveStiffness` of ``spec`` (keyword arguments as :func:`analyse_groove`)."""
    return analyse_groove(spec, **kwargs).result
