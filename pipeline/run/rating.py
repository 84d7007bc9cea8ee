"""The rating step of a run: ISO 6336 safety factors of every mesh beside the loaded contact.

With a ``[rating]`` table (:class:`~pipeline.rating.options.RatingOptions`), every mesh is
rated by ISO 6336 method B (:func:`pipeline.rating.pair_rating.rate_pair`): a pair's one
mesh, a planetary set's sun-planet and planet-ring meshes (the speed relative to the
carrier, the sun and the ring meeting one planet after another, the planet an idler with
Y_M 0.7, K_v the larger of the two meshes', as KISSsoft's ``KV = max(KV12, KV23)``), a
herringbone mesh as one helical half at half the load (ISO 6336-1: b_B of each half).
What the standard leaves to the analyst comes from the run where it can:

* the face load factor K_Hbeta: ISO 6336-1 method C's (:mod:`pipeline.rating.face_load`),
  the loaded contact's (the largest over the mean of the cycle-mean line load across the
  face, :mod:`pipeline.contact.distribution`) with ``face_load_factor = "contact"``, or the
  number given; the other two are shown beside. A pair on shafts solves its contact with
  the shafts' deflection (:mod:`pipeline.run.shafts`; the mesh's contact is that one,
  :func:`pipeline.run.chain.static_stages`), so its contact K_Hbeta is the system's, and it
  is the default there (:mod:`pipeline.config.rating`); method C's the default elsewhere;
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
import warnings
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from pipeline.config import Gearbox
from pipeline.contact.distribution import LoadDistribution
from pipeline.contact.root_stress import RootStress
from pipeline.dynamics.models.planetary_gears import helical_half
from pipeline.progress import Steps
from pipeline.rating.local_safety import LocalSafety, local_safety, rating_limits
from pipeline.rating.pair_rating import PairRating, RatingInputs, rate_pair
from pipeline.rating.pair_spectrum import rate_pair_spectrum
from pipeline.rating.spectrum import SpectrumRating
from pipeline.run.chain import MeshStages
from pipeline.run.rating_inputs import (
    blank_factor,
    computed_load_sharing,
    gear_inputs,
    load_sharing,
    mesh_spectrum,
    model_dynamic_factor,
    pinion_load,
    unrated_reason,
)
from pipeline.validation import PhysicsWarning

ROLES = {"mesh": ("pinion", "gear"), "sun_planet": ("sun", "planet"),
         "planet_ring": ("planet", "ring")}
"""The gear tables rated in each mesh, (pinion, gear)."""

_SOURCE = {"contact": "loaded contact", "method_c": "ISO 6336-1 method C"}
SHAFT_CONTACT = "loaded contact with the shafts' deflection"
"""The K_Hbeta source of a mesh whose contact was solved on its shafts."""


def k_hbeta_source(choice: str | float, on_shafts: bool) -> str:
    """The report's name of where K_Hbeta came from: ``face_load_factor``'s ``choice``, the
    contact solved with the shafts' deflection when ``on_shafts``."""
    if choice == "contact" and on_shafts:
        return SHAFT_CONTACT
    return _SOURCE.get(choice, "given") if isinstance(choice, str) else "given"


@dataclass(frozen=True)
class MeshRating:
    """The rating of one mesh and what the run knows beside it.

    Attributes
    ----------
    mesh : "mesh", "sun_planet" or "planet_ring".
    gears : the gear tables rated, (pinion, gear).
    rating : every factor (:class:`~pipeline.rating.pair_rating.PairRating`).
    k_hbeta_source : "ISO 6336-1 method C", "loaded contact", "loaded contact with the
        shafts' deflection" (:data:`SHAFT_CONTACT`) or "given".
    k_hbeta_contact : the loaded contact's K_Hbeta (-; with the shafts' deflection when the
        pair sits on shafts).
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


def _warn_validity(m: MeshRating) -> None:
    """One PhysicsWarning line per factor taken outside the range the standard validates:
    the notch parameter q_s of Y_S (ISO 6336-3: 1 <= q_s < 8)."""
    for role, root in zip(m.gears, m.rating.roots, strict=True):
        if root is not None and not root.in_range:
            warnings.warn(f"rating: the {role}'s notch parameter q_s = s_Fn / (2 rho_F) = "
                          f"{root.q_s:.4g} lies outside 1 <= q_s < 8, where ISO 6336-3 "
                          "validates its stress correction factor Y_S", PhysicsWarning,
                          stacklevel=3)


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
        k_gamma, sharing = load_sharing(box, computed)
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
            torque, rpm = pinion_load(st)
            torque = torque / 2.0 if whole else torque
            inputs = RatingInputs(
                application_factor=opts.application_factor,
                life_hours=opts.life_hours(box.operation.speed),
                accuracy_grade=opts.accuracy_grade, viscosity_40=opts.viscosity_40,
                k_hbeta=khb, load_sharing=k_gamma, face_load=method_c,
                blank_factor=blank_factor(box, ROLES[name]),
                minimum_safety_pitting=opts.minimum_safety_pitting,
                minimum_safety_bending=opts.minimum_safety_bending)
            gears = tuple(gear_inputs(box, name, role, k) for k, role in enumerate(ROLES[name]))
            cases[name] = (pair, torque, rpm, inputs, gears,
                           "pair" if name == "mesh" else name, dist, whole or half_set)
            bins[name] = None if opts.spectrum is None else mesh_spectrum(
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
                k_hbeta_source(opts.face_load_factor, meshes[name].shafts is not None),
                dist.k_hbeta, sharing, computed, half, dist.hertz_max.value,
                (None, None) if root is None else (root.pinion.max_stress,
                                                   root.gear.max_stress),
                (gears[0].sigma_hlim, gears[1].sigma_hlim),
                (gears[0].sigma_flim, gears[1].sigma_flim),
                opts.minimum_safety_pitting, opts.minimum_safety_bending,
                model_dynamic_factor(dynamics, name), local,
                None if bins[name] is None else rate_pair_spectrum(
                    pair, bins[name], inputs, gears, mesh, planets, double_helical=half),
                tuple(unrated_reason(box, role, gear.internal) for role, gear
                      in zip(ROLES[name], (pair.pinion, pair.gear), strict=True)))
        for m in out.values():
            _warn_validity(m)
        stage = RatingStage(out, opts.minimum_safety_pitting, opts.minimum_safety_bending)
        note["text"] = stage.line()
    return stage
