"""The herringbone section of a sun-planet report: both helical halves from the contact
through the groove, beside the one helical half at an equal split that the other sections
report.

Columns ``left``, ``right`` and ``equal split``; every row says the torque and speed it is
at: the torque through each half on one planet mesh at its mean load (and on the whole
sun), the absolute speeds (ring fixed) and those relative to the carrier, in which the
contact is solved. The numbers are the stages' (:mod:`pipeline.contact.herringbone_distribution`,
:mod:`pipeline.contact.root_stress`, :mod:`pipeline.geometry.planetary_speeds`); this
module only puts them in report units.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

from pipeline.contact.herringbone_distribution import HalfDistribution, HerringboneDistribution
from pipeline.contact.herringbone_results import HerringboneCycle
from pipeline.contact.root_stress import RootStress
from pipeline.geometry.planetary_speeds import PlanetarySpeeds
from pipeline.report.content import MM, MPA, N_PER_MM, N_PER_UM, RPM, quantity
from pipeline.report.model import Figure, Section

COLUMNS = ("left", "right", "equal split")
_HALF_MEAN = "mean over the cycle"


def _iso(root: RootStress | None, gear: str) -> float | None:
    if root is None:
        return None
    g = root.pinion if gear == "pinion" else root.gear
    return None if g.iso is None else g.iso.sigma_f0 * MPA


def _fe(root: RootStress | None, gear: str) -> float | None:
    if root is None:
        return None
    return (root.pinion if gear == "pinion" else root.gear).max_stress * MPA


def herringbone_section(halves: HerringboneDistribution, roots: Mapping[str, RootStress],
                        speeds: PlanetarySpeeds, cycle: HerringboneCycle, groove_kj: float, *,
                        sun_torque: float, figures: Sequence[Figure] = ()) -> Section:
    """Both halves of a herringbone sun-planet mesh (module docstring).

    Parameters
    ----------
    halves : the halves' distribution, with its equal split (else that column is dashes).
    roots : root stress under each half's loads ("left", "right") and at the equal split
        ("equal split"); a missing entry shows as a dash.
    speeds : the set's speeds (rad/s).
    cycle : the contact of both halves through the groove (how the sun is loaded and held).
    groove_kj : the groove's equivalent torsional stiffness K_j, N m^2.
    sun_torque : T_s, the sun's torque (all planets, both halves), N m.
    figures : shown under the table.
    """
    eq = halves.equal_split
    cols: dict[str, HalfDistribution | None] = {"left": halves.left, "right": halves.right,
                                                "equal split": eq}
    n = halves.n_planets

    def each(key, label, unit, fn):
        return quantity(key, label, unit, *(None if cols[c] is None else fn(cols[c])
                                            for c in COLUMNS))

    def dist(key, label, unit, fn):
        return each(key, label, unit, lambda x: fn(x.distribution))

    def same(key, label, unit, value):
        return quantity(key, label, unit, value, value, value)

    b = halves.left.distribution.face_width
    rows = [
        each("torque", "sun torque through the half on one planet mesh (at its mean load)",
             "N m", lambda x: x.operation.torque),
        each("sun_torque", f"sun torque through the half from all {n} planets", "N m",
             lambda x: x.sun_torque),
        same("sun_speed", "sun speed (ring fixed)", "rpm", speeds.sun * RPM),
        same("sun_speed_relative", "sun speed relative to the carrier (the contact's frame)",
             "rpm", speeds.sun_relative * RPM),
        same("planet_speed", "planet speed (+ in the sun's sense)", "rpm", speeds.planet * RPM),
        same("planet_speed_relative", "planet speed relative to the carrier", "rpm",
             speeds.planet_relative * RPM),
        same("carrier_speed", "carrier speed", "rpm", speeds.carrier * RPM),
        each("load_share_mean", f"share of the mesh load P_h / P, {_HALF_MEAN}", "-",
             lambda x: float(x.share.mean())),
        each("load_share_min", "share of the mesh load, least over the cycle", "-",
             lambda x: float(x.share.min())),
        each("load_share_max", "share of the mesh load, largest over the cycle", "-",
             lambda x: float(x.share.max())),
        dist("load", f"load along the transverse line of action P_h, {_HALF_MEAN}", "N",
             lambda x: x.load),
        dist("mean_line_load", f"mean line load P_h / b (b = {b * MM:.4g} mm, one half)",
             "N/mm", lambda x: x.mean_line_load * N_PER_MM),
        dist("max_line_load", "largest line load w", "N/mm",
             lambda x: x.line_load_max.value * N_PER_MM),
        each("max_line_load_over_equal_split", "largest line load over the equal split's",
             "-", lambda x: halves.over_equal_split(x.side)),
        dist("max_line_load_face_position", "its face position b_z in the half", "mm",
             lambda x: x.line_load_max.z * MM),
        dist("K_Hbeta", "face load factor K_Hbeta", "-", lambda x: x.k_hbeta),
        dist("pair_unit_load_ratio", "tooth-pair unit load ratio (largest over mean)", "-",
             lambda x: x.pair_load_ratio),
        dist("max_hertz_pressure", "largest Hertz pressure p_H", "MPa",
             lambda x: x.hertz_max.value * MPA),
        dist("mesh_stiffness_mean", "own mesh stiffness dP_h/dx_h, mean (without the groove)",
             "N/um", lambda x: float(x.mesh_stiffness.mean()) * N_PER_UM),
        quantity("root_stress_sun", "FE 2D: largest principal root stress, sun", "MPa",
                 *(_fe(roots.get(c), "pinion") for c in COLUMNS)),
        quantity("root_stress_planet", "FE 2D: largest principal root stress, planet", "MPa",
                 *(_fe(roots.get(c), "gear") for c in COLUMNS)),
        quantity("iso_root_stress_sun", "ISO 6336-3 method B: sigma_F0 of the sun at P_h",
                 "MPa", *(_iso(roots.get(c), "pinion") for c in COLUMNS)),
        quantity("iso_root_stress_planet",
                 "ISO 6336-3 method B: sigma_F0 of the planet at P_h", "MPa",
                 *(_iso(roots.get(c), "gear") for c in COLUMNS)),
        quantity("governs", "governs (the larger maximum line load)", "",
                 halves.governing == "left", halves.governing == "right", None),
    ]
    g, o = halves.governing, halves.other
    c = cycle
    holding = (f"held axially at {c.axial_slide * MM:g} mm on "
               f"{c.axial_support_stiffness:.3g} N/m" if c.sun_axial == "held"
               else "free axially")
    notes = [
        f"Both helical halves solved together through the sun's relief groove (3D FE, "
        f"K_j = {groove_kj:.4g} N m^2; the sun's torque leaves at "
        f"{'both halves' if c.torque_entry == 'both' else 'the ' + c.torque_entry + ' half'}"
        f"; the sun "
        f"{holding}), at the sun torque T_s = {sun_torque:.6g} N m "
        f"({halves.operation.torque:.6g} N m on each of the {n} planet meshes) and the sun "
        f"speed {speeds.sun * RPM:.4g} rpm, {speeds.sun_relative * RPM:.4g} rpm relative to "
        f"the carrier (which turns at {speeds.carrier * RPM:.4g} rpm), the frame the contact "
        "is solved in.",
        f"The {g} half governs: its largest line load, "
        f"{halves.half(g).max_line_load * N_PER_MM:.4g} N/mm, is "
        f"{halves.line_load_ratio:.3f} times the {o} half's"
        + (f" and {halves.over_equal_split(g):.3f} times the equal split's "
           f"({eq.max_line_load * N_PER_MM:.4g} N/mm)" if eq is not None else "")
        + ". The other sections of this report are one helical half at the equal split "
        "(T_s / (2 N) per planet mesh).",
        "Root stress: FE 2D under each half's own line loads over the cycle; ISO 6336-3 "
        "method B at the half's mean load (no K factors), as in the root stress section.",
    ]
    return Section("herringbone", "Herringbone halves through the groove", tuple(rows),
                   columns=COLUMNS, figures=tuple(figures), notes=tuple(notes))
