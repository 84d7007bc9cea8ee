"""The root stress section of a mesh report: FE 2D under the solved loads beside ISO 6336-3."""

from __future__ import annotations

import math
from collections.abc import Sequence

from pipeline.contact.root_stress import RootStress
from pipeline.report.content import MM, MPA, quantity
from pipeline.report.model import Figure, Section


def root_stress_section(root: RootStress, figures: Sequence[Figure],
                        tip_share: float = 0.0) -> Section:
    """Both gears side by side: FE maximum and where, ISO 6336-3 factors and stress, the
    difference, and the method; ``tip_share`` (-) the largest share of the load a tip corner
    carries beyond the path of contact in the cycle (0: none)."""
    p, g = root.pinion, root.gear

    def both(key, label, unit, fn):
        return quantity(key, label, unit, fn(p), fn(g))

    def iso(fn):
        return lambda x: None if x.iso is None else fn(x.iso)

    rows = (
        both("fe_max", "FE 2D: largest principal root stress over the cycle", "MPa",
             lambda x: x.max_stress * MPA),
        both("fe_max_diameter", "where: diameter of the root point", "mm",
             lambda x: 2 * x.max_radius * MM),
        both("fe_max_arc", "where: arc length from the middle of the tooth space", "mm",
             lambda x: x.max_arc * MM),
        both("fe_max_load_diameter", "when: diameter of the tooth's own contact", "mm",
             lambda x: 2 * x.max_load_radius * MM),
        both("fe_max_face_position", "when: face position b_z of the slice", "mm",
             lambda x: x.max_face_position * MM),
        both("iso_sigma_F0", "ISO 6336-3 method B: nominal root stress sigma_F0", "MPa",
             iso(lambda i: i.sigma_f0 * MPA)),
        both("iso_Y_F", "ISO: form factor Y_F", "-", iso(lambda i: i.y_f)),
        both("iso_Y_S", "ISO: stress correction factor Y_S", "-", iso(lambda i: i.y_s)),
        both("iso_Y_beta", "ISO: helix factor Y_beta", "-", iso(lambda i: i.y_beta)),
        both("iso_s_Fn", "ISO: root chord s_Fn at the 30 deg tangents", "mm",
             iso(lambda i: i.s_fn * MM)),
        both("iso_rho_F", "ISO: fillet radius rho_F there", "mm", iso(lambda i: i.rho_f * MM)),
        both("iso_h_Fe", "ISO: bending arm h_Fe", "mm", iso(lambda i: i.h_fe * MM)),
        both("iso_load_diameter", "ISO: load diameter d_en (virtual gear)", "mm",
             iso(lambda i: i.load_diameter * MM)),
        both("difference", "FE over ISO minus 1", "%", lambda x: None if x.iso is None or
             math.isnan(x.difference_to_iso) else 100.0 * x.difference_to_iso),
    )
    notes = (
        f"FE: 2D whole-gear model ({root.kind.replace('_', ' ')}, P2 triangles, flank and "
        f"fillet elements m_n / {12 * root.refinement:g}, clamped at the bore; "
        f"{root.n_dof[0]} / {root.n_dof[1]} unknowns), each tooth followed through the mesh "
        "under the solved line loads of its own and its neighbours' contacts, section by "
        "section; the largest in-plane principal stress on the loaded-side root (the tension "
        "side) from the middle of the tooth space to the form circle.",
        iso_note(root),
    )
    if tip_share > 0.0:
        notes += (f"Teeth touch beyond the path of contact at their tip corners, which carry "
                  f"up to {tip_share:.0%} of the load: where ISO puts the whole load on one "
                  "tooth (the outer point of single pair contact) the FE tooth shares it with "
                  "a corner contact, so its stress lies below ISO's by about that share. A "
                  "tip relief longer and deeper than the deflection restores single contact.",)
    if p.iso is None or g.iso is None:
        notes += ("ISO 6336-3 method B form factors are implemented for external gears only: "
                  "no ISO value for the internal gear.",)
    return Section("root_stress", "Tooth root stress", rows, columns=("pinion", "gear"),
                   figures=tuple(figures), notes=notes)


def iso_note(root: RootStress) -> str:
    """How ISO 6336-3 method B loads the tooth; for a high-contact-ratio pair, why its
    nominal stress lies above the FE stress (the whole F_t on a tooth that shares it)."""
    iso = root.pinion.iso or root.gear.iso
    high = iso is not None and iso.high_contact_ratio
    point = "at d_en of the virtual spur gear" if high else (
        "at the outer point of single pair contact of the virtual spur gear")
    text = (f"ISO 6336-3:2019 method B for the same load: F_t = P cos(alpha_t) = "
            f"{root.tangential_load:.5g} N at the reference circle on one tooth {point}; "
            "Y_B = 1 (solid rim), Y_DT = 1 (clause 10: 1 for eps_alpha_n <= 2.05 or a "
            "tolerance class above 4; no class is given); no K factors. ISO's nominal stress "
            "includes the notch factor Y_S, so it compares with the FE peak stress.")
    if not high:
        return text
    return text + (
        f" Here eps_alpha_n = {iso.virtual_contact_ratio:.3f} >= 2 (high contact ratio): no "
        "tooth ever carries the load alone, and d_en (ISO's formula for the outer point of "
        "single pair contact, which it keeps) is the outer point of double pair contact, "
        "where the tooth shares the load with one other pair. The FE tooth carries its "
        "solved share (see the load sharing), so an FE stress well below ISO's is expected: "
        "the difference measures ISO's whole-load-on-one-tooth assumption, not an error of "
        "either model.")
