"""The contact stage's entry points: a compliance source and a loaded mesh cycle.

From Python a user goes pair -> :func:`analytical_compliance` (or an FE source,
:mod:`pipeline.contact.fe2d_source`, :mod:`pipeline.contact.fe3d_source`) ->
:func:`analyse_contact` -> :class:`LoadedMeshCycle`, without a command module. The command
``gearpipe contact`` composes the same calls.
"""

from __future__ import annotations

import warnings

from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.options import ContactOptions
from pipeline.contact.results import LoadedMeshCycle
from pipeline.contact.source import ComplianceSource, SliceCompliance
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.mesh import PairModel
from pipeline.stiffness.options import StiffnessOptions
from pipeline.stiffness.tooth import classical_tooth_model, hertz_compliance
from pipeline.validation import PhysicsWarning, check_choice

TOOTH_MODELS = ("exact", "classical")


def analytical_compliance(
    pair: GearPair,
    operation: OperatingPoint,
    contact: ContactOptions | None = None,
    stiffness: StiffnessOptions | None = None,
    *,
    tooth_model: str = "exact",
    model: PairModel | None = None,
) -> SliceCompliance:
    """The analytical slice compliance of a pair (Yang et al. 2026, sec. 2.1-2.4).

    Parameters
    ----------
    pair : the *actual* pair (after assembly errors, see ``Gearbox.actual_pair``).
    operation : driver, torque (N m) and speed (rad/s): friction direction and EHL load.
    contact : slices, slice coupling and tip contact (defaults if ``None``); a spur pair
        gets one slice unless its modifications vary along the face
        (``ContactOptions.face_slices``).
    stiffness : friction model and foundation correction (defaults if ``None``).
    tooth_model : "exact" (involute + trochoidal fillet) or "classical" (involute clamped
        at the base circle, Yang et al. 2026 eqs. 11-13).
    model : prebuilt tooth models of ``pair`` (skips building them).
    """
    contact = contact or ContactOptions()
    stiffness = stiffness or StiffnessOptions()
    check_choice("tooth_model", tooth_model, TOOTH_MODELS)
    if model is None and tooth_model == "classical":
        model = PairModel(pair, classical_tooth_model(pair.pinion),
                          classical_tooth_model(pair.gear),
                          hertz_compliance(pair.pinion, pair.gear))
    model = model or PairModel.build(pair)
    return SliceCompliance(model, contact.face_slices(pair), stiffness.friction_model, operation,
                           stiffness.foundation_correction, contact.slice_coupling,
                           contact.tip_contact)


def line_of_action_load(pair: GearPair, operation: OperatingPoint) -> float:
    """P = driving torque / driver's base radius, N (along the transverse line of action)."""
    driver = pair.pinion if operation.driver == "pinion" else pair.gear
    return operation.torque / driver.base_radius


def analyse_contact(
    source: ComplianceSource,
    operation: OperatingPoint,
    options: ContactOptions | None = None,
    *,
    show_progress: bool = False,
    warn: bool = True,
) -> LoadedMeshCycle:
    """Loaded tooth contact over one mesh cycle at the operating torque.

    Parameters
    ----------
    source : compliance of the candidate contact points (analytical or FE).
    operation : the driving torque (N m) sets the load P along the line of action.
    options : positions, local contact model, flank modifications (defaults if ``None``).
    show_progress : progress bar on stderr.
    warn : issue the cycle's physics warnings (:func:`warn_physics`); a fixed point that
        solves the contact again and again warns once, for the cycle it keeps.
    """
    options = options or ContactOptions()
    load = line_of_action_load(source.pair, operation)
    cycle = loaded_mesh_cycle(source, load, options.modifications, options.local_contact,
                              options.positions, driver=operation.driver,
                              show_progress=show_progress)
    if warn:
        warn_physics(cycle)
    return cycle


def warn_physics(cycle: LoadedMeshCycle) -> None:
    """Issue :meth:`LoadedMeshCycle.physics_warnings` as :class:`PhysicsWarning`."""
    for text in cycle.physics_warnings():
        warnings.warn(text, PhysicsWarning, stacklevel=3)
