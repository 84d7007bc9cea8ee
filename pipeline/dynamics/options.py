"""Options of the dynamics stage: the lumped model of a gear pair, the response solver,
the frequency sweep (all SI)."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_choice, check_int_range, check_range

RESPONSE_METHODS = ("harmonic_balance", "floquet", "time")


@dataclass(frozen=True)
class ResponseOptions:
    """Steady-response solver settings.

    Attributes
    ----------
    method : "harmonic_balance", "floquet" (exact propagator, periodic orbit) or "time"
        (time integration from rest).
    n_harmonics : harmonics of the harmonic balance, in [1, 500].
    segments : piecewise-constant segments per period (propagator), or ``None`` for the
        default from the stiffness samples.
    periods : mesh periods integrated by "time", in [1, 100000].
    """

    method: str = "harmonic_balance"
    n_harmonics: int = 40
    segments: int | None = None
    periods: int = 200

    def __post_init__(self) -> None:
        check_choice("response.method", self.method, RESPONSE_METHODS)
        check_int_range("response.n_harmonics", self.n_harmonics, 1, 500)
        if self.segments is not None:
            check_int_range("response.segments", self.segments, 8, 1_000_000)
        check_int_range("response.periods", self.periods, 1, 100_000)


@dataclass(frozen=True)
class SweepOptions:
    """Frequency sweep settings (mesh frequencies in Hz).

    Attributes
    ----------
    f_min, f_max : first and last mesh frequency, Hz, 0 < f_min < f_max <= 1e6.
    points : frequencies of the full sweep, in [2, 100000].
    points_coarse : frequencies of the default (coarse) sweep, in [2, 100000].
    method : "harmonic_balance" or "floquet".
    n_harmonics : harmonics of the harmonic balance, in [1, 500].
    """

    f_min: float = 10.0
    f_max: float = 5000.0
    points: int = 500
    points_coarse: int = 100
    method: str = "harmonic_balance"
    n_harmonics: int = 20

    def __post_init__(self) -> None:
        check_range("sweep.f_min", self.f_min, 0.0, 1e6, lo_open=True, unit="Hz")
        check_range("sweep.f_max", self.f_max, self.f_min, 1e6, lo_open=True, unit="Hz")
        check_int_range("sweep.points", self.points, 2, 100_000)
        check_int_range("sweep.points_coarse", self.points_coarse, 2, 100_000)
        check_choice("sweep.method", self.method, ("harmonic_balance", "floquet"))
        check_int_range("sweep.n_harmonics", self.n_harmonics, 1, 500)

    def frequencies(self, full: bool) -> np.ndarray:
        """Mesh frequencies of the sweep, shape (points,), Hz."""
        return np.linspace(self.f_min, self.f_max, self.points if full else self.points_coarse)


@dataclass(frozen=True)
class PairDynamicsOptions:
    """The lumped model of one gear pair (everything not derived from the geometry).

    Attributes
    ----------
    dofs : "lateral_torsional" (x, y, theta of each gear: 6 DOF) or "torsional" (2 DOF).
    bearing_stiffness : N/m in x and y for both gears, in [0, 1e14].
    bearing_damping : N s/m in x and y, in [0, 1e9].
    damping_ratio : mesh damping ratio zeta, in [0, 1].
    excitation : where k(t) and the friction terms come from: "analytical" (the
        potential-energy stiffness of the pair at the operating point).
    mesh_stiffness : an explicit k(tau) over one mesh period (N/m) replacing the derived
        one, or ``None``.
    friction : include the friction stiffness and torques of the stiffness stage.
    """

    dofs: str = "lateral_torsional"
    bearing_stiffness: float = 1.0e8
    bearing_damping: float = 0.0
    damping_ratio: float = 0.05
    excitation: str = "analytical"
    mesh_stiffness: PeriodicSignal | None = None
    friction: bool = True
    response: ResponseOptions = field(default_factory=ResponseOptions)
    sweep: SweepOptions = field(default_factory=SweepOptions)

    def __post_init__(self) -> None:
        check_choice("dynamics.dofs", self.dofs, ("lateral_torsional", "torsional"))
        check_range("dynamics.bearing_stiffness", self.bearing_stiffness, 0.0, 1e14, unit="N/m")
        check_range("dynamics.bearing_damping", self.bearing_damping, 0.0, 1e9, unit="N s/m")
        check_range("dynamics.damping_ratio", self.damping_ratio, 0.0, 1.0)
        check_choice("dynamics.excitation", self.excitation, ("analytical",))
        if self.mesh_stiffness is not None and np.any(self.mesh_stiffness.values <= 0):
            raise InputError("dynamics.mesh_stiffness must be > 0 N/m everywhere")
