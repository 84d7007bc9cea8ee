"""The tables of a gearbox file and their keys (see :mod:`pipeline.config.gearbox`).

Each key's unit is the suffix of its name (:mod:`pipeline.config.units`); the
ranges are those of the input dataclass it fills (restated in the file's unit
when a value is refused).

Allowed ranges, in the file's units (each is a range a real run on a 2-core, 24 GB machine
meets in minutes at most; a refused value names the key, the value and the range):

* ``[gear]`` ``teeth``: 5 .. 100000 (internal 10 ..)
* ``[gear]`` ``module_mm``: 0.01 .. 1000
* ``[gear]`` ``pressure_angle_deg`` / ``helix_angle_deg``: (0, 35] / [0, 45)
* ``[gear]`` ``face_width_mm``: 0.5 .. 250 normal modules (thinner bodies degenerate, wider
  are no gears)
* ``[gear]`` ``profile_shift`` / ``addendum_coef`` / ``dedendum_coef``: [-1.5, 1.5] / [0.3,
  2] / [addendum_coef, 2.5]
* ``[gear]`` ``bore_radius_mm``: 0 (solid) .. 0.98 r_f; internal ``rim_outer_radius_mm``
  (1.0001, 10] r_f
* ``[gear]`` ``groove_width_mm``: 0 .. 10000 (herringbone only)
* ``[material]`` ``youngs_modulus_GPa`` / ``poisson_ratio`` / ``density_kg_m3``: 0.001 ..
  10000 / (-1, 0.5) / 1 .. 1e5
* ``[operation]`` ``torque_Nm`` / ``speed_rpm``: (0, 1e8] / (0, 954930]
* ``[stiffness]`` ``friction`` / ``positions`` / ``slices``: [0, 0.5] or "ehl" / 8 ..
  100000 / 1 .. 2000
* ``[stiffness]`` ``foundation_correction`` / ``roughness_um`` / ``viscosity_mPas``: [0.5,
  2] / [0, 100] / [0.01, 10000] (the last two with ``friction = "ehl"`` only)
* ``[contact]`` ``positions`` / ``slices``: 2 .. 10000 / 1 .. 1000 (the solve grows as
  slices^2.3: 2.5 s per position at 1000)
* ``[contact]`` ``slice_coupling`` / ``load_map_profile_points``: [0, 0.25) / 2 .. 2000
* ``[contact]`` ``tip_relief_length_*_mm``: [0, path of contact] (the shortest mesh's)
* ``[contact]`` ``tip_relief_*_um``, ``crowning_um``, ``slope_deviation_um``,
  ``pitch_errors_um``: magnitude <= 1000; ``pitch_errors_um`` (tooth pairs k = 0, 1, ... of
  the mesh cycle) at most the smaller gear's teeth entries, a warning names those of pairs
  k >= epsilon_alpha (they never mesh)
* ``[contact.errors]`` ``single_pitch_*_um`` / ``eccentricity_*_um`` /
  ``eccentricity_phase_*_deg``: one entry per tooth, each of magnitude <= 1000, summing to 0
  within 0.5 / [0, 1000] / [-360, 360]; mesh cycles of the span x ``[contact] positions``
  <= 100000
* ``[<gear>.modifications]`` amounts ``*_um``: [0, 1000] (slopes and twist magnitude <=
  1000); relief starts inside the gear's active flank of the mesh (``*_length_mm`` [0,
  active flank], ``*_start_diameter_mm`` the active flank's diameters); end relief lengths
  [0, face width], together at most the face width; a root relief ends below the tip
  relief's start
* ``[fe]`` ``teeth`` / ``points``: 1 .. 99 (contact sources 3 .., a 3D sector at least the
  tooth pairs in contact) / 2 .. 1000 (2D source 4 .., 3D source 2 .. 200); points x teeth
  (``gearpipe fe``) or points x loaded teeth (x ``face_points`` in 3D) <= 8000 flank points
* ``[fe]`` ``refinement``: 0.1 .. 20 (3D source 0.2 .. 4); and the estimated model size
  (:mod:`pipeline.fem.size3d`)
* ``[groove]`` ``mesh_size_mm``: 1e-4 .. 2 root radii, and the estimated model size
  (:mod:`pipeline.fem.size3d`)
* ``[groove]`` ``planets`` / ``torque_Nm``: 1 .. 64 (``coupling = "tooth_forces"`` only; a
  planetary set's own) / [-1e9, 1e9]
* ``[dynamics]`` ``bearing_stiffness_N_per_m`` / ``bearing_damping_Ns_per_m`` /
  ``damping_ratio``: [0, 1e14] / [0, 1e9] / [0, 1]
* ``[dynamics.response]`` ``n_harmonics`` / ``segments`` / ``periods``: 1 .. 500 / 8 .. 1e6
  / 1 .. 100000 (each only with the ``method`` that reads it)
* ``[dynamics.sweep]`` ``f_min_Hz`` < ``f_max_Hz`` (either may be omitted: default f_m / 4
  to max(4 f_m, 1.25 f_n*); a range without f_m is warned about) / ``points`` /
  ``n_harmonics``: (0, 1e6] / 2 .. 100000 / 1 .. 500
* ``[planetary]`` ``planet_angles_deg``: one per planet, each in [-360, 360]
* ``[dynamics.mesh_stiffness]`` stiffness levels, ``mean``, ``amplitudes`` / ``start`` /
  ``phases_rad``: magnitude <= 1e14 N/m / [0, 1) / [-2 pi, 2 pi]
* ``[lumped_model]`` ``mesh_frequency_Hz`` / masses, inertias / radii / stiffnesses: 0.001
  .. 1e6 / (0, 1e7] / (0, 10000] mm / [0, 1e15]
* ``[lumped_model]`` ``phase_*`` / ``planet_angles_deg`` / torque, speed: [-1, 1] mesh
  periods / [-360, 360] / magnitude <= 1e8 N m, 954930 rpm
"""

from __future__ import annotations

from pipeline.config.schema import Key
from pipeline.rating.materials import CORE_HARDNESS, MATERIALS

N = "number"
I = "integer"  # noqa: E741
B = "boolean"
S = "string"
L = "numbers"

MATERIAL = (
    Key("youngs_modulus_GPa"),
    Key("poisson_ratio"),
    Key("density_kg_m3"),
    Key("name", S),
)

GEAR = (
    Key("teeth", I, required=True, help="number of teeth"),
    Key("module_mm", N, required=True, help="normal module"),
    Key("pressure_angle_deg", N, required=True, help="normal pressure angle"),
    Key("face_width_mm", N, required=True, help="toothed face width (herringbone: both halves)"),
    Key("helix_angle_deg", N),
    Key("hand", S, choices=("right", "left", "none")),
    Key("profile_shift", N),
    Key("addendum_coef", N),
    Key("dedendum_coef", N),
    Key("cutter_tip_radius_coef", N),
    Key("bore_radius_mm", N),
    Key("rim_outer_radius_mm", N, field="bore_radius", help="internal gears: outer rim radius"),
    Key("internal", B),
    Key("herringbone", B),
    Key("groove_width_mm", N),
    Key("tip_radius_mm", N),
    Key("tip_rounding_mm", N, help="radius of the rounded edge between flank and tip land "
        "(0: a sharp corner)"),
    Key("name", S),
)
"""Keys of a gear table that describe the gear itself (:class:`GearSpec`)."""

BODY = (
    Key("web_width_mm", N),
    Key("rim_inner_radius_mm", N),
    Key("hub_radius_mm", N),
    Key("mass_kg", N, help="override of the mass derived from the geometry"),
    Key("inertia_kgm2", N, help="override of the polar moment derived from the geometry"),
)
"""Keys of a gear table that describe its body for the dynamics (:class:`GearBody`)."""

CARRIER = (
    Key("mass_kg", N, required=True),
    Key("inertia_kgm2", N, required=True),
)

PAIR = (
    Key("centre_distance_mm", N),
    Key("assembly_error_pinion_um", L, field="pinion", length=2),
    Key("assembly_error_gear_um", L, field="gear", length=2),
)

PLANETARY = (
    Key("planets", I, field="n_planets", required=True, help="number of planets"),
    Key("planet_angles_deg", L, field="planet_angles"),
    Key("direction", I, help="+1: sun turns counter-clockwise relative to the carrier"),
    Key("centre_distance_mm", N, help="carrier radius, the operating centre distance of both "
                                      "meshes (default: from the profile shifts)"),
)

ROTATIONS = ("clockwise", "counterclockwise")
OPERATION = (
    Key("torque_Nm", N, help="torque on the driving gear"),
    Key("speed_rpm", N, help="speed of the driving gear"),
    Key("driver", S, choices=("pinion", "gear")),
    Key("pinion_rotation", S, choices=ROTATIONS,
        help="the pinion's sense of rotation seen from the end its shafts' positions grow "
             "towards (gears on shafts)"),
)

STIFFNESS = (
    Key("friction", "number_or_string", choices=("ehl",)),
    Key("positions", I),
    Key("slices", I),
    Key("foundation_correction", N),
    Key("roughness_um", N),
    Key("viscosity_mPas", N),
)

CONTACT = (
    Key("compliance", S, choices=("analytical", "fe2d", "fe3d"),
        help="compliance source of the loaded contact ([fe] holds the FE settings)"),
    Key("positions", I),
    Key("slices", I),
    Key("local_contact", S, choices=("weber", "linear", "none")),
    Key("slice_coupling", N),
    Key("load_map_profile_points", I),
    Key("render", B),
    Key("tip_contact", B, help="teeth may touch beyond the path of contact at a tip corner"),
)
MODIFICATIONS = (
    Key("tip_relief_pinion_um", N),
    Key("tip_relief_length_pinion_mm", N, field="relief_length_pinion"),
    Key("tip_relief_gear_um", N),
    Key("tip_relief_length_gear_mm", N, field="relief_length_gear"),
    Key("relief_shape", S, choices=("linear", "parabolic")),
    Key("crowning_um", N),
    Key("slope_deviation_um", N),
    Key("pitch_errors_um", L),
)
"""Keys of the ``[contact]`` table that set :class:`FlankModifications`: the short form of
:data:`GEAR_MODIFICATIONS` (tip reliefs by roll length, lead crowning and slope on the
pinion) and the pitch errors."""

RELIEF_SHAPES = ("linear", "parabolic", "arc")
GEAR_MODIFICATIONS = (
    Key("tip_relief_um", N, help="C_a, reached at the active tip"),
    Key("tip_relief_length_mm", N, help="its start as roll length down from the active tip"),
    Key("tip_relief_start_diameter_mm", N, field="tip_relief_diameter",
        help="its start as a diameter, instead"),
    Key("tip_relief_shape", S, choices=RELIEF_SHAPES),
    Key("root_relief_um", N, help="C_f, reached at the start of active profile"),
    Key("root_relief_length_mm", N,
        help="its start as roll length up from the start of active profile"),
    Key("root_relief_start_diameter_mm", N, field="root_relief_diameter",
        help="its start as a diameter, instead"),
    Key("root_relief_shape", S, choices=RELIEF_SHAPES),
    Key("profile_crowning_um", N, help="C_alpha over the active flank"),
    Key("profile_slope_um", N, help="f_Halpha, positive: more removed towards the tip"),
    Key("lead_crowning_um", N, help="C_beta over the gear's face width"),
    Key("helix_slope_um", N, help="f_Hbeta, positive: more removed towards face 2"),
    Key("end_relief_face1_um", N, help="C_I at face 1 (the pinion's reference face side)"),
    Key("end_relief_face1_length_mm", N),
    Key("end_relief_face2_um", N, help="C_II at face 2"),
    Key("end_relief_face2_length_mm", N),
    Key("end_relief_shape", S, choices=("linear", "parabolic")),
    Key("twist_um", N, help="S: profile slope -S/2 at face 1 to +S/2 at face 2"),
    Key("topography_csv", S, max_chars=4096,
        help="deviation grid: face_position_mm, roll_length_mm or diameter_mm, deviation_um"),
)
"""Keys of each gear's ``[<gear>.modifications]``: a pair's ``[pinion.modifications]`` and
``[gear.modifications]``, a planetary set's ``[sun.modifications]``,
``[planet.modifications]`` and ``[ring.modifications]``
(:class:`~pipeline.contact.modifications.GearModification`; positive amounts remove
material)."""

ERRORS = (
    Key("single_pitch_pinion_um", L,
        help="single pitch deviations f_pt of the pinion's teeth 0 .. z1 - 1 (ISO 1328-1)"),
    Key("single_pitch_gear_um", L, help="single pitch deviations f_pt of the gear's teeth"),
    Key("eccentricity_pinion_um", N, help="runout: the pinion's teeth off its axis by e"),
    Key("eccentricity_phase_pinion_deg", N, help="angle of the pinion's eccentricity"),
    Key("eccentricity_gear_um", N),
    Key("eccentricity_phase_gear_deg", N),
    Key("span", S, choices=("hunting", "pinion", "gear"),
        help="the hunting cycle (LCM(z1, z2) mesh cycles) or one revolution of a gear"),
)
"""Keys of ``[contact.errors]`` (:mod:`pipeline.config.tooth_errors`)."""

FE = (
    Key("teeth", I, help="teeth in the FE model (default: gearpipe fe 5, contact sources "
                         "the whole gear)"),
    Key("points", I, help="tabulated points per flank (profile direction)"),
    Key("refinement", N, help="mesh refinement: flank element size m_n / (12 refinement) "
                              "in 2D, m_n / (3 refinement) in 3D"),
    Key("kind", S, choices=("plane_strain", "plane_stress"), help="2D model"),
    Key("mesh", S, choices=("graded", "uniform"),
        help="FE sources: graded from the loaded teeth (default) or every tooth at the "
             "flank size (the reference)"),
    Key("patch_mn", N, field="patch",
        help="2D source: load patch half-width in m_n (the flank grid ends 1.1 patch "
             "inside the involute; below 0.1, at least 0.1 / refinement)"),
    Key("face_points", I, help="3D: tabulated points across the face width"),
    Key("ends", S, choices=("free", "sliding"), help="3D: end faces free or u_z = 0"),
    Key("solver", S, help="3D: linear solver (pipeline.fem.solvers)"),
)
FE_MODEL_KEYS = {
    "analytical": ("teeth", "points", "refinement", "kind"),
    "fe2d": ("teeth", "points", "refinement", "kind", "mesh", "patch"),
    "fe3d": ("teeth", "points", "refinement", "face_points", "ends", "solver", "mesh"),
}
"""The ``[fe]`` keys of the FE model each ``[contact] compliance`` reads (each names the
settings field it sets): ``gearpipe fe``'s 2D sectors with the analytical compliance, the
2D source's model (:class:`~pipeline.fem.settings.FE2DSettings`), the 3D source's
(:class:`~pipeline.fem.settings.FE3DSettings`)."""

GROOVE = (
    Key("gear", S, field="gear_role", help="the herringbone gear with the groove"),
    Key("bottom_diameter_mm", N, field="groove_bottom_diameter", required=True),
    Key("shaft_length_left_mm", N),
    Key("shaft_length_right_mm", N),
    Key("shaft_diameter_left_mm", N),
    Key("shaft_diameter_right_mm", N),
    Key("torque_Nm", N, field="sun_torque"),
    Key("mesh_size_mm", N),
    Key("teeth_model", S, choices=("root_cylinder", "helical_teeth")),
    Key("coupling", S, choices=("distributed", "rigid", "tooth_forces")),
    Key("planets", I),
)

HERRINGBONE = (
    Key("torque_entry", S, choices=("right", "left", "both"),
        help="where the sun torque leaves the herringbone sun"),
    Key("sun_axial", S, choices=("held", "free"), help="sun held at axial_slide_mm, or free"),
    Key("axial_slide_mm", N, help="slide of the sun towards the right half (held sun)"),
    Key("axial_support_stiffness_N_per_m", N, help="held sun: axial support (default rigid)"),
)
"""Keys of ``[herringbone]`` (:class:`~pipeline.contact.herringbone.HerringboneOptions`)."""

RATING = (
    Key("application_factor", help="K_A (ISO 6336-1, 6336-6 Annex A)"),
    Key("life_h", field="life", help="required life"),
    Key("life_cycles", help="required life as load cycles of the driving gear, instead"),
    Key("accuracy_grade", I, help="ISO 1328-1:1995 accuracy grade of every gear"),
    Key("oil_viscosity_40_mm2_per_s", field="viscosity_40",
        help="kinematic viscosity of the oil at 40 deg C"),
    Key("oil_grade", S, help='ISO VG grade ("VG 220"), instead of the viscosity'),
    Key("face_load_factor", "number_or_string", choices=("method_c", "contact"),
        help='K_Hbeta: "method_c" (ISO 6336-1), "contact" (the loaded contact\'s line '
             'load) or a number'),
    Key("load_sharing", "number_or_string", choices=("computed",),
        help='K_gamma: a number, or "computed" (planetary sets: the dynamic model\'s planets)'),
    Key("minimum_safety_pitting", help="S_Hmin"),
    Key("minimum_safety_bending", help="S_Fmin"),
)
"""Keys of ``[rating]`` (:class:`~pipeline.rating.options.RatingOptions`); each gear's
table ``[rating.<gear>]`` holds :data:`RATING_GEAR`, ``[rating.method_c]``
:data:`RATING_METHOD_C` and ``[rating.pinion_shaft]`` :data:`RATING_PINION_SHAFT`."""
RATING_METHOD_C = (
    Key("helix_modification", S, choices=("none", "central_crowning",
                                          "central_crowning_with_deflection",
                                          "helix_correction", "helix_correction_and_crowning",
                                          "end_relief"),
        help="ISO 6336-1 Table 8 (B1, B2)"),
    Key("contact_pattern_proven", B, help="a favourable contact pattern proven: Eq. (53)"),
    Key("power_share_percent", N, field="power_share",
        help="share of the pinion's power through this mesh (a sun: 100 / planets)"),
    Key("f_ma_um", N, help="mesh misalignment from manufacture (default: from f_Hbeta)"),
    Key("f_ma_rule", S, choices=("rss", "larger"),
        help="f_ma from both gears' f_Hbeta: root sum of squares or the larger"),
)
"""Keys of ``[rating.method_c]`` (:class:`~pipeline.rating.face_load.FaceLoadInputs`)."""
RATING_PINION_SHAFT = (
    Key("span_mm", N, required=True, help="bearing span l"),
    Key("offset_mm", N, required=True, help="offset s of the pinion from mid-span"),
    Key("shaft_diameter_mm", N, field="diameter", required=True,
        help="shaft diameter d_sh for bending"),
    Key("arrangement", S, required=True, choices=("a", "b", "c", "d", "e"),
        help="ISO 6336-1 Figure 13"),
    Key("stiffening", B, help="the pinion can stiffen its shaft (default: the standard's rule)"),
    Key("bore_diameter_mm", N, field="bore"),
)
"""Keys of ``[rating.pinion_shaft]`` (:class:`~pipeline.rating.face_load.PinionShaft`): the
shaft of a pair's pinion or a planetary set's sun for f_sh of method C."""
RATING_GEAR = (
    Key("material", S, choices=tuple(MATERIALS), help="ISO 6336-5 material kind"),
    Key("quality", S, choices=("ML", "MQ", "ME"), help="ISO 6336-5 quality grade"),
    Key("surface_hardness_HV", help="surface hardness, Vickers (kinds whose lines use HV)"),
    Key("surface_hardness_HBW", help="surface hardness, Brinell (kinds whose lines use HBW)"),
    Key("core_hardness", S, choices=CORE_HARDNESS,
        help="case_hardened MQ: the bending row by core hardness"),
    Key("pitting_permitted", B, help="ISO 6336-2's life line with limited pitting"),
    Key("sigma_Hlim_MPa", field="sigma_hlim", help="allowable contact stress number, given"),
    Key("sigma_Flim_MPa", field="sigma_flim", help="nominal bending stress number, given"),
    Key("hardness_HB", field="hardness_hb", help="through-hardened gear: Brinell hardness "
                                                  "for Z_W"),
    Key("proof_stress_MPa", field="proof_stress",
        help="through-hardened gear: 0.2 % proof stress (the root's slip layer)"),
    Key("cutter_teeth", I, help="internal gear: teeth of the pinion-type cutter"),
    Key("cutter_profile_shift", N, help="internal gear: the cutter's profile shift x_0"),
    Key("cutter_tip_radius_coef", N,
        help="internal gear: the cutter's tip radius rho_a0* (default the gear's "
             "cutter_tip_radius_coef)"),
    Key("cutter_addendum_coef", N,
        help="internal gear: the cutter's addendum h_a0* (default: it cuts the root circle)"),
    Key("flank_roughness_Rz_um", field="flank_roughness", help="flank R_z"),
    Key("root_roughness_Rz_um", field="root_roughness", help="root R_z"),
)
"""Keys of ``[rating.<gear>]`` (:class:`~pipeline.rating.options.GearRatingOptions`)."""

SHAFT = (
    Key("model", S, choices=("beam", "fe3d"), help="Timoshenko beam FE or 3D FE superelement"),
    Key("gear_position_mm", N, required=True, help="the gear's mid-face on the shaft"),
    Key("torque_position_mm", N, required=True, help="where the torque is held"),
    Key("hub", S, choices=("rigid", "integral"), help="the gear's seat"),
)
"""Keys of ``[<gear>.shaft]`` (:mod:`pipeline.config.shafts`)."""
SHAFT_SEGMENT = (
    Key("start_mm", N, required=True),
    Key("end_mm", N, required=True),
    Key("outer_diameter_mm", N, required=True),
    Key("inner_diameter_mm", N),
)
SHAFT_BEARING = (
    Key("position_mm", N, required=True),
    Key("radial_stiffness_N_per_m", N, help="left out: rigid"),
    Key("tilting_stiffness_Nm_per_rad", "number_or_string", choices=("rigid",),
        help='"rigid": clamped (a cantilevered shaft or pin); left out: 0, free to tilt'),
    Key("axial", B, help="this bearing locates the shaft axially"),
)
PLANET_PIN = (
    Key("model", S, choices=("beam",), help="a planet's pin is a Timoshenko beam"),
    Key("gear_position_mm", N, required=True, help="the planet's mid-face on its pin"),
    Key("planet_bearing_radial_stiffness_N_per_m", N,
        help="the bearing between the planet and its pin; left out: rigid"),
)
"""Keys of ``[planet.shaft]``: the planet's pin (:func:`pipeline.config.shafts.pin_layout`);
its ``[[segments]]`` and ``[[bearings]]`` (the pin's supports in the carrier) as a shaft's."""
PIN_ONLY = ("planet_bearing_radial_stiffness_N_per_m",)
"""Keys of ``[planet.shaft]`` that a shaft's table has not."""

EXCITATIONS = ("analytical", "contact")
DYNAMICS = (
    Key("dofs", S, choices=("lateral_torsional", "torsional")),
    Key("bearing_stiffness_N_per_m", N),
    Key("bearing_damping_Ns_per_m", N),
    Key("damping_ratio", N),
    Key("excitation", S, choices=EXCITATIONS,
        help="mesh excitation: analytical stiffness, or the loaded contact of [contact]"),
    Key("friction", B),
    Key("drive_inertia_kgm2", N,
        help="the motor's inertia at the pinion shaft's torque point (needs [pinion.shaft])"),
    Key("load_inertia_kgm2", N,
        help="the driven machine's inertia at the gear shaft's torque point (needs "
             "[gear.shaft])"),
)
"""Keys of ``[dynamics]`` for a gear pair (:class:`PairDynamicsOptions`)."""
DYNAMICS_SUBTABLES = ("mesh_stiffness", "response", "sweep")

DYNAMICS_PLANETARY = (
    Key("sun_bearing_stiffness_N_per_m", N),
    Key("ring_bearing_stiffness_N_per_m", N),
    Key("carrier_bearing_stiffness_N_per_m", N),
    Key("planet_bearing_stiffness_N_per_m", N, help="radial and tangential, planet to carrier"),
    Key("sun_torsional_stiffness_Nm_per_rad", N),
    Key("ring_torsional_stiffness_Nm_per_rad", N),
    Key("carrier_torsional_stiffness_Nm_per_rad", N),
    Key("sun_axial_stiffness_N_per_m", N, help="herringbone sets"),
    Key("ring_axial_stiffness_N_per_m", N, help="herringbone sets"),
    Key("carrier_axial_stiffness_N_per_m", N, help="herringbone sets"),
    Key("planet_axial_stiffness_N_per_m", N, help="herringbone sets"),
    Key("groove_torsional_stiffness_Nm_per_rad", N, help="herringbone sun: groove torsion"),
    Key("groove_lateral_stiffness_N_per_m", N, help="herringbone sun: groove x, y, z"),
    Key("sun_load_side", S, choices=("both", "L", "R")),
    Key("damping_ratio", N),
    Key("modal_damping_ratio", N),
    Key("drive_inertia_kgm2", N,
        help="the motor's inertia at the sun shaft's torque point (needs [sun.shaft])"),
    Key("excitation", S, choices=EXCITATIONS,
        help="mesh excitation: analytical stiffness, or the loaded contact of [contact]"),
)
"""Keys of ``[dynamics]`` for a planetary set (:class:`PlanetaryDynamicsOptions`)."""
DYNAMICS_PLANETARY_SUBTABLES = ("sun_mesh_stiffness", "ring_mesh_stiffness", "response",
                                "sweep")

RESPONSE = (
    Key("method", S, choices=("harmonic_balance", "floquet", "time")),
    Key("n_harmonics", I),
    Key("segments", I),
    Key("periods", I),
)

SWEEP = (
    Key("f_min_Hz", N),
    Key("f_max_Hz", N),
    Key("points", I),
    Key("points_coarse", I),
    Key("method", S, choices=("harmonic_balance", "floquet")),
    Key("n_harmonics", I),
)

SIGNAL_KINDS = ("rectangular", "contact_line", "harmonic", "constant", "csv")
SIGNAL = {
    "rectangular": (Key("k_single_N_per_m", required=True),
                    Key("k_double_N_per_m", required=True),
                    Key("contact_ratio", required=True), Key("samples", I), Key("start")),
    "contact_line": (Key("k_mean_N_per_m", required=True),
                     Key("transverse_ratio", required=True),
                     Key("overlap_ratio", required=True), Key("samples", I)),
    "harmonic": (Key("mean_N_per_m", required=True), Key("amplitudes_N_per_m", L, required=True),
                 Key("phases_rad", L), Key("samples", I)),
    "constant": (Key("value_N_per_m", required=True),),
    "csv": (Key("path", S, required=True, max_chars=4096),  # PATH_MAX of Linux
            Key("column", S, max_chars=200)),
}
"""Keys of a periodic stiffness table, by its ``kind``."""
