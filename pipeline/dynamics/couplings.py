"""Couplings between bodies: springs, bearings, shafts, gear meshes, matrix couplings, ties.

Every coupling is written through *linear measures*: sparse maps
``{(body, dof): coefficient}`` that turn the generalized coordinates q into one
scalar deflection ``delta = v . q`` (m or rad). A spring of stiffness k on that
measure stores the energy ``k delta^2 / 2`` and contributes ``k v v^T`` to the
stiffness matrix, so a new gearbox layout is a list of bodies and couplings,
never new equations.

Gear mesh sign convention (owned here): ``delta`` is the *compression* of the
mesh along the line of action, positive when the teeth are loaded; the mesh
force on the coordinates is ``-F v`` with ``F = k(t) (delta - e(t)) + c (d/dt)(delta - e)``.
A transmission error ``e`` (m) is a geometric separation of the flanks, so a
positive ``e`` unloads the mesh.

Friction (Jin et al. 2018, eqs. 15-17): the friction force ``f = K_f(t) delta`` and the
friction torques ``T_i = K_Tfi(t) delta`` are written as :class:`FrictionLoad`
entries, each a signed periodic coefficient (N/m or N m/m) and the generalized
force pattern it acts along (a measure, e.g. the in-plane direction normal to the
line of action on both gears, or one gear's rotation). The friction force of the
mesh damping force is neglected, as in Jin et al. (2018) (K_f = lambda mu K).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field

import numpy as np

from pipeline.dynamics.bodies import Coordinate
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_range


def _freeze_measure(measure: Mapping[Coordinate, float], what: str) -> tuple:
    items = tuple(sorted((tuple(k), float(v)) for k, v in measure.items() if v != 0.0))
    if not items:
        raise InputError(
            f"{what}: the measure is empty (no coordinate with a non-zero coefficient)"
        )
    for (body, dof), v in items:
        if not math.isfinite(v):
            raise InputError(f"{what}: coefficient on {body}.{dof} is not finite")
    return items


@dataclass(frozen=True)
class Spring:
    """A linear spring-damper on one measure (to ground if the measure names one body).

    Attributes
    ----------
    name : label.
    measure : ``{(body, dof): coefficient}``; deflection ``delta = sum c q``.
    stiffness : N/m (or N m/rad for a pure rotation measure), >= 0.
    damping : N s/m (or N m s/rad), >= 0.
    """

    name: str
    measure: Mapping[Coordinate, float]
    stiffness: float
    damping: float = 0.0

    def __post_init__(self) -> None:
        object.__setattr__(self, "measure", _freeze_measure(self.measure, self.name))
        check_range(f"{self.name}.stiffness", self.stiffness, 0.0, 1e15, unit="N/m")
        check_range(f"{self.name}.damping", self.damping, 0.0, 1e12, unit="N s/m")


@dataclass(frozen=True)
class Bearing:
    """Support of one body to ground (or to the carrier frame), per DOF of the body.

    Attributes
    ----------
    body : body name.
    stiffness : ``{dof: k}`` in N/m for x, y, z and N m/rad for theta.
    damping : ``{dof: c}`` in N s/m or N m s/rad.
    """

    body: str
    stiffness: Mapping[str, float]
    damping: Mapping[str, float] = field(default_factory=dict)

    def springs(self) -> list[Spring]:
        dofs = sorted(set(self.stiffness) | set(self.damping))
        return [
            Spring(
                f"{self.body}.bearing.{d}",
                {(self.body, d): 1.0},
                float(self.stiffness.get(d, 0.0)),
                float(self.damping.get(d, 0.0)),
            )
            for d in dofs
        ]


@dataclass(frozen=True)
class TorsionalShaft:
    """Torsional shaft between the rotations of two bodies.

    Attributes
    ----------
    body1, body2 : body names (both with ``theta``).
    stiffness : N m/rad.
    damping : N m s/rad.
    """

    body1: str
    body2: str
    stiffness: float
    damping: float = 0.0

    def springs(self) -> list[Spring]:
        return [
            Spring(
                f"{self.body1}-{self.body2}.shaft",
                {(self.body1, "theta"): 1.0, (self.body2, "theta"): -1.0},
                self.stiffness,
                self.damping,
            )
        ]


@dataclass(frozen=True)
class FrictionLoad:
    """A friction force or torque proportional to the mesh compression.

    The generalized force is ``Q = coefficient(tau) * delta * pattern``.

    Attributes
    ----------
    coefficient : periodic signed coefficient over one mesh period, N/m for a force
        pattern (friction stiffness K_f) or N m/m for a torque pattern (K_Tf).
    pattern : ``{(body, dof): weight}``: unit force directions (translations) or
        unit torques (rotations) on which the friction acts.
    """

    coefficient: PeriodicSignal
    pattern: Mapping[Coordinate, float]

    def __post_init__(self) -> None:
        object.__setattr__(self, "pattern", _freeze_measure(self.pattern, "friction pattern"))


@dataclass(frozen=True)
class GearMesh:
    """A gear mesh: time-varying spring along the line of action.

    Attributes
    ----------
    name : label used for outputs (mesh force, DTE).
    measure : line-of-action projection ``{(body, dof): c}``; ``delta = sum c q`` (m).
        Build it with :func:`pipeline.dynamics.mesh_geometry.cylindrical_mesh_measure`.
    stiffness : mesh stiffness over one mesh period, N/m (a float means constant).
    damping_ratio : zeta (-) of ``c = 2 zeta sqrt(k_mean m_e)``.
    equivalent_mass : m_e in kg; ``None`` takes ``1 / (v^T M^-1 v)`` over the
        rotational coordinates of the measure (torsional equivalent mass).
    phase : delay of this mesh in mesh periods: ``k(tau - phase)``.
    order : mesh cycles per system period (1 for one-stage systems).
    transmission_error : e(tau) in m over one mesh period, or ``None``.
    friction : friction forces/torques of Jin et al. (2018).
    """

    name: str
    measure: Mapping[Coordinate, float]
    stiffness: PeriodicSignal | float
    damping_ratio: float = 0.0
    equivalent_mass: float | None = None
    phase: float = 0.0
    order: int = 1
    transmission_error: PeriodicSignal | None = None
    friction: tuple[FrictionLoad, ...] = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "measure", _freeze_measure(self.measure, self.name))
        if not isinstance(self.stiffness, PeriodicSignal):
            check_range(
                f"{self.name}.stiffness", self.stiffness, 0.0, 1e15, lo_open=True, unit="N/m"
            )
            object.__setattr__(
                self, "stiffness", PeriodicSignal(np.full(4, float(self.stiffness)))
            )
        elif self.stiffness.values.min() < 0:
            raise InputError(
                f"{self.name}.stiffness has negative samples "
                f"(min {self.stiffness.values.min():.6g} N/m)"
            )
        check_range(f"{self.name}.damping_ratio", self.damping_ratio, 0.0, 1.0)
        if self.equivalent_mass is not None:
            check_range(
                f"{self.name}.equivalent_mass",
                self.equivalent_mass,
                0.0,
                1e7,
                lo_open=True,
                unit="kg",
            )
        check_range(f"{self.name}.phase", self.phase, -1e6, 1e6)
        if int(self.order) != self.order or self.order < 1:
            raise InputError(f"{self.name}.order = {self.order!r} must be a whole number >= 1")
        object.__setattr__(self, "friction", tuple(self.friction))


@dataclass(frozen=True)
class MatrixCoupling:
    """A general symmetric stiffness (and damping) matrix between listed coordinates.

    Used for a condensed FE coupling such as the herringbone relief groove.

    Attributes
    ----------
    name : label.
    coordinates : the k coordinates the matrix acts on, in order.
    stiffness : (k, k) symmetric positive semi-definite, SI units per coordinate pair.
    damping : (k, k) or ``None``.
    """

    name: str
    coordinates: tuple[Coordinate, ...]
    stiffness: np.ndarray
    damping: np.ndarray | None = None

    def __post_init__(self) -> None:
        k = np.asarray(self.stiffness, dtype=float)
        n = len(self.coordinates)
        if k.shape != (n, n):
            raise InputError(f"{self.name}.stiffness has shape {k.shape}; need ({n}, {n})")
        if not np.allclose(k, k.T, rtol=1e-9, atol=1e-9 * np.abs(k).max()):
            raise InputError(f"{self.name}.stiffness must be symmetric")
        object.__setattr__(self, "stiffness", k)
        object.__setattr__(self, "coordinates", tuple(tuple(c) for c in self.coordinates))
        if self.damping is not None:
            c = np.asarray(self.damping, dtype=float)
            if c.shape != (n, n):
                raise InputError(f"{self.name}.damping has shape {c.shape}; need ({n}, {n})")
            object.__setattr__(self, "damping", c)


@dataclass(frozen=True)
class Tie:
    """Rigid connection: the listed DOFs of two bodies move together (a constraint).

    Attributes
    ----------
    body1, body2 : body names.
    dofs : DOF kinds tied (each must exist on both bodies).
    """

    body1: str
    body2: str
    dofs: tuple[str, ...] = ("x", "y", "z", "theta")


@dataclass(frozen=True)
class Load:
    """A constant external generalized force: N on a translation, N m on a rotation.

    Attributes
    ----------
    body : body name.
    dof : DOF kind.
    value : N or N m.
    """

    body: str
    dof: str
    value: float


Coupling = Spring | Bearing | TorsionalShaft | GearMesh | MatrixCoupling | Tie
