"""Cases of the flank modifications: each shape against its closed form written in the
gear's own coordinates, and a topography grid against the modifications it samples.

A gear's modification is written in its roll length ``rho = sqrt(r^2 - r_b^2)`` and its
face position (ISO 21771:2007, 4.3 and 7.3); the contact evaluates it on the path of
contact ``s`` and the pair's face coordinate ``z``. Here each term of the pinion's and the
gear's modification at 41 x 9 points of the path of contact is compared with its formula
in that gear's coordinates, written independently of the code: the pinion's roll length is
``s``, the gear's ``T1T2 - s``; the gear, 4 mm wider, is centred (its face position is
``z + 2 mm``); an internal ring's roll length is ``T1T2 + s``, its tip the small
diameter at the path's start. The relief shapes themselves: linear ``C x / L``,
parabolic ``C (x / L)^2`` and the circular arc through (0, 0) tangent to the flank and
through (L, C), ``x^2 + (R - w)^2 = R^2``.

A topography grid is interpolated bilinearly on its cells, so a grid written from
modifications that are bilinear on each cell (linear reliefs with grid lines at their
starts, slopes, a twist, a linear end relief) reproduces them exactly: the same gap to
round-off, and the same loaded contact.
"""

from __future__ import annotations

import math
import tempfile
import warnings
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.validation import PhysicsWarning
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Outcome, Quantity

if TYPE_CHECKING:
    from pipeline.contact.modifications import GearModification
    from pipeline.contact.separations import FlankModifications

UM_ = 1e-6
MM_ = 1e-3
STEEL = Material(youngs_modulus=200e9, poisson_ratio=0.3)
ROUND_OFF = 1e-12
"""Tolerance as a fraction of the term's amount: the formulas and the code differ only in
the order of their floating-point operations."""


def _spur(teeth: int, name: str, face_width: float = 0.02) -> GearSpec:
    """A spur gear of the assembly-error paper's pair: m 3 mm, 20 deg, 21 mm bore."""
    return GearSpec(teeth=teeth, module=3e-3, pressure_angle=math.radians(20.0),
                    face_width=face_width, bore_radius=0.021, material=STEEL, name=name)


def _deviation(name: str, got: np.ndarray, want: np.ndarray) -> Quantity:
    amount = float(np.abs(want).max())
    return Quantity(f"{name}: largest |code - formula| (amount {amount / UM_:.3g} um)", "m",
                    0.0, float(np.abs(got - want).max()), "absolute", ROUND_OFF * amount,
                    "round-off: 1e-12 of the amount (the tests' tolerance)", UM)


def _relief_shapes() -> list[Quantity]:
    from pipeline.contact.modifications import shapes

    c, n = 20 * UM_, 5 * MM_
    x = np.linspace(-1 * MM_, n, 61)
    inside = np.clip(x, 0.0, None)
    q = [_deviation(f"{shape} relief C (x / L)^{p}, C 20 um over L 5 mm",
                    shapes.relief(x, c, n, shape), c * (inside / n) ** p)
         for shape, p in (("linear", 1), ("parabolic", 2))]
    w = shapes.relief(x, c, n, "arc")
    r = (n * n + c * c) / (2 * c)
    circle = float(np.abs((inside**2 + (r - w) ** 2) / (r * r) - 1.0).max())
    q += [Quantity("arc relief: largest |(x^2 + (R - w)^2) / R^2 - 1|", "-", 0.0, circle,
                   "absolute", 1e-15, "round-off of R^2 ~ 0.4 m^2 (the tests' tolerance)"),
          Quantity("arc relief at L", "m", c, float(w[-1]), "relative", ROUND_OFF,
                   "round-off", UM)]
    return q


@dataclass(frozen=True)
class ModifiedFlanks:
    """Both gears' modifications and each term's closed form at sampled points.

    Attributes
    ----------
    pinion, gear : GearModification
        The modifications of the pinion's and the gear's flank.
    pinion_terms, gear_terms : dict of str to ndarray
        Each term's formula (m) at the points, by the name ``GearModification.terms`` gives
        it.
    """

    pinion: GearModification
    gear: GearModification
    pinion_terms: dict[str, np.ndarray]
    gear_terms: dict[str, np.ndarray]


def terms_in_own_coordinates(pair: GearPair, s: np.ndarray, z: np.ndarray) -> ModifiedFlanks:
    """Every profile and lead modification term on a pair of 20 mm (pinion) and 24 mm (gear,
    centred) wide gears, and each term's closed form at the points ``s`` (m, on the path of
    contact), ``z`` (m, from the pair's first face end) written in that gear's own roll
    length and face position (ISO 21771:2007, 4.3 and 7.3), independently of the code.

    The pinion: arc tip relief 12 um from 4 mm of roll length below its tip (by diameter),
    profile crowning 3 um, profile slope -2 um, lead crowning 5 um, helix slope 4 um. The
    gear: parabolic tip relief 9 um over 5 mm, linear root relief 6 um from 3 mm above its
    SAP (by diameter), parabolic end reliefs 7 um over 4 mm and 8 um over 5 mm, twist 5 um.
    The pinion's roll length is ``s``, the gear's ``T1T2 - s``; the gear's face position
    ``z + 2 mm``.
    """
    from pipeline.contact.modifications import (
        GearModification,
        LeadModification,
        ProfileModification,
    )

    p, g = pair.pinion, pair.gear
    if (p.face_width, g.face_width) != (0.020, 0.024):
        raise ValueError(f"the formulas are written for face widths 20 mm / 24 mm, not "
                         f"{p.face_width * 1e3:g} mm / {g.face_width * 1e3:g} mm")
    rho1, rho2 = s, pair.t1t2 - s
    rho1_tip = math.sqrt(p.active_tip_radius**2 - p.base_radius**2)
    rho2_tip = math.sqrt(g.active_tip_radius**2 - g.base_radius**2)
    rho1_sap, rho2_sap = pair.s_start, pair.t1t2 - pair.s_end
    z1, b1, z2, b2 = z, 0.020, z + 0.002, 0.024
    la = rho1_tip - rho1_sap
    rho_ca = rho1_tip - 4 * MM_
    pinion = GearModification(
        profile=ProfileModification(tip_relief=12 * UM_,
                                    tip_relief_diameter=2 * math.hypot(rho_ca, p.base_radius),
                                    tip_relief_shape="arc", crowning=3 * UM_,
                                    slope=-2 * UM_),
        lead=LeadModification(crowning=5 * UM_, slope=4 * UM_))
    rho_cf = rho2_sap + 3 * MM_
    gear = GearModification(
        profile=ProfileModification(tip_relief=9 * UM_, tip_relief_length=5 * MM_,
                                    tip_relief_shape="parabolic", root_relief=6 * UM_,
                                    root_relief_diameter=2 * math.hypot(rho_cf,
                                                                        g.base_radius)),
        lead=LeadModification(end_relief_face1=7 * UM_, end_relief_face1_length=4 * MM_,
                              end_relief_face2=8 * UM_, end_relief_face2_length=5 * MM_,
                              end_relief_shape="parabolic"),
        twist=5 * UM_)
    # the circle R - sqrt(R^2 - x^2) loses digits to cancellation (R ~ 0.7 m, w ~ 10 um):
    # evaluated in extended precision
    r = ((np.longdouble(4 * MM_) ** 2 + np.longdouble(12 * UM_) ** 2)
         / (2 * np.longdouble(12 * UM_)))
    x = np.clip(rho1.astype(np.longdouble) - np.longdouble(rho_ca), 0.0, None)
    u1, u2 = rho1 - rho1_sap, rho2 - rho2_sap
    want_p = {
        "tip_relief": (r - np.sqrt(r * r - x * x)).astype(float),
        "profile_crowning": 3 * UM_ * (2 * u1 / la - 1) ** 2,
        "profile_slope": -2 * UM_ * (u1 / la - 0.5),
        "lead_crowning": 5 * UM_ * (2 * z1 / b1 - 1) ** 2,
        "helix_slope": 4 * UM_ * (z1 / b1 - 0.5),
    }
    want_g = {
        "tip_relief": 9 * UM_ * (np.clip(rho2 - (rho2_tip - 5 * MM_), 0, None) / (5 * MM_))
        ** 2,
        "root_relief": 6 * UM_ * np.clip(rho_cf - rho2, 0, None) / (rho_cf - rho2_sap),
        "end_relief_face1": 7 * UM_ * (np.clip(4 * MM_ - z2, 0, None) / (4 * MM_)) ** 2,
        "end_relief_face2": 8 * UM_ * (np.clip(z2 - (b2 - 5 * MM_), 0, None) / (5 * MM_))
        ** 2,
        "twist": 5 * UM_ * (u2 / la - 0.5) * (z2 / b2 - 0.5),
    }
    return ModifiedFlanks(pinion, gear, want_p, want_g)


def _terms_in_own_coordinates() -> list[Quantity]:
    from pipeline.contact.modifications import flank_frames, modification_gap

    pair = GearPair(_spur(50, "pinion"), _spur(50, "gear", face_width=0.024))
    ss, zz = np.meshgrid(np.linspace(pair.s_start, pair.s_end, 41),
                         np.linspace(0.0, pair.face_width, 9))
    s, z = ss.ravel(), zz.ravel()
    flanks = terms_in_own_coordinates(pair, s, z)
    fp, fg = flank_frames(pair)
    q = []
    for gear_name, mod, frame, want in (("pinion", flanks.pinion, fp, flanks.pinion_terms),
                                        ("gear", flanks.gear, fg, flanks.gear_terms)):
        got = mod.terms(frame, s, z)
        missing = set(want) ^ set(got)
        if missing:
            raise ValueError(f"{gear_name}: terms {sorted(missing)} differ from "
                             f"{sorted(want)}")
        q += [_deviation(f"{gear_name} {name.replace('_', ' ')}", got[name], want[name])
              for name in want]
    total = sum(flanks.pinion_terms.values()) + sum(flanks.gear_terms.values())
    q.append(_deviation("gap: the sum of both flanks' terms",
                        modification_gap(pair, s, z, (flanks.pinion, flanks.gear)), total))
    corners = flanks.gear.terms(fg, np.array([pair.s_start, pair.s_end]),  # its tip, root
                                np.array([0.024, 0.0]) - 0.002)["twist"]  # face 2, face 1
    q += [Quantity(f"gear twist at its {where}", "m", 5 * UM_ / 4, float(v), "relative",
                   ROUND_OFF, "S / 4 at the corners: round-off", UM)
          for where, v in zip(("tip on face 2", "root on face 1"), corners, strict=True)]
    return q


def internal_gear_terms(pair: GearPair, s: np.ndarray, z: np.ndarray
                        ) -> tuple[GearModification, dict[str, np.ndarray]]:
    """A ring's (the internal gear of ``pair``) linear tip relief 15 um from 2.5 mm of roll
    length beyond its tip (by diameter) and parabolic root relief 5 um over 2 mm, and each
    term's closed form (m) at the points ``s``, ``z`` (m) in the ring's own roll length
    ``T1T2 + s`` (its tip the small diameter at the path's start; ISO 21771:2007, 4.3)."""
    from pipeline.contact.modifications import GearModification, ProfileModification

    g = pair.gear
    rho2 = pair.t1t2 + s
    rho_tip = math.sqrt(g.active_tip_radius**2 - g.base_radius**2)
    rho_a, rho_sap = rho_tip + 2.5 * MM_, pair.t1t2 + pair.s_end
    ring = GearModification(profile=ProfileModification(
        tip_relief=15 * UM_, tip_relief_diameter=2 * math.hypot(rho_a, g.base_radius),
        root_relief=5 * UM_, root_relief_length=2 * MM_, root_relief_shape="parabolic"))
    return ring, {
        "tip_relief": 15 * UM_ * np.clip(rho_a - rho2, 0, None) / (rho_a - rho_tip),
        "root_relief": 5 * UM_ * (np.clip(rho2 - (rho_sap - 2 * MM_), 0, None) / (2 * MM_))
        ** 2}


def _internal_gear_terms() -> list[Quantity]:
    """A ring (internal, 80 teeth) against a 30-tooth planet (:func:`internal_gear_terms`)."""
    from pipeline.contact.modifications import flank_frames

    ring_spec = GearSpec(teeth=80, module=3e-3, pressure_angle=math.radians(20.0),
                         face_width=0.02, bore_radius=0.13575, material=STEEL, name="gear",
                         internal=True)
    pair = GearPair(_spur(30, "pinion"), ring_spec)
    g = pair.gear
    ss, zz = np.meshgrid(np.linspace(pair.s_start, pair.s_end, 41),
                         np.linspace(0.0, pair.face_width, 9))
    s, z = ss.ravel(), zz.ravel()
    rho_tip = math.sqrt(g.active_tip_radius**2 - g.base_radius**2)
    ring, want = internal_gear_terms(pair, s, z)
    terms = ring.terms(flank_frames(pair)[1], s, z)
    return [Quantity("ring: roll length of its tip against T1T2 + s_start", "m", rho_tip,
                     pair.t1t2 + pair.s_start, "relative", ROUND_OFF, "round-off", UM),
            _deviation("ring tip relief (linear, by diameter)", terms["tip_relief"],
                       want["tip_relief"]),
            _deviation("ring root relief (parabolic, by roll length)", terms["root_relief"],
                       want["root_relief"])]


def case_flank_modification_shapes(context: Context) -> Outcome:
    """Relief shapes and every modification term of both gears against their closed forms
    in each gear's own coordinates."""
    q = _relief_shapes() + _terms_in_own_coordinates() + _internal_gear_terms()
    inputs = (("pair", "z 50/50, m 3 mm, 20 deg, b 20 mm (pinion) / 24 mm (gear, centred)"),
              ("pinion", "arc tip relief 12 um from 4 mm below the tip (by diameter), "
                         "profile crowning 3 um, profile slope -2 um, lead crowning 5 um, "
                         "helix slope 4 um"),
              ("gear", "parabolic tip relief 9 um over 5 mm, linear root relief 6 um from "
                       "3 mm above the SAP (by diameter), parabolic end reliefs 7 um over "
                       "4 mm and 8 um over 5 mm, twist 5 um"),
              ("ring", "internal z 80 against a z 30 planet: linear tip relief 15 um from "
                       "2.5 mm of roll length beyond its tip (by diameter), parabolic root "
                       "relief 5 um over 2 mm"),
              ("points", "41 x 9 over the path of contact and the face"))
    return Outcome("Exact: the modifications' definitions in roll length and face position "
                   "(ISO 21771:2007, 4.3 and 7.3), written independently of the code",
                   inputs, tuple(q))


def _write_grid(path: Path, mod, frame, roll_lines, face_lines):
    """A topography CSV of ``mod`` on a grid through roll_lines x face_lines (m), written in
    mm and um with 17 significant digits, read back as a user's file is."""
    from pipeline.config.modifications import read_topography

    lo, hi = frame.active_roll
    roll = np.unique(np.r_[np.linspace(lo - 0.2 * MM_, hi + 0.2 * MM_, 9), roll_lines])
    face = np.unique(np.r_[np.linspace(0.0, frame.face_width, 5), face_lines])
    rr, zz = np.meshgrid(roll, face)
    s = np.array([frame.s_at_roll(r) for r in rr.ravel()])
    w = mod.deviation(frame, s, zz.ravel() - frame.face_shift)
    rows = ["face_position_mm,roll_length_mm,deviation_um"]
    rows += [f"{a * 1e3:.17g},{b * 1e3:.17g},{c * 1e6:.17g}" for a, b, c in
             zip(zz.ravel(), rr.ravel(), w, strict=True)]
    path.write_text("\n".join(rows) + "\n", encoding="utf-8")
    return read_topography(path, "modifications.topography_csv")


def bilinear_topography(pair: GearPair, folder: Path
                        ) -> tuple[FlankModifications, FlankModifications]:
    """Analytical modifications of ``pair`` that are bilinear on the cells of a topography
    grid, and the grids written from them (CSV files in ``folder``, in mm and um with 17
    significant digits, read back as a user's are): (analytical, gridded).

    The pinion: linear tip relief 12 um over 4 mm, profile slope 3 um, helix slope -5 um,
    linear end relief 6 um over 4 mm on face 2, twist 4 um; the gear: linear tip relief
    10 um from 5 mm below its tip (by diameter), linear root relief 5 um over 3 mm; grid
    lines at the reliefs' starts. Bilinear interpolation reproduces them exactly.
    """
    from pipeline.contact.modifications import (
        GearModification,
        LeadModification,
        ProfileModification,
        flank_frames,
    )
    from pipeline.contact.separations import FlankModifications

    fp, fg = flank_frames(pair)
    pinion = GearModification(
        profile=ProfileModification(tip_relief=12 * UM_, tip_relief_length=4 * MM_,
                                    slope=3 * UM_),
        lead=LeadModification(slope=-5 * UM_, end_relief_face2=6 * UM_,
                              end_relief_face2_length=4 * MM_),
        twist=4 * UM_)
    d_start = 2 * math.hypot(fg.active_roll[1] - 5 * MM_, pair.gear.base_radius)
    gear = GearModification(profile=ProfileModification(
        tip_relief=10 * UM_, tip_relief_diameter=d_start, root_relief=5 * UM_,
        root_relief_length=3 * MM_))
    grid_p = _write_grid(folder / "p.csv", pinion, fp, [fp.active_roll[1] - 4 * MM_],
                         [pair.face_width - 4 * MM_])
    grid_g = _write_grid(folder / "g.csv", gear, fg,
                         [fg.active_roll[1] - 5 * MM_, fg.active_roll[0] + 3 * MM_], [])
    return (FlankModifications(pinion_flank=pinion, gear_flank=gear),
            FlankModifications(pinion_flank=GearModification(topography=grid_p),
                               gear_flank=GearModification(topography=grid_g)))


def case_topography_equals_analytical(context: Context) -> Outcome:
    """A topography grid written from analytical modifications that are bilinear on its
    cells (linear reliefs with grid lines at their starts, slopes, a twist, a linear end
    relief) against those modifications: the gap, and the loaded contact's TE and loads."""
    from pipeline.contact.analysis import analyse_contact
    from pipeline.contact.compliance import compliance_source
    from pipeline.contact.modifications import modification_gap
    from pipeline.contact.options import ContactOptions
    from pipeline.operation import OperatingPoint
    from pipeline.stiffness.options import StiffnessOptions

    pair = GearPair(_spur(50, "pinion"), _spur(50, "gear"))
    with tempfile.TemporaryDirectory() as tmp:
        analytic, gridded = bilinear_topography(pair, Path(tmp))
    ss, zz = np.meshgrid(np.linspace(pair.s_start, pair.s_end, 97),
                         np.linspace(0.0, pair.face_width, 13))
    s, z = ss.ravel(), zz.ravel()
    want = modification_gap(pair, s, z, analytic.flanks)
    got = modification_gap(pair, s, z, gridded.flanks)
    op = OperatingPoint(torque=340.0, speed=245.0)

    def cycle(mods):
        opts = ContactOptions(positions=12, slices=10, modifications=mods)
        # the gear's tip corner touches beyond the path at two positions, alike in both
        # runs: the comparison is between them, so its warning says nothing here
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", PhysicsWarning)
            return analyse_contact(compliance_source(pair, op, opts, StiffnessOptions(),
                                                     None), op, opts)

    a, b = cycle(analytic), cycle(gridded)
    te = np.abs(b.transmission_error / a.transmission_error - 1.0).max()
    load_tol = 1e-8 * np.abs(a.point_load) + 1e-10 * a.point_load.max()
    load = np.abs(b.point_load - a.point_load) / load_tol
    q = (Quantity("gap of the grid: largest |grid - analytical|", "m", 0.0,
                  float(np.abs(got - want).max()), "absolute", 1e-13 * np.abs(want).max(),
                  "round-off of 17 printed digits and the mm / um scaling (the tests' "
                  "1e-13 of the largest gap)", UM),
         Quantity("gap span of the modifications (they act)", "m", 10 * UM_, float(np.ptp(want)),
                  "lower_bound", 0.0, "the tests ask more than 10 um", UM),
         Quantity("loaded TE, 12 positions: largest |grid / analytical - 1|", "-", 0.0,
                  float(te), "absolute", 1e-11, "round-off through the contact solve (the "
                                                "tests' rtol 1e-11)"),
         Quantity("point loads: largest |grid - analytical| / (1e-8 |F| + 1e-10 F_max)", "-",
                  0.0, float(load.max()), "upper_bound", 1.0,
                  "the tests' rtol 1e-8 and atol 1e-10 of the largest point load: at most "
                  "1 passes"))
    inputs = (("pair", "z 50/50, m 3 mm, 20 deg, b 20 mm; 340 N m, 12 positions, 10 slices"),
              ("pinion", "linear tip relief 12 um over 4 mm, profile slope 3 um, helix slope "
                         "-5 um, linear end relief 6 um over 4 mm on face 2, twist 4 um"),
              ("gear", "linear tip relief 10 um from 5 mm below the tip (by diameter), linear "
                       "root relief 5 um over 3 mm"),
              ("grids", "9 + start lines roll lengths x 5 + start lines face positions, "
                        "CSV in mm and um"))
    return Outcome("Exact: bilinear interpolation reproduces a function bilinear on each "
                   "grid cell (the modifications above with grid lines at their starts)",
                   inputs, q)
