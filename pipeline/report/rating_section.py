"""The ISO 6336 rating sections of a mesh report, laid out as a commercial rating report.

Two tables: the load factors of the mesh (value, where it comes from), and both gears side
by side through the contact stress, the permissible contact stress and S_H, the root
stress, the permissible root stress and S_F, each row with its symbol, unit and the part
and method of ISO 6336 it follows; beside the standard's sigma_H and sigma_F the loaded
contact's largest Hertz pressure and the FE root stress (both at the nominal torque).
"""

from __future__ import annotations

from collections.abc import Sequence

from pipeline.report.content import MPA, quantity
from pipeline.report.model import Figure, Section

ISO1, ISO2, ISO3 = "ISO 6336-1", "ISO 6336-2 method B", "ISO 6336-3 method B"
N_PER_MM_UM = 1e-9  # N/m^2 -> N/(mm um)


def rating_load_section(m) -> Section:
    """Mesh-wide factors of :class:`pipeline.run.rating.MeshRating` ``m``; beside K_v the run's
    dynamic model's factor at the operating speed (a dash without dynamics)."""
    r = m.rating
    rows = [
        quantity("F_t", "nominal tangential load at the reference circle F_t", "N",
                 r.tangential_load, ISO1 if m.mesh == "mesh" else f"{ISO1}: one planet's"),
        quantity("v", "pitch line velocity v", "m/s", r.velocity,
                 f"{ISO1}, relative to the carrier" if m.mesh != "mesh" else ISO1),
        quantity("K_A", "application factor K_A", "-", r.application_factor,
                 "[rating] application_factor"),
        quantity("K_gamma", "mesh load factor K_gamma", "-", r.load_sharing,
                 m.load_sharing_source),
        quantity("C_R", "gear blank factor C_R", "-", r.blank_factor,
                 f"{ISO1} method B: the webbed blank's, 1 for solid discs"),
        quantity("c_prime", "single tooth stiffness c'", "N/(mm um)",
                 r.single_stiffness * N_PER_MM_UM, f"{ISO1} method B"),
        quantity("c_gamma_alpha", "mesh stiffness c_gamma_alpha", "N/(mm um)",
                 r.mesh_stiffness * N_PER_MM_UM, f"{ISO1} method B"),
        quantity("f_pb", "base pitch deviation f_pb (larger gear)", "um",
                 max(t.f_pb for t in r.tolerances) * 1e6, "ISO 1328-1:1995"),
        quantity("f_falpha", "profile form deviation f_falpha (larger gear)", "um",
                 max(t.f_falpha for t in r.tolerances) * 1e6, "ISO 1328-1:1995"),
        quantity("K_v", "dynamic factor K_v", "-", r.dynamic.factor,
                 f"{ISO1} method B, {r.dynamic.range} range" + (
                     "; the larger of the set's two meshes" if m.mesh != "mesh" else "")),
        quantity("resonance_ratio", "resonance ratio N = n_1 / n_E1", "-",
                 r.dynamic.resonance_ratio, f"{ISO1} method B"),
    ]
    if m.dynamic_factor_model is not None:
        rows.append(quantity("K_v_model", "dynamic factor of the run's dynamic model", "-",
                             m.dynamic_factor_model,
                             "largest over mean mesh force at the operating speed"))
    if m.k_gamma_computed is not None:
        rows.insert(4, quantity("K_gamma_computed", "K_gamma of the dynamic model's planet "
                                "forces", "-", m.k_gamma_computed,
                                "largest planet over the mean, at the operating speed"))
    rows += [
        quantity("K_Hbeta", "face load factor K_Hbeta", "-", r.k_hbeta, m.k_hbeta_source),
        quantity("K_Hbeta_contact", "K_Hbeta of the loaded contact's line load", "-",
                 m.k_hbeta_contact, "largest over mean of the cycle-mean line load"),
        *_method_c_rows(r.face_load),
        quantity("K_Fbeta", "face load factor K_Fbeta", "-", r.k_fbeta,
                 f"{ISO1}: K_Hbeta^N_F"),
        quantity("K_Halpha", "transverse load factor K_Halpha", "-", r.transverse.k_halpha,
                 f"{ISO1} method B"),
        quantity("K_Falpha", "transverse load factor K_Falpha", "-", r.transverse.k_falpha,
                 f"{ISO1} method B"),
    ]
    notes = [
        f"K_Hbeta used: {m.k_hbeta_source} ([rating] face_load_factor; a pair on shafts "
        "takes the contact's unless told); the others are shown beside it. The loaded "
        "contact's K_Hbeta holds what the contact model holds: with [<gear>.shaft] the "
        "shafts' deflection, on rigid supports an aligned pair gives about 1 unless the "
        "misalignment is given "
        "([contact] slope_deviation_um); method C estimates the shaft's deflection and the "
        "manufacturing misalignment from the accuracy grade.",
    ]
    if m.herringbone_half:
        notes.append("Herringbone: rated as one helical half (face width b_B) at half the load.")
    return Section("rating_loads", "ISO 6336 rating: load factors", tuple(rows),
                   ("value", "source"), notes=tuple(notes))


def _method_c_rows(c) -> list:
    """ISO 6336-1 method C's K_Hbeta and its misalignments (none without its inputs)."""
    if c is None:
        return []
    src = f"{ISO1} method C"
    return [
        quantity("K_Hbeta_method_c", "K_Hbeta by method C", "-", c.k_hbeta, src),
        quantity("f_sh", "method C: misalignment from shaft deflection f_sh", "um",
                 c.f_sh * 1e6, f"{src}, Eq. (57)/(58)"),
        quantity("f_ma", "method C: misalignment from manufacture f_ma", "um", c.f_ma * 1e6,
                 src),
        quantity("F_betax", "method C: initial equivalent misalignment F_betax", "um",
                 c.f_beta_x * 1e6, f"{src}, Eq. (52)-(56)"),
        quantity("y_beta", "method C: running-in allowance y_beta", "um", c.y_beta * 1e6, src),
        quantity("F_betay", "method C: effective equivalent misalignment F_betay", "um",
                 c.f_beta_y * 1e6, src),
    ]


def rating_section(m, figures: Sequence[Figure]) -> Section:
    """Both gears of :class:`pipeline.run.rating.MeshRating` ``m`` side by side (module
    docstring)."""
    r = m.rating
    c = r.contact
    pit, bend, roots = r.pitting, r.bending, r.roots

    def gear(key, label, unit, values, method):
        return quantity(key, label, unit, *values, method)

    def each(fn, items):
        return tuple(None if x is None else fn(x) for x in items)

    rows = [
        gear("Z_H", "zone factor Z_H", "-", (c.zone_factor,) * 2, ISO2),
        gear("Z_E", "elasticity factor Z_E", "(N/mm^2)^0.5", (c.elasticity_factor * 1e-3,) * 2,
             ISO2),
        gear("Z_eps", "contact ratio factor Z_eps", "-", (c.contact_ratio_factor,) * 2, ISO2),
        gear("Z_beta", "helix angle factor Z_beta", "-", (c.helix_factor,) * 2, ISO2),
        gear("Z_BD", "single pair tooth contact factor Z_B / Z_D", "-", c.single_pair_factors,
             ISO2),
        gear("sigma_H0", "nominal contact stress sigma_H0", "MPa", (c.nominal * MPA,) * 2, ISO2),
        gear("sigma_H", "contact stress sigma_H", "MPa", tuple(s * MPA for s in c.stress), ISO2),
        gear("p_H_contact", "loaded contact: largest Hertz pressure (nominal torque)", "MPa",
             (m.contact_pressure_max * MPA,) * 2, "beside sigma_H0 Z_B,D: the contact's own"),
        gear("N_L", "load cycles over the life N_L", "-", r.cycles,
             "speed x life x mates per revolution"),
        gear("Z_NT", "life factor Z_NT", "-", each(lambda p: p.life_factor, pit), ISO2),
        gear("Z_L", "lubricant factor Z_L", "-", each(lambda p: p.lubricant_factor, pit), ISO2),
        gear("Z_v", "velocity factor Z_v", "-", each(lambda p: p.velocity_factor, pit), ISO2),
        gear("Z_R", "roughness factor Z_R", "-", each(lambda p: p.roughness_factor, pit), ISO2),
        gear("Z_W", "work hardening factor Z_W", "-",
             each(lambda p: p.work_hardening_factor, pit), ISO2),
        gear("Z_X", "size factor Z_X", "-", each(lambda p: p.size_factor, pit), ISO2),
        gear("sigma_Hlim", "allowable contact stress number sigma_Hlim", "MPa",
             tuple(x * MPA for x in m.sigma_hlim), "[rating.<gear>] (ISO 6336-5)"),
        gear("S_Hmin", "minimum safety factor S_Hmin", "-", (m.minimum_pitting,) * 2,
             "[rating] minimum_safety_pitting"),
        gear("sigma_HG", "pitting stress limit sigma_HG", "MPa",
             each(lambda p: p.permissible * m.minimum_pitting * MPA, pit), ISO2),
        gear("sigma_HP", "permissible contact stress sigma_HP", "MPa",
             each(lambda p: p.permissible * MPA, pit), f"{ISO2}, with S_Hmin"),
        gear("S_H", "safety factor for pitting S_H", "-", each(lambda p: p.safety, pit), ISO2),
        gear("Y_F", "form factor Y_F", "-", each(lambda x: x.y_f, roots), ISO3),
        gear("Y_S", "stress correction factor Y_S", "-", each(lambda x: x.y_s, roots), ISO3),
        gear("Y_beta", "helix angle factor Y_beta", "-", each(lambda x: x.y_beta, roots), ISO3),
        gear("Y_B", "rim thickness factor Y_B", "-", each(lambda x: x.y_b, roots), ISO3),
        gear("Y_DT", "deep tooth factor Y_DT", "-", each(lambda x: x.y_dt, roots), ISO3),
        gear("sigma_F0", "nominal root stress sigma_F0", "MPa",
             each(lambda b: b.nominal * MPA, bend), ISO3),
        gear("sigma_F", "root stress sigma_F", "MPa", each(lambda b: b.stress * MPA, bend), ISO3),
        gear("sigma_F_fe", "FE root stress: largest over the cycle (nominal torque)", "MPa",
             each(lambda s: s * MPA, m.root_stress_fe), "beside sigma_F0: the FE 2D model"),
        gear("sigma_Flim", "nominal bending stress number sigma_Flim", "MPa",
             tuple(x * MPA for x in m.sigma_flim), "[rating.<gear>] (ISO 6336-5)"),
        gear("Y_ST", "stress correction factor of the test gear Y_ST", "-", (2.0, 2.0), ISO3),
        gear("Y_NT", "life factor Y_NT", "-", each(lambda b: b.life_factor, bend), ISO3),
        gear("Y_deltarelT", "relative notch sensitivity factor Y_deltarelT", "-",
             each(lambda b: b.notch_factor, bend), ISO3),
        gear("Y_RrelT", "relative surface factor Y_RrelT", "-",
             each(lambda b: b.surface_factor, bend), ISO3),
        gear("Y_X", "size factor Y_X", "-", each(lambda b: b.size_factor, bend), ISO3),
        gear("Y_M", "mean stress factor Y_M", "-", each(lambda b: b.mean_stress_factor, bend),
             f"{ISO3}: 0.7 for an idler"),
        gear("S_Fmin", "minimum safety factor S_Fmin", "-", (m.minimum_bending,) * 2,
             "[rating] minimum_safety_bending"),
        gear("sigma_FG", "root stress limit sigma_FG", "MPa", each(lambda b: b.limit * MPA,
                                                                  bend), ISO3),
        gear("sigma_FP", "permissible root stress sigma_FP", "MPa",
             each(lambda b: b.permissible * MPA, bend), f"{ISO3}, with S_Fmin"),
        gear("S_F", "safety factor for bending S_F", "-", each(lambda b: b.safety, bend), ISO3),
    ]
    if m.spectrum is not None:
        sp = m.spectrum
        src = "ISO 6336-6, Miner sum"
        rows += [
            gear("spectrum_D_H", "load spectrum: pitting damage D_H over its time", "-",
                 each(lambda d: d.total, sp.pitting), src),
            gear("spectrum_S_H", "load spectrum: pitting safety (D_H = 1)", "-",
                 each(lambda d: d.safety, sp.pitting), src),
            gear("spectrum_D_F", "load spectrum: bending damage D_F over its time", "-",
                 each(lambda d: d.total, sp.bending), src),
            gear("spectrum_S_F", "load spectrum: bending safety (D_F = 1)", "-",
                 each(lambda d: d.safety, sp.bending), src),
        ]
    notes = ["sigma_H = Z_B,D sigma_H0 sqrt(K_A K_gamma K_v K_Hbeta K_Halpha); sigma_F = "
             "sigma_F0 K_A K_gamma K_v K_Fbeta K_Falpha; S_H = sigma_Hlim Z_NT Z_L Z_v Z_R Z_W "
             "Z_X / sigma_H; S_F = sigma_Flim Y_ST Y_NT Y_deltarelT Y_RrelT Y_X Y_M / sigma_F "
             "(Y_ST = 2)."]
    if m.spectrum is not None:
        notes.append("Load spectrum ([[rating.spectrum]]): each bin rated at its torque and "
                     "speed with K_A = 1, its load cycles against the gear's S-N line; the "
                     "safety is the factor on every bin's stress that makes the Miner sum 1.")
    for why in m.unrated:
        if why is not None:
            notes.append(f"Not rated in bending: {why}.")
    if any(c is not None for c in (getattr(x, "cutter", None) for x in roots)):
        notes.append("Internal gear: the root section the pinion-type cutter generates "
                     "(its fillet exactly, the 60 deg tangent), not ISO 6336-3:2006's "
                     "internal-gear approximation; the load point and Y_F, Y_S as for "
                     "external gears with a signed tooth count.")
    return Section("rating", "ISO 6336 rating: pitting and tooth root", tuple(rows),
                   (*m.gears, "method"), figures=tuple(figures), notes=tuple(notes))


def rating_local_section(m, figures: Sequence[Figure]) -> Section:
    """Where the flanks and roots of :class:`pipeline.run.rating.MeshRating` ``m`` are at
    risk: each gear's smallest local pitting safety and where, and with the FE root stress
    its largest value along the face and the smallest local bending safety
    (:mod:`pipeline.rating.local_safety`)."""
    loc = m.local
    pit = loc.pitting

    def gear(key, label, unit, values, method):
        return quantity(key, label, unit, *values, method)

    src = "loaded contact, envelope over the cycle"
    rows = [
        gear("sigma_HG", "pitting stress limit sigma_HG = sigma_HP S_Hmin", "MPa",
             tuple(p.limit * MPA for p in pit), ISO2),
        gear("S_H_loc_min", "smallest local pitting safety S_H,loc", "-",
             tuple(p.minimum for p in pit), src),
        gear("S_H_loc_diameter", "where: diameter of the gear", "mm",
             tuple(p.minimum_diameter * 1e3 for p in pit), src),
        gear("S_H_loc_face", "where: face position b_z", "mm",
             tuple(p.minimum_z * 1e3 for p in pit), src),
    ]
    if loc.bending is not None:
        bend = loc.bending
        fe = "FE 2D root stress under the contact's loads"
        rows += [
            gear("sigma_F_fe_face_max", "FE root stress: largest along the face", "MPa",
                 tuple(float(b.stress.max()) * MPA for b in bend), fe),
            gear("sigma_F_fe_face", "where: face position b_z", "mm",
                 tuple(b.minimum_z * 1e3 for b in bend), fe),
            gear("S_F_loc_min", "smallest local bending safety S_F,loc (there)", "-",
                 tuple(None if b.limit is None else b.minimum for b in bend), fe),
        ]
    notes = [
        f"S_H,loc = sigma_HG / (p_H sqrt(K_A K_gamma K_v)) at every point of each flank, p_H "
        f"the loaded contact's largest Hertz pressure there over the mesh cycle at the nominal "
        f"torque; K_A K_gamma K_v = {loc.load_factor:.4g}. Z_B / Z_D, Z_eps, K_Hbeta and "
        "K_Halpha are not applied: the contact resolves the load across the face, its "
        "sharing between the pairs and the pressure at each point itself. The smallest "
        "S_H,loc therefore differs from ISO's S_H by the ratio of ISO's sigma_H to the "
        "contact's largest pressure (both with the same external factors).",
        "The contact knows the modifications and deviations given in [contact] and the "
        "gears' [<gear>.modifications], not the "
        "accuracy grade's deviations that ISO's K_Halpha allows for.",
    ]
    if loc.bending is not None:
        notes.append(
            "S_F,loc = sigma_FG / (sigma_FE K_A K_gamma K_v) along the face, sigma_FE the "
            "largest FE root stress in each slice over the cycle (K_Fbeta, K_Falpha not "
            "applied: the FE stress under the contact's loads holds them). The FE peak stress "
            "is not ISO's nominal sigma_F0 (see the root stress section) and sigma_FG is "
            "calibrated against ISO's: S_F,loc shows where along the face the root is most at "
            "risk, not ISO's S_F.")
    else:
        notes.append("No FE root stress in this run: the root stress along the face is not "
                     "shown.")
    if loc.z.size <= 3:
        notes.append("The contact was solved with one slice across the face (a spur pair "
                     "without lead modifications or slope deviation): the maps are uniform "
                     "across the face by construction.")
    return Section("rating_local", "Local safety over the flank and along the root (loaded "
                   "contact)", tuple(rows), (*m.gears, "source"), figures=tuple(figures),
                   notes=tuple(notes))
