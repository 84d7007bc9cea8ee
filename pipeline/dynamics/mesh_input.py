"""Mesh excitation of the dynamic models: :class:`MeshExcitation` and its sources.

A :class:`MeshExcitation` holds, over one mesh period and along the transverse line
of action, the mesh stiffness k(t), the displacement excitation (transmission error)
e(t), the friction stiffness K_f(t) and the friction torque coefficients KT_f1, KT_f2
of Jin et al. (2018), eqs. 15-17: the periodic signals a
:class:`~pipeline.dynamics.couplings.GearMesh` takes (mesh force
``F = k (delta - e)``, friction force ``K_f (delta - e)``, friction torques
``KT_fi (delta - e)``). Sources:

* the analytical stiffness stage (:mod:`pipeline.stiffness.mesh`):
  :func:`excitation_from_stiffness`, :func:`analytical_excitation` (no transmission
  error: the unloaded flanks are perfect);
* the loaded tooth contact (:mod:`pipeline.contact`):
  :func:`pipeline.dynamics.contact_excitation.excitation_from_contact` (loaded k(t),
  static transmission error, friction of the loaded points);
* a given k(t): :func:`excitation_from_signal`.

Sign conventions (the dynamics' own, see :mod:`pipeline.dynamics.mesh_geometry`
and :func:`pipeline.dynamics.excitation.constant_pair_excitation`): the friction
force acts along +n on the pinion (n = line of action turned by +90 deg) with
coefficient K_f, and the friction torques are positive in each gear's own sense
of rotation. The stiffness stage (:mod:`pipeline.stiffness.friction`) writes KT_f2
positive when the friction torque on the driven gear acts *with the load torque*,
i.e. against the gear's own rotation, so its sign is flipped here, in
:func:`friction_signals`, for every source; K_f and KT_f1 carry over unchanged.
"""

from __future__ import annotations

import importlib.util
import math
from dataclasses import dataclass, replace

import numpy as np

from pipeline.geometry.pair import GearPair
from pipeline.signals import JUMP_TOLERANCE, Jump, PeriodicSignal, resample_with_jumps
from pipeline.stiffness.mesh import (
    FrictionModel,
    MeshStiffness,
    OperatingPoint,
    PairModel,
    mesh_stiffness,
)
from pipeline.stiffness.tooth import classical_tooth_model, hertz_compliance
from pipeline.validation import InputError, check_int_range


@dataclass(frozen=True)
class MeshExcitation:
    """Periodic mesh inputs of one gear mesh over one mesh period (transverse line of action).

    All signals are sampled at the same ``n`` phases ``tau_k = k / n`` of one mesh period,
    ``tau = 0`` at the first position of the source's mesh cycle (the leading tooth pair
    at the start of contact, :meth:`GearPair.mesh_cycle`).

    Attributes
    ----------
    stiffness : k(tau), N/m.
    friction_stiffness : K_f(tau), N/m (force on the pinion along +n per m of compression).
    friction_torque_pinion, friction_torque_gear : KT_f(tau), N m/m, positive in each
        gear's own sense of rotation.
    mesh_period : s, at the operating speed of the stiffness computation.
    tooth_model : the model behind the signals: "exact" (involute + trochoid fillet) or
        "classical" (involute to the base circle) for the analytical stiffness, the local
        contact model for a contact excitation.
    transmission_error : e(tau), m, the displacement excitation along the line of action
        (a positive e unloads the mesh, :class:`~pipeline.dynamics.couplings.GearMesh`),
        or ``None`` (perfect flanks, e = 0).
    load : P, N, the static mesh load the signals belong to (the contact analysis' load
        along the transverse line of action), or ``None`` when they do not depend on it.
    source : where the signals come from: "analytical", "contact" or "given".
    """

    stiffness: PeriodicSignal
    friction_stiffness: PeriodicSignal
    friction_torque_pinion: PeriodicSignal
    friction_torque_gear: PeriodicSignal
    mesh_period: float
    tooth_model: str = "exact"
    transmission_error: PeriodicSignal | None = None
    load: float | None = None
    source: str = "analytical"

    def __post_init__(self) -> None:
        n = self.stiffness.values.size
        for name in ("friction_stiffness", "friction_torque_pinion", "friction_torque_gear",
                     "transmission_error"):
            sig = getattr(self, name)
            if sig is not None and sig.values.size != n:
                raise InputError(f"mesh excitation: {name} has {sig.values.size} samples; "
                                 f"the stiffness has {n}")
        if np.any(self.stiffness.values <= 0.0):
            raise InputError("mesh excitation: the mesh stiffness must be > 0 N/m at every "
                             f"sample (min {self.stiffness.values.min():.6g} N/m)")

    @property
    def has_friction(self) -> bool:
        """True when any friction coefficient is non-zero."""
        return bool(
            abs(self.friction_stiffness.values).max() > 0
            or abs(self.friction_torque_pinion.values).max() > 0
        )


EXCITATION_SAMPLES = 360
"""Samples per mesh period of an excitation whose tooth-pair jumps are resolved
(:func:`with_resolved_jumps`); more when the source has more."""

_SIGNALS = ("stiffness", "friction_stiffness", "friction_torque_pinion", "friction_torque_gear",
            "transmission_error")


def tooth_pair_jumps(pair: GearPair) -> tuple[Jump, ...]:
    """Phases of one mesh cycle (:meth:`GearPair.mesh_cycle`) where a spur pair's mesh
    signals jump: a tooth pair enters at 0 (the sample there holds it: the path of contact
    is closed) and the leaving pair drops out at ``eps_alpha - floor(eps_alpha)`` (the
    sample there still holds it). None for helical gears, whose contact lines enter and
    leave gradually, nor when eps_alpha is a whole number (entry and exit coincide)."""
    if pair.pinion.base_helix_angle != 0.0:
        return ()
    eps = pair.transverse_contact_ratio
    leave = eps - math.floor(eps)
    if min(leave, 1.0 - leave) < JUMP_TOLERANCE:
        return ()
    return (Jump(0.0, "after"), Jump(leave, "before"))


def with_resolved_jumps(excitation: MeshExcitation, pair: GearPair) -> MeshExcitation:
    """The excitation at ``max(n, EXCITATION_SAMPLES)`` phases with the jumps where a
    spur pair's tooth pairs enter and leave contact at their exact phases
    (:func:`tooth_pair_jumps`, :func:`pipeline.signals.resample_with_jumps`).

    Sampled over a mesh cycle, k(t) and e(t) ramp across the sample interval holding an
    entry or exit; the damping force ``c (delta' - e')`` and the response then depend on
    the sampling (the demo pair's dynamic factor moved 0.68 % from 60 to 360 contact
    positions; resolved, 0.004 %). Unchanged for helical pairs.
    """
    jumps = tooth_pair_jumps(pair)
    if not jumps:
        return excitation
    n = max(excitation.stiffness.values.size, EXCITATION_SAMPLES)
    fields = {name: resample_with_jumps(getattr(excitation, name), jumps, n)
              for name in _SIGNALS if getattr(excitation, name) is not None}
    return replace(excitation, **fields)


def exact_profile_available() -> bool:
    """True when :mod:`pipeline.geometry.profile` (exact tooth profile) can be imported."""
    return importlib.util.find_spec("pipeline.geometry.profile") is not None


def pair_model(pair: GearPair, n_sections: int = 3000) -> tuple[PairModel, str]:
    """Tooth models of a pair: exact profile when available, else the classical model.

    Returns
    -------
    (PairModel, "exact" | "classical").
    """
    check_int_range("n_sections", n_sections, 100, 1_000_000)
    if exact_profile_available():
        return PairModel.build(pair, n_sections), "exact"
    return (
        PairModel(
            pair,
            classical_tooth_model(pair.pinion, n_sections),
            classical_tooth_model(pair.gear, n_sections),
            hertz_compliance(pair.pinion, pair.gear),
        ),
        "classical",
    )


def friction_signals(
    friction_stiffness: np.ndarray,
    friction_torque_pinion: np.ndarray,
    friction_torque_gear: np.ndarray,
    period: float,
) -> tuple[PeriodicSignal, PeriodicSignal, PeriodicSignal]:
    """K_f, KT_f1, KT_f2 in the stiffness stage's signs -> the dynamics' signals.

    Parameters
    ----------
    friction_stiffness : shape (n,), K_f = sum lam mu k, N/m (:mod:`pipeline.stiffness.friction`).
    friction_torque_pinion, friction_torque_gear : shape (n,), KT_f,i = sum lam mu k rho_i,
        N m/m, positive when the torque acts with the driving (pinion) or the load (gear)
        torque.
    period : mesh period, s.

    Returns
    -------
    (K_f, KT_f1, KT_f2) as :class:`PeriodicSignal`, torques positive in each gear's own sense
    of rotation: KT_f2 changes sign (module docstring), the others do not.
    """
    return (PeriodicSignal(friction_stiffness, period),
            PeriodicSignal(friction_torque_pinion, period),
            PeriodicSignal(-np.asarray(friction_torque_gear, dtype=float), period))


def excitation_from_stiffness(ms: MeshStiffness, tooth_model: str = "exact") -> MeshExcitation:
    """Convert a :class:`MeshStiffness` (stiffness-stage signs) to a :class:`MeshExcitation`;
    sampled over one mesh cycle of a spur pair, its jumps are resolved
    (:func:`with_resolved_jumps`)."""
    T = ms.mesh_period
    kf, kt1, kt2 = friction_signals(ms.friction_stiffness, ms.friction_torque_pinion,
                                    ms.friction_torque_gear, T)
    excitation = MeshExcitation(
        stiffness=PeriodicSignal(ms.total, T),
        friction_stiffness=kf,
        friction_torque_pinion=kt1,
        friction_torque_gear=kt2,
        mesh_period=T,
        tooth_model=tooth_model,
        source="analytical",
    )
    return with_resolved_jumps(excitation, ms.pair) if ms.pair.is_mesh_cycle(ms.s0) else excitation


def excitation_from_signal(
    stiffness: PeriodicSignal,
    transmission_error: PeriodicSignal | None = None,
    mesh_period: float = math.nan,
) -> MeshExcitation:
    """A given k(tau) (N/m) and optional e(tau) (m) without friction, as a :class:`MeshExcitation`.

    ``transmission_error`` must have as many samples as ``stiffness``; ``mesh_period`` in s
    (NaN when the signals are used in phase only).
    """
    zero = PeriodicSignal(np.zeros(stiffness.values.size), mesh_period)
    return MeshExcitation(stiffness=stiffness, friction_stiffness=zero,
                          friction_torque_pinion=zero, friction_torque_gear=zero,
                          mesh_period=mesh_period, transmission_error=transmission_error,
                          source="given")


def analytical_excitation(
    pair: GearPair,
    friction: FrictionModel | None = None,
    operating: OperatingPoint | None = None,
    positions: int = 360,
    slices: int = 60,
    n_sections: int = 3000,
) -> MeshExcitation:
    """Analytical (potential-energy) mesh stiffness and friction coefficients of a pair.

    Parameters
    ----------
    pair : the (actual) gear pair, including assembly errors through its centre distance.
    friction : constant mu or EHL friction (Jin et al. 2018, eq. 9); default none.
    operating : torque (N m) and speed (rad/s) of the driver (EHL load and mesh period).
    positions : samples per mesh period.
    slices : slices across the face for helical gears.
    n_sections : tooth sections of the potential-energy integration.
    """
    model, kind = pair_model(pair, n_sections)
    ms = mesh_stiffness(model, positions, slices, friction, operating)
    return excitation_from_stiffness(ms, kind)
