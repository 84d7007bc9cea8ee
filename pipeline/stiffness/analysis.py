"""One call from a pair configuration to its analytical stiffness.

This is what the CLI and the workflows use.
"""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.config import PairConfig
from pipeline.geometry.assembly_errors import AssembledPair
from pipeline.geometry.pair import GearPair
from pipeline.stiffness.iso6336 import ContactLineStiffness, IsoStiffness, contact_line_stiffness
from pipeline.stiffness.mesh import (
    FrictionModel,
    MeshStiffness,
    OperatingPoint,
    PairModel,
    mesh_stiffness,
)


@dataclass(frozen=True)
class PairStiffness:
    """Analytical stiffness of a configured pair.

    Attributes
    ----------
    nominal : the pair as designed.
    actual : the pair at its installed centre distance (equal to ``nominal`` without errors).
    assembled : the assembly-error geometry, or ``None`` without errors.
    mesh : potential-energy mesh stiffness over one mesh cycle (N/m).
    contact_line : contact-line method (ISO 6336) over the same cycle (N/m).
    iso : ISO 6336-1 single and mesh stiffness.
    model : the tooth models of the actual pair (reusable for further runs).
    """

    nominal: GearPair
    actual: GearPair
    assembled: AssembledPair | None
    mesh: MeshStiffness
    contact_line: ContactLineStiffness
    iso: IsoStiffness
    model: PairModel


def friction_model(cfg: PairConfig) -> FrictionModel:
    """The friction model a configuration asks for."""
    st = cfg.stiffness
    if isinstance(st.friction, str):
        return FrictionModel(kind="ehl", roughness=st.roughness, viscosity=st.viscosity)
    return FrictionModel(mu=float(st.friction))


def analyse_pair(cfg: PairConfig, model: PairModel | None = None) -> PairStiffness:
    """Mesh stiffness (potential energy + contact-line/ISO) of a configured pair.

    ``model`` may pass prebuilt tooth models of the *actual* pair to skip rebuilding them.
    """
    nominal = GearPair(cfg.pinion, cfg.gear, cfg.centre_distance)
    errors = cfg.assembly_errors
    assembled = None if errors.is_zero else AssembledPair(nominal, errors)
    actual = nominal if assembled is None else assembled.actual
    model = model or PairModel.build(actual)
    op = OperatingPoint(cfg.operation.torque, cfg.operation.speed, cfg.operation.driver)
    mesh = mesh_stiffness(
        model,
        positions=cfg.stiffness.positions,
        slices=cfg.stiffness.slices,
        friction=friction_model(cfg),
        operating=op,
        foundation_correction=cfg.stiffness.foundation_correction,
    )
    t1 = op.torque if op.driver == "pinion" else op.torque / actual.gear_ratio
    ft = t1 / cfg.pinion.reference_radius
    cl = contact_line_stiffness(actual, cfg.stiffness.positions, tangential_load=ft)
    return PairStiffness(nominal, actual, assembled, mesh, cl, cl.iso, model)
