"""The sections of a mesh report from the results of the stages (numbers in report units).

Pure functions: stage results in, :class:`~pipeline.report.model.Section` out. Units of
the report: mm, deg, um, urad, N/mm (line and unit loads), N/um (mesh stiffness), MPa
(pressures, stresses), N m, rpm; every row states its unit.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.contact.distribution import LoadDistribution
from pipeline.contact.options import ContactOptions
from pipeline.contact.separations import FlankModifications
from pipeline.geometry.analysis import GeometryResult
from pipeline.geometry.pair import GearPair
from pipeline.geometry.planetary_speeds import PlanetarySpeeds
from pipeline.operation import OperatingPoint
from pipeline.report.model import Figure, Quantity, Section
from pipeline.stiffness.analysis import StiffnessResult

MM, UM, MPA, N_PER_MM, N_PER_UM = 1e3, 1e6, 1e-6, 1e-3, 1e-6
RPM = 60.0 / (2.0 * math.pi)


def quantity(key: str, label: str, unit: str, *values: Any) -> Quantity:
    """A table row; numpy scalars become Python numbers (JSON, formatting)."""
    return Quantity(key, label, tuple(_plain(v) for v in values), unit)


def _plain(v: Any) -> Any:
    """Python numbers for numpy scalars; NaN becomes None (strict JSON; shown as a dash)."""
    if isinstance(v, (np.floating, float)):
        return None if math.isnan(v) else float(v)
    if isinstance(v, (np.integer,)):
        return int(v)
    if isinstance(v, (np.bool_,)):
        return bool(v)
    return v


@dataclass(frozen=True)
class PlanetaryMesh:
    """Where the operating point of a planetary set's mesh sits in the set.

    Attributes
    ----------
    mesh : "sun_planet" (the sun drives it) or "planet_ring" (the planet drives it).
    sun_torque : T_s, torque on the sun from all planets (both halves), N m.
    n_planets : N.
    herringbone : the mesh is one helical half of a herringbone set at an equal split.
    halves_solved : the report also shows both halves solved through the groove.
    speeds : the set's speeds, ring fixed (rad/s).
    """

    mesh: str
    sun_torque: float
    n_planets: int
    herringbone: bool
    halves_solved: bool
    speeds: PlanetarySpeeds


def _planetary_rows(operation: OperatingPoint, planetary: PlanetaryMesh
                    ) -> tuple[list[Quantity], tuple[str, ...]]:
    """Torque and speed rows of a planetary mesh, saying what they are, and a note."""
    v, n = planetary.speeds, planetary.n_planets
    driver = "sun" if planetary.mesh == "sun_planet" else "planet"
    half = ", one helical half at an equal split of the mesh load" if planetary.herringbone \
        else ""
    rows = [
        quantity("torque", f"torque on the {driver} at its mesh with one planet{half}"
                 if driver == "sun" else f"torque on the planet at its ring mesh{half}", "N m",
                 operation.torque),
        quantity("sun_torque", f"sun torque T_s (all {n} planets"
                 f"{', both halves' if planetary.herringbone else ''})", "N m",
                 planetary.sun_torque),
        quantity("speed", f"speed of the {driver} relative to the carrier, magnitude (the "
                 "frame the contact is solved in)", "rpm", operation.speed * RPM),
        quantity("speed_sun", "sun speed (ring fixed)", "rpm", v.sun * RPM),
        quantity("speed_carrier", "carrier speed", "rpm", v.carrier * RPM),
        quantity("speed_planet", "planet speed (+ in the sun's sense)", "rpm", v.planet * RPM),
    ]
    notes: tuple[str, ...] = ()
    if planetary.herringbone:
        notes = ("One helical half of the herringbone set with half the mesh load "
                 f"(T_s / (2 N) on the sun, N = {n}), as if the halves shared it equally; "
                 + ("both halves solved together through the sun's relief groove are in "
                    "the section 'Herringbone halves through the groove'."
                    if planetary.halves_solved else
                    "the halves are not solved together (a [groove] table of the sun "
                    "gives them through its relief groove)." if driver == "sun" else
                    "the two halves of the planet-ring mesh are not solved together."),)
    return rows, notes


def operation_section(pair: GearPair, operation: OperatingPoint, contact: ContactOptions,
                      compliance: str, dist: LoadDistribution,
                      planetary: PlanetaryMesh | None = None) -> Section:
    """Operating point and how the contact was solved; for a planetary set's mesh
    (``planetary``) the torque and speed say which member and frame they are."""
    driver = pair.pinion if operation.driver == "pinion" else pair.gear
    f_t = operation.torque / driver.reference_radius
    if planetary is None:
        head = [quantity("torque", f"torque on the driving gear ({operation.driver})", "N m",
                         operation.torque),
                quantity("speed", f"speed of the driving gear ({operation.driver})", "rpm",
                         operation.speed * RPM)]
        notes: tuple[str, ...] = ()
    else:
        head, notes = _planetary_rows(operation, planetary)
    return Section("operation", "Operating point and analysis", (
        *head,
        quantity("load_line_of_action", "load along the transverse line of action P", "N",
           dist.load),
        quantity("tangential_load", "nominal tangential load F_t at the reference circle", "N",
            f_t),
        quantity("compliance", "compliance source of the loaded contact", "", compliance),
        quantity("local_contact", "local contact model", "", contact.local_contact),
        quantity("positions", "mesh positions per cycle", "-", len(dist.transmission_error)),
        quantity("slices", "slices across the face width", "-", dist.slices_across_face),
    ), notes=notes)


def geometry_section(geometry: GeometryResult, actual: GearPair, figures: Sequence[Figure]
                     ) -> Section:
    """Both gears side by side, then the pair (contact ratios of the installed pair)."""
    p, g = actual.pinion, actual.gear
    fp, fg = (prof.form_radius for prof in geometry.profiles)

    def both(key, label, unit, fn):
        return quantity(key, label, unit, fn(p), fn(g))

    rows = [
        both("name", "gear", "", lambda x: x.name),
        both("teeth", "number of teeth z", "-", lambda x: x.teeth),
        both("normal_module", "normal module m_n", "mm", lambda x: x.module * MM),
        both("pressure_angle", "normal pressure angle alpha_n", "deg",
             lambda x: math.degrees(x.pressure_angle)),
        both("helix_angle", "helix angle beta", "deg", lambda x: math.degrees(x.helix_angle)),
        both("hand", "hand of helix", "", lambda x: x.hand),
        both("face_width", "face width b", "mm", lambda x: x.face_width * MM),
        both("profile_shift", "profile shift coefficient x", "-", lambda x: x.profile_shift),
        both("internal", "internal gear", "", lambda x: bool(x.internal)),
        both("reference_diameter", "reference diameter d", "mm",
             lambda x: 2 * x.reference_radius * MM),
        both("base_diameter", "base diameter d_b", "mm", lambda x: 2 * x.base_radius * MM),
        both("tip_diameter", "tip diameter d_a", "mm", lambda x: 2 * x.tip_radius_ * MM),
        both("tip_rounding", "tip rounding radius (0: a sharp corner)", "mm",
             lambda x: x.tip_rounding * MM),
        both("active_tip_diameter", "end of the involute (the rounding's tangency), d_Na",
             "mm", lambda x: 2 * x.active_tip_radius * MM),
        both("root_diameter", "root diameter d_f", "mm", lambda x: 2 * x.root_radius * MM),
        quantity("form_diameter", "form diameter d_Ff (fillet meets involute)", "mm", 2 * fp * MM,
           2 * fg * MM),
        both("cutter_tip_radius", "rack cutter tip radius rho_a0", "mm",
             lambda x: x.cutter_tip_radius_coef * x.module * MM),
        both("bore_diameter", "bore diameter (ring: rim outer diameter)", "mm",
             lambda x: 2 * x.bore_radius * MM),
        both("youngs_modulus", "Young's modulus E", "GPa",
             lambda x: x.material.youngs_modulus * 1e-9),
        both("poisson_ratio", "Poisson's ratio nu", "-", lambda x: x.material.poisson_ratio),
    ]
    gears = Section("geometry", "Gears", tuple(rows), columns=("pinion", "gear"),
                    figures=tuple(figures))
    return gears


def pair_section(actual: GearPair, nominal: GearPair) -> Section:
    """Centre distance, pressure angle, contact ratios and the path of contact."""
    a = actual
    nominal_label = ("nominal centre distance (pair.centre_distance_mm)"
                     if nominal.centre_distance is not None else
                     "nominal centre distance = zero-backlash distance from the profile "
                     "shifts (ISO 21771)")
    sign = "-" if a.gear.internal else "+"
    return Section("pair", "Pair (as installed)", (
        quantity("centre_distance", "operating centre distance a_w", "mm",
           a.operating_centre_distance * MM),
        quantity("centre_distance_nominal", nominal_label, "mm",
           nominal.operating_centre_distance * MM),
        quantity("centre_distance_reference", "reference centre distance a = m_t (z2 "
                 f"{sign} z1) / 2 (unshifted gears)", "mm",
                 nominal.reference_centre_distance * MM),
        quantity("operating_pressure_angle", "transverse operating pressure angle alpha_wt", "deg",
           math.degrees(a.operating_pressure_angle)),
        quantity("circular_backlash", "transverse circular backlash j_wt on the operating "
                 "pitch circles (negative: interference)", "um", a.circular_backlash * UM),
        quantity("transverse_contact_ratio", "transverse contact ratio eps_alpha", "-",
           a.transverse_contact_ratio),
        quantity("overlap_ratio", "overlap ratio eps_beta", "-", a.overlap_ratio),
        quantity("total_contact_ratio", "total contact ratio eps_gamma", "-",
            a.total_contact_ratio),
        quantity("base_pitch", "transverse base pitch p_bt", "mm", a.base_pitch * MM),
        quantity("path_of_contact", "length of the path of contact g_alpha", "mm",
           a.path_length * MM),
        quantity("gear_ratio", "gear ratio u = z2 / z1", "-", a.gear_ratio),
    ))


def modifications_section(contact: ContactOptions, assembly: Any, assembled: Any,
                          figures: Sequence[Figure] = (),
                          gears: tuple[str, str] = ("pinion", "gear")) -> Section:
    """Profile and lead modifications (each gear's, or ``[contact]``'s short form), pitch
    errors and assembly errors; ``figures``: the flanks' modification maps; ``gears``: the
    gear tables of the mesh's pinion and gear (a planetary mesh: "sun", "planet", "ring")."""
    m = contact.modifications
    pitch = ", ".join(f"{e * UM:g}" for e in m.pitch_errors) or "none"
    per_gear = m.pinion_flank is not None or m.gear_flank is not None
    rows = _gear_modification_rows(m, gears) if per_gear else _short_form_rows(m)
    rows += [
        quantity("pitch_errors", "pitch errors of tooth pairs k = 0, 1, ... (k = 0 enters "
                 "contact at the start of the cycle)", "um", pitch),
        quantity("assembly_error_pinion", "pinion centre displacement (e_x, e_y)", "um",
           ", ".join(f"{e * UM:g}" for e in assembly.pinion)),
        quantity("assembly_error_gear", "gear centre displacement (e_x, e_y)", "um",
           ", ".join(f"{e * UM:g}" for e in assembly.gear)),
    ]
    if assembled is not None:
        rows.append(quantity("centre_distance_change", "centre distance change from the errors",
                       "um", assembled.summary()["centre_distance_change_um"]))
    notes = ()
    if figures:
        notes = ("Modification maps: material removed (positive) over each modified flank's "
                 "active part, face position across, roll length along the profile with the "
                 "tip up (diameter on the right); the initial gap at a contact point is the "
                 "sum of both flanks' values there.",)
    return Section("modifications", "Modifications and errors", tuple(rows),
                   figures=tuple(figures), notes=notes)


def _short_form_rows(m: FlankModifications) -> list[Quantity]:
    """``[contact]``'s short form: tip reliefs by roll length, crowning, slope deviation."""
    return [
        quantity("tip_relief_pinion", "tip relief C_a of the pinion", "um",
            m.tip_relief_pinion * UM),
        quantity("tip_relief_length_pinion", "tip relief length of the pinion (roll)", "mm",
           m.relief_length_pinion * MM),
        quantity("tip_relief_gear", "tip relief C_a of the gear", "um", m.tip_relief_gear * UM),
        quantity("tip_relief_length_gear", "tip relief length of the gear (roll)", "mm",
           m.relief_length_gear * MM),
        # the shape of an absent relief is no property of the gears
        quantity("relief_shape", "relief shape", "",
                 m.relief_shape if m.tip_relief_pinion > 0.0 or m.tip_relief_gear > 0.0
                 else "none (no tip relief)"),
        quantity("crowning", "lead crowning C_b (both gears)", "um", m.crowning * UM),
        quantity("slope_deviation", "helix slope deviation / misalignment f_Hb", "um",
           m.slope_deviation * UM),
    ]


def _gear_modification_rows(m: FlankModifications, gears: tuple[str, str]) -> list[Quantity]:
    """Each gear's modifications, the ones given (``[<gear>.modifications]``), by the gear
    tables ``gears`` of the mesh's pinion and gear."""
    rows = []
    for role, g in zip(gears, m.flanks, strict=True):
        p, q = g.profile, g.lead
        for end, sym in (("tip", "C_a"), ("root", "C_f")):
            amount = getattr(p, f"{end}_relief")
            if not amount:
                continue
            length = getattr(p, f"{end}_relief_length")
            start = (f"roll length {length * MM:.4g} mm from the "
                     f"{'active tip' if end == 'tip' else 'start of active profile'}"
                     if length is not None else
                     f"diameter {getattr(p, f'{end}_relief_diameter') * MM:.6g} mm")
            rows += [quantity(f"{role}_{end}_relief", f"{role}: {end} relief {sym}", "um",
                              amount * UM),
                     quantity(f"{role}_{end}_relief_start", f"{role}: {end} relief start "
                              f"({getattr(p, f'{end}_relief_shape')})", "", start)]
        for key, label, value in (
                ("profile_crowning", "profile crowning C_alpha", p.crowning),
                ("profile_slope", "profile slope f_Halpha (+: more removed at the tip)", p.slope),
                ("lead_crowning", "lead crowning C_beta", q.crowning),
                ("helix_slope", "helix slope f_Hbeta (+: more removed at face 2)", q.slope),
                ("end_relief_face1", f"end relief at face 1 over "
                 f"{q.end_relief_face1_length * MM:.4g} mm ({q.end_relief_shape})",
                 q.end_relief_face1),
                ("end_relief_face2", f"end relief at face 2 over "
                 f"{q.end_relief_face2_length * MM:.4g} mm ({q.end_relief_shape})",
                 q.end_relief_face2),
                ("twist", "twist S (profile slope -S/2 at face 1 to +S/2 at face 2)", g.twist)):
            if value:
                rows.append(quantity(f"{role}_{key}", f"{role}: {label}", "um", value * UM))
        if g.topography is not None:
            rows.append(quantity(f"{role}_topography", f"{role}: topography grid", "",
                                 g.topography.source))
        if g.is_zero:
            rows.append(quantity(f"{role}_modifications", f"{role}: modifications", "",
                                 "none"))
    return rows


def stiffness_section(stiffness: StiffnessResult, dist: LoadDistribution, compliance: str,
                      figures: Sequence[Figure]) -> Section:
    """Analytical, loaded (LTCA) and ISO 6336-1 mesh stiffness."""
    an = stiffness.mesh.total
    k = dist.mesh_stiffness
    iso = stiffness.iso
    return Section("stiffness", "Mesh stiffness", (
        quantity("analytical_mean", "analytical (potential energy), mean", "N/um",
            an.mean() * N_PER_UM),
        quantity("analytical_min", "analytical, min", "N/um", an.min() * N_PER_UM),
        quantity("analytical_max", "analytical, max", "N/um", an.max() * N_PER_UM),
        quantity("loaded_mean", f"loaded (LTCA, {compliance}), tangent dP/dx, mean", "N/um",
           k.mean() * N_PER_UM),
        quantity("loaded_min", "loaded, min", "N/um", k.min() * N_PER_UM),
        quantity("loaded_max", "loaded, max", "N/um", k.max() * N_PER_UM),
        quantity("iso_gear_1", "ISO 6336-1 gear 1 (fewer virtual teeth; an internal gear is "
                 "gear 2)", "", iso.gear_1),
        quantity("iso_single", "ISO 6336-1 single stiffness c'", "N/(mm um)", iso.c_single * 1e-9),
        quantity("iso_mesh_per_width", "ISO 6336-1 mesh stiffness c_gamma_alpha", "N/(mm um)",
           iso.c_gamma_alpha * 1e-9),
        quantity("iso_mesh", "ISO 6336-1 mean mesh stiffness c_gamma_alpha b", "N/um",
           iso.mesh_stiffness * N_PER_UM),
        quantity("loaded_over_iso", "loaded mean over ISO c_gamma_alpha b", "-",
           k.mean() / iso.mesh_stiffness),
    ), figures=tuple(figures))


def transmission_error_section(dist: LoadDistribution, figures: Sequence[Figure]) -> Section:
    """Loaded static TE, its mesh orders and the load sharing."""
    rows = [
        quantity("peak_to_peak", "loaded static TE, peak-to-peak (line of action)", "um",
           dist.te_peak_to_peak * UM),
        quantity("peak_to_peak_angle", "loaded static TE, peak-to-peak (pinion angle)", "urad",
           dist.te_peak_to_peak_angle * 1e6),
        quantity("mean", "loaded static TE, mean", "um",
            float(dist.transmission_error.mean()) * UM),
    ]
    for j, a in enumerate(dist.te_orders, start=1):
        rows.append(quantity(f"order_{j}", f"amplitude of mesh order {j}", "um", float(a) * UM))
    rows.append(quantity("max_load_share", "largest load share of one tooth pair", "-",
                   float(dist.load_share.max())))
    notes = ()
    if np.isnan(dist.te_orders).any():
        n = int(np.isfinite(dist.te_orders).sum())
        notes = (f"{len(dist.transmission_error)} positions per cycle resolve mesh orders up "
                 f"to {n}; raise [contact] positions to at least 22 for orders 1-10.",)
    return Section("transmission_error", "Transmission error and load sharing", tuple(rows),
                   figures=tuple(figures), notes=notes)


def load_distribution_section(dist: LoadDistribution, pair: GearPair,
                              figures: Sequence[Figure],
                              modifications: FlankModifications | None = None) -> Section:
    """Line load over the face, K_Hbeta and the tooth-pair unit load ratio."""
    w = dist.line_load_max
    notes = ["K_Hbeta = largest over mean of the line load averaged over the mesh cycle "
             "(ISO 6336-1: maximum over mean load per unit face width); the tooth-pair unit "
             "load ratio = largest mean unit load of a tooth pair over the mean unit load of "
             "all contact lines in contact, the largest over the cycle (from the computed "
             "load sharing; it is not ISO 6336-1's transverse load factor K_Halpha, which is "
             "1 for a perfect pair)."]
    if dist.slices_across_face == 1 and modifications is not None \
            and modifications.varies_across_face:
        notes.append("Analysed with one slice across the face ([contact] slices = 1): the "
                     "lead crowning / helix slope deviation of this file cannot shape the "
                     "line load, which is uniform by construction (K_Hbeta = 1); raise "
                     "[contact] slices.")
    elif dist.slices_across_face == 1:
        notes.append("Spur pair without lead crowning or helix slope deviation, analysed "
                     "with one slice across the face: the line load is uniform by "
                     "construction (K_Hbeta = 1).")
    return Section("load_distribution", "Line load and load factors", (
        quantity("K_Hbeta", "face load factor K_Hbeta", "-", dist.k_hbeta),
        quantity("K_Hbeta_position_max", "largest instantaneous max/mean line load", "-",
           float(dist.k_hbeta_position.max())),
        quantity("pair_unit_load_ratio", "tooth-pair unit load ratio (largest over mean)", "-",
                 dist.pair_load_ratio),
        quantity("mean_line_load", "mean line load P / b", "N/mm", dist.mean_line_load * N_PER_MM),
        quantity("max_line_load", "largest line load w", "N/mm", w.value * N_PER_MM),
        quantity("max_line_load_face_position", "its face position b_z", "mm", w.z * MM),
        quantity("max_line_load_pinion_angle", "its pinion angle in the cycle", "deg",
           math.degrees(w.pinion_angle)),
    ), figures=tuple(figures), notes=tuple(notes))


def contact_pressure_section(dist: LoadDistribution, figures: Sequence[Figure]) -> Section:
    """Hertz pressure, its maximum and where; a tip corner's apart (edge loading)."""
    h, c = dist.hertz_max, dist.tip_corner_max
    corner = () if c is None else (
        quantity("max_tip_corner_pressure", "largest Hertz pressure at a tip corner beyond "
                 "the path of contact (edge loading)", "MPa", c.value * MPA),
        quantity("tip_corner_pinion_angle", "tip corner: when, pinion angle in the cycle",
                 "deg", math.degrees(c.pinion_angle)),
        quantity("tip_corner_tooth_pair", "tip corner: which tooth pair", "-",
                 dist.pair_number(c.tooth_pair)),
    )
    notes = ("Hertz line contact (Johnson 1985, eq. 4.45) at every loaded point: unit load "
             "along the contact line, normal-section radii of curvature, plane-strain moduli "
             "of both gears; the envelope over the mesh cycle is drawn on each flank.",)
    if c is not None:
        notes += ("Teeth touch beyond the path of contact at a tip corner; its pressure is "
                  "Hertz of the tip rounding (tip_rounding_mm; a sharp corner: a 0.05 m_n "
                  "radius) against the mate's flank, an edge load a tip relief longer and "
                  "deeper than the deflection removes. The largest p_H above is the flanks', "
                  "on the path of contact.",)
    return Section("contact_pressure", "Contact pressure", (
        quantity("max_hertz_pressure", "largest Hertz pressure p_H on the flanks", "MPa",
                 h.value * MPA),
        quantity("pinion_diameter", "where: pinion diameter", "mm", 2 * h.pinion_radius * MM),
        quantity("gear_diameter", "where: gear diameter", "mm", 2 * h.gear_radius * MM),
        quantity("face_position", "where: face position b_z", "mm", h.z * MM),
        quantity("roll_coordinate", "where: roll coordinate s from T1", "mm", h.s * MM),
        quantity("pinion_angle", "when: pinion angle in the cycle", "deg",
           math.degrees(h.pinion_angle)),
        quantity("tooth_pair", "which tooth pair (numbered as they take load in the cycle)",
                 "-", dist.pair_number(h.tooth_pair)),
        *corner,
    ), figures=tuple(figures), notes=notes)


def figures_section(key: str, title: str, figures: Sequence[Figure],
                    rows: Sequence[Quantity] = (), notes: Sequence[str] = ()) -> Section:
    """A section of stage figures (load maps, dynamics) with optional rows."""
    return Section(key, title, tuple(rows), figures=tuple(figures), notes=tuple(notes))


def provenance_section(record: dict[str, Any]) -> Section:
    """Configuration hash, code revision, versions, run time."""
    rows = [
        quantity("configuration_hash", "configuration hash (gearbox inputs)", "",
           record["configuration_hash"]),
        quantity("gearbox_file_sha256", "gearbox file SHA-256", "", record["gearbox_file_sha256"]),
        quantity("code_revision", "code revision (git)", "", record["code_revision"]),
        quantity("command", "command", "", record["command"]),
        quantity("time_utc", "written (UTC)", "", record["time_utc"]),
        quantity("run_time", "run time before the report (stages, tables, figures)", "s",
                 record["run_time_s"]),
    ]
    for name, v in record["versions"].items():
        rows.append(quantity(f"version_{name.replace('-', '_')}", name, "", v))
    return Section("provenance", "Provenance", tuple(rows))
