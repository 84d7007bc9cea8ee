"""Result of the herringbone sun-planet loaded contact: both halves and the groove between them.

:class:`HerringboneCycle` holds one :class:`~pipeline.contact.results.LoadedMeshCycle`
per helical half (its own flank approach, its own mesh stiffness, unit loads over its
flank; its ``load`` is the half's mean load, the per-position loads are here) and, per
mesh position, what couples them: the load on each half, the approach of the planet
common to both, the twist and axial stretch of the groove and the sun's axial position.
It stores itself bit for bit (.npz) for the content-hash cache.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from pipeline.contact.cycle_io import cycle_arrays, cycle_from_arrays
from pipeline.contact.results import LoadedMeshCycle

SIDES = ("left", "right")
LEFT_FRACTION = {"right": 0.0, "left": 1.0, "both": 0.5}  # torque entering at O_L


@dataclass(frozen=True)
class HerringboneCycle:
    """Loaded contact of one herringbone sun-planet mesh over a mesh cycle (``m`` positions).

    Attributes
    ----------
    left, right : each half's contact (:class:`LoadedMeshCycle`): ``transmission_error``
        is the approach of that half's flanks along its transverse line of action (m),
        ``mesh_stiffness`` its own tangent stiffness dP_h/dx_h (N/m: teeth and local
        contact of that half, without groove and supports), point loads and unit loads
        (N, N/m) over its flank as for a helical pair, ``point_z`` in the half's own face
        frame [0, b_half] (m; the right half is the mirror image of the left, so equal z
        are equal distances from the same face of the pair's helical-half model);
        ``load`` is the half's mean load (N).
    load_left, load_right : (m,) load of each half along the transverse line of action, N.
    approach : (m,) approach of the planet against the sun's torque-carrying end along
        the transverse line of action, m: the loaded static transmission error of the
        whole mesh (both halves, groove and axial support in series).
    mesh_stiffness : (m,) tangent stiffness of the whole mesh dP/d(approach), N/m.
    groove_twist : (m,) rotation of O_L relative to O_R about the axis, rad (+ in the sense
        the left half's mesh torque turns it).
    groove_torque : (m,) torque through the groove from all planets, N m.
    groove_axial : (m,) axial displacement of O_L relative to O_R, m.
    sun_axial_position : (m,) axial position of the sun relative to the planets, m
        (+ towards the right half); the given slide plus the support's deflection, or the
        position of axial force balance for a free sun.
    load : P, total load of the mesh along the transverse line of action, N.
    n_planets : planets carrying the sun (the groove carries all of their torque).
    base_radius : sun base radius r_b, m. base_helix_angle : beta_b, rad.
    torque_entry, sun_axial : as in
        :class:`~pipeline.contact.herringbone.HerringboneOptions`.
    axial_slide : given slide z_a, m. axial_support_stiffness : N/m (inf: rigid).
    groove_compliance : (2, 2) of :class:`~pipeline.contact.groove_flank.GrooveFlankCoupling`.
    """

    left: LoadedMeshCycle
    right: LoadedMeshCycle
    load_left: np.ndarray
    load_right: np.ndarray
    approach: np.ndarray
    mesh_stiffness: np.ndarray
    groove_twist: np.ndarray
    groove_torque: np.ndarray
    groove_axial: np.ndarray
    sun_axial_position: np.ndarray
    load: float
    n_planets: int
    base_radius: float
    base_helix_angle: float
    torque_entry: str
    sun_axial: str
    axial_slide: float
    axial_support_stiffness: float
    groove_compliance: np.ndarray

    def __len__(self) -> int:
        return int(self.approach.size)

    def half(self, side: str) -> LoadedMeshCycle:
        """The contact of ``side`` ("left" or "right")."""
        return self.left if side == "left" else self.right

    def half_load(self, side: str) -> np.ndarray:
        """(m,) load of ``side`` along the transverse line of action, N."""
        return self.load_left if side == "left" else self.load_right

    def series_mesh_stiffness(self, side: str) -> np.ndarray:
        """(m,) stiffness of ``side``'s mesh in series with the groove and the axial support
        its own load meets, N/m: ``1 / (1 / k_h + N w_h^T C w_h + N tan^2(beta_b) / k_a)``
        with the groove weights ``w_L = (1 - f) [r_b, tan(beta_b)]``,
        ``w_R = f [-r_b, tan(beta_b)]`` (f: torque fraction entering at O_L). It is what a
        model with the groove inside the mesh spring (Xu et al. 2020, eq. 14) would call the
        side's mesh stiffness; the half's own stiffness is ``half(side).mesh_stiffness``."""
        f = LEFT_FRACTION[self.torque_entry]
        t = math.tan(self.base_helix_angle)
        w = (np.array([self.base_radius, t]) * (1.0 - f) if side == "left"
             else np.array([-self.base_radius, t]) * f)
        c = self.n_planets * float(w @ self.groove_compliance @ w)
        if math.isfinite(self.axial_support_stiffness) and self.sun_axial == "held":
            c += self.n_planets * t * t / self.axial_support_stiffness
        k = self.half(side).mesh_stiffness
        with np.errstate(divide="ignore"):
            return np.where(k > 0.0, 1.0 / (1.0 / np.where(k > 0.0, k, 1.0) + c), 0.0)

    @property
    def groove_torsional_stiffness(self) -> float:
        """k_t of the condensed groove, N m/rad (inf: rigid)."""
        c = float(self.groove_compliance[0, 0])
        return math.inf if c == 0.0 else 1.0 / c

    def summary(self) -> dict[str, Any]:
        """Per half: mean load and share, max unit load, mean/max/min own mesh stiffness,
        mean and peak-to-peak flank approach; the groove and the sun (SI, units in keys)."""
        out: dict[str, Any] = {"load_N": self.load, "n_planets": self.n_planets,
                               "torque_entry": self.torque_entry, "sun_axial": self.sun_axial,
                               "axial_slide_m": self.axial_slide}
        for side in SIDES:
            c, p = self.half(side), self.half_load(side)
            out[side] = {
                "load_mean_N": float(p.mean()), "load_share_mean": float(p.mean() / self.load),
                "max_unit_load_N_per_m": float(c.max_unit_load.max()),
                "mesh_stiffness_mean_N_per_m": float(c.mesh_stiffness.mean()),
                "mesh_stiffness_max_N_per_m": float(c.mesh_stiffness.max()),
                "mesh_stiffness_min_N_per_m": float(c.mesh_stiffness.min()),
                "transmission_error_mean_m": float(c.transmission_error.mean()),
                "transmission_error_peak_to_peak_m": float(np.ptp(c.transmission_error)),
            }
        out.update({
            "mesh_stiffness_mean_N_per_m": float(self.mesh_stiffness.mean()),
            "approach_mean_m": float(self.approach.mean()),
            "groove_twist_mean_rad": float(self.groove_twist.mean()),
            "groove_torque_mean_Nm": float(self.groove_torque.mean()),
            "groove_torsional_stiffness_Nm_per_rad": self.groove_torsional_stiffness,
            "sun_axial_position_mean_m": float(self.sun_axial_position.mean()),
            "max_residual_m": float(max(self.left.residual.max(), self.right.residual.max())),
        })
        return out

    def columns(self) -> dict[str, np.ndarray]:
        """Per-position columns (shape (m,) each), named with their units."""
        cols = {"roll_coordinate_s0 [m]": self.left.s0,
                "sun_angle [rad]": self.left.pinion_angle,
                "load_left [N]": self.load_left, "load_right [N]": self.load_right,
                "approach [m]": self.approach,
                "mesh_stiffness_total [N/m]": self.mesh_stiffness}
        for side in SIDES:
            c = self.half(side)
            cols[f"transmission_error_{side} [m]"] = c.transmission_error
            cols[f"mesh_stiffness_{side} [N/m]"] = c.mesh_stiffness
            cols[f"max_unit_load_{side} [N/m]"] = c.max_unit_load
        cols.update({"groove_twist [rad]": self.groove_twist,
                     "groove_torque [N m]": self.groove_torque,
                     "groove_axial [m]": self.groove_axial,
                     "sun_axial_position [m]": self.sun_axial_position})
        return cols


_OWN = [f.name for f in fields(HerringboneCycle) if f.name not in SIDES]
_SCALARS = {"load": float, "n_planets": int, "base_radius": float, "base_helix_angle": float,
            "torque_entry": str, "sun_axial": str, "axial_slide": float,
            "axial_support_stiffness": float}


def herringbone_arrays(cycle: HerringboneCycle) -> dict[str, np.ndarray]:
    """The cycle as named arrays, each half's fields prefixed ``"left:"`` / ``"right:"``
    (:func:`herringbone_from_arrays` reads them back)."""
    arrays = {n: np.asarray(getattr(cycle, n)) for n in _OWN}
    for side in SIDES:
        arrays.update({f"{side}:{k}": v for k, v in cycle_arrays(cycle.half(side)).items()})
    return arrays


def herringbone_from_arrays(z: dict[str, np.ndarray]) -> HerringboneCycle:
    """The cycle of :func:`herringbone_arrays` (KeyError when a field is missing)."""
    kw: dict[str, Any] = {n: _SCALARS[n](z[n]) if n in _SCALARS else z[n] for n in _OWN}
    for side in SIDES:
        prefix = f"{side}:"
        kw[side] = cycle_from_arrays({k[len(prefix):]: v for k, v in z.items()
                                      if k.startswith(prefix)})
    return HerringboneCycle(**kw)
