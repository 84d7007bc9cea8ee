"""Mesh excitation of the dynamic models from the pipeline's analytical stiffness.

The stiffness stage (:mod:`pipeline.stiffness.mesh`) gives, over one mesh
cycle, the mesh stiffness k(t), the friction stiffness K_f(t) and the friction
torque coefficients KT_f1, KT_f2 of Jin et al. (2018), eqs. 15-17. This module turns them
into the periodic signals a :class:`~pipeline.dynamics.couplings.GearMesh` takes.

Sign conventions (the dynamics' own, see :mod:`pipeline.dynamics.mesh_geometry`
and :func:`pipeline.dynamics.excitation.constant_pair_excitation`): the friction
force acts along +n on the pinion (n = line of action turned by +90 deg) with
coefficient K_f, and the friction torques are positive in each gear's own sense
of rotation. The stiffness stage writes KT_f2 positive when the friction torque
on the driven gear acts *with the load torque*, i.e. against the gear's own
rotation, so its sign is flipped here; K_f and KT_f1 carry over unchanged.
"""

from __future__ import annotations

import importlib.util
from dataclasses import dataclass

from pipeline.geometry.pair import GearPair
from pipeline.signals import PeriodicSignal
from pipeline.stiffness.mesh import (
    FrictionModel,
    MeshStiffness,
    OperatingPoint,
    PairModel,
    mesh_stiffness,
)
from pipeline.stiffness.tooth import classical_tooth_model, hertz_compliance
from pipeline.validation import check_int_range


@dataclass(frozen=True)
class MeshExcitation:
    """Periodic mesh inputs of one gear mesh over one mesh period.

    Attributes
    ----------
    stiffness : k(tau), N/m.
    friction_stiffness : K_f(tau), N/m (force on the pinion along +n per m of compression).
    friction_torque_pinion, friction_torque_gear : KT_f(tau), N m/m, positive in each
        gear's own sense of rotation.
    mesh_period : s, at the operating speed of the stiffness computation.
    tooth_model : "exact" (involute + trochoid fillet) or "classical" (involute to the
        base circle, used while the exact profile module is not available).
    """

    stiffness: PeriodicSignal
    friction_stiffness: PeriodicSignal
    friction_torque_pinion: PeriodicSignal
    friction_torque_gear: PeriodicSignal
    mesh_period: float
    tooth_model: str

    @property
    def has_friction(self) -> bool:
        """True when any friction coefficient is non-zero."""
        return bool(
            abs(self.friction_stiffness.values).max() > 0
            or abs(self.friction_torque_pinion.values).max() > 0
        )


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


def excitation_from_stiffness(ms: MeshStiffness, tooth_model: str = "exact") -> MeshExcitation:
    """Convert a :class:`MeshStiffness` (stiffness-stage signs) to a :class:`MeshExcitation`."""
    T = ms.mesh_period
    return MeshExcitation(
        stiffness=PeriodicSignal(ms.total, T),
        friction_stiffness=PeriodicSignal(ms.friction_stiffness, T),
        friction_torque_pinion=PeriodicSignal(ms.friction_torque_pinion, T),
        friction_torque_gear=PeriodicSignal(-ms.friction_torque_gear, T),
        mesh_period=T,
        tooth_model=tooth_model,
    )


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
