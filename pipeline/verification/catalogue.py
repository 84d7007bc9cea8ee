"""The catalogue of verification cases: each case's id, title, kind, tier and function.

The ``fast`` tier runs in about a minute on two cores (the test suite runs it); ``full``
adds the slower cases. Ids are stable: reports, tests and ``gearpipe validate --case``
refer to them.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass

from pipeline.validation import InputError
from pipeline.verification import (
    cases_calculix,
    cases_calculix_rerun,
    cases_calculix_torques,
    cases_compliance,
    cases_contact,
    cases_contact_convergence,
    cases_dynamics,
    cases_elasticity,
    cases_fe3d_convergence,
    cases_fe_convergence,
    cases_fsh,
    cases_rating,
    cases_revolution,
    cases_root_stress,
    cases_shaft,
    cases_spectrum,
    cases_tangency,
    cases_tip_contact,
    cases_whole3d,
)
from pipeline.verification.context import Context
from pipeline.verification.model import KINDS, Outcome

TIERS = ("fast", "full")


@dataclass(frozen=True)
class Case:
    """One catalogue entry.

    Attributes
    ----------
    id : stable identifier (lower case, underscores).
    title : one line saying what is compared with what.
    kind : one of :data:`pipeline.verification.model.KINDS`.
    tier : ``"fast"`` (in every run) or ``"full"`` (only with ``full``).
    function : ``function(context) -> Outcome``.
    """

    id: str
    title: str
    kind: str
    tier: str
    function: Callable[[Context], Outcome]

    def __post_init__(self) -> None:
        if self.kind not in KINDS:
            raise ValueError(f"case {self.id}: kind {self.kind!r} is not one of {KINDS}")
        if self.tier not in TIERS:
            raise ValueError(f"case {self.id}: tier {self.tier!r} is not one of {TIERS}")


CATALOGUE: tuple[Case, ...] = (
    Case("cantilever_tip", "2D FE cantilever tip deflection against exact elasticity",
         "exact", "fast", cases_elasticity.case_cantilever_tip),
    Case("shaft_torsion_gj_over_l", "3D FE torsional stiffness of a hollow shaft against "
         "G J / L", "exact", "fast", cases_elasticity.case_shaft_torsion),
    Case("shaft_beam_simply_supported", "Timoshenko beam shaft under a central load against "
         "its closed form", "exact", "fast", cases_shaft.case_simply_supported_shaft),
    Case("iso_6336_3_root_geometry", "ISO 6336-3 method B root chord, fillet radius, arm "
         "and load angle against the exact profile; FE tip-load root stress level", "exact",
         "fast", cases_root_stress.case_iso_6336_3_root_geometry),
    Case("yang_2026_tooth_compliance", "potential-energy bending, shear and axial tooth "
         "compliance against Yang et al. (2026)'s closed-form integrals", "exact", "fast",
         cases_compliance.case_yang_2026_tooth_compliance),
    Case("tip_corner_gap_and_lever", "tip-corner gap and lever factors beyond the path of "
         "contact against the textbook involute construction", "exact", "fast",
         cases_tip_contact.case_tip_corner_gap_and_lever),
    Case("iso_6336_1_fsh_beside_beam", "ISO 6336-1 method C f_sh (Eq. 57, Figure 13 "
         "arrangements a, b, c) beside the beam shaft's face tilt", "exact", "fast",
         cases_fsh.case_iso_6336_1_fsh_beside_beam),
    Case("hertz_cylinders", "Hertz line contact of two steel cylinders against Shigley's "
         "formulas", "exact", "fast", cases_contact.case_hertz_cylinders),
    Case("tangency_hertz_limits", "line contact solver against Hertz (Johnson 1985); a "
         "rounded tip's tangency correction at its exact limits", "exact", "fast",
         cases_tangency.case_tangency_hertz_limits),
    Case("weber_half_plane", "Weber's local approach against the half-plane solution by "
         "quadrature", "exact", "fast", cases_contact.case_weber_half_plane),
    Case("runout_revolution", "loaded contact through a revolution with a pinion runout: "
         "the mesh cycle at each centre distance plus e sin(phi + theta)", "exact", "fast",
         cases_revolution.case_runout_revolution),
    Case("two_inertia_pair", "torsional spur pair natural frequency", "exact", "fast",
         cases_dynamics.case_two_inertia_pair),
    Case("piecewise_stiffness_monodromy", "Floquet multipliers of a square-wave stiffness "
         "against the closed-form monodromy", "exact", "fast",
         cases_dynamics.case_piecewise_monodromy),
    Case("lin_parker_1999", "planetary natural frequencies and mode types against Lin and "
         "Parker (1999) Table 2", "published", "fast", cases_dynamics.case_lin_parker_1999),
    Case("iso_tr_6336_30_example_1", "ISO 6336-2 pitting chain against ISO/TR 6336-30 "
         "example 1", "published", "fast", cases_rating.case_iso_tr_6336_30_example_1),
    Case("iso_6336_1_stiffness_kisssoft", "ISO 6336-1 stiffness of the NREL 5 MW helical "
         "stage against KISSsoft's report", "published", "fast",
         cases_rating.case_iso_6336_1_stiffness_kisssoft),
    Case("iso_6336_1_stiffness_planetary", "ISO 6336-1 stiffness of the NREL 5 MW "
         "planetary sun-planet and planet-ring meshes against KISSsoft's report", "published",
         "fast", cases_rating.case_iso_6336_1_stiffness_planetary),
    Case("kisssoft_helical_rating", "ISO 6336 rating of the NREL 5 MW helical stage (K_v to "
         "S_F) against KISSsoft's report", "published", "fast",
         cases_rating.case_kisssoft_helical_rating),
    Case("iso_6336_6_annex_c", "Miner sum of a 42-bin load spectrum against ISO 6336-6 "
         "Annex C, Table C.2", "published", "fast", cases_spectrum.case_iso_6336_6_annex_c),
    Case("harris_1958_light_load_te", "light-load TE with tip relief against Harris (1958)",
         "published", "fast", cases_contact.case_harris_light_load),
    Case("calculix_demo_pair", "FE-enriched loaded contact (TE, mesh stiffness, 24 "
         "positions, 2 loads) against CalculiX", "independent_fe", "fast",
         cases_calculix.case_calculix_demo_pair),
    Case("calculix_demo_pair_nominal", "loaded contact confined to the path of contact "
         "against CalculiX's nominal-path run", "independent_fe", "fast",
         cases_calculix.case_calculix_demo_pair_nominal),
    Case("calculix_corner_torques", "driving torque at CalculiX's own rotations where a tip "
         "corner touches (free of the load-step secant)", "independent_fe", "fast",
         cases_calculix_torques.case_calculix_corner_torques),
    Case("calculix_rounded_tips", "loaded contact of the demo pair with tips rounded by "
         "0.3 mm against CalculiX meshing the same rounding", "independent_fe", "fast",
         cases_calculix.case_calculix_rounded_tips),
    Case("calculix_high_contact_ratio", "loaded contact of a high-contact-ratio spur pair "
         "(eps_alpha 2.06) against CalculiX", "independent_fe", "fast",
         cases_calculix.case_calculix_high_contact_ratio),
    Case("cantilever_l2_convergence", "L2 convergence rate of the P2 cantilever against "
         "its a-priori order", "convergence", "fast",
         cases_elasticity.case_cantilever_convergence),
    Case("calculix_reference_convergence", "the CalculiX reference's loaded TE over its "
         "contact mesh (0.2 / 0.1 / 0.05 mm)", "convergence", "fast",
         cases_contact_convergence.case_reference_mesh_convergence),
    Case("contact_table_convergence", "loaded TE of the demo pair with the FE tables "
         "refined twice as fine", "convergence", "fast",
         cases_contact_convergence.case_contact_table_convergence),
    Case("fe2d_tooth_compliance_convergence", "2D FE single-tooth compliance over four "
         "mesh refinements: change and observed order", "convergence", "fast",
         cases_fe_convergence.case_fe2d_tooth_compliance_convergence),
    Case("shaft_torsion_frequency_convergence", "beam shaft torsional frequency: O(h^2) "
         "convergence", "convergence", "fast",
         cases_shaft.case_torsional_frequency_convergence),
    Case("mathieu_convergence", "Floquet multiplier of the Mathieu equation: O(h^2) "
         "convergence of the propagator", "convergence", "fast",
         cases_dynamics.case_mathieu_convergence),
    Case("calculix_rerun", "CalculiX rerun at two committed coarse-mesh positions "
         "reproduces the committed torques (needs ccx)", "independent_fe", "full",
         cases_calculix_rerun.case_calculix_rerun),
    Case("shaft_fe3d_convergence", "3D shaft superelement: central flexibility over five "
         "meshes against Timoshenko, with its rate", "convergence", "full",
         cases_shaft.case_shaft_fe3d_convergence),
    Case("contact_table_convergence_fine", "loaded TE of the demo pair over FE table "
         "refinements 1, 2, 4, and at the tip-corner positions against CalculiX",
         "convergence", "full",
         cases_contact_convergence.case_contact_table_convergence_fine),
    Case("fe2d_tooth_compliance_convergence_fine", "2D FE single-tooth compliance over five "
         "mesh refinements (refinement 16)", "convergence", "full",
         cases_fe_convergence.case_fe2d_tooth_compliance_convergence_fine),
    Case("whole3d_plane_strain", "3D whole gear with sliding end faces against the 2D "
         "plane-strain whole gear (its exact limit)", "exact", "full",
         cases_whole3d.case_whole3d_plane_strain),
    Case("whole3d_plane_strain_convergence", "3D whole gear with sliding end faces: its gap "
         "to plane strain over refinements 0.6, 1, 1.6", "convergence", "full",
         cases_whole3d.case_whole3d_plane_strain_convergence),
    Case("fe3d_table_convergence", "3D FE tables of a helical pair over refinements 0.6 to "
         "2: mesh stiffness rate, limit, graded against uniform", "convergence", "full",
         cases_fe3d_convergence.case_fe3d_table_convergence),
)
"""Every case, in report order."""


def case_ids(catalogue: Sequence[Case] = CATALOGUE) -> list[str]:
    return [c.id for c in catalogue]


def select(ids: Sequence[str] | None = None, full: bool = False,
           catalogue: Sequence[Case] = CATALOGUE) -> tuple[Case, ...]:
    """The cases to run: those named by ``ids`` (any tier, catalogue order), else the fast
    tier, with ``full`` every case.

    Raises
    ------
    InputError : an id not in the catalogue (the message names it and lists the valid
        ones).
    """
    if ids:
        known = case_ids(catalogue)
        unknown = [i for i in ids if i not in known]
        if unknown:
            raise InputError(f"--case: unknown case id {', '.join(unknown)}; the cases are "
                             f"{', '.join(known)}")
        return tuple(c for c in catalogue if c.id in set(ids))
    return tuple(c for c in catalogue if full or c.tier == "fast")
