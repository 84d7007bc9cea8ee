"""Time-varying mesh stiffness over one mesh cycle: spur pairs, and helical/herringbone by slicing.

Each tooth pair in contact is a series chain (pinion tooth + pinion body +
Hertz contact + gear tooth + gear body); pairs in contact act in parallel.
Helical gears are cut into ``N`` thin spur slices across the face (Yang et al. 2026,
section 2.1); slice ``j`` at face position ``z_j`` meets its mate at roll
coordinate ``s + z_j tan(beta_b)``, so each slice has its own load position,
friction direction and contact state. Everything is evaluated as one array of
shape (positions, pairs, slices): no Python loop over positions or slices.

The stiffness is referred to the transverse line of action (force along it
over approach along it), in N/m.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.signals import PeriodicSignal
from pipeline.stiffness.friction import (
    ehl_friction_coefficient,
    friction_direction,
    hertz_line_pressure,
)
from pipeline.stiffness.tooth import ToothModel, hertz_compliance, tooth_compliance, tooth_model
from pipeline.validation import InputError, check_int_range, check_range


@dataclass(frozen=True)
class FrictionModel:
    """Friction coefficient: constant ``mu`` or ``"ehl"`` (Jin et al. 2018, eq. 9).

    Attributes
    ----------
    mu : constant coefficient (-) used when ``kind == "constant"``.
    kind : "constant" or "ehl".
    roughness : RMS composite roughness, m (EHL).
    viscosity : dynamic viscosity at inlet temperature, Pa s (EHL).
    """

    mu: float = 0.0
    kind: str = "constant"
    roughness: float = 0.5e-6
    viscosity: float = 0.02

    def __post_init__(self) -> None:
        check_range("friction.mu", self.mu, 0.0, 0.5)
        if self.kind not in ("constant", "ehl"):
            raise InputError(f"friction.kind = {self.kind!r} is not one of 'constant', 'ehl'")


@dataclass(frozen=True)
class MeshStiffness:
    """Mesh stiffness over one mesh cycle.

    Attributes
    ----------
    s0 : shape (m,), roll coordinate of the leading tooth pair, m.
    pinion_angle : shape (m,), pinion rotation from the start of the cycle, rad.
    total : shape (m,), mesh stiffness k(t), N/m.
    pairs : shape (m, K), stiffness of each tooth pair (0 when out of contact), N/m.
    friction_stiffness : shape (m,), K_f = sum lam mu k (Jin et al. 2018, eq. 15), N/m.
    friction_torque_pinion, friction_torque_gear : shape (m,), KT_f,i = sum lam mu k rho_i,
        N m/m (friction torque on gear i per metre of mesh deflection).
    mu : shape (m, K, N), friction coefficient at every slice contact (0 out of contact).
    contact_length : shape (m,), total contact line length, m.
    mesh_period : duration of one mesh cycle at the operating speed, s.
    pair : the (actual) pair the stiffness was computed for.
    """

    s0: np.ndarray
    pinion_angle: np.ndarray
    total: np.ndarray
    pairs: np.ndarray
    friction_stiffness: np.ndarray
    friction_torque_pinion: np.ndarray
    friction_torque_gear: np.ndarray
    mu: np.ndarray
    contact_length: np.ndarray
    mesh_period: float
    pair: GearPair

    @property
    def mean(self) -> float:
        return float(self.total.mean())

    @property
    def max(self) -> float:
        return float(self.total.max())

    @property
    def min(self) -> float:
        return float(self.total.min())

    def as_periodic(self) -> PeriodicSignal:
        """k over one mesh period as a :class:`PeriodicSignal` (N/m)."""
        return PeriodicSignal(self.total, self.mesh_period)

    def summary(self) -> dict[str, float]:
        return {
            "mean_N_per_m": self.mean,
            "max_N_per_m": self.max,
            "min_N_per_m": self.min,
            "peak_to_peak_percent": 100.0 * (self.max - self.min) / self.mean,
        }


@dataclass(frozen=True)
class PairModel:
    """Precomputed tooth models of a pair (the expensive part; reuse across positions)."""

    pair: GearPair
    pinion: ToothModel
    gear: ToothModel
    hertz: float  # m^2/N per unit width

    @classmethod
    def build(cls, pair: GearPair, n_sections: int = 3000) -> PairModel:
        return cls(pair, tooth_model(pair.pinion, n_sections), tooth_model(pair.gear, n_sections),
                   hertz_compliance(pair.pinion, pair.gear))


def slice_positions(pair: GearPair, s0: np.ndarray, n_slices: int) -> tuple[np.ndarray, float]:
    """Roll coordinates of every (position, pair, slice), shape (m, K, N), and slice width (m)."""
    b = pair.face_width
    if pair.pinion.is_helical:
        dz = b / n_slices
        z = (np.arange(n_slices) + 0.5) * dz
    else:
        n_slices, dz, z = 1, b, np.zeros(1)
    s_pairs, _ = pair.pair_positions(s0)  # (m, K): the contact of each pair at z = 0
    s = s_pairs[:, :, None] + z[None, None, :] * math.tan(pair.pinion.base_helix_angle)
    return s, dz


def mesh_stiffness(
    model: PairModel,
    positions: int = 360,
    slices: int = 100,
    friction: FrictionModel | None = None,
    operating: OperatingPoint | None = None,
    foundation_correction: float = 1.0,
) -> MeshStiffness:
    """Time-varying mesh stiffness of a spur, helical or herringbone-half pair.

    Parameters
    ----------
    model : :class:`PairModel` (tooth models of both gears).
    positions : samples over one mesh cycle.
    slices : slices across the face (helical gears; spur gears use one).
    friction : friction model (default: none).
    operating : torque and speed (for EHL friction and the mesh period).
    foundation_correction : factor on the body stiffness while more than one tooth
        pair is in contact (the assembly-error paper uses 1.1; 1 leaves Sainsot's formula as is).
    """
    check_int_range("stiffness.positions", positions, 8, 10_000_000)
    return stiffness_at(model, model.pair.mesh_cycle(positions), slices, friction, operating,
                        foundation_correction)


def stiffness_at(
    model: PairModel,
    s0: np.ndarray,
    slices: int = 100,
    friction: FrictionModel | None = None,
    operating: OperatingPoint | None = None,
    foundation_correction: float = 1.0,
    half_offset: float = 0.0,
) -> MeshStiffness:
    """Mesh stiffness at the leading-pair roll coordinates ``s0`` (m, shape (m,)).

    For herringbone gears both helical halves are evaluated and summed; the right
    half runs ``half_offset`` base pitches (fraction, [0, 1)) behind the left one
    (0 for halves cut in line; see Xu et al. 2020 for the phase a twisted sun adds).
    ``pairs`` then holds the left half's pairs followed by the right half's.
    """
    check_int_range("stiffness.slices", slices, 1, 100_000)
    check_range("stiffness.foundation_correction", foundation_correction, 0.5, 2.0)
    check_range("stiffness.half_offset", half_offset, 0.0, 1.0, hi_open=True)
    friction = friction or FrictionModel()
    operating = operating or OperatingPoint()
    pair = model.pair
    s0 = np.asarray(s0, dtype=float)
    if pair.pinion.herringbone:
        halves = [_half(model, s0, slices, friction, operating, foundation_correction, 0.5),
                  _half(model, s0 - half_offset * pair.base_pitch, slices, friction, operating,
                        foundation_correction, 0.5)]
    else:
        halves = [_half(model, s0, slices, friction, operating, foundation_correction, 1.0)]
    w1 = operating.speed if operating.driver == "pinion" else operating.speed * pair.gear_ratio

    def total(key: str) -> np.ndarray:
        return sum(h[key] for h in halves)

    pairs = np.concatenate([h["pairs"] for h in halves], axis=1)
    return MeshStiffness(
        s0=s0,
        pinion_angle=(s0 - s0[0]) / pair.pinion.base_radius,
        total=pairs.sum(axis=1),
        pairs=pairs,
        friction_stiffness=total("kf"),
        friction_torque_pinion=total("kt1"),
        friction_torque_gear=total("kt2"),
        mu=np.concatenate([h["mu"] for h in halves], axis=1),
        contact_length=total("length"),
        mesh_period=2.0 * math.pi / (w1 * pair.pinion.teeth),
        pair=pair,
    )


def _half(model: PairModel, s0: np.ndarray, slices: int, friction: FrictionModel,
          operating: OperatingPoint, foundation_correction: float, load_share: float) -> dict:
    """Stiffness arrays of one helical half (or a spur/helical pair); see :func:`stiffness_at`."""
    pair = model.pair
    s, dz = slice_positions(pair, s0, slices)
    inside = (s >= pair.s_start) & (s <= pair.s_end)
    sc = np.where(inside, s, pair.s_pitch)  # evaluate safely; masked afterwards
    lam = friction_direction(sc, pair.s_pitch, operating.driver)
    mu = friction_coefficients(pair, sc, inside, friction, operating, dz, load_share)
    r1, r2 = pair.contact_radii(sc)
    c1 = tooth_compliance(model.pinion, r1, mu, lam)
    c2 = tooth_compliance(model.gear, r2, mu, lam)
    n_pairs = np.any(inside, axis=2).sum(axis=1)  # tooth pairs in contact, shape (m,)
    corr = np.where(n_pairs > 1, foundation_correction, 1.0)[:, None, None]
    compliance = c1.tooth + c2.tooth + (c1.foundation + c2.foundation) / corr + model.hertz
    k_slice = np.where(inside, dz / compliance, 0.0)
    rho1, rho2 = pair.curvature_radii(sc)
    fk = lam * mu * k_slice
    return {
        "pairs": k_slice.sum(axis=2),
        "kf": fk.sum(axis=(1, 2)),
        "kt1": (fk * rho1).sum(axis=(1, 2)),
        "kt2": (fk * np.abs(rho2)).sum(axis=(1, 2)),
        "mu": np.where(inside, mu, 0.0),
        "length": inside.sum(axis=(1, 2)) * dz / math.cos(pair.pinion.base_helix_angle),
    }


def friction_coefficients(pair: GearPair, s: np.ndarray, inside: np.ndarray,
                           friction: FrictionModel, op: OperatingPoint, dz: float,
                           load_share: float = 1.0) -> np.ndarray:
    """Friction coefficient at every slice contact (same shape as ``s``)."""
    if friction.kind == "constant":
        return np.full(s.shape, friction.mu)
    w1 = op.speed if op.driver == "pinion" else op.speed * pair.gear_ratio
    u1, u2 = pair.rolling_velocities(s, w1)
    rho1, rho2 = pair.curvature_radii(s)
    r_eff = np.abs(rho1 * rho2 / (rho1 + rho2))
    # normal load shared evenly over the contact lines (the LTCA refines this)
    t1 = op.torque if op.driver == "pinion" else op.torque / pair.gear_ratio
    f_normal = load_share * t1 / (pair.pinion.base_radius * math.cos(pair.pinion.base_helix_angle))
    length = inside.sum(axis=(1, 2), keepdims=True) * dz / math.cos(pair.pinion.base_helix_angle)
    w = f_normal / np.maximum(length, 1e-12)
    e_prime = 2.0 / (1.0 / pair.pinion.material.plane_strain_modulus
                     + 1.0 / pair.gear.material.plane_strain_modulus)
    ph = hertz_line_pressure(w, r_eff, e_prime)
    sr = 2.0 * (u1 - u2) / (u1 + u2)
    mu = ehl_friction_coefficient(sr, ph, u1 + u2, friction.viscosity, r_eff, friction.roughness)
    return np.where(inside, mu, 0.0)
