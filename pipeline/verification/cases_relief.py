"""Cases of linear tip relief on the assembly-error paper's spur pair
(``workflows/configs/spur_pair_assembly_errors.toml``, 340 N m): a design study's optimum
and a Harris map's minima, each point through the run's static stages
(:func:`pipeline.run.chain.mesh_stages`) as a study evaluates it (the verification layer
sits beside the study layer, not above it).

* The classic estimate of the best long linear relief is the combined tooth deflection at
  the operating load, F / (b c_gamma_alpha) with ISO 6336-1's mesh stiffness
  (F = 340 N m / r_b1 = 4824 N, c_gamma_alpha = 22.0 N/(mm um), b = 20 mm: 10.96 um). The
  TE peak-to-peak minimum of the FE 2D study (relief 0 to 24 um on both gears, 2 um grid,
  parabola through the three lowest points) lies near it.
* Harris (1958, Proc. IMechE 172, "Dynamic loads on the teeth of spur gears"): a linear
  relief C_a on both gears spanning the double-contact zones gives, for a tooth pair of
  constant stiffness k, TE peak-to-peak |F / k - C_a| / 2, so the minimum lies at the load
  whose single-pair deflection F / k equals C_a, and twice the relief at twice the load.
  The single-pair deflection per N m is the unmodified pair's mean TE over its
  single-contact positions at 340 N m (tip corners off).
"""

from __future__ import annotations

import copy
import warnings
from pathlib import Path

import numpy as np

from pipeline.verification.context import Context
from pipeline.verification.model import Outcome, Plot, Quantity, Series

BASE = "configs/spur_pair_assembly_errors.toml"
"""The pair's gearbox file, under a source checkout's ``workflows/``."""

RELIEF_SET = {"contact.compliance": "fe2d", "contact.positions": 30, "contact.render": False,
              "contact.tip_relief_length_pinion_mm": 6.2,
              "contact.tip_relief_length_gear_mm": 6.2}
"""The relief study's settings on the base file (relief 0 to 24 um on both gears)."""
RELIEFS_UM = np.linspace(0.0, 24.0, 13)

HARRIS_POSITIONS = 24
HARRIS_SET = {"contact.positions": HARRIS_POSITIONS, "contact.render": False,
              "contact.tip_relief_length_pinion_mm": 6.68,
              "contact.tip_relief_length_gear_mm": 6.68}
"""The Harris map's settings: relief length the double-contact zone of the pair,
(eps_alpha - 1) p_b = 15.540 - 8.856 = 6.684 mm."""
HARRIS_RELIEFS_UM = (10.0, 20.0)
HARRIS_TORQUES_NM = np.linspace(40.0, 600.0, 15)


def _base(context: Context) -> Path:
    path = context.reference_dir.parent / BASE
    if not path.is_file():
        raise FileNotFoundError(f"{path} is missing (it is in a source checkout's workflows/)")
    return path


def _set(doc: dict, dotted: str, value) -> None:
    *tables, last = dotted.split(".")
    for t in tables:
        doc = doc.setdefault(t, {})
    doc[last] = value


def _contact(context: Context, base: Path, settings: dict):
    """The main mesh's loaded contact cycle of the base file with ``settings`` (dotted
    keys, file units)."""
    from pipeline.config import gearbox_from_dict
    from pipeline.config.toml_file import read_input_file
    from pipeline.progress import Steps
    from pipeline.run.chain import RunOptions, mesh_stages

    doc = copy.deepcopy(read_input_file(base).document)
    for k, v in settings.items():
        _set(doc, k, v)
    options = RunOptions(cache=context.cache, show_progress=False, cache_cycles=False)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        meshes = mesh_stages(gearbox_from_dict(doc, name="point"), options,
                             Steps("", enabled=False))
    return next(iter(meshes.values())).contact


def _te_pp_um(context: Context, base: Path, settings: dict) -> float:
    return float(np.ptp(_contact(context, base, settings).transmission_error)) * 1e6


def _vertex(x: np.ndarray, y: np.ndarray) -> float:
    """The abscissa of the parabola's vertex through the lowest point and its neighbours
    (the lowest point itself at either end or where the three do not bend upwards), as
    the Harris map takes it."""
    i = int(np.argmin(y))
    if not 0 < i < x.size - 1:
        return float(x[i])
    c = np.polyfit(x[i - 1:i + 2], y[i - 1:i + 2], 2)
    if c[0] <= 0:
        return float(x[i])
    return float(np.clip(-c[1] / (2 * c[0]), x[i - 1], x[i + 1]))


def case_tip_relief_optimum(context: Context) -> Outcome:
    """The FE 2D study's best relief against F / (b c_gamma_alpha)."""
    from pipeline.config import load_gearbox
    from pipeline.stiffness.analysis import analyse_stiffness

    base = _base(context)
    box = load_gearbox(base)
    force = box.operation.torque / box.pair.pinion.base_radius
    iso = analyse_stiffness(box.pair, box.operation, box.stiffness).summary()["iso6336"]
    estimate = force / (iso["c_gamma_alpha_N_per_mm_um"] * box.pinion.face_width * 1e3)  # um
    x = RELIEFS_UM
    y = np.array([_te_pp_um(context, base, {**RELIEF_SET, "contact.tip_relief_pinion_um": r,
                                            "contact.tip_relief_gear_um": r}) for r in x])
    i = int(np.clip(np.argmin(y), 1, y.size - 2))
    c = np.polyfit(x[i - 1:i + 2], y[i - 1:i + 2], 2)
    best = -c[1] / (2 * c[0])
    q = (Quantity("the estimate F / (b c_gamma_alpha)", "um", 10.96, estimate, "absolute", 0.05,
                  "the value printed to 0.01 um (the tests hold 0.05 um)"),
         Quantity("relief of the smallest TE peak-to-peak", "um", estimate, best, "relative",
                  0.2, "the estimate takes a constant mesh stiffness and a linear contact; "
                       "the tests hold 20 %"),
         Quantity("smallest TE peak-to-peak over the unmodified pair's", "-", 0.25,
                  y.min() / y[0], "upper_bound", 0.0,
                  "the relief must cut the TE peak-to-peak more than 4x (the tests' bound)"))
    plot = Plot("Long linear tip relief on both gears, 340 N m (FE 2D)",
                "tip relief C_a [um]", "TE peak-to-peak [um]",
                (Series("gearpipe, study", x, y, "-o"),
                 Series("F / (b c_gamma_alpha)", [estimate, estimate], [0.0, y.max()], "--")))
    inputs = (("pair", f"workflows/{BASE} (spur z 25/40 of the assembly-error paper), "
                       "340 N m, FE 2D compliance, 30 positions"),
              ("relief", "linear, length 6.2 mm on both gears, 0 to 24 um in 2 um steps"),
              ("ISO 6336-1", f"c_gamma_alpha {iso['c_gamma_alpha_N_per_mm_um']:.3g} N/(mm um), "
                             f"F {force:.0f} N"))
    return Outcome("classic estimate of the best long relief: the combined tooth deflection "
                   "F / (b c_gamma_alpha), ISO 6336-1 mesh stiffness", inputs, q, plots=(plot,))


def _single_pair_deflection_um_per_Nm(context: Context, base: Path) -> float:
    """The unmodified pair's mean TE over its single-contact positions at 340 N m, per N m."""
    c = _contact(context, base, {"contact.positions": HARRIS_POSITIONS,
                                 "contact.render": False, "contact.tip_contact": False})
    single = (c.pair_loads > 0).sum(axis=1) == 1
    if not 4 <= single.sum() <= 8:  # (2 - eps_alpha) x 24 = 5.9 positions
        raise ValueError(f"{single.sum()} single-contact positions of 24, expected 4 to 8")
    return float(c.transmission_error[single].mean()) * 1e6 / 340.0


def case_harris_map_minimum(context: Context) -> Outcome:
    """Each relief's smallest TE peak-to-peak at the torque whose single-pair deflection
    equals C_a (Harris 1958)."""
    base = _base(context)
    per = _single_pair_deflection_um_per_Nm(context, base)
    te = np.array([[_te_pp_um(context, base, {**HARRIS_SET, "operation.torque_Nm": t,
                                              "contact.tip_relief_pinion_um": ca,
                                              "contact.tip_relief_gear_um": ca})
                    for t in HARRIS_TORQUES_NM] for ca in HARRIS_RELIEFS_UM])
    tmin = np.array([_vertex(HARRIS_TORQUES_NM, y) for y in te])
    expected = np.array(HARRIS_RELIEFS_UM) / per
    reason = ("the pair's stiffness varies along the path and Hertz contact is not linear "
              "(measured +6.7 % and +7.4 %); the tests hold 10 %")
    q = [Quantity("single-pair deflection per torque", "um/(N m)", 0.0685, per, "relative",
                  0.02, "the value printed to 3 digits from the pipeline's own run; the tests "
                        "hold 2 %"),
         Quantity("torque of the smallest TE p-p, C_a 10 um", "N m", expected[0], tmin[0],
                  "relative", 0.10, reason),
         Quantity("torque of the smallest TE p-p, C_a 20 um", "N m", expected[1], tmin[1],
                  "relative", 0.10, reason),
         Quantity("ratio of the two minima' torques (twice the relief)", "-", 2.0,
                  tmin[1] / tmin[0], "absolute", 0.2, "the tests hold 2 +- 0.2 (measured "
                                                      "2.01)")]
    for v, lab in enumerate(("10", "20")):
        q.append(Quantity(f"C_a {lab} um: smallest TE p-p over the smaller end value", "-",
                          1.0 / 3.0, te[v].min() / min(te[v, 0], te[v, -1]), "upper_bound",
                          0.0, "the minimum is a V: under a third of either end (the tests' "
                               "bound)"))
    series = []
    for v, lab in enumerate(("10", "20")):
        series += [Series(f"gearpipe, C_a {lab} um", HARRIS_TORQUES_NM, te[v], "-o"),
                   Series(f"Harris minimum, C_a {lab} um", [expected[v]] * 2,
                          [0.0, float(np.nanmax(te))], "--")]
    plot = Plot("Harris map: TE peak-to-peak over torque", "pinion torque [N m]",
                "TE peak-to-peak [um]", tuple(series))
    inputs = (("pair", f"workflows/{BASE} (spur z 25/40), Weber's contact, "
                       f"{HARRIS_POSITIONS} positions"),
              ("relief", "linear on both gears, length 6.68 mm "
                         "(the double-contact zone), C_a 10 and 20 um"),
              ("torque", "40 to 600 N m, 15 points"))
    return Outcome("Harris (1958), Proc. IMechE 172, 'Dynamic loads on the teeth of spur "
                   "gears': the minimum where the single-pair deflection equals C_a", inputs,
                   tuple(q), plots=(plot,))
