"""The operating mesh frequency of a gearbox and the shaft speeds that go with it.

All speeds of a gear train are fixed multiples of its mesh frequency, so one number per
member, the mesh events per revolution of that member (its *mesh order*), turns any
mesh frequency f (Hz) of a sweep into the member's speed, n = 60 f / order (rpm):

* a pair, pinion driving at n_1: f_m = z_1 n_1 / 60 = z_2 n_2 / 60; the orders are the
  tooth counts z_1 and z_2;
* a planetary set with the ring fixed and the sun driving (the project's planetary
  models): the teeth mesh relative to the carrier, f_m = z_s |n_s - n_c| / 60 with
  n_c = n_s z_s / (z_s + z_r) (Xu et al. 2020, eq. 7), so f_m = z_r n_c / 60
  = z_s z_r n_s / (60 (z_s + z_r)); the orders are z_s z_r / (z_s + z_r) for the sun and
  z_r for the carrier;
* a ``[lumped_model]`` without gears: its mesh frequency, and the carrier's order
  2 pi f_m / Omega_c when the model's carrier turns.

Speeds are in rad/s here (SI); figures and reports give them in rpm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.validation import check_positive

MESH_ORDERS = 10
"""Mesh harmonics whose resonances at the operating speed matter: a mode at f_n resonates
with harmonic h when f_n = h f_m; orders 1-10 are the ones the reports resolve (the
transmission error's mesh orders, the spectra)."""

RIGID_TOL = 1e-6
"""A mode is a rigid-body mode when its frequency is at most ``RIGID_TOL`` times the
highest natural frequency of the model (the eigen-solvers return them as 0 or as
round-off of the largest eigenvalue)."""


@dataclass(frozen=True)
class OperatingFrequency:
    """The operating mesh frequency and the mesh orders of the members that turn.

    Attributes
    ----------
    mesh_frequency : Hz, the mesh frequency at the operating point (> 0).
    orders : ((member, mesh events per revolution of the member), ...); the first member
        is the one the file gives the speed of (the driver). Empty when the model has no
        gear data (a lumped model with a carrier at rest).
    """

    mesh_frequency: float
    orders: tuple[tuple[str, float], ...] = ()

    def __post_init__(self) -> None:
        check_positive("operating mesh frequency", self.mesh_frequency, "Hz")
        for member, order in self.orders:
            check_positive(f"mesh order of the {member}", order, "-")

    @property
    def members(self) -> tuple[str, ...]:
        """The members with a speed, driver first."""
        return tuple(m for m, _ in self.orders)

    def _frequency_and_order(self, member: str, mesh_frequency) -> tuple:
        orders = dict(self.orders)
        if member not in orders:
            raise KeyError(f"no speed for {member!r}; members: {', '.join(orders) or 'none'}")
        return (self.mesh_frequency if mesh_frequency is None else mesh_frequency), \
            orders[member]

    def speed(self, member: str, mesh_frequency=None):
        """Speed of ``member`` in rad/s, 2 pi f / order, at ``mesh_frequency`` (Hz, a number
        or an array; default: the operating one)."""
        f, order = self._frequency_and_order(member, mesh_frequency)
        return 2.0 * math.pi * f / order

    def rpm(self, member: str, mesh_frequency=None):
        """Speed of ``member`` in rpm, 60 f / order (the unit of files and reports)."""
        f, order = self._frequency_and_order(member, mesh_frequency)
        return 60.0 * f / order

    def summary(self) -> dict:
        """Mesh frequency (Hz), each member's mesh order and speed (rpm)."""
        return {"mesh_frequency_Hz": self.mesh_frequency,
                "mesh_orders": dict(self.orders),
                "speeds_rpm": {m: self.rpm(m) for m in self.members}}


def pair_operating_frequency(pinion_teeth: int, gear_teeth: int,
                             pinion_speed: float) -> OperatingFrequency:
    """A pair with the pinion driving at ``pinion_speed`` rad/s: f_m = z_1 omega_1 / 2 pi."""
    check_positive("pinion speed", pinion_speed, "rad/s")
    return OperatingFrequency(pinion_teeth * pinion_speed / (2.0 * math.pi),
                              (("pinion", float(pinion_teeth)), ("gear", float(gear_teeth))))


def planetary_operating_frequency(sun_teeth: int, ring_teeth: int,
                                  sun_speed: float) -> OperatingFrequency:
    """A planetary set, ring fixed, sun driving at ``sun_speed`` rad/s:
    f_m = z_s |omega_s - omega_c| / 2 pi with omega_c = omega_s z_s / (z_s + z_r)."""
    check_positive("sun speed", sun_speed, "rad/s")
    zs, zr = sun_teeth, ring_teeth
    omega_c = sun_speed * zs / (zs + zr)
    f_m = zs * abs(sun_speed - omega_c) / (2.0 * math.pi)
    return OperatingFrequency(f_m, (("sun", zs * zr / (zs + zr)), ("carrier", float(zr))))


def system_operating_frequency(system) -> OperatingFrequency:
    """A model known only by its system (a ``[lumped_model]``): f_m = 1 / T, and the
    carrier's mesh order 2 pi f_m / Omega_c when the carrier turns."""
    f_m = 1.0 / system.period
    omega_c = abs(getattr(system, "carrier_speed", 0.0))
    orders = (("carrier", 2.0 * math.pi * f_m / omega_c),) if omega_c > 0 else ()
    return OperatingFrequency(f_m, orders)


def elastic_modes(frequencies: np.ndarray) -> np.ndarray:
    """Indices of the elastic modes (frequency above :data:`RIGID_TOL` times the highest
    one), shape (k,), in the order given."""
    f = np.asarray(frequencies, dtype=float)
    if f.size == 0:
        return np.zeros(0, dtype=int)
    return np.flatnonzero(f > RIGID_TOL * f.max())


def modes_that_matter(frequencies: np.ndarray, mesh_frequency: float,
                      sweep_top: float) -> tuple[np.ndarray, float]:
    """The elastic modes a report lists: every one up to the cut
    ``max(MESH_ORDERS f_m, sweep_top)`` (the modes that mesh harmonics 1-10 excite at the
    operating speed, and every mode the sweep plot marks).

    Parameters
    ----------
    frequencies : shape (m,), natural frequencies, Hz (rigid-body modes included).
    mesh_frequency : operating mesh frequency f_m, Hz.
    sweep_top : upper end of the sweep, Hz.

    Returns
    -------
    (indices into ``frequencies`` of the listed modes, ascending frequency; the cut, Hz).
    """
    check_positive("operating mesh frequency", mesh_frequency, "Hz")
    cut = max(MESH_ORDERS * mesh_frequency, sweep_top)
    f = np.asarray(frequencies, dtype=float)
    idx = elastic_modes(f)
    idx = idx[f[idx] <= cut]
    return idx[np.argsort(f[idx], kind="stable")], cut
