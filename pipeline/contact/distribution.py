"""Tooth load distribution of a loaded mesh cycle: the quantities a load distribution report
and a design study rank gears by.

:func:`load_distribution` turns a :class:`~pipeline.contact.results.LoadedMeshCycle` (the
loads of every candidate point at every mesh position) into:

* **Line load** ``w(z, t)`` (N/m): the transverse load along the line of action per unit
  face width at face position ``z`` (slice centres) and mesh position ``t``, summed over
  the tooth pairs touching in that section: ``w = sum_k F_k(z, t) / width``. Its face mean
  is ``P / b`` at every position. ``envelope`` is its largest value at each ``z`` over the
  cycle, ``cycle_mean`` its mean over the cycle.
* **Face load factor** ``K_Hbeta`` (ISO 6336-1: maximum over mean load per unit face width),
  from the cycle-mean line load: ``K_Hbeta = max_z w_bar(z) / mean_z w_bar(z)``. Averaging
  over the cycle removes the way the load moves between the tooth pairs (which is the
  tooth-pair unit load ratio's), so a pair loaded evenly across its face has exactly 1, and
  a spur pair of uniform mesh stiffness ``c_gamma`` (N/m per m of face) with a helix slope
  deviation ``f_Hb`` has ISO 6336-1's closed form ``1 + f_Hb c_gamma / (2 P / b)`` while the
  whole face carries load (``sqrt(2 f_Hb c_gamma / (P / b))`` once part of it lifts off at
  one position). ``k_hbeta_position`` is the same ratio at every position (``max_z w / (P(t)
  / b)``).
* **Tooth-pair unit load ratio** (``pair_load_ratio``): how unevenly the tooth pairs in
  contact share the load, from the computed sharing: at each position the largest mean unit
  load of a tooth pair, ``F_k / L_k`` (its load over its contact-line length on the plane of
  action), over the mean unit load of all its contact lines ``P(t) / sum_k L_k``; the ratio
  is the largest over the cycle (1 in single contact, and for pairs sharing in proportion to
  their contact lengths). This is the LTCA's own measure and not ISO 6336-1's transverse
  load factor ``K_Halpha`` (an empirical factor for deviations, 1 for a perfect pair, built
  to go with the contact ratio factor ``Z_eps``): hence its own name.
* **Hertz contact pressure** at every loaded point (Johnson 1985, eq. 4.45) in the normal
  section of the flanks: unit load ``p`` (N/m along the contact line), effective radius
  ``R_n = R_t / cos(beta_b)``, contact modulus ``E*``; the same pressure acts on both flanks,
  at the pinion radius ``r_1(s)`` and the gear radius ``r_2(s)``. Its maximum and where
  (roll coordinate, face position, both radii, mesh position), on the path of contact. A
  tip corner touching beyond the path presses with its local corner radius
  (:func:`pipeline.geometry.tip_contact.curvature_radii_at`) and its normal force
  (:attr:`LoadedMeshCycle.point_pressure`): its largest pressure is given apart, as edge
  loading (GPa for the 0.15 mm corner of an m 3 mm tooth), not as the flank's p_H.
* **Loaded static transmission error** (m, and as a pinion angle in rad), its
  peak-to-peak, and the amplitudes of mesh orders 1..10 (single-sided, from the DFT of the
  equally spaced positions; orders at or above half the number of positions are NaN).
* **Load sharing** ``F_k / P(t)`` of every tooth pair at every position.

``P(t)`` is the load the cycle carries at each position (the sum of its point loads): the
constant ``P`` of a pair solved at one load (to the solver's tolerance), and a helical half's
own share of a herringbone mesh, which moves over the cycle
(:mod:`pipeline.contact.herringbone_distribution`); ``P`` (``load``) is its mean.

Conventions: SI inside; the summary keys carry their units.

Checks (``tests/test_contact_distribution.py``): K_Hbeta is 1 to 1e-12 under an even load,
and on a spur pair of uniform stiffness with a helix slope deviation it equals the closed
form on N slices to 1e-9 in both of ISO's regimes; the Hertz pressure at the pitch point in
single contact equals ISO 6336-2's ``Z_H Z_E sqrt(F_t / (d_1 b) (u + 1) / u)`` to 1e-9. A
spur pair with lead crowning or a helix slope deviation is cut into ``[contact] slices``
across the face, like a helical pair; other spur pairs get one slice (their line load is
even by construction; the report says so). Measured values on the example gearboxes:
:mod:`pipeline.report`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from pipeline.contact.analysis import line_of_action_load
from pipeline.contact.results import LoadedMeshCycle, pairs_in_order_of_entry
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError

MESH_ORDERS = 10  # transmission-error orders reported (1..MESH_ORDERS)


def _readonly(a: np.ndarray) -> np.ndarray:
    out = np.array(a, dtype=float, copy=True)
    out.setflags(write=False)
    return out


@dataclass(frozen=True)
class PeakLocation:
    """Where a maximum occurs.

    Attributes
    ----------
    value : the maximum, in the unit of the quantity.
    position : mesh position index (0 .. m-1).
    pinion_angle : pinion rotation from the first position, rad.
    s : roll coordinate on the transverse line of action, m.
    z : face position from the pinion's reference face, m.
    pinion_radius, gear_radius : radius of the point on each flank, m.
    tooth_pair : tooth-pair index k (:meth:`GearPair.pair_indices`).
    """

    value: float
    position: int
    pinion_angle: float
    s: float
    z: float
    pinion_radius: float
    gear_radius: float
    tooth_pair: int


@dataclass(frozen=True)
class LoadDistribution:
    """Load distribution of one loaded mesh cycle (module docstring for the definitions).

    Attributes
    ----------
    z : (n_z,) face positions of the slices, m.
    line_load : (m, n_z) transverse load per unit face width w(z, t), N/m.
    mean_line_load : P / b, N/m.
    envelope : (n_z,) largest line load at each face position over the cycle, N/m.
    cycle_mean : (n_z,) mean line load at each face position over the cycle, N/m.
    k_hbeta : face load factor K_Hbeta (-).
    k_hbeta_position : (m,) max_z w(z, t) / (P(t) / b) at each position (-).
    pair_load_ratio : tooth-pair unit load ratio, the largest over the cycle (-).
    pair_load_ratio_position : (m,) the same ratio at each position (-).
    hertz_pressure : (n_total,) Hertz maximum pressure p_H of every candidate point of the
        cycle (the order of ``cycle.point_*``), Pa; 0 where unloaded.
    hertz_max : largest p_H on the flanks, on the path of contact, and where (Pa).
    tip_corner_max : largest p_H where a tip corner touches beyond the path (edge loading,
        Hertz of the corner's local radius), and where; None when no corner carries load.
    line_load_max : largest line load w and where (N/m).
    pinion_angle : (m,) pinion rotation from the first position, rad.
    transmission_error : (m,) loaded static TE along the line of action, m.
    te_peak_to_peak : m; te_peak_to_peak_angle : as pinion angle, rad.
    te_orders : (10,) single-sided amplitudes of mesh orders 1..10, m (NaN when the
        positions cannot resolve an order).
    pair_index : (K,) tooth-pair indices; load_share : (m, K) F_k / P(t) (-).
    mesh_stiffness : (m,) tangent mesh stiffness dP/dx_s, N/m.
    load : P, total load along the transverse line of action (its mean over the cycle), N.
    face_width : b, m.
    slices_across_face : number of distinct face positions (1 for a spur pair solved with one
        slice, as ``ContactOptions.face_slices`` gives one without lead crowning or helix
        slope deviation: then the face distribution is uniform by construction).
    """

    z: np.ndarray
    line_load: np.ndarray
    mean_line_load: float
    envelope: np.ndarray
    cycle_mean: np.ndarray
    k_hbeta: float
    k_hbeta_position: np.ndarray
    pair_load_ratio: float
    pair_load_ratio_position: np.ndarray
    hertz_pressure: np.ndarray
    hertz_max: PeakLocation
    tip_corner_max: PeakLocation | None
    line_load_max: PeakLocation
    pinion_angle: np.ndarray
    transmission_error: np.ndarray
    te_peak_to_peak: float
    te_peak_to_peak_angle: float
    te_orders: np.ndarray
    pair_index: np.ndarray
    load_share: np.ndarray
    mesh_stiffness: np.ndarray
    load: float
    face_width: float
    slices_across_face: int = field(default=1)

    def __post_init__(self) -> None:
        for name in ("z", "line_load", "envelope", "cycle_mean", "k_hbeta_position",
                     "pair_load_ratio_position", "hertz_pressure", "pinion_angle",
                     "transmission_error", "te_orders", "load_share", "mesh_stiffness"):
            object.__setattr__(self, name, _readonly(getattr(self, name)))

    def summary(self) -> dict[str, Any]:
        """The key figures (SI; keys carry units): load factors, pressures, TE, sharing."""
        h, w = self.hertz_max, self.line_load_max
        out: dict[str, Any] = {
            "load_N": self.load,
            "face_width_m": self.face_width,
            "K_Hbeta": self.k_hbeta,
            "pair_unit_load_ratio": self.pair_load_ratio,
            "mean_line_load_N_per_m": self.mean_line_load,
            "max_line_load_N_per_m": w.value,
            "max_line_load_face_position_m": w.z,
            "max_hertz_pressure_Pa": h.value,
            "max_hertz_pressure_roll_coordinate_m": h.s,
            "max_hertz_pressure_face_position_m": h.z,
            "max_hertz_pressure_pinion_diameter_m": 2.0 * h.pinion_radius,
            "max_hertz_pressure_gear_diameter_m": 2.0 * h.gear_radius,
            "max_hertz_pressure_pinion_angle_rad": h.pinion_angle,
            "max_tip_corner_pressure_Pa": (0.0 if self.tip_corner_max is None
                                           else self.tip_corner_max.value),
            "transmission_error_peak_to_peak_m": self.te_peak_to_peak,
            "transmission_error_peak_to_peak_rad": self.te_peak_to_peak_angle,
            "max_load_share": float(self.load_share.max()),
            "mesh_stiffness_mean_N_per_m": float(self.mesh_stiffness.mean()),
            "slices_across_face": self.slices_across_face,
        }
        for j, a in enumerate(self.te_orders, start=1):
            out[f"transmission_error_order_{j}_amplitude_m"] = float(a)
        return out

    def columns(self) -> dict[str, np.ndarray]:
        """Per-position columns over the cycle (shape (m,) each), named with their units."""
        cols = {
            "pinion_angle [rad]": self.pinion_angle,
            "transmission_error [m]": self.transmission_error,
            "mesh_stiffness_tangent [N/m]": self.mesh_stiffness,
            "K_Hbeta_at_position [-]": self.k_hbeta_position,
            "pair_unit_load_ratio_at_position [-]": self.pair_load_ratio_position,
        }
        for n, j in enumerate(pairs_in_order_of_entry(self.load_share), start=1):
            cols[f"load_share_tooth_pair_{n} [-]"] = self.load_share[:, j]
        return cols

    def pair_number(self, k: int) -> int:
        """The reader's number (1, 2, ...: in the order the pairs take load over the cycle,
        as the load-share figures count them) of the tooth pair with index ``k``
        (:meth:`GearPair.pair_indices`)."""
        return pairs_in_order_of_entry(self.load_share).index(
            int(np.flatnonzero(self.pair_index == k)[0])) + 1

    def face_columns(self) -> dict[str, np.ndarray]:
        """Per-face-position columns (shape (n_z,) each): mean and envelope line load."""
        return {"face_position_z [m]": self.z,
                "line_load_cycle_mean [N/m]": self.cycle_mean,
                "line_load_envelope [N/m]": self.envelope}


def mesh_order_amplitudes(values: np.ndarray, orders: int = MESH_ORDERS) -> np.ndarray:
    """Single-sided amplitudes of orders 1..``orders`` of equally spaced samples over one
    period (same unit as ``values``); NaN for orders the samples cannot resolve
    (``order >= n / 2``)."""
    v = np.asarray(values, dtype=float)
    n = v.size
    c = np.fft.rfft(v) / n
    out = np.full(orders, np.nan)
    for j in range(1, orders + 1):
        if 2 * j < n:
            out[j - 1] = 2.0 * abs(c[j])
    return out


def _peak(values: np.ndarray, cycle: LoadedMeshCycle, pair: GearPair) -> PeakLocation:
    i = int(np.argmax(values))
    pos = int(cycle.point_position[i])
    s = float(cycle.point_s[i])
    r1, r2 = contact_radii_at(pair, s)
    return PeakLocation(float(values[i]), pos, float(cycle.pinion_angle[pos]), s,
                        float(cycle.point_z[i]), float(r1), float(r2),
                        int(cycle.point_pair[i]))


def _line_loads(cycle: LoadedMeshCycle) -> tuple[np.ndarray, np.ndarray]:
    """Face positions (n_z,) and line loads (m, n_z), N/m."""
    zq = np.round(cycle.point_z, 12)
    z, iz = np.unique(zq, return_inverse=True)
    w = np.zeros((len(cycle), z.size))
    np.add.at(w, (cycle.point_position, iz), cycle.point_load / cycle.point_width)
    return z, w


def position_loads(cycle: LoadedMeshCycle) -> np.ndarray:
    """(m,) load P(t) the cycle carries at each position, N: the sum of its point loads."""
    return np.bincount(cycle.point_position, weights=cycle.point_load, minlength=len(cycle))


def _transverse_factor(cycle: LoadedMeshCycle, pair: GearPair) -> np.ndarray:
    """max_k (F_k / L_k) / (P(t) / sum_k L_k) at every position (module docstring)."""
    lengths = pair.contact_line_lengths(cycle.s0)  # (m, K) on the plane of action, m
    k_all = pair.pair_indices()
    cols = np.searchsorted(k_all, cycle.pair_index)
    L = lengths[:, cols]
    loaded = (cycle.pair_loads > 0.0) & (L > 0.0)
    unit = np.where(loaded, cycle.pair_loads / np.where(L > 0.0, L, 1.0), 0.0)
    mean_unit = position_loads(cycle) / np.where(loaded, L, 0.0).sum(axis=1)
    return unit.max(axis=1) / mean_unit


def load_distribution(cycle: LoadedMeshCycle, pair: GearPair,
                      operation: OperatingPoint) -> LoadDistribution:
    """Load distribution quantities of a loaded mesh cycle (module docstring).

    Parameters
    ----------
    cycle : loaded contact over one mesh cycle (:func:`pipeline.contact.analyse_contact`).
    pair : the pair the cycle was solved on (the *actual* pair, after assembly errors).
    operation : the operating point the cycle was solved at (its load is checked against
        ``cycle.load``).

    Returns
    -------
    LoadDistribution
    """
    if len(cycle) < 1 or cycle.point_load.size == 0:
        raise InputError("load distribution: the contact cycle has no loaded points")
    if not np.isin(cycle.pair_index, pair.pair_indices()).all():
        raise InputError("load distribution: the cycle's tooth pairs do not belong to this pair")
    expected = line_of_action_load(pair, operation)
    if not math.isclose(cycle.load, expected, rel_tol=1e-9):
        raise InputError(f"load distribution: the cycle was solved at P = {cycle.load:.6g} N, "
                         f"the operating point gives {expected:.6g} N (torque "
                         f"{operation.torque:.6g} N m on the {operation.driver}); pass the "
                         f"pair and operating point the cycle was solved for")
    z, w = _line_loads(cycle)
    p_t = position_loads(cycle)
    if not np.all(p_t > 0.0):
        raise InputError("load distribution: the contact cycle carries no load at some mesh "
                         "positions")
    b = pair.face_width
    w_m = cycle.load / b
    cycle_mean = w.mean(axis=0)
    k_hb = float(cycle_mean.max() / cycle_mean.mean())
    kha = _transverse_factor(cycle, pair)
    hertz = cycle.point_pressure
    corner = cycle.point_corner > 0
    iz = np.searchsorted(z, np.round(cycle.point_z, 12))
    line_at_point = w[cycle.point_position, iz]
    te = cycle.transmission_error
    rb1 = pair.pinion.base_radius
    return LoadDistribution(
        z=z, line_load=w, mean_line_load=float(w_m), envelope=w.max(axis=0),
        cycle_mean=cycle_mean, k_hbeta=k_hb,
        k_hbeta_position=w.max(axis=1) / (p_t / b),
        pair_load_ratio=float(kha.max()), pair_load_ratio_position=kha, hertz_pressure=hertz,
        hertz_max=_peak(np.where(corner, 0.0, hertz), cycle, pair),
        tip_corner_max=(_peak(np.where(corner, hertz, 0.0), cycle, pair)
                        if np.any(corner & (hertz > 0.0)) else None),
        line_load_max=_peak(line_at_point, cycle, pair),
        pinion_angle=cycle.pinion_angle, transmission_error=te,
        te_peak_to_peak=float(np.ptp(te)), te_peak_to_peak_angle=float(np.ptp(te) / rb1),
        te_orders=mesh_order_amplitudes(te), pair_index=np.array(cycle.pair_index),
        load_share=cycle.pair_loads / p_t[:, None], mesh_stiffness=cycle.mesh_stiffness,
        load=float(cycle.load), face_width=float(b), slices_across_face=int(z.size))
