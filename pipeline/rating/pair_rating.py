"""The ISO 6336 rating of one gear mesh, every factor in one record.

:func:`rate_pair` chains the pieces of this package for a pair at its operating point:
the tolerances of the accuracy grade (:mod:`.accuracy`), the running-in allowances and
the dynamic factor K_v (:mod:`.dynamic`), ISO 6336-1's stiffness (c', c_gamma,
:mod:`pipeline.stiffness.iso6336`), the transverse load factors (:mod:`.transverse`), the
face load factor K_Hbeta as given (the standard's method C and the loaded contact's line
load are to come), then the contact stress and S_H (:mod:`.pitting`) and the root stress
and S_F (:mod:`.bending`) of both gears. SI inside; the record keeps each factor.

A mesh is a pair, or one mesh of a planetary set (``"sun_planet"``: the sun as pinion;
``"planet_ring"``: the planet as pinion, the ring internal), with the speed relative to the
carrier: the reduced mass of K_v is the mesh's (:func:`.dynamic.reduced_mass`), and a gear
meets as many teeth per revolution as it has mates (the sun and the ring one per planet),
which sets its load cycles. An internal gear's root section is the one its pinion-type
cutter generates (:class:`~pipeline.contact.iso_root_stress.ShaperCutter`); without a cutter
its bending entry is ``None``, as is that of a gear whose slip layer is not built.

Checked end to end against KISSsoft's report of the NREL 5 MW gearbox's parallel helical
stage (``tests/test_rating_pair.py``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.contact.iso_root_stress import IsoRootStress, ShaperCutter, iso_root_stress
from pipeline.geometry.pair import GearPair
from pipeline.rating.accuracy import Tolerances, tolerances
from pipeline.rating.bending import BendingSafety, bending_safety, face_load_factor
from pipeline.rating.bending import strength_curve as bending_curve
from pipeline.rating.dynamic import (
    HARDENING,
    DynamicFactor,
    dynamic_factor,
    gear_mass,
    reduced_mass,
    running_in,
    running_in_relief,
)
from pipeline.rating.face_load import FaceLoadFactor, FaceLoadInputs, face_load_method_c
from pipeline.rating.life import StrengthCurve
from pipeline.rating.pitting import (
    ContactStress,
    PittingSafety,
    contact_ratio_factor,
    contact_stress,
    pitting_safety,
    work_hardening_factor,
)
from pipeline.rating.pitting import strength_curve as pitting_curve
from pipeline.rating.transverse import TransverseLoadFactors, transverse_load_factors
from pipeline.stiffness.iso6336 import iso_stiffness
from pipeline.validation import InputError, check_choice, check_int_range, check_range

SLIP_LAYER_HARDENED = 0.0030e-3
"""Slip-layer thickness rho' of Y_deltarelT (ISO 6336-3), m: a case-hardened or flame- or
induction-hardened root (Eh, IF)."""
SLIP_LAYER_THROUGH_HARDENED = ((500e6, 0.0281e-3), (600e6, 0.0194e-3), (800e6, 0.0064e-3),
                               (1000e6, 0.0014e-3))
"""rho' (m) of a through-hardened steel, GTS or pearlitic GGG at its 0.2 % proof stress
(Pa), ISO 6336-3's table points, linear between them (KISSsoft's 34CrNiMo6 ring of the NREL
5 MW gearbox, yield 1000 N/mm^2, prints Y_deltarelT 1.005 with it). The other materials'
rho' (St, GG, GGG ferr., NT, NV) and their Y_RrelT lines are not built: such a gear is not
rated in bending unless its ``slip_layer`` is given."""
NOTCH_CLASSES = ("hardened", "through_hardened")


def slip_layer(notch_class: str | None, proof_stress: float | None) -> float | None:
    """rho' (m) of a gear of ``notch_class`` ("hardened": Eh, IF; "through_hardened": V,
    GTS, GGG perl. with its 0.2 % ``proof_stress`` in Pa), or None where it is not built."""
    if notch_class == "hardened":
        return SLIP_LAYER_HARDENED
    if notch_class != "through_hardened" or proof_stress is None:
        return None
    xs, ys = zip(*SLIP_LAYER_THROUGH_HARDENED, strict=True)
    check_range("rating.proof_stress", proof_stress, xs[0], xs[-1], unit="Pa",
                note="the points of ISO 6336-3's slip-layer table")
    return float(np.interp(proof_stress, xs, ys))


@dataclass(frozen=True)
class GearRatingInputs:
    """One gear's rating inputs (SI).

    Attributes
    ----------
    sigma_hlim, sigma_flim : sigma_Hlim and sigma_Flim (the test gear's, without Y_ST), Pa.
    hardening : running-in class of ISO 6336-1: "hardened" (Eh, IF, NT, NV),
        "through_hardened" (St, V, GGG perl., GTS) or "cast_iron" (GG, GGG ferr.).
    pitting_line : ISO 6336-2 life line (:data:`pipeline.rating.pitting.LIFE_LINES`).
    bending_line, size_class : ISO 6336-3 life line and Y_X class, or None for
        ``hardening``'s.
    hardness_hb : Brinell hardness of a through-hardened gear (for Z_W against a hardened
        mate), or None.
    flank_roughness, root_roughness : R_z of the flank and of the root, m.
    slip_layer : rho' of Y_deltarelT, m, or None for :func:`slip_layer`'s.
    notch_class : :data:`NOTCH_CLASSES` entry of the root's material (its rho' and
        Y_RrelT line), or None where not built (not rated in bending without ``slip_layer``).
    proof_stress : 0.2 % proof stress of a through-hardened gear, Pa (its rho').
    cutter : the pinion-type cutter that cut an internal gear (its root section), or None
        (an internal gear is then not rated in bending).
    inner_radius : the inner radius of K_v's gear mass m* (a webbed gear's rim), m, or None
        for the gear's bore.
    mean_stress_factor : Y_M (1; 0.7 for an idler).
    tip_relief : C_a, m, or None for the running-in relief C_ay.
    """

    sigma_hlim: float
    sigma_flim: float
    hardening: str = "hardened"
    pitting_line: str = "hardened"
    bending_line: str | None = None
    size_class: str | None = None
    hardness_hb: float | None = None
    flank_roughness: float = 4.8e-6
    root_roughness: float = 20e-6
    slip_layer: float | None = None
    notch_class: str | None = "hardened"
    proof_stress: float | None = None
    cutter: ShaperCutter | None = None
    inner_radius: float | None = None
    mean_stress_factor: float = 1.0
    tip_relief: float | None = None

    def __post_init__(self) -> None:
        check_choice("rating.hardening", self.hardening, HARDENING)

    @property
    def bending_class(self) -> str:
        """The ISO 6336-3 life line."""
        return self.bending_line or self.hardening


@dataclass(frozen=True)
class RatingInputs:
    """The pair's rating inputs (SI).

    Attributes
    ----------
    application_factor : K_A; load_sharing : K_gamma (1 for a single mesh).
    life_hours : required life, h.
    accuracy_grade : ISO 1328-1:1995 grade of both gears.
    viscosity_40 : kinematic viscosity of the oil at 40 deg C, m^2/s.
    k_hbeta : the face load factor K_Hbeta used, or None for ISO 6336-1 method C's.
    face_load : method C's inputs (:class:`~pipeline.rating.face_load.FaceLoadInputs`): its
        K_Hbeta is computed whenever they are given (shown beside a K_Hbeta given), and
        used when ``k_hbeta`` is None.
    blank_factor : C_R of ISO 6336-1's stiffness (1 for solid blanks).
    minimum_safety_pitting, minimum_safety_bending : S_Hmin, S_Fmin.
    """

    application_factor: float
    life_hours: float
    accuracy_grade: int
    viscosity_40: float
    k_hbeta: float | None
    load_sharing: float = 1.0
    face_load: FaceLoadInputs | None = None
    blank_factor: float = 1.0
    minimum_safety_pitting: float = 1.0
    minimum_safety_bending: float = 1.4

    def __post_init__(self) -> None:
        check_range("rating.application_factor", self.application_factor, 1.0, 5.0)
        check_range("rating.life_hours", self.life_hours, 0.0, 1e7, lo_open=True, unit="h")
        check_int_range("rating.accuracy_grade", self.accuracy_grade, 1, 12)
        if self.k_hbeta is None:
            if self.face_load is None:
                raise InputError("rating: K_Hbeta needs a value or method C's inputs")
        else:
            check_range("rating.k_hbeta", self.k_hbeta, 1.0, 10.0)
        check_range("rating.load_sharing", self.load_sharing, 1.0, 3.0)


@dataclass(frozen=True)
class PairRating:
    """Every factor of a pair's rating (SI; gear-wise tuples are (pinion, wheel)):
    ``face_load`` ISO 6336-1 method C's K_Hbeta with its intermediates (None without its
    inputs); ``cycles`` the load cycles of each gear over the life; ``roots`` ISO 6336-3's nominal
    root stress with its form factors (None where the gear is not rated in bending);
    ``curves`` each gear's S-N lines (pitting, bending or None) of
    :class:`~pipeline.rating.life.StrengthCurve`, ``cycles_per_revolution`` each gear's
    load cycles per revolution of the pinion (the load spectrum's bookkeeping);
    ``blank_factor`` C_R of the stiffness."""

    tangential_load: float
    velocity: float
    application_factor: float
    load_sharing: float
    tolerances: tuple[Tolerances, Tolerances]
    single_stiffness: float
    mesh_stiffness: float
    dynamic: DynamicFactor
    transverse: TransverseLoadFactors
    k_hbeta: float
    k_fbeta: float
    contact: ContactStress
    pitting: tuple[PittingSafety, PittingSafety]
    bending: tuple[BendingSafety | None, BendingSafety | None]
    face_load: FaceLoadFactor | None = None
    cycles: tuple[float, float] = (0.0, 0.0)
    roots: tuple[IsoRootStress | None, IsoRootStress | None] = (None, None)
    curves: tuple[tuple[StrengthCurve, StrengthCurve | None], ...] = ()
    cycles_per_revolution: tuple[float, float] = (1.0, 1.0)
    blank_factor: float = 1.0

    @property
    def safety_pitting_min(self) -> float:
        return min(p.safety for p in self.pitting)

    @property
    def safety_bending_min(self) -> float:
        """The smaller S_F of the gears rated in bending (NaN when none is)."""
        rated = [b.safety for b in self.bending if b is not None]
        return min(rated) if rated else math.nan


MESHES = ("pair", "sun_planet", "planet_ring")


def cycles_per_revolution(pair: GearPair, mesh: str, planets: int = 1) -> tuple[float, float]:
    """Load cycles of the pinion and the gear per revolution of the pinion (relative to a
    planet carrier) in a ``mesh`` of :data:`MESHES`: a sun or a ring meets each of the
    ``planets`` once per revolution, the gear turns 1 / |u| times."""
    contacts = {"pair": (1, 1), "sun_planet": (planets, 1), "planet_ring": (1, planets)}[mesh]
    return (float(contacts[0]), contacts[1] * pair.pinion.teeth / pair.gear.teeth)


def rate_pair(pair: GearPair, torque: float, speed: float, inputs: RatingInputs,
              gears: tuple[GearRatingInputs, GearRatingInputs], mesh: str = "pair",
              planets: int = 1, dynamic: DynamicFactor | None = None,
              double_helical: bool = False) -> PairRating:
    """The rating of ``pair`` with the pinion ``torque`` (N m) at ``speed`` (rpm; a
    planetary mesh's relative to the carrier) as a ``mesh`` of :data:`MESHES` in a set of
    ``planets`` planets (module docstring). ``dynamic``: the K_v to use instead of this
    mesh's own (a planetary set takes the larger of its two meshes' K_v, as KISSsoft does:
    ``KV = max(KV12, KV23)``). ``double_helical``: ``pair`` is one helix of a double helical
    pair at half the load (method C's Eq. (58) with both helices, K_Fbeta with ``b_B``)."""
    check_range("rating.torque", torque, 0.0, math.inf, lo_open=True, unit="N m")
    check_choice("rating.mesh", mesh, MESHES)
    if pair.gear.internal != (mesh == "planet_ring") and mesh != "pair":
        raise InputError(f"rating: a {mesh} mesh has "
                         + ("an internal" if mesh == "planet_ring" else "no internal")
                         + " gear")
    p, g = pair.pinion, pair.gear
    b = pair.face_width
    d1 = 2.0 * p.reference_radius
    ft = 2.0 * torque / d1
    v = p.reference_radius * speed * math.pi / 30.0
    ka, kg = inputs.application_factor, inputs.load_sharing
    at = p.transverse_pressure_angle
    tols = tuple(tolerances(inputs.accuracy_grade, gear.module, 2.0 * gear.reference_radius,
                            b, at) for gear in (p, g))
    f_pb = max(t.f_pb for t in tols)
    f_fa = max(t.f_falpha for t in tols)
    materials = tuple((gi.hardening, gi.sigma_hlim) for gi in gears)
    y_p, y_f = (running_in(f, materials, v) for f in (f_pb, f_fa))
    st = iso_stiffness(pair, ft, ka, c_r=inputs.blank_factor)
    masses = [gear_mass(2.0 * gear.tip_radius_, 2.0 * gear.root_radius, 2.0 * gear.base_radius,
                        2.0 * (gi.inner_radius if gi.inner_radius is not None
                               else gear.bore_radius), gear.material.density)
              for gear, gi in zip((p, g), gears, strict=True) if not gear.internal]
    # an internal pair's ring is not a mass of the mesh (a planet-ring mesh's rule)
    m_red = reduced_mass(masses[0], masses[1] if len(masses) > 1 else None,
                         "planet_ring" if g.internal else mesh, planets)
    reliefs = [gi.tip_relief if gi.tip_relief is not None else running_in_relief(gi.sigma_hlim)
               for gi in gears]
    kv = dynamic_factor(teeth_1=p.teeth, speed_1=speed, single_stiffness=st.c_single,
                        mesh_stiffness=st.c_gamma_alpha, reduced_mass_per_width=m_red,
                        line_load=ka * ft / b, total_contact_ratio=pair.total_contact_ratio,
                        base_pitch_deviation=f_pb, form_deviation=f_fa, pitch_allowance=y_p,
                        form_allowance=y_f, tip_relief=0.5 * (reliefs[0] + reliefs[1]))
    kv = kv if dynamic is None else dynamic
    depth = min(abs(gear.tip_radius_ - gear.root_radius) for gear in (p, g))
    method_c = None
    if inputs.face_load is not None:
        tol5 = [tolerances(5, gear.module, 2.0 * gear.reference_radius, b, at) for gear in (p, g)]
        method_c = face_load_method_c(
            inputs.face_load, line_load=ft * ka * kg * kv.factor / b,
            face_width=(2.0 if double_helical else 1.0) * b, pinion_diameter=d1,
            c_gamma_beta=st.c_gamma_beta,
            helix_slope_deviations=(tols[0].f_Hbeta, tols[1].f_Hbeta),
            materials=materials, velocity=v,
            tooth_height=max(abs(gear.tip_radius_ - gear.root_radius) for gear in (p, g)),
            grade5_helix_slope_deviation=max(t.f_Hbeta for t in tol5),
            double_helical=double_helical)
    khb = method_c.k_hbeta if inputs.k_hbeta is None else inputs.k_hbeta
    kha = transverse_load_factors(
        mesh_stiffness=st.c_gamma_alpha, base_pitch_deviation=f_pb, form_deviation=f_fa,
        allowance=y_p, line_load_h=ft * ka * kg * kv.factor * khb / b,
        transverse_contact_ratio=pair.transverse_contact_ratio,
        total_contact_ratio=pair.total_contact_ratio,
        contact_ratio_factor=contact_ratio_factor(pair.transverse_contact_ratio,
                                                  pair.overlap_ratio))
    chain = contact_stress(pair, torque, speed, ka * kg * kv.factor * khb * kha.k_halpha)
    kfb = face_load_factor(khb, b, depth)
    per_rev = cycles_per_revolution(pair, mesh, planets)
    cycles = tuple(speed * 60.0 * inputs.life_hours * c for c in per_rev)
    lower = min(gi.sigma_hlim for gi in gears)
    rz = 0.5 * (gears[0].flank_roughness + gears[1].flank_roughness)
    pit, bend, roots, curves = [], [], [], []
    for k, (gear, gi, n) in enumerate(zip((p, g), gears, cycles, strict=True)):
        other = gears[1 - k]
        zw = (work_hardening_factor(gi.hardness_hb) if gi.hardening == "through_hardened"
              and other.hardening == "hardened" and gi.hardness_hb is not None else 1.0)
        pit.append(pitting_safety(chain.stress[k], gi.sigma_hlim, n, gi.pitting_line,
                                  inputs.viscosity_40, rz, chain,
                                  inputs.minimum_safety_pitting, mesh_sigma_hlim=lower,
                                  work_hardening=zw))
        curve_h = pitting_curve(gi.sigma_hlim, gi.pitting_line, inputs.viscosity_40, rz, chain,
                                mesh_sigma_hlim=lower, work_hardening=zw)
        slip = gi.slip_layer if gi.slip_layer is not None \
            else slip_layer(gi.notch_class, gi.proof_stress)
        if (gear.internal and gi.cutter is None) or slip is None:
            bend.append(None)
            roots.append(None)
            curves.append((curve_h, None))
            continue
        root = iso_root_stress(gear, pair, ft, cutter=gi.cutter if gear.internal else None)
        roots.append(root)
        bend.append(bending_safety(root, ka * kg * kv.factor * kfb * kha.k_falpha,
                                   gi.sigma_flim, n, gi.bending_class, slip,
                                   gi.root_roughness, gi.size_class or gi.hardening,
                                   gear.module, inputs.minimum_safety_bending,
                                   mean_stress_factor=gi.mean_stress_factor,
                                   proof_stress=gi.proof_stress))
        curves.append((curve_h, bending_curve(root, gi.sigma_flim, gi.bending_class, slip,
                                              gi.root_roughness, gi.size_class or gi.hardening,
                                              gear.module,
                                              mean_stress_factor=gi.mean_stress_factor,
                                              proof_stress=gi.proof_stress)))
    return PairRating(ft, v, ka, kg, tols, st.c_single, st.c_gamma_alpha, kv, kha, khb, kfb, chain,
                      (pit[0], pit[1]), (bend[0], bend[1]), method_c, cycles,
                      (roots[0], roots[1]), (curves[0], curves[1]),
                      per_rev, inputs.blank_factor)
