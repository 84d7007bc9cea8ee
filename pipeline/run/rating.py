"""The rating step of a run: ISO 6336 safety factors of every mesh beside the loaded contact.

With a ``[rating]`` table (:class:`~pipeline.rating.options.RatingOptions`), every mesh is
rated by ISO 6336 method B (:func:`pipeline.rating.pair_rating.rate_pair`): a pair's one
mesh, a planetary set's sun-planet and planet-ring meshes (the speed relative to the
carrier, the sun and the ring meeting one planet after another, the planet an idler with
Y_M 0.7, K_v the larger of the two meshes', as KISSsoft's ``KV = max(KV12, KV23)``), a
herringbone mesh as one helical half at half the load (ISO 6336-1: b_B of each half).
What the standard leaves to the analyst comes from the run where it can:

* the face load factor K_Hbeta: ISO 6336-1 method C's (the default,
  :mod:`pipeline.rating.face_load`), the loaded contact's (the largest over the mean of the
  cycle-mean line load across the face, :mod:`pipeline.contact.distribution`) with
  ``face_load_factor = "contact"``, or the number given; the other two are shown beside;
* the gear blank factor C_R of a webbed body (:func:`blank_factor`) and K_v's gear mass of
  a webbed gear from its rim;
* the planets' load sharing K_gamma: the default for the number of planets
  (:data:`~pipeline.rating.options.PLANET_LOAD_SHARING`), a number, or ``"computed"``: the
  largest planet's mean sun-mesh force over the mean of all planets in the dynamic model's
  response at the operating speed (shown beside whenever the run has dynamics);
* the tip relief C_a of K_v: the ``[contact]`` tip relief of the gear where given, else
  the standard's running-in value C_ay;
* beside sigma_H and sigma_F: the loaded contact's largest Hertz pressure and the FE root
  stress of each gear, both at the nominal torque (no load factors);
* where the flank is at risk: the local pitting safety over each flank from the loaded
  contact's Hertz pressure and, with the FE root stress, the root stress along the face with
  its local bending safety (:mod:`pipeline.rating.local_safety`).

An internal gear's root section is the one its pinion-type cutter generates
(``cutter_teeth``); a gear without it, or whose material's slip layer is not built, is
rated in pitting only, and the report says which key is missing. With
``[[rating.spectrum]]`` each mesh is also rated over the load spectrum (ISO 6336-6,
:mod:`pipeline.rating.pair_spectrum`).
"""

from __future__ import annotations

import dataclasses
import math
import re
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.config import Gearbox
from pipeline.contact.distribution import LoadDistribution
from pipeline.contact.root_stress import RootStress
from pipeline.dynamics.models.planetary_gears import helical_half
from pipeline.progress import Steps
from pipeline.rating.local_safety import LocalSafety, local_safety, rating_limits
from pipeline.rating.options import planet_load_sharing
from pipeline.rating.pair_rating import GearRatingInputs, PairRating, RatingInputs, rate_pair
from pipeline.rating.pair_spectrum import rate_pair_spectrum
from pipeline.rating.spectrum import LoadBin, LoadSpectrum, SpectrumRating
from pipeline.run.chain import MeshStages
from pipeline.stiffness.iso6336 import blank_factor_cr
from pipeline.validation import InputError, PhysicsWarning

ROLES = {"mesh": ("pinion", "gear"), "sun_planet": ("sun", "planet"),
         "planet_ring": ("planet", "ring")}
"""The gear tables rated in each mesh, (pinion, gear)."""
IDLER_MEAN_STRESS = 0.7
"""Y_M of an idler, whose teeth are bent both ways (:mod:`pipeline.rating.bending`; KISSsoft
prints 0.700 for the planets of the NREL 5 MW gearbox)."""

_SOURCE = {"contact": "loaded contact", "method_c": "ISO 6336-1 method C"}
_SUN_MESH = re.compile(r"^s-p(\d+)[LR]?$")


@dataclass(frozen=True)
class MeshRating:
    """The rating of one mesh and what the run knows beside it.

    Attributes
    ----------
    mesh : "mesh", "sun_planet" or "planet_ring".
    gears : the gear tables rated, (pinion, gear).
    rating : every factor (:class:`~pipeline.rating.pair_rating.PairRating`).
    k_hbeta_source : "ISO 6336-1 method C", "loaded contact" or "given".
    k_hbeta_contact : the loaded contact's K_Hbeta (-).
    load_sharing_source : "single mesh", "default for N planets", "given" or "computed".
    k_gamma_computed : K_gamma from the dynamic model's planet forces, or None.
    herringbone_half : rated as one helical half at half the load.
    contact_pressure_max : the loaded contact's largest Hertz pressure, Pa (nominal torque).
    root_stress_fe : the FE root stress's largest value of each gear, Pa (nominal torque;
        None where not computed).
    sigma_hlim, sigma_flim : the gears' allowable stress numbers, Pa.
    minimum_pitting, minimum_bending : S_Hmin, S_Fmin (-).
    dynamic_factor_model : the run's dynamic model's largest over mean mesh force at the
        operating speed (the largest over a set's planets), or None without dynamics.
    local : the local pitting safety over both flanks and, where the FE root stress was
        computed, the root stress along the face with its local bending safety
        (:class:`~pipeline.rating.local_safety.LocalSafety`), or None.
    spectrum : the Miner sums over ``[[rating.spectrum]]``
        (:func:`pipeline.rating.pair_spectrum.rate_pair_spectrum`), or None.
    unrated : why each gear is not rated in bending (None where it is).
    """

    mesh: str
    gears: tuple[str, str]
    rating: PairRating
    k_hbeta_source: str
    k_hbeta_contact: float
    load_sharing_source: str
    k_gamma_computed: float | None
    herringbone_half: bool
    contact_pressure_max: float
    root_stress_fe: tuple[float | None, float | None]
    sigma_hlim: tuple[float, float]
    sigma_flim: tuple[float, float]
    minimum_pitting: float
    minimum_bending: float
    dynamic_factor_model: float | None = None
    local: LocalSafety | None = None
    spectrum: SpectrumRating | None = None
    unrated: tuple[str | None, str | None] = (None, None)

    def summary(self) -> dict[str, Any]:
        """The safety factors and the load factors (keys carry units)."""
        r = self.rating
        out: dict[str, Any] = {
            "K_v": r.dynamic.factor, "K_Hbeta": r.k_hbeta, "K_Hbeta_source": self.k_hbeta_source,
            "K_Hbeta_loaded_contact": self.k_hbeta_contact,
            "K_Hbeta_method_C": None if r.face_load is None else r.face_load.k_hbeta,
            "K_Fbeta": r.k_fbeta,
            "K_Halpha": r.transverse.k_halpha, "K_Falpha": r.transverse.k_falpha,
            "K_gamma_source": self.load_sharing_source,
        }
        if self.k_gamma_computed is not None:
            out["K_gamma_computed"] = self.k_gamma_computed
        for k, role in enumerate(self.gears):
            b = r.bending[k]
            out[role] = {"sigma_H_Pa": r.contact.stress[k], "S_H": r.pitting[k].safety,
                         "sigma_F_Pa": None if b is None else b.stress,
                         "S_F": None if b is None else b.safety}
            if self.spectrum is not None:
                d = self.spectrum.pitting[k], self.spectrum.bending[k]
                out[role].update({
                    "spectrum_damage_pitting": d[0].total, "spectrum_S_H": d[0].safety,
                    "spectrum_damage_bending": None if d[1] is None else d[1].total,
                    "spectrum_S_F": None if d[1] is None else d[1].safety})
        if self.local is not None:
            out["local"] = self.local.summary()
        return out


@dataclass(frozen=True)
class RatingStage:
    """The rating of every mesh, and its smallest safety factors."""

    meshes: Mapping[str, MeshRating]
    minimum_pitting: float
    minimum_bending: float

    def smallest(self, kind: str, spectrum: bool = False) -> tuple[float, str, str]:
        """(S, gear, mesh) of the smallest S_H (``kind`` "pitting") or S_F ("bending") at the
        constant load, or over the load spectrum (``spectrum``; NaN without one)."""
        out = (math.inf, "", "")
        for name, m in self.meshes.items():
            source = m.spectrum if spectrum else m.rating
            if source is None:
                return (math.nan, "", "")
            for k, role in enumerate(m.gears):
                item = getattr(source, kind)[k]
                if item is not None and item.safety < out[0]:
                    out = (item.safety, role, name)
        return out

    def line(self) -> str:
        """One line: the smallest S_H and S_F, which gear, against their minimums (and over
        the load spectrum, when there is one)."""
        has_spectrum = next(iter(self.meshes.values())).spectrum is not None
        parts = []
        for spectrum in (False, True) if has_spectrum else (False,):
            for kind, sym, minimum in (("pitting", "S_H", self.minimum_pitting),
                                       ("bending", "S_F", self.minimum_bending)):
                s, role, mesh = self.smallest(kind, spectrum)
                where = role if len(self.meshes) == 1 else f"{role}, {mesh.replace('_', '-')}"
                flag = "" if s >= minimum else f" BELOW {sym}min {minimum:g}"
                head = "spectrum (ISO 6336-6): " if spectrum and kind == "pitting" else ""
                parts.append(f"{head}{sym} min {s:.3f} ({where}){flag}")
        return "; ".join(parts)

    def summary(self) -> dict[str, Any]:
        """Smallest S_H and S_F with their gear and mesh, and each mesh's figures."""
        out: dict[str, Any] = {"verdict": self.line()}
        for kind in ("pitting", "bending"):
            s, role, mesh = self.smallest(kind)
            out[f"safety_{kind}_min"] = s
            out[f"safety_{kind}_min_gear"] = role
            out[f"safety_{kind}_min_mesh"] = mesh
            if next(iter(self.meshes.values())).spectrum is not None:
                s, role, mesh = self.smallest(kind, spectrum=True)
                out[f"spectrum_safety_{kind}_min"] = s
                out[f"spectrum_safety_{kind}_min_gear"] = role
                out[f"spectrum_safety_{kind}_min_mesh"] = mesh
        out["meshes"] = {k: m.summary() for k, m in self.meshes.items()}
        return out


def computed_load_sharing(dynamics: Any) -> float | None:
    """K_gamma from the dynamic model's response at the operating speed: the largest
    planet's mean sun-mesh force (both halves of a herringbone planet together) over the
    mean of all planets; None without planets."""
    resp = dynamics.response.response
    mean = resp.mean_mesh_force()
    per_planet: dict[int, float] = {}
    for i, name in enumerate(resp.mesh_names):
        m = _SUN_MESH.match(name)
        if m is not None:
            per_planet[int(m.group(1))] = per_planet.get(int(m.group(1)), 0.0) + float(mean[i])
    if not per_planet:
        return None
    forces = np.array(list(per_planet.values()))
    return float(forces.max() / forces.mean())


def model_dynamic_factor(dynamics: Any, mesh: str) -> float | None:
    """The dynamic model's largest over mean mesh force at the operating speed for ``mesh``
    (a pair's one mesh; a planetary set's sun or ring meshes, ``s-p*`` / ``r-p*``), or None
    without dynamics."""
    if dynamics is None:
        return None
    resp = dynamics.response.response
    prefix = {"sun_planet": "s-", "planet_ring": "r-"}.get(mesh, "")
    rows = [i for i, n in enumerate(resp.mesh_names) if n.startswith(prefix)]
    force = resp.mesh_force[:, resp.steady_slice()]
    elastic = resp.elastic_mesh_force()[:, resp.steady_slice()]
    ratios = [float(elastic[i].max() / force[i].mean()) for i in rows if force[i].mean() > 0]
    return max(ratios) if ratios else None


def _mesh_spectrum(spectrum: LoadSpectrum, operation: Any, torque: float, rpm: float
                   ) -> LoadSpectrum:
    """The spectrum's bins (the driving gear's torque and speed, as ``[operation]``) as this
    mesh's pinion sees them: scaled with the mesh's pinion torque (N m) and speed (rpm)."""
    t_ref, n_ref = operation.torque, operation.speed * 30.0 / math.pi
    return LoadSpectrum(tuple(LoadBin(torque * b.torque / t_ref, rpm * b.speed / n_ref,
                                      b.hours) for b in spectrum.bins), spectrum.key)


def _pinion_load(st: MeshStages) -> tuple[float, float]:
    """The pinion's torque (N m) and speed (rpm) of a mesh, whichever gear drives."""
    op, pair = st.case.operation, st.case.pair
    rpm = op.speed * 30.0 / math.pi
    if op.driver == "pinion":
        return op.torque, rpm
    ratio = pair.gear.teeth / pair.pinion.teeth
    return op.torque / ratio, rpm * ratio


def _gear_inputs(box: Gearbox, role: str, k: int) -> GearRatingInputs:
    g = box.rating.gear(role)
    relief = getattr(box.contact.modifications, ("tip_relief_pinion", "tip_relief_gear")[k])
    return GearRatingInputs(
        sigma_hlim=g.sigma_hlim, sigma_flim=g.sigma_flim, hardening=g.running_in,
        pitting_line=g.pitting_line, bending_line=g.bending_line, size_class=g.size_class,
        hardness_hb=g.hardness_hb, notch_class=g.notch_class, proof_stress=g.proof_stress,
        cutter=g.cutter, inner_radius=box.bodies[role].rim_inner_radius,
        flank_roughness=g.flank_roughness,
        root_roughness=g.root_roughness,
        mean_stress_factor=IDLER_MEAN_STRESS if role == "planet" else 1.0,
        tip_relief=relief if relief > 0.0 else None)


def _warn_validity(m: MeshRating) -> None:
    """One PhysicsWarning line per factor taken outside the range the standard validates:
    the notch parameter q_s of Y_S (ISO 6336-3: 1 <= q_s < 8)."""
    for role, root in zip(m.gears, m.rating.roots, strict=True):
        if root is not None and not root.in_range:
            warnings.warn(f"rating: the {role}'s notch parameter q_s = s_Fn / (2 rho_F) = "
                          f"{root.q_s:.4g} lies outside 1 <= q_s < 8, where ISO 6336-3 "
                          "validates its stress correction factor Y_S", PhysicsWarning,
                          stacklevel=3)


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


def _unrated(box: Gearbox, role: str, internal: bool) -> str | None:
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


def _load_sharing(box: Gearbox, computed: float | None) -> tuple[float, str]:
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


def rating_stage(box: Gearbox, meshes: Mapping[str, MeshStages],
                 distributions: Mapping[str, LoadDistribution],
                 root_stress: Mapping[str, RootStress], dynamics: Any,
                 log: Steps) -> RatingStage | None:
    """The :class:`RatingStage` of a gearbox with a ``[rating]`` table (module docstring),
    one timed step; None without the table. ``distributions``: each mesh's load
    distribution; ``root_stress``: each mesh's FE root stress where computed (shown beside
    sigma_F); ``dynamics``: the run's dynamics stages or None."""
    opts = box.rating
    if opts is None:
        return None
    with log.step("ISO 6336 rating") as note:
        computed = None if dynamics is None or box.kind != "planetary" \
            else computed_load_sharing(dynamics)
        k_gamma, sharing = _load_sharing(box, computed)
        planets = box.planetary.n_planets if box.kind == "planetary" else 1
        cases, bins = {}, {}
        half_set = box.kind == "planetary" and box.planetary.sun.herringbone
        for name, st in meshes.items():
            dist = distributions[name]
            khb = {"contact": dist.k_hbeta, "method_c": None}.get(opts.face_load_factor,
                                                                 opts.face_load_factor)
            method_c = opts.method_c
            if name == "planet_ring":  # the planet on its pin: no pinion shaft of Figure 13
                method_c = dataclasses.replace(method_c, shaft=None)
            elif name == "sun_planet" and method_c.power_share is None:
                method_c = dataclasses.replace(method_c, power_share=100.0 / planets)
            # a planetary set's meshes are halves already (pipeline.run.chain.mesh_cases)
            whole = st.case.pair.pinion.herringbone
            pair = helical_half(st.stiffness.actual)
            torque, rpm = _pinion_load(st)
            torque = torque / 2.0 if whole else torque
            inputs = RatingInputs(
                application_factor=opts.application_factor,
                life_hours=opts.life_hours(box.operation.speed),
                accuracy_grade=opts.accuracy_grade, viscosity_40=opts.viscosity_40,
                k_hbeta=khb, load_sharing=k_gamma, face_load=method_c,
                blank_factor=blank_factor(box, ROLES[name]),
                minimum_safety_pitting=opts.minimum_safety_pitting,
                minimum_safety_bending=opts.minimum_safety_bending)
            gears = tuple(_gear_inputs(box, role, k) for k, role in enumerate(ROLES[name]))
            cases[name] = (pair, torque, rpm, inputs, gears,
                           "pair" if name == "mesh" else name, dist, whole or half_set)
            bins[name] = None if opts.spectrum is None else _mesh_spectrum(
                opts.spectrum, box.operation, torque, rpm)
        first = {n: rate_pair(*c[:5], mesh=c[5], planets=planets, double_helical=c[7])
                 for n, c in cases.items()}
        kv = max((r.dynamic for r in first.values()), key=lambda d: d.factor)
        out = {}
        for name, (pair, torque, rpm, inputs, gears, mesh, dist, half) in cases.items():
            rating = first[name] if len(first) == 1 else \
                rate_pair(pair, torque, rpm, inputs, gears, mesh, planets, dynamic=kv,
                          double_helical=half)
            root = root_stress.get(name)
            hg, fg, external = rating_limits(rating, opts.minimum_safety_pitting)
            local = local_safety(meshes[name].contact, dist, meshes[name].stiffness.actual,
                                 pitting_limit=hg, bending_limit=fg, load_factor=external,
                                 root=root, gears=ROLES[name])
            out[name] = MeshRating(
                name, ROLES[name], rating,
                _SOURCE.get(opts.face_load_factor, "given"),
                dist.k_hbeta, sharing, computed, half, dist.hertz_max.value,
                (None, None) if root is None else (root.pinion.max_stress,
                                                   root.gear.max_stress),
                (gears[0].sigma_hlim, gears[1].sigma_hlim),
                (gears[0].sigma_flim, gears[1].sigma_flim),
                opts.minimum_safety_pitting, opts.minimum_safety_bending,
                model_dynamic_factor(dynamics, name), local,
                None if bins[name] is None else rate_pair_spectrum(
                    pair, bins[name], inputs, gears, mesh, planets, double_helical=half),
                tuple(_unrated(box, role, gear.internal) for role, gear
                      in zip(ROLES[name], (pair.pinion, pair.gear), strict=True)))
        for m in out.values():
            _warn_validity(m)
        stage = RatingStage(out, opts.minimum_safety_pitting, opts.minimum_safety_bending)
        note["text"] = stage.line()
    return stage
