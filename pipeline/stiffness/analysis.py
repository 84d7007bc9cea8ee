"""The stiffness stage's entry point: a pair and its operating point -> analytical stiffness.

``analyse_stiffness(pair, operation, options, assembly_errors=...)`` takes the
stage's own inputs (never a configuration object) and returns a
:class:`StiffnessResult` that knows its summary and its columns with units.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.geometry.assembly_errors import AssembledPair, AssemblyErrors, assemble
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.stiffness.iso6336 import ContactLineStiffness, IsoStiffness, contact_line_stiffness
from pipeline.stiffness.mesh import MeshStiffness, PairModel, mesh_stiffness
from pipeline.stiffness.options import StiffnessOptions


@dataclass(frozen=True)
class StiffnessResult:
    """Analytical stiffness of a pair over one mesh cycle.

    Attributes
    ----------
    nominal : the pair as designed.
    actual : the pair at its installed centre distance (equal to ``nominal`` without errors).
    assembled : the assembly-error geometry, or ``None`` without errors.
    mesh : potential-energy mesh stiffness over one mesh cycle (N/m), friction terms.
    contact_line : contact-line method (ISO 6336) over the same cycle (N/m).
    iso : ISO 6336-1 single and mesh stiffness.
    model : the tooth models of the actual pair (reusable for further runs).
    options : the options it was computed with.
    """

    nominal: GearPair
    actual: GearPair
    assembled: AssembledPair | None
    mesh: MeshStiffness
    contact_line: ContactLineStiffness
    iso: IsoStiffness
    model: PairModel
    options: StiffnessOptions

    def summary(self, harmonics: int = 10) -> dict:
        """Scalars with their units in the keys (SI), and the first Fourier orders of k(t)."""
        m = self.mesh
        fs = m.as_periodic().fourier(min(harmonics, m.total.size // 2 - 1))
        out = {
            "potential_energy": m.summary(),
            "contact_line_ISO6336": {
                "mean_N_per_m": float(self.contact_line.total.mean()),
                "max_N_per_m": float(self.contact_line.total.max()),
                "min_N_per_m": float(self.contact_line.total.min()),
            },
            "iso6336": {
                "c_prime_N_per_mm_um": self.iso.c_single * 1e-9,
                "c_gamma_alpha_N_per_mm_um": self.iso.c_gamma_alpha * 1e-9,
                "mesh_stiffness_N_per_m": self.iso.mesh_stiffness,
            },
            "transverse_contact_ratio": self.actual.transverse_contact_ratio,
            "overlap_ratio": self.actual.overlap_ratio,
            "mesh_period_s": m.mesh_period,
            "fourier_N_per_m": {"mean": fs.mean, "amplitude": fs.amplitude, "phase_rad": fs.phase},
            # body-term fit ranges: Sainsot's for external gears, the ring fit for rings
            "sainsot_fit_range_ok": {
                "pinion": self.model.pinion.foundation.in_fit_range,
                "gear": self.model.gear.foundation.in_fit_range,
            },
        }
        if self.assembled is not None:
            out["assembly_errors"] = self.assembled.summary()
        return out

    def columns(self) -> dict[str, np.ndarray]:
        """Per-position columns over the mesh cycle, named with their units."""
        m = self.mesh
        return {
            "pinion_angle [rad]": m.pinion_angle,
            "roll_coordinate_s0 [m]": m.s0,
            "mesh_stiffness [N/m]": m.total,
            "contact_line_method [N/m]": self.contact_line.total,
            "friction_stiffness [N/m]": m.friction_stiffness,
            "friction_torque_coef_pinion [N m/m]": m.friction_torque_pinion,
            "friction_torque_coef_gear [N m/m]": m.friction_torque_gear,
            "contact_length [m]": m.contact_length,
        }


def analyse_stiffness(
    pair: GearPair,
    operation: OperatingPoint,
    options: StiffnessOptions | None = None,
    *,
    assembly_errors: AssemblyErrors | None = None,
    model: PairModel | None = None,
) -> StiffnessResult:
    """Mesh stiffness of a pair: potential energy over one mesh cycle, ISO 6336, contact lines.

    Parameters
    ----------
    pair : the nominal pair.
    operation : torque (N m) and speed (rad/s) of the driving gear.
    options : positions, slices, friction, foundation correction (defaults if ``None``).
    assembly_errors : centre displacements (m); the stiffness is that of the displaced pair.
    model : prebuilt tooth models of the *actual* pair, to skip rebuilding them.
    """
    options = options or StiffnessOptions()
    assembled = assemble(pair, assembly_errors)
    actual = pair if assembled is None else assembled.actual
    model = model or PairModel.build(actual)
    mesh = mesh_stiffness(
        model,
        positions=options.positions,
        slices=options.slices,
        friction=options.friction_model,
        operating=operation,
        foundation_correction=options.foundation_correction,
    )
    t1 = operation.torque if operation.driver == "pinion" else operation.torque / actual.gear_ratio
    ft = t1 / pair.pinion.reference_radius
    cl = contact_line_stiffness(actual, options.positions, tangential_load=ft)
    return StiffnessResult(pair, actual, assembled, mesh, cl, cl.iso, model, options)
