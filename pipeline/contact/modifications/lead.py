"""Lead modifications of one gear's flank: lead crowning, end relief at each face, helix slope.

All act across the face, the same at every point of the profile, at the gear's own face
position ``z_i`` in ``[0, b_i]`` (:class:`~pipeline.contact.modifications.frame.FlankFrame`:
face 1 at ``z_i = 0``, on the side of the pinion's reference face; face 2 at ``z_i = b_i``):

* **lead crowning** ``C_beta``: ``C_beta (2 z_i / b_i - 1)^2``, ``C_beta`` at both faces, 0 at
  mid-face;
* **helix slope** ``f_Hbeta``: ``f_Hbeta (z_i / b_i - 1/2)``, positive when more material is
  removed towards face 2 (a sign by material, not ISO 1328's by helix angle);
* **end relief** at face 1 (``C_I`` over ``L_I``) and face 2 (``C_II`` over ``L_II``): the
  relief shape (:mod:`.shapes`, linear or parabolic) of the distance into the relief,
  ``L_I - z_i`` and ``z_i - (b_i - L_II)``, the amount reached at the face.

Positive values remove material. ``[contact]``'s short form (crowning, slope deviation)
is evaluated over the mesh's common face width ``b`` and face position ``z`` instead
(``common_width``), as it was defined before the gears had modifications of their own.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.contact.modifications import shapes
from pipeline.contact.modifications.frame import FlankFrame
from pipeline.contact.modifications.profile import MAX_AMOUNT
from pipeline.validation import InputError, check_choice, check_range

FACES = ("face1", "face2")


@dataclass(frozen=True)
class LeadModification:
    """One gear's lead modifications (module docstring; SI, m).

    Attributes
    ----------
    crowning : lead crowning C_beta, m, in [0, 1e-3].
    slope : helix slope f_Hbeta, m, in [-1e-3, 1e-3].
    end_relief_face1, end_relief_face2 : end relief amounts C_I, C_II, m, in [0, 1e-3].
    end_relief_face1_length, end_relief_face2_length : their lengths L_I, L_II across the
        face, m, > 0 with an amount (at most the face width together: check_fits).
    end_relief_shape : "linear" or "parabolic".
    common_width : evaluate over the mesh's common face width and face position (the short
        form) instead of the gear's own.
    """

    crowning: float = 0.0
    slope: float = 0.0
    end_relief_face1: float = 0.0
    end_relief_face1_length: float = 0.0
    end_relief_face2: float = 0.0
    end_relief_face2_length: float = 0.0
    end_relief_shape: str = "linear"
    common_width: bool = False

    def __post_init__(self) -> None:
        check_range("modifications.lead_crowning", self.crowning, 0.0, MAX_AMOUNT, unit="m")
        check_range("modifications.helix_slope", self.slope, -MAX_AMOUNT, MAX_AMOUNT, unit="m")
        check_choice("modifications.end_relief_shape", self.end_relief_shape,
                     shapes.END_RELIEF_SHAPES)
        for face in FACES:
            amount = check_range(f"modifications.end_relief_{face}",
                                 getattr(self, f"end_relief_{face}"), 0.0, MAX_AMOUNT, unit="m")
            length = check_range(f"modifications.end_relief_{face}_length",
                                 getattr(self, f"end_relief_{face}_length"), 0.0, math.inf,
                                 unit="m")
            if amount > 0.0 and length == 0.0:
                raise InputError(f"modifications.end_relief_{face}_length = 0 m: modifications."
                                 f"end_relief_{face} = {amount:.6g} m needs a length > 0 m")
            if amount == 0.0 and length > 0.0:
                raise InputError(f"modifications.end_relief_{face}_length = {length:.6g} m "
                                 "changes nothing without an amount modifications."
                                 f"end_relief_{face}")

    @property
    def is_zero(self) -> bool:
        return not (self.crowning or self.slope or self.end_relief_face1
                    or self.end_relief_face2)

    def terms(self, frame: FlankFrame, z: np.ndarray) -> dict[str, np.ndarray]:
        """Material removed (m) at the mesh's face positions ``z`` (m) by each modification
        given, by name, in the order they are summed."""
        if self.common_width:
            zi, b = np.asarray(z, dtype=float), frame.common_width
        else:
            zi, b = np.asarray(z, dtype=float) + frame.face_shift, frame.face_width
        out = {}
        if self.crowning:
            out["lead_crowning"] = shapes.crowning(zi, self.crowning, b)
        if self.slope:
            out["helix_slope"] = shapes.slope(zi, self.slope, b)
        if self.end_relief_face1:
            n = self.end_relief_face1_length
            out["end_relief_face1"] = shapes.relief(n - zi, self.end_relief_face1, n,
                                                    self.end_relief_shape)
        if self.end_relief_face2:
            n = self.end_relief_face2_length
            out["end_relief_face2"] = shapes.relief(zi - (b - n), self.end_relief_face2, n,
                                                    self.end_relief_shape)
        return out

    def check_fits(self, frame: FlankFrame) -> None:
        """Refuse end reliefs longer than the face width ``b_i`` of ``frame``, alone or
        together."""
        note = f"the {frame.role}'s face width"
        for face in FACES:
            check_range(f"modifications.end_relief_{face}_length",
                        getattr(self, f"end_relief_{face}_length"), 0.0, frame.face_width,
                        unit="m", note=note)
        total = self.end_relief_face1_length + self.end_relief_face2_length
        if total > frame.face_width:
            raise InputError(
                f"modifications.end_relief_face1_length + end_relief_face2_length = "
                f"{total * 1e3:.6g} mm is more than the {frame.role}'s face width "
                f"{frame.face_width * 1e3:.6g} mm: the end reliefs would overlap")
