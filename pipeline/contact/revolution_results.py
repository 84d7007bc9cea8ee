"""The full-revolution loaded contact as a result: transmission error, its order spectrum,
the worst tooth pair.

Orders are per revolution of the pinion (as in the dynamics' spectra,
:mod:`pipeline.dynamics.operating`): the mesh orders are ``n z1``; a once-per-revolution
modulation of the pinion puts sidebands at ``n z1 +- 1``, of the gear at
``n z1 +- z1 / z2``. The spectrum is the one-sided amplitude of the discrete Fourier
transform of the transmission error over the span (``R = N / z1`` pinion revolutions,
``N m`` equally spaced samples): ``A(o) = 2 |X_q| / (N m)`` at order ``o = q / R`` (the
Nyquist bin, without a mirror, ``|X_q| / (N m)``); order 0 holds the signed mean, as in
the dynamics' DTE spectrum (:meth:`pipeline.dynamics.results.Response.dte_spectrum`). A
sinusoid of order ``o`` whose period divides the span comes out at its exact amplitude: the
hunting cycle resolves both gears' orders, one revolution of a gear that gear's (the other
gear's orders ``k z1 / z2`` fall between the bins unless ``z2`` divides ``k z1``).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, fields
from typing import Any

import numpy as np

from pipeline.contact.cycle_io import cycle_arrays, cycle_from_arrays
from pipeline.contact.results import LoadedMeshCycle


@dataclass(frozen=True)
class Spectrum:
    """One-sided amplitude spectrum of the transmission error.

    Attributes
    ----------
    order : (q,) orders per pinion revolution, from 0 (the mean's bin) in steps of 1 / R.
    amplitude : (q,) amplitudes, m (order 0: the signed mean).
    mesh_order : z1, the first mesh order.
    """

    order: np.ndarray
    amplitude: np.ndarray
    mesh_order: int

    def at(self, order: float) -> float:
        """Amplitude at ``order`` (the nearest bin), m."""
        return float(self.amplitude[int(np.argmin(np.abs(self.order - order)))])

    def sidebands(self) -> np.ndarray:
        """Mask of the sideband bins: orders in ``[z1 / 2, highest)`` that are not a mesh
        order (the modulation of the mesh harmonics; below ``z1 / 2`` lie the rotation
        orders of the errors themselves)."""
        mesh = np.isclose(np.mod(self.order + 0.5 * self.mesh_order, self.mesh_order),
                          0.5 * self.mesh_order, atol=1e-9)
        return (self.order >= 0.5 * self.mesh_order) & ~mesh

    def largest_sideband(self) -> tuple[float, float]:
        """(order, amplitude in m) of the largest sideband; (nan, 0) when there is none."""
        side = self.sidebands()
        if not side.any():
            return float("nan"), 0.0
        i = np.flatnonzero(side)[int(np.argmax(self.amplitude[side]))]
        return float(self.order[i]), float(self.amplitude[i])


@dataclass(frozen=True)
class LoadedRevolution:
    """Loaded contact at ``N m`` positions through the span (:mod:`pipeline.contact.revolution`).

    Attributes
    ----------
    contact : every position as one :class:`LoadedMeshCycle` (``N m`` positions, ``s0`` the
        unrolled roll coordinate in m, ``pinion_angle`` the unrolled pinion rotation in
        rad, ``point_separation`` including the errors' gaps; pair columns per index k).
    mesh_cycles : N.
    positions_per_cycle : m.
    teeth : (2,) int, z1 and z2.
    span : "hunting", "pinion" or "gear".
    runout_gap : (N m,) the gap both eccentricities open at each position, m.
    centre_distance_change : (N m,) the change of the centre distance both eccentricities
        give at each position, m (the position is solved on the pair at that distance).
    """

    contact: LoadedMeshCycle
    mesh_cycles: int
    positions_per_cycle: int
    teeth: np.ndarray
    span: str
    runout_gap: np.ndarray
    centre_distance_change: np.ndarray

    def __len__(self) -> int:
        return len(self.contact)

    @property
    def transmission_error(self) -> np.ndarray:
        """(N m,) loaded static transmission error along the line of action, m."""
        return self.contact.transmission_error

    @property
    def pinion_revolutions(self) -> float:
        """R = N / z1, pinion revolutions in the span."""
        return self.mesh_cycles / int(self.teeth[0])

    @property
    def cycle_index(self) -> np.ndarray:
        """(N m,) mesh cycle c of each position."""
        return np.repeat(np.arange(self.mesh_cycles), self.positions_per_cycle)

    def spectrum(self) -> Spectrum:
        """Amplitude spectrum of the transmission error against pinion orders (module
        docstring)."""
        te = self.transmission_error
        x = np.fft.rfft(te - te.mean()) / te.size
        amp = 2.0 * np.abs(x)
        amp[0] = te.mean()
        if te.size % 2 == 0:
            amp[-1] *= 0.5  # the Nyquist bin has no mirror
        order = np.arange(amp.size) / self.pinion_revolutions
        return Spectrum(order, amp, int(self.teeth[0]))

    def point_teeth(self) -> tuple[np.ndarray, np.ndarray]:
        """Pinion and gear tooth of every candidate point (flat, like ``contact.point_*``)."""
        c = self.cycle_index[self.contact.point_position]
        n = c - self.contact.point_pair
        return np.mod(n, int(self.teeth[0])), np.mod(n, int(self.teeth[1]))

    @property
    def base_pitch(self) -> float:
        """p_bt, m: the span's positions are ``p_bt / m`` apart."""
        s0 = self.contact.s0
        return float(s0[1] - s0[0]) * self.positions_per_cycle if s0.size > 1 else math.nan

    def pair_roll(self) -> np.ndarray:
        """Roll coordinate at z = 0 of every candidate point's tooth pair in its own mesh
        cycle, ``s0_j + k p_bt``, m (flat, like ``contact.point_*``)."""
        c = self.cycle_index[self.contact.point_position]
        return (self.contact.s0[self.contact.point_position]
                + (self.contact.point_pair - c) * self.base_pitch)

    def worst_pair(self) -> dict[str, Any]:
        """The tooth pair with the largest Hertz pressure over the span: its pinion and gear
        tooth, that pressure (Pa), its largest normal load on one point (N) and the mesh
        position (index) where it occurs."""
        c = self.contact
        i = int(np.argmax(c.point_pressure))
        t1, t2 = self.point_teeth()
        return {"pinion_tooth": int(t1[i]), "gear_tooth": int(t2[i]),
                "pressure_Pa": float(c.point_pressure[i]),
                "normal_load_N": float(c.point_normal_load[i]),
                "position": int(c.point_position[i])}

    def pair_points(self, pinion_tooth: int, gear_tooth: int) -> np.ndarray:
        """Mask of the candidate points of the tooth pair of the given teeth."""
        t1, t2 = self.point_teeth()
        return (t1 == pinion_tooth) & (t2 == gear_tooth)

    def pair_cycle(self, pinion_tooth: int, gear_tooth: int) -> LoadedMeshCycle:
        """``contact`` with only the candidate points of the tooth pair of the given teeth:
        its passage through the mesh, for a load map of that pair
        (:func:`pipeline.contact.loadmap.flank_load_map`)."""
        keep = self.pair_points(pinion_tooth, gear_tooth)
        c = self.contact
        return dataclasses.replace(c, **{f.name: getattr(c, f.name)[keep] for f in fields(c)
                                         if f.name.startswith("point_")})

    def summary(self) -> dict[str, Any]:
        """TE peak to peak, mesh-order and once-per-revolution amplitudes, the largest
        sideband and the worst tooth pair (SI; keys carry units)."""
        te, sp = self.transmission_error, self.spectrum()
        order, amp = sp.largest_sideband()
        z1 = int(self.teeth[0])
        return {
            "span": self.span,
            "mesh_cycles": self.mesh_cycles,
            "positions": len(self),
            "transmission_error_peak_to_peak_m": float(te.max() - te.min()),
            "first_order_amplitude_m": sp.at(1.0),
            "mesh_order_amplitude_m": sp.at(float(z1)),
            "largest_sideband_amplitude_m": amp,
            "largest_sideband_order": order,
            "worst_pair": self.worst_pair(),
            "max_residual_m": float(self.contact.residual.max()),
        }

    def columns(self) -> dict[str, np.ndarray]:
        """Per-position columns over the span (shape (N m,) each), named with units."""
        c = self.contact
        return {
            "pinion_angle [rad]": c.pinion_angle,
            "mesh_cycle [-]": self.cycle_index,
            "roll_coordinate_s0 [m]": c.s0,
            "transmission_error [m]": c.transmission_error,
            "runout_gap [m]": self.runout_gap,
            "centre_distance_change [m]": self.centre_distance_change,
            "mesh_stiffness_tangent [N/m]": c.mesh_stiffness,
            "max_unit_load [N/m]": c.max_unit_load,
            "residual [m]": c.residual,
        }

    def spectrum_columns(self) -> dict[str, np.ndarray]:
        """The spectrum as CSV columns: order per pinion revolution (-) and amplitude (m;
        order 0: the signed mean)."""
        sp = self.spectrum()
        return {"pinion_order [-]": sp.order, "transmission_error_amplitude [m]": sp.amplitude}


def revolution_arrays(rev: LoadedRevolution) -> dict[str, np.ndarray]:
    """Every field of ``rev`` as arrays (the contact's prefixed ``contact.``), for the cache."""
    out = {f"contact.{k}": v for k, v in cycle_arrays(rev.contact).items()}
    for f in fields(rev):
        if f.name != "contact":
            out[f.name] = np.asarray(getattr(rev, f.name))
    return out


def revolution_from_arrays(z: dict[str, np.ndarray]) -> LoadedRevolution:
    """The result of :func:`revolution_arrays` (KeyError when a field is missing)."""
    contact = cycle_from_arrays({k[8:]: v for k, v in z.items() if k.startswith("contact.")})
    return LoadedRevolution(contact=contact, mesh_cycles=int(z["mesh_cycles"]),
                            positions_per_cycle=int(z["positions_per_cycle"]),
                            teeth=np.asarray(z["teeth"]), span=str(z["span"]),
                            runout_gap=np.asarray(z["runout_gap"]),
                            centre_distance_change=np.asarray(z["centre_distance_change"]))
