"""The relief-groove stiffness that the dynamic models take directly.

Xu et al. (2020) join the left and right helical halves of the sun gear at nodes O_L
and O_R by a torsion beam of rigidity K_j = G I_j (N m^2, eq. 1) over l_LR, and
by coupling stiffnesses k_LRs in x, y, z (eqs. 20-21). :class:`GrooveStiffness`
carries the full 12 x 12 stiffness between the two nodes from a 3D FE model, the
torsional stiffness k_t and the equivalent K_j = k_t l_LR, and the left/right
mesh phase shift of eq. 11.
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass, field
from pathlib import Path

import numpy as np

from pipeline.io import write_json

DOF_NAMES = ("ux_L", "uy_L", "uz_L", "rx_L", "ry_L", "rz_L",
             "ux_R", "uy_R", "uz_R", "rx_R", "ry_R", "rz_R")


@dataclass(frozen=True)
class PhaseShift:
    """Relative twist of the sun halves and the mesh phase it causes.

    Attributes
    ----------
    phi_LR : relative twist angle between O_L and O_R, rad (Xu et al. 2020, eq. 1).
    lambda_LR : phase coefficient dec(z_s phi_LR / 2 pi) (-), fractional part
        with the sign of phi_LR (Xu et al. 2020, eq. 11).
    """

    phi_LR: float
    lambda_LR: float


@dataclass(frozen=True, eq=False)
class GrooveStiffness:
    """Stiffness joining the two halves of a herringbone sun gear (SI).

    Attributes
    ----------
    torsional_stiffness : k_t, N m/rad: torque over relative twist of O_L and O_R
        under a pure torque (other generalised forces zero).
    equivalent_Kj : K_j = k_t l_LR, N m^2 (the G I_j of Xu et al. 2020, eq. 1).
    l_LR : distance O_L - O_R, m.
    coupling_matrix : (12, 12), DOFs [ux, uy, uz, rx, ry, rz] at O_L then O_R
        (z = gear axis); blocks in N/m, N/rad (= N m/m) and N m/rad; symmetric,
        positive semi-definite, null space = the six rigid-body motions.
    node_z : (2,) axial positions of O_L and O_R, m (origin mid-groove).
    sun_teeth : z_s, used by :meth:`phase_shift`.
    teeth_model, coupling : how the body and the loads were modelled.
    n_dof : DOFs of the FE model; solver : sparse solver that factorised it.
    mesh_size : largest element edge, m.
    section_Kj : dict of G J (N m^2) of simple sections for comparison
        ("root" cylinder, "groove" bottom).
    timings : wall times in s ("mesh", "assembly", "factor", "solve", "total").
    """

    torsional_stiffness: float
    equivalent_Kj: float
    l_LR: float
    coupling_matrix: np.ndarray
    node_z: tuple[float, float]
    sun_teeth: int
    teeth_model: str
    coupling: str
    n_dof: int
    solver: str
    mesh_size: float
    section_Kj: dict = field(default_factory=dict)
    timings: dict = field(default_factory=dict)

    def phase_shift(self, sun_torque_Nm: float, groove_torque_fraction: float = 1.0
                    ) -> PhaseShift:
        """Relative twist and mesh phase coefficient for sun torque T_s (N m).

        ``phi_LR = f T_s / k_t = f T_s l_LR / K_j`` (Xu et al. 2020, eq. 1 with f = 1: the
        whole sun torque twists the groove) and ``lambda_LR = dec(z_s phi / 2 pi)``
        (eq. 11). ``groove_torque_fraction`` f is the share of T_s crossing the
        groove: 1 as in Xu et al. (2020); 0.5 when both halves take half the mesh torque
        and it leaves through the right shaft.
        """
        phi = groove_torque_fraction * sun_torque_Nm / self.torsional_stiffness
        return PhaseShift(phi_LR=phi, lambda_LR=math.fmod(self.sun_teeth * phi / (2 * math.pi),
                                                          1.0))

    def to_dict(self) -> dict:
        d = asdict(self)
        d["coupling_matrix"] = self.coupling_matrix.tolist()
        d["dof_names"] = list(DOF_NAMES)
        d["units"] = {"torsional_stiffness": "N m/rad", "equivalent_Kj": "N m^2", "l_LR": "m",
                      "coupling_matrix": "N/m (translations), N/rad, N m/rad (rotations)",
                      "node_z": "m", "mesh_size": "m", "section_Kj": "N m^2", "timings": "s"}
        return d

    @classmethod
    def from_dict(cls, d: dict) -> GrooveStiffness:
        d = {k: v for k, v in d.items() if k not in ("dof_names", "units")}
        d["coupling_matrix"] = np.asarray(d["coupling_matrix"], dtype=float)
        d["node_z"] = tuple(d["node_z"])
        return cls(**d)

    def save(self, path: str | Path) -> Path:
        """Write as JSON (atomic)."""
        return write_json(path, self.to_dict())

    @classmethod
    def load(cls, path: str | Path) -> GrooveStiffness:
        return cls.from_dict(json.loads(Path(path).read_text(encoding="utf-8")))
