"""Options of the dynamics stage: the lumped model of a gear pair or a planetary set, the
response solver, the frequency sweep (all SI)."""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

import numpy as np

from pipeline.dynamics.operating import MESH_ORDERS, elastic_modes
from pipeline.signals import PeriodicSignal
from pipeline.validation import (
    InputError,
    PhysicsWarning,
    check_choice,
    check_int_range,
    check_positive,
    check_range,
)

RESPONSE_METHODS = ("harmonic_balance", "floquet", "time")
EXCITATIONS = ("analytical", "contact")
"""Sources of the mesh excitation: the potential-energy stiffness stage, or the loaded
tooth contact (:func:`pipeline.dynamics.contact_excitation.excitation_from_contact`)."""
SUN_LOAD_SIDES = ("both", "L", "R")


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


SWEEP_LOW_FRACTION = 0.25
"""Default lower end of a sweep: f_min = SWEEP_LOW_FRACTION f_m."""
SWEEP_HARMONICS = 4
"""Default upper end of a sweep reaches at least SWEEP_HARMONICS f_m."""
SWEEP_MODE_MARGIN = 1.25
"""... and SWEEP_MODE_MARGIN times the natural frequency it must cover (the resonance
peak and its fall beyond, for mesh damping ratios up to about 0.1)."""


def default_sweep_range(mesh_frequency: float,
                        natural_frequencies: np.ndarray = ()) -> tuple[float, float]:
    """The default sweep range (Hz) at the operating mesh frequency f_m (Hz).

    ``f_min = f_m / 4`` and ``f_max = max(4 f_m, 1.25 f_n*)``, f_n* the highest elastic
    natural frequency up to 10 f_m (:data:`~pipeline.dynamics.operating.MESH_ORDERS`: the
    modes mesh harmonics 1-10 excite at the operating speed), or the lowest elastic one
    when none lies there; ``natural_frequencies`` in Hz, rigid-body modes skipped
    (:func:`~pipeline.dynamics.operating.elastic_modes`). The sweep then holds the
    operating point, its harmonics 2-4 f_m and the first-order resonance of every mode
    that matters at the operating speed.
    """
    check_positive("operating mesh frequency", mesh_frequency, "Hz")
    fn = np.asarray(natural_frequencies, dtype=float)
    elastic = fn[elastic_modes(fn)]
    top = SWEEP_HARMONICS * mesh_frequency
    if elastic.size:
        reached = elastic[elastic <= MESH_ORDERS * mesh_frequency]
        f_star = float(reached.max()) if reached.size else float(elastic.min())
        top = max(top, SWEEP_MODE_MARGIN * f_star)
    return SWEEP_LOW_FRACTION * mesh_frequency, top


@dataclass(frozen=True)
class SweepOptions:
    """Frequency sweep settings (mesh frequencies in Hz).

    Attributes
    ----------
    f_min, f_max : first and last mesh frequency, Hz, 0 < f_min < f_max <= 1e6, or
        ``None`` (the default) for the range derived from the operating point
        (:func:`default_sweep_range`): f_min = f_m / 4 and f_max = max(4 f_m, 1.25 f_n*),
        f_m the operating mesh frequency, f_n* the highest elastic natural frequency of
        the model up to 10 f_m (the lowest one when none lies there). The default sweep
        holds the operating point, its harmonics 2-4 f_m and the first-order resonance of
        every mode that mesh harmonics 1-10 excite at the operating speed. A given end is
        used as given (a range that leaves out f_m is warned about in one line).
    points : frequencies of the full sweep, in [2, 100000].
    points_coarse : frequencies of the default (coarse) sweep, in [2, 100000].
    method : "harmonic_balance" or "floquet".
    n_harmonics : harmonics of the harmonic balance, in [1, 500].
    """

    f_min: float | None = None
    f_max: float | None = None
    points: int = 500
    points_coarse: int = 100
    method: str = "harmonic_balance"
    n_harmonics: int = 20

    def __post_init__(self) -> None:
        if self.f_min is not None:
            check_range("sweep.f_min", self.f_min, 0.0, 1e6, lo_open=True, unit="Hz")
        if self.f_max is not None:
            check_range("sweep.f_max", self.f_max, self.f_min or 0.0, 1e6, lo_open=True,
                        unit="Hz")
        check_int_range("sweep.points", self.points, 2, 100_000)
        check_int_range("sweep.points_coarse", self.points_coarse, 2, 100_000)
        check_choice("sweep.method", self.method, ("harmonic_balance", "floquet"))
        check_int_range("sweep.n_harmonics", self.n_harmonics, 1, 500)

    @property
    def given(self) -> bool:
        """True when the file gives either end of the range."""
        return self.f_min is not None or self.f_max is not None

    def bounds(self, mesh_frequency: float,
               natural_frequencies: np.ndarray = ()) -> tuple[float, float]:
        """(f_min, f_max) in Hz: the given ends, the others from :func:`default_sweep_range`
        at the operating mesh frequency ``mesh_frequency`` (Hz) and the model's
        ``natural_frequencies`` (Hz). Warns (:class:`PhysicsWarning`) when the range
        leaves out the operating mesh frequency."""
        lo, hi = default_sweep_range(mesh_frequency, natural_frequencies)
        lo = lo if self.f_min is None else self.f_min
        hi = hi if self.f_max is None else self.f_max
        if lo >= hi:
            name, value = (("f_min_Hz", self.f_min) if self.f_min is not None
                           else ("f_max_Hz", self.f_max))
            raise InputError(f"dynamics.sweep.{name} = {value:g} Hz leaves an empty range "
                             f"with the default other end ({lo:.6g}-{hi:.6g} Hz at the "
                             f"operating mesh frequency {mesh_frequency:.6g} Hz); give both "
                             "f_min_Hz and f_max_Hz")
        if not lo <= mesh_frequency <= hi:
            warnings.warn(f"dynamics.sweep: the range {lo:.6g}-{hi:.6g} Hz leaves out the "
                          f"operating mesh frequency {mesh_frequency:.6g} Hz (omit f_min_Hz "
                          "and f_max_Hz for a range around it)", PhysicsWarning, stacklevel=2)
        return lo, hi

    def frequencies(self, full: bool, mesh_frequency: float | None = None,
                    natural_frequencies: np.ndarray = ()) -> np.ndarray:
        """Mesh frequencies of the sweep, shape (points,), Hz, evenly spaced over
        :meth:`bounds` (``mesh_frequency`` is needed unless both ends are given)."""
        if mesh_frequency is None:
            if self.f_min is None or self.f_max is None:
                raise ValueError("a sweep without a given range needs the operating mesh "
                                 "frequency")
            lo, hi = self.f_min, self.f_max
        else:
            lo, hi = self.bounds(mesh_frequency, natural_frequencies)
        return np.linspace(lo, hi, self.points if full else self.points_coarse)


@dataclass(frozen=True)
class PairDynamicsOptions:
    """The lumped model of one gear pair (everything not derived from the geometry).

    Attributes
    ----------
    dofs : "lateral_torsional" (x, y, theta of each gear: 6 DOF) or "torsional" (2 DOF).
    bearing_stiffness : N/m in x and y for both gears, in [0, 1e14].
    bearing_damping : N s/m in x and y, in [0, 1e9].
    damping_ratio : mesh damping ratio zeta, in [0, 1].
    excitation : where k(t), e(t) and the friction terms come from: "analytical" (the
        potential-energy stiffness of the pair at the operating point; e = 0) or
        "contact" (the loaded tooth contact of the pair at the operating torque: tangent
        k(t), static transmission error, friction of the loaded points).
    mesh_stiffness : an explicit k(tau) over one mesh period (N/m) replacing the derived
        one, or ``None``.
    friction : include the friction stiffness and torques of the stiffness stage.
    drive_inertia : kg m^2 of the motor at the pinion shaft's torque point, in (0, 1e6],
        or None (the input torque acts on the pinion); needs the pinion on a shaft.
    load_inertia : kg m^2 of the driven machine at the gear shaft's torque point, in
        (0, 1e6], or None; needs the gear on a shaft.
    """

    dofs: str = "lateral_torsional"
    bearing_stiffness: float = 1.0e8
    bearing_damping: float = 0.0
    damping_ratio: float = 0.05
    excitation: str = "analytical"
    mesh_stiffness: PeriodicSignal | None = None
    friction: bool = True
    drive_inertia: float | None = None
    load_inertia: float | None = None
    response: ResponseOptions = field(default_factory=ResponseOptions)
    sweep: SweepOptions = field(default_factory=SweepOptions)

    def __post_init__(self) -> None:
        check_choice("dynamics.dofs", self.dofs, ("lateral_torsional", "torsional"))
        for name in ("drive_inertia", "load_inertia"):
            if getattr(self, name) is not None:
                check_range(f"dynamics.{name}", getattr(self, name), 0.0, 1e6, lo_open=True,
                            unit="kg m^2")
        check_range("dynamics.bearing_stiffness", self.bearing_stiffness, 0.0, 1e14, unit="N/m")
        check_range("dynamics.bearing_damping", self.bearing_damping, 0.0, 1e9, unit="N s/m")
        check_range("dynamics.damping_ratio", self.damping_ratio, 0.0, 1.0)
        check_choice("dynamics.excitation", self.excitation, EXCITATIONS)
        if self.mesh_stiffness is not None and np.any(self.mesh_stiffness.values <= 0):
            raise InputError("dynamics.mesh_stiffness must be > 0 N/m everywhere")


@dataclass(frozen=True)
class PlanetaryDynamicsOptions:
    """The lumped model of a planetary set (everything not derived from the gears).

    Supports act on the rigid gear bodies at their bores (the ring: outside its rim), in
    the carrier frame; see :mod:`pipeline.dynamics.contact_excitation` for what the mesh
    stiffness already contains.

    Attributes
    ----------
    sun_bearing_stiffness, ring_bearing_stiffness, carrier_bearing_stiffness : N/m, x and
        y of each central member, in [0, 1e14].
    planet_bearing_stiffness : N/m, radial and tangential, planet to carrier, in [0, 1e14].
    sun_torsional_stiffness, carrier_torsional_stiffness : N m/rad, rotation to ground,
        in [0, 1e14] (0: free, the drive path).
    ring_torsional_stiffness : N m/rad, in (0, 1e14], or ``None``: 1e9 N/m at the ring's
        base circle, ``1e9 r_b,ring^2`` (Lin and Parker 1999, Table 1).
    sun_axial_stiffness, ring_axial_stiffness, carrier_axial_stiffness,
    planet_axial_stiffness : N/m (herringbone sets), in [0, 1e14], or ``None``: the
        member's bearing stiffness.
    groove_torsional_stiffness : N m/rad, torsion of a herringbone sun's relief groove
        between the halves (Xu et al. 2020, K_j / l), in (0, 1e14], or ``None``: halves tied.
    groove_lateral_stiffness : N/m, x, y, z of the groove joint (with
        ``groove_torsional_stiffness``), in (0, 1e14], or ``None``: tied.
    sun_load_side : "both" halves of a herringbone sun take the sun torque, or only the
        "L" or "R" half (the other half is loaded through the groove).
    damping_ratio : mesh damping ratio zeta, in [0, 1].
    modal_damping_ratio : constant modal damping (Xu et al. 2020), in [0, 1].
    drive_inertia : kg m^2 of the motor at the sun shaft's torque point, in (0, 1e6], or
        None (the torque acts on the sun); needs the sun on a shaft (planar sets).
    excitation : "analytical" or "contact" (as for a pair), for every sun-planet and
        ring-planet mesh.
    sun_mesh_stiffness, ring_mesh_stiffness : an explicit k(tau) (N/m, transverse line of
        action, one mesh; herringbone: one half; tau = 0 with the leading tooth pair at the
        start of contact, as the derived ones) replacing the derived one, or ``None``.
    """

    sun_bearing_stiffness: float = 1.0e8
    ring_bearing_stiffness: float = 1.0e8
    carrier_bearing_stiffness: float = 1.0e8
    planet_bearing_stiffness: float = 1.0e8
    sun_torsional_stiffness: float = 0.0
    ring_torsional_stiffness: float | None = None
    carrier_torsional_stiffness: float = 0.0
    sun_axial_stiffness: float | None = None
    ring_axial_stiffness: float | None = None
    carrier_axial_stiffness: float | None = None
    planet_axial_stiffness: float | None = None
    groove_torsional_stiffness: float | None = None
    groove_lateral_stiffness: float | None = None
    sun_load_side: str = "both"
    damping_ratio: float = 0.05
    modal_damping_ratio: float = 0.0
    drive_inertia: float | None = None
    excitation: str = "analytical"
    sun_mesh_stiffness: PeriodicSignal | None = None
    ring_mesh_stiffness: PeriodicSignal | None = None
    response: ResponseOptions = field(default_factory=ResponseOptions)
    sweep: SweepOptions = field(default_factory=SweepOptions)

    def __post_init__(self) -> None:
        for name in ("sun_bearing_stiffness", "ring_bearing_stiffness",
                     "carrier_bearing_stiffness", "planet_bearing_stiffness",
                     "sun_torsional_stiffness", "carrier_torsional_stiffness",
                     "sun_axial_stiffness", "ring_axial_stiffness", "carrier_axial_stiffness",
                     "planet_axial_stiffness"):
            value = getattr(self, name)
            if value is not None:
                unit = "N m/rad" if "torsional" in name else "N/m"
                check_range(f"dynamics.{name}", value, 0.0, 1e14, unit=unit)
        for name, unit in (("ring_torsional_stiffness", "N m/rad"),
                           ("groove_torsional_stiffness", "N m/rad"),
                           ("groove_lateral_stiffness", "N/m")):
            value = getattr(self, name)
            if value is not None:
                check_range(f"dynamics.{name}", value, 0.0, 1e14, lo_open=True, unit=unit)
        if self.groove_lateral_stiffness is not None and self.groove_torsional_stiffness is None:
            raise InputError("dynamics.groove_lateral_stiffness needs "
                             "dynamics.groove_torsional_stiffness (without it the halves of "
                             "the sun are tied)")
        check_choice("dynamics.sun_load_side", self.sun_load_side, SUN_LOAD_SIDES)
        check_range("dynamics.damping_ratio", self.damping_ratio, 0.0, 1.0)
        check_range("dynamics.modal_damping_ratio", self.modal_damping_ratio, 0.0, 1.0)
        if self.drive_inertia is not None:
            check_range("dynamics.drive_inertia", self.drive_inertia, 0.0, 1e6, lo_open=True,
                        unit="kg m^2")
        check_choice("dynamics.excitation", self.excitation, EXCITATIONS)
        for name in ("sun_mesh_stiffness", "ring_mesh_stiffness"):
            sig = getattr(self, name)
            if sig is not None and np.any(sig.values <= 0):
                raise InputError(f"dynamics.{name} must be > 0 N/m everywhere")

    @property
    def herringbone_keys(self) -> tuple[str, ...]:
        """The options that only a herringbone set uses, as given (not ``None``/default)."""
        given = [n for n in ("sun_axial_stiffness", "ring_axial_stiffness",
                             "carrier_axial_stiffness", "planet_axial_stiffness",
                             "groove_torsional_stiffness", "groove_lateral_stiffness")
                 if getattr(self, n) is not None]
        if self.sun_load_side != "both":
            given.append("sun_load_side")
        return tuple(given)
