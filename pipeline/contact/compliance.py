"""The compliance source a gearbox file asks for: ``[contact] compliance``.

* ``"analytical"`` - the potential-energy slice compliance
  (:func:`pipeline.contact.analysis.analytical_compliance`; Yang et al. 2026, sec. 2).
* ``"fe2d"`` - 2D FE influence coefficients of both whole gears
  (:class:`pipeline.contact.fe2d_source.FE2DCompliance`), same-section coupling.
* ``"fe3d"`` - 3D FE influence coefficients (:class:`pipeline.contact.fe3d_source.FE3DCompliance`),
  coupling across the face.

FE influence coefficients are for loads normal to the flank; with friction in
``[stiffness]`` the slice model's relative friction change scales them
(:class:`pipeline.contact.source.FrictionCorrected`), so every source sees the same
friction. The FE settings come from the ``[fe]`` table (:mod:`pipeline.config`), the
slices across the face from ``[contact] slices`` for all three
(:meth:`~pipeline.contact.options.ContactOptions.face_slices`: one for a spur pair without
lead crowning or helix slope deviation).
"""

from __future__ import annotations

import dataclasses
from typing import Any

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.contact.analysis import analytical_compliance
from pipeline.contact.options import COMPLIANCES, ContactOptions
from pipeline.contact.source import ComplianceSource, FrictionCorrected
from pipeline.fem.settings import FE2DSettings, FE3DSettings
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.mesh import PairModel
from pipeline.stiffness.options import StiffnessOptions
from pipeline.validation import InputError, check_choice


def fe_settings(compliance: str, fe: FE2DSettings | FE3DSettings | None,
                contact: ContactOptions) -> FE2DSettings | FE3DSettings | None:
    """The FE settings of ``compliance`` with the contact slices (``None`` for analytical;
    defaults when ``fe`` is None)."""
    check_choice("contact.compliance", compliance, COMPLIANCES)
    if compliance == "analytical":
        return None
    kind = FE2DSettings if compliance == "fe2d" else FE3DSettings
    if fe is None:
        fe = kind()
    if not isinstance(fe, kind):
        raise InputError(f"contact.compliance = {compliance!r} needs {kind.__name__}, "
                         f"got {type(fe).__name__}")
    return dataclasses.replace(fe, slices=contact.slices)


def compliance_source(
    pair: GearPair,
    operation: OperatingPoint,
    contact: ContactOptions | None = None,
    stiffness: StiffnessOptions | None = None,
    fe: FE2DSettings | FE3DSettings | None = None,
    *,
    cache: Cache = DEFAULT_CACHE,
    tooth_model: str = "exact",
    model: PairModel | None = None,
    show_progress: bool = False,
    prebuilt: Any = None,
) -> ComplianceSource:
    """The compliance source ``contact.compliance`` names, for the installed ``pair``.

    Parameters
    ----------
    pair : the actual pair (after assembly errors).
    operation : driver, torque (N m), speed (rad/s).
    contact : contact options; ``contact.compliance`` picks the source.
    stiffness : friction model and foundation correction.
    fe : FE settings of the chosen FE source (defaults if ``None``).
    cache : the on-disk cache of FE meshes and tables.
    tooth_model, model : tooth model of the analytical slices
        (:func:`~pipeline.contact.analysis.analytical_compliance`); with an FE source they
        give only the friction change.
    show_progress : progress of the FE build on stderr.
    prebuilt : an FE source of the same gears and settings built earlier (a design study
        ships it to its workers): its tables are used for ``pair`` instead of building or
        reading them.
    """
    contact = contact or ContactOptions()
    slices = analytical_compliance(pair, operation, contact, stiffness,
                                   tooth_model=tooth_model, model=model)
    settings = fe_settings(contact.compliance, fe, contact)
    if settings is None:
        return slices
    settings = dataclasses.replace(settings, slices=slices.slices)
    if prebuilt is not None:
        base = dataclasses.replace(prebuilt, pair=pair, settings=settings,
                                   tip_contact=contact.tip_contact)
    elif contact.compliance == "fe2d":
        from pipeline.contact.fe2d_source import FE2DCompliance

        base = FE2DCompliance.build(pair, settings, cache=cache, show_progress=show_progress,
                                    tip_contact=contact.tip_contact)
    else:
        from pipeline.contact.fe3d_source import FE3DCompliance

        base = FE3DCompliance.build(pair, settings, cache=cache, show_progress=show_progress,
                                    tip_contact=contact.tip_contact)
    if slices.friction.mu == 0.0 and slices.friction.kind == "constant":
        return base
    return FrictionCorrected(base, slices)
