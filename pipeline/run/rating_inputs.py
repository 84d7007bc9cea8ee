"""What the rating step takes from the run and the gearbox file (:mod:`pipeline.run.rating`):
each mesh's pinion load, each gear's rating inputs, the planets' load sharing (given, by
planet count, or from the dynamic model), the dynamic model's factor, the gear blank factor
of a webbed body, a load spectrum scaled to a mesh, why a gear is not rated in bending."""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from pipeline.config import Gearbox
from pipeline.dynamics.mesh_names import planet_meshes
from pipeline.rating.options import planet_load_sharing
from pipeline.rating.pair_rating import GearRatingInputs
from pipeline.rating.spectrum import LoadBin, LoadSpectrum
from pipeline.run.chain import MeshStages
from pipeline.stiffness.iso6336 import blank_factor_cr
from pipeline.validation import InputError

IDLER_MEAN_STRESS = 0.7
"""Y_M of an idler, whose teeth are bent both ways (:mod:`pipeline.rating.bending`; KISSsoft
prints 0.700 for the planets of the NREL 5 MW gearbox)."""


def computed_load_sharing(dynamics: Any) -> float | None:
    """K_gamma from the dynamic model's response at the operating speed: the largest
    planet's mean sun-mesh force (both halves of a herringbone planet together) over the
    mean of all planets; None without planets."""
    resp = dynamics.response.response
    mean = resp.mean_mesh_force()
    per_planet: dict[int, float] = {}
    for half in planet_meshes(resp.mesh_names, "sun_planet").values():
        for planet, name in half.items():
            per_planet[planet] = per_planet.get(planet, 0.0) + float(mean[resp.mesh(name)])
    if not per_planet:
        return None
    forces = np.array(list(per_planet.values()))
    return float(forces.max() / forces.mean())


def model_dynamic_factor(dynamics: Any, mesh: str) -> float | None:
    """The dynamic model's largest over mean mesh force at the operating speed for ``mesh``
    (a pair's one mesh; a planetary set's sun or ring meshes of every planet and half), or
    None without dynamics."""
    if dynamics is None:
        return None
    resp = dynamics.response.response
    rows = [resp.mesh(n) for half in planet_meshes(resp.mesh_names, mesh).values()
            for n in half.values()]
    force = resp.mesh_force[:, resp.steady_slice()]
    elastic = resp.elastic_mesh_force()[:, resp.steady_slice()]
    ratios = [float(elastic[i].max() / force[i].mean()) for i in rows if force[i].mean() > 0]
    return max(ratios) if ratios else None


def mesh_spectrum(spectrum: LoadSpectrum, operation: Any, torque: float, rpm: float
                   ) -> LoadSpectrum:
    """The spectrum's bins (the driving gear's torque and speed, as ``[operation]``) as this
    mesh's pinion sees them: scaled with the mesh's pinion torque (N m) and speed (rpm)."""
    t_ref, n_ref = operation.torque, operation.speed * 30.0 / math.pi
    return LoadSpectrum(tuple(LoadBin(torque * b.torque / t_ref, rpm * b.speed / n_ref,
                                      b.hours) for b in spectrum.bins), spectrum.key)


def pinion_load(st: MeshStages) -> tuple[float, float]:
    """The pinion's torque (N m) and speed (rpm) of a mesh, whichever gear drives."""
    op, pair = st.case.operation, st.case.pair
    rpm = op.speed * 30.0 / math.pi
    if op.driver == "pinion":
        return op.torque, rpm
    ratio = pair.gear.teeth / pair.pinion.teeth
    return op.torque / ratio, rpm * ratio


def gear_inputs(box: Gearbox, mesh: str, role: str, k: int) -> GearRatingInputs:
    """The rating inputs of gear ``role``, gear ``k`` (0: pinion, 1: gear) of ``mesh``; its
    tip relief C_a is its flank's in that mesh (:meth:`Gearbox.mesh_contact`)."""
    g = box.rating.gear(role)
    relief = box.mesh_contact(mesh).modifications.flanks[k].profile.tip_relief
    return GearRatingInputs(
        sigma_hlim=g.sigma_hlim, sigma_flim=g.sigma_flim, hardening=g.running_in,
        pitting_line=g.pitting_line, bending_line=g.bending_line, size_class=g.size_class,
        hardness_hb=g.hardness_hb, notch_class=g.notch_class, proof_stress=g.proof_stress,
        cutter=g.cutter, inner_radius=box.bodies[role].rim_inner_radius,
        flank_roughness=g.flank_roughness,
        root_roughness=g.root_roughness,
        mean_stress_factor=IDLER_MEAN_STRESS if role == "planet" else 1.0,
        tip_relief=relief if relief > 0.0 else None)


def blank_factor(box: Gearbox, roles: tuple[str, str]) -> float:
    """ISO 6336-1's gear blank factor C_R of a mesh: the smaller of its gears' (a solid disc's
    is 1; a webbed body's from its web width over the face width and its rim thickness
    ``s_R`` = root radius - rim inner radius, :func:`pipeline.stiffness.iso6336.blank_factor_cr`;
    KISSsoft prints the webbed wheel's 0.898 for the NREL 5 MW parallel stage with its solid
    pinion)."""
    out = 1.0
    for role in roles:
        body = box.bodies[role]
        g = body.gear
        if body.web_width is None or g.internal:
            continue
        web, rim = body.web_width / g.face_width, (g.root_radius - body.rim_inner_radius)
        if not 0.2 <= web <= 1.2:
            raise InputError(f"{role}.web_width_mm = {body.web_width * 1e3:.6g} mm is "
                             f"{web:.4g} of the face width; ISO 6336-1's gear blank factor "
                             "C_R holds for 0.2 to 1.2")
        if rim < g.module:
            raise InputError(f"{role}.rim_inner_radius_mm = {body.rim_inner_radius * 1e3:.6g} mm "
                             f"leaves a rim of {rim * 1e3:.6g} mm under the root, less than "
                             "m_n, where ISO 6336-1's gear blank factor C_R holds")
        out = min(out, blank_factor_cr(rim / g.module, web))
    return out


def unrated_reason(box: Gearbox, role: str, internal: bool) -> str | None:
    """Why the gear ``role`` is not rated in bending, or None."""
    g = box.rating.gear(role)
    if internal and g.cutter is None:
        return (f"{role}: give rating.{role}.cutter_teeth (its pinion-type cutter sets its "
                "root section)")
    if g.notch_class is None:
        return (f"{role}: the slip layer of its material's root (ISO 6336-3's Y_deltarelT) "
                "is not built")
    if g.notch_class == "through_hardened" and g.proof_stress is None:
        return (f"{role}: give rating.{role}.proof_stress_MPa (the slip layer of a "
                "through-hardened root)")
    return None


def load_sharing(box: Gearbox, computed: float | None) -> tuple[float, str]:
    opts = box.rating
    if box.kind != "planetary":
        return 1.0, "single mesh"
    n = box.planetary.n_planets
    if opts.load_sharing is None:
        return planet_load_sharing(n), f"default for {n} planets"
    if opts.load_sharing == "computed":
        if computed is None:
            raise InputError('rating.load_sharing = "computed" takes the planets\' loads from '
                             "the dynamic model: the file needs a [dynamics] table")
        return computed, "computed"
    return float(opts.load_sharing), "given"
