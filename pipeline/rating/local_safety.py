"""Local safety over the flank and along the root, from the loaded contact: where a gear is
at risk, beside ISO 6336's single number of how much.

Pitting. The local pitting safety of gear ``k`` at roll coordinate ``s`` and face position
``z`` is

    S_H,loc,k(s, z) = sigma_HG,k / (p_H(s, z) sqrt(K_A K_gamma K_v)),

``p_H(s, z)`` the loaded contact's largest Hertz pressure at that point of the flank over
the mesh cycle at the nominal torque
(:func:`pipeline.contact.pressure_envelope.pressure_envelope`),
``sigma_HG,k = sigma_Hlim Z_NT Z_L Z_v Z_R Z_W Z_X`` the gear's pitting stress limit
(ISO 6336-2, clause 6: ``sigma_HP S_Hmin``), NaN where the flank carries no load. The
same pressure acts on both flanks, so the two maps differ by their ``sigma_HG`` and by the
diameter each point lies at on its own gear.

Which factors, and why only these. ISO's ``sigma_H = Z_B,D sigma_H0 sqrt(K_A K_gamma K_v
K_Hbeta K_Halpha)`` builds the stress at the determinant point from a nominal one:
``sigma_H0`` is the pitch-point Hertz stress of the load spread evenly across the face,
``Z_eps`` in it the share of the load a tooth pair carries, ``Z_B`` / ``Z_D`` move it to the
inner point of single pair contact of each gear, ``K_Hbeta`` raises it for the load's
unevenness across the face and ``K_Halpha`` for its uneven sharing between the pairs in
contact. The loaded contact solves exactly these: its line load varies across the face with
the misalignment, crowning and elastic deflection given, its pairs share the load by their
stiffness and separations, and its Hertz pressure is evaluated at every point with the
local radii of curvature. Applying ``Z_B``, ``Z_D``, ``K_Hbeta`` or ``K_Halpha`` again
would count them twice. What the contact at the nominal torque does not carry is the load
from outside the mesh: the application factor ``K_A``, the planets' load sharing
``K_gamma`` and the dynamic factor ``K_v``; they scale the load, and a Hertz line contact's
pressure grows as the square root of its load, hence ``sqrt(K_A K_gamma K_v)``. The
scaling keeps the nominal torque's load pattern: under a larger load a misaligned contact
spreads across more of the face, so its peak grows by less than the square root, and the
map is on the safe side there. The contact knows the deviations it is given (``[contact]``
modifications and pitch errors), not the accuracy grade's that ISO's ``K_Halpha`` allows
for: the map is for the modelled flanks.

Tooth root. For each gear, ``sigma_root,FE(z)``: the largest principal FE root stress over
the fillet, the tooth's passage through the mesh and the cycle in each slice ``z``
(:attr:`pipeline.contact.root_stress.GearRootStress.face_envelope`, at the nominal torque),
and the local bending safety

    S_F,loc,k(z) = sigma_FG,k / (sigma_root,FE,k(z) K_A K_gamma K_v),

``sigma_FG = sigma_Flim Y_ST Y_NT Y_deltarelT Y_RrelT Y_X Y_M`` the gear's root stress limit
(:attr:`pipeline.rating.bending.BendingSafety.limit`). Root stress is linear in the load
(linear elasticity), so the external factors enter as they are; ``K_Fbeta`` and
``K_Falpha`` are not applied, as the FE root stress under the contact's loads already holds
the load's distribution across the face and between the pairs. The FE stress is not ISO's:
ISO 6336-3's ``sigma_F0`` is a nominal stress at the 30 deg tangents with the whole load on
one tooth at the outer point of single pair contact, its notch effect through ``Y_S``; the
FE stress is the plane-section peak on the fillet under the solved loads (the report's root
stress section says how they compare). ``sigma_FG`` is calibrated against ISO's way of
computing the stress, so ``S_F,loc`` shows where along the face the root is most at risk
and how the risk varies; it is not ISO's ``S_F``, and the rating's verdict stays ISO's.

Measured, the smallest S_H,loc against ISO's S_H (``S_H,loc,min / S_H = sigma_H / (max p_H
sqrt(K_A K_gamma K_v))``): the demo's spur pair (z 50/50, 340 N m), analytical compliance,
contact on the path only: 0.8655 - ISO's ``Z_eps`` (0.8651) lowers its stress below the
Hertz pressure of the whole load on one pair in single contact, which the contact has; the
same with tip contact allowed (the default): 1.019, the tip corners taking up to 39 % of
the load where ISO has single contact; the demo run (FE 2D): 1.330 / 1.500 = 0.887; the
demo pair made helical (15 deg) with f_Hb 15 um, 20 slices, analytical: 1.409 / 1.304 =
1.080 (K_Hbeta 1.53 the contact's own in both).

Grids: the pitting maps on (``profile_points`` roll points from the start to the end of the
path) x (slice centres and the face ends 0 and b); the root stress on the same face
positions (the end slices' values holding to the face ends, as the slice model has them).
SI throughout. Checks: ``tests/test_rating_local_safety.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.contact.distribution import LoadDistribution
from pipeline.contact.pressure_envelope import pressure_envelope, to_face_ends
from pipeline.contact.results import LoadedMeshCycle
from pipeline.contact.root_stress import GearRootStress, RootStress
from pipeline.geometry.pair import GearPair
from pipeline.rating.pair_rating import PairRating
from pipeline.validation import InputError, check_range

PROFILE_POINTS = 80
"""Roll points of the pitting map along the path of contact (the report's pressure map's)."""


@dataclass(frozen=True)
class LocalPitting:
    """The local pitting safety of one gear's flank.

    Attributes
    ----------
    gear : the gear's role ("pinion", "gear", "sun", ...).
    diameter : (n_s,) diameter of this gear at each roll point of the map, m.
    safety : (n_s, n_z) S_H,loc (-), NaN where the flank carries no load.
    limit : sigma_HG, Pa.
    minimum : the smallest S_H,loc (-); minimum_diameter, minimum_z : where, m.
    """

    gear: str
    diameter: np.ndarray
    safety: np.ndarray
    limit: float
    minimum: float
    minimum_diameter: float
    minimum_z: float


@dataclass(frozen=True)
class LocalBending:
    """The FE root stress along the face of one gear and its local bending safety.

    Attributes
    ----------
    gear : the gear's role.
    stress : (n_z,) largest FE root stress in each face position over the cycle, Pa.
    limit : sigma_FG, Pa, or None for a gear not rated in bending.
    safety : (n_z,) S_F,loc (-), NaN without ``limit``.
    minimum : the smallest S_F,loc (NaN without ``limit``); minimum_z : where it is, the face
        position of the largest stress, m.
    """

    gear: str
    stress: np.ndarray
    limit: float | None
    safety: np.ndarray
    minimum: float
    minimum_z: float


@dataclass(frozen=True)
class LocalSafety:
    """Local safety of both gears of a mesh (module docstring).

    Attributes
    ----------
    s : (n_s,) roll coordinate along the path of contact, m.
    z : (n_z,) face position, 0 .. b, m.
    pressure : (n_s, n_z) p_H, the largest Hertz pressure over the cycle at the nominal
        torque, Pa (0 where unloaded).
    load_factor : K_A K_gamma K_v (-).
    pitting : per gear (pinion, gear).
    bending : per gear, or None without the FE root stress.
    """

    s: np.ndarray
    z: np.ndarray
    pressure: np.ndarray
    load_factor: float
    pitting: tuple[LocalPitting, LocalPitting]
    bending: tuple[LocalBending, LocalBending] | None = None

    def summary(self) -> dict[str, Any]:
        """Per gear: the smallest S_H,loc and where; the largest FE root stress along the face,
        where, and the smallest S_F,loc, which is there (SI; keys carry units)."""
        out: dict[str, Any] = {"load_factor_KA_Kgamma_Kv": self.load_factor}
        for k, p in enumerate(self.pitting):
            g: dict[str, Any] = {"S_H_local_min": p.minimum,
                                 "S_H_local_min_diameter_m": p.minimum_diameter,
                                 "S_H_local_min_face_position_m": p.minimum_z}
            if self.bending is not None:
                b = self.bending[k]
                g.update({"root_stress_fe_max_Pa": float(b.stress.max()),
                          "root_stress_fe_max_face_position_m": b.minimum_z,
                          "S_F_local_min": None if math.isnan(b.minimum) else b.minimum})
            out[p.gear] = g
        return out

    def columns(self) -> dict[str, np.ndarray]:
        """One row per point of the (s, z) grid, s varying slowest: the coordinates, each
        gear's diameter there, p_H, each gear's S_H,loc, and (with the root stress) each
        gear's FE root stress and S_F,loc at that face position (the same for every s)."""
        n_s, n_z = self.pressure.shape
        cols = {"roll_coordinate_s [m]": np.repeat(self.s, n_z),
                "face_position_z [m]": np.tile(self.z, n_s)}
        for p in self.pitting:
            cols[f"diameter_{p.gear} [m]"] = np.repeat(p.diameter, n_z)
        cols["hertz_pressure_envelope_nominal_torque [Pa]"] = self.pressure.ravel()
        for p in self.pitting:
            cols[f"S_H_local_{p.gear} [-]"] = p.safety.ravel()
        for b in self.bending or ():
            cols[f"root_stress_fe_along_face_{b.gear} [Pa]"] = np.tile(b.stress, n_s)
            cols[f"S_F_local_{b.gear} [-]"] = np.tile(b.safety, n_s)
        return cols


def local_pitting_safety(pressure: np.ndarray, limit: float, load_factor: float
                         ) -> np.ndarray:
    """``limit / (pressure sqrt(load_factor))`` (-): S_H,loc from p_H (Pa), sigma_HG (Pa)
    and K_A K_gamma K_v (-); NaN where ``pressure`` is 0 (no contact)."""
    p = np.asarray(pressure, dtype=float)
    out = np.full(p.shape, np.nan)
    np.divide(limit, p * math.sqrt(load_factor), out=out, where=p > 0.0)
    return out


def local_bending_safety(stress: np.ndarray, limit: float | None, load_factor: float
                         ) -> np.ndarray:
    """``limit / (stress load_factor)`` (-): S_F,loc from the FE root stress (Pa), sigma_FG
    (Pa) and K_A K_gamma K_v (-); NaN where the stress is 0 or without ``limit``."""
    s = np.asarray(stress, dtype=float)
    out = np.full(s.shape, np.nan)
    if limit is not None:
        np.divide(limit, s * load_factor, out=out, where=s > 0.0)
    return out


def rating_limits(rating: PairRating, minimum_pitting: float
                  ) -> tuple[tuple[float, float], tuple[float | None, float | None], float]:
    """From an ISO rating: (sigma_HG of each gear = sigma_HP S_Hmin, Pa; sigma_FG of each
    gear, Pa, None where not rated in bending; K_A K_gamma K_v)."""
    hg = tuple(p.permissible * minimum_pitting for p in rating.pitting)
    fg = tuple(None if b is None else b.limit for b in rating.bending)
    return ((hg[0], hg[1]), (fg[0], fg[1]),
            rating.application_factor * rating.load_sharing * rating.dynamic.factor)


def _smallest(values: np.ndarray, z: np.ndarray) -> tuple[int, ...]:
    """Index of the smallest of ``values`` (NaN skipped; the last axis along the face
    positions ``z``); of equal smallest values the one nearest the middle of the face, so
    that a map uniform across the face names its middle rather than one end."""
    v = np.where(np.isnan(values), np.inf, values)
    ties = np.argwhere(v <= v.min() + 1e-12 * abs(v.min()))
    middle = 0.5 * (z[0] + z[-1])
    best = min(ties, key=lambda ij: abs(z[ij[-1]] - middle))
    return tuple(int(x) for x in best)


def _pitting(gear: str, diameter: np.ndarray, z: np.ndarray, pressure: np.ndarray,
             limit: float, load_factor: float) -> LocalPitting:
    safety = local_pitting_safety(pressure, limit, load_factor)
    i, j = _smallest(safety, z)
    return LocalPitting(gear, diameter, safety, float(limit), float(safety[i, j]),
                        float(diameter[i]), float(z[j]))


def _bending(gear: str, root: GearRootStress, z: np.ndarray, face_width: float,
             limit: float | None, load_factor: float) -> LocalBending:
    zr, sr = to_face_ends(np.asarray(root.face_z), np.asarray(root.face_envelope)[None, :],
                          face_width)
    if zr.size != z.size or not np.allclose(zr, z, rtol=0.0, atol=1e-9):
        raise InputError("local safety: the root stress was computed on other slices than the "
                         "contact cycle's; pass the root stress of the same cycle")
    stress = sr[0]
    safety = local_bending_safety(stress, limit, load_factor)
    (j,) = _smallest(-stress, z)
    return LocalBending(gear, stress, limit, safety,
                        math.nan if limit is None else float(safety[j]), float(z[j]))


def local_safety(cycle: LoadedMeshCycle, dist: LoadDistribution, pair: GearPair, *,
                 pitting_limit: tuple[float, float],
                 bending_limit: tuple[float | None, float | None] = (None, None),
                 load_factor: float, root: RootStress | None = None,
                 gears: tuple[str, str] = ("pinion", "gear"),
                 profile_points: int = PROFILE_POINTS) -> LocalSafety:
    """The local pitting safety of both flanks and, with ``root``, the root stress along
    the face and the local bending safety (module docstring).

    Parameters
    ----------
    cycle, dist, pair : the loaded contact cycle at the nominal torque, its load
        distribution and the pair it was solved on.
    pitting_limit : sigma_HG of (pinion, gear), Pa.
    bending_limit : sigma_FG of (pinion, gear), Pa, None for a gear not rated in bending.
    load_factor : K_A K_gamma K_v (-), at least 1.
    root : the FE root stress of both gears under ``cycle``'s loads, or None.
    gears : the gears' roles, for the columns and the figures.
    profile_points : roll points of the map along the path of contact (at least 2).
    """
    check_range("rating.load_factor", load_factor, 1.0, 10.0)
    for lim in (*pitting_limit, *(x for x in bending_limit if x is not None)):
        check_range("rating.stress_limit", lim, 0.0, math.inf, lo_open=True, unit="Pa")
    if profile_points < 2:
        raise InputError(f"local safety: profile_points = {profile_points}; at least 2")
    env = pressure_envelope(cycle, dist, pair, profile_points)
    if not np.any(env.pressure > 0.0):
        raise InputError("local safety: the contact cycle carries no load on the path of "
                         "contact")
    radii = pair.contact_radii(env.s)
    pitting = tuple(_pitting(gears[k], 2.0 * np.asarray(radii[k]), env.z, env.pressure,
                             pitting_limit[k], load_factor) for k in (0, 1))
    bending = None
    if root is not None:
        bending = tuple(_bending(gears[k], g, env.z, pair.face_width, bending_limit[k],
                                 load_factor) for k, g in enumerate((root.pinion, root.gear)))
    return LocalSafety(env.s, env.z, env.pressure, float(load_factor),
                       (pitting[0], pitting[1]),
                       None if bending is None else (bending[0], bending[1]))
