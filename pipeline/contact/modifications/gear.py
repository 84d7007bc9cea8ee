"""All modifications of one gear's flank, and the topological twist.

:class:`GearModification` holds one gear's profile (:mod:`.profile`), lead (:mod:`.lead`)
and topography (:mod:`.topography`) modifications and the **twist** ``S`` (m), the
topological modification of ISO 21771:2007 (7.3, "profile twist"; KISSsoft's profile twist):
the profile slope varies linearly across the face, from ``-S/2`` at face 1 to ``+S/2`` at
face 2, i.e. ``f_Halpha(z_i) = S (z_i / b_i - 1/2)``, so that

    w_twist = S (u / L_AE - 1/2) (z_i / b_i - 1/2)

(``u`` from the start of active profile, ``L_AE`` the active flank's length, ``z_i`` the face
position, ``b_i`` the face width; :mod:`.frame`). The same surface is a helix slope varying
linearly up the profile ("helix twist"), so one amount describes both; ``S`` > 0 removes
material at the tip of face 2 and the root of face 1 (``S/4`` there). The map of each
modification alone, the twist's among them: ``workflows/modification_catalogue.py``.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pipeline.contact.modifications.frame import FlankFrame
from pipeline.contact.modifications.lead import LeadModification
from pipeline.contact.modifications.profile import MAX_AMOUNT, ProfileModification
from pipeline.contact.modifications.topography import Topography
from pipeline.validation import check_range

TERMS = ("tip_relief", "root_relief", "profile_crowning", "profile_slope", "lead_crowning",
         "helix_slope", "end_relief_face1", "end_relief_face2", "twist", "topography")
"""The modifications of a flank in the order their contributions are summed."""


@dataclass(frozen=True)
class GearModification:
    """One gear's flank modifications (module docstring; SI, m).

    Attributes
    ----------
    profile : profile modifications.
    lead : lead modifications.
    twist : S, m, in [-1e-3, 1e-3].
    topography : a deviation grid added to the rest, or None.
    """

    profile: ProfileModification = field(default_factory=ProfileModification)
    lead: LeadModification = field(default_factory=LeadModification)
    twist: float = 0.0
    topography: Topography | None = None

    def __post_init__(self) -> None:
        check_range("modifications.twist", self.twist, -MAX_AMOUNT, MAX_AMOUNT, unit="m")

    @property
    def is_zero(self) -> bool:
        return (self.profile.is_zero and self.lead.is_zero and not self.twist
                and self.topography is None)

    @property
    def varies_across_face(self) -> bool:
        """Some term changes along the face (the solve then needs slices across it)."""
        return bool(not self.lead.is_zero or self.twist
                    or (self.topography is not None and self.topography.varies_across_face))

    def terms(self, frame: FlankFrame, s: np.ndarray, z: np.ndarray) -> dict[str, np.ndarray]:
        """Material removed (m) at a mesh's roll coordinates ``s`` and face positions ``z``
        (m, same shape) by each modification given, by name (:data:`TERMS`)."""
        out = {**self.profile.terms(frame, s), **self.lead.terms(frame, z)}
        if self.twist:
            u = frame.into(s, frame.root_s) / frame.active_length - 0.5
            zi = np.asarray(z, dtype=float) + frame.face_shift
            out["twist"] = self.twist * u * (zi / frame.face_width - 0.5)
        if self.topography is not None:
            out.update(self.topography.terms(frame, s, z))
        return out

    def deviation(self, frame: FlankFrame, s: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Total material removed (m) at roll coordinates ``s`` and face positions ``z``."""
        total = np.zeros(np.broadcast(np.asarray(s), np.asarray(z)).shape)
        for term in self.terms(frame, *np.broadcast_arrays(s, z)).values():
            total = total + term
        return total

    def check_fits(self, frame: FlankFrame, mesh: str = "") -> None:
        """Refuse starts outside the active flank, overlapping reliefs and a grid that does
        not cover the flank of ``frame``."""
        self.profile.check_fits(frame, mesh)
        self.lead.check_fits(frame)
        if self.topography is not None:
            self.topography.check_fits(frame, mesh)

    def describe(self) -> str:
        """One line in the gearbox file's units (um, mm), or ``""``."""
        p, q = self.profile, self.lead
        parts = []
        for end in ("tip", "root"):
            amount = getattr(p, f"{end}_relief")
            if amount:
                length = getattr(p, f"{end}_relief_length")
                start = (f"over {length * 1e3:.3g} mm" if length is not None else
                         f"from d {getattr(p, f'{end}_relief_diameter') * 1e3:.5g} mm")
                parts.append(f"{end} relief {amount * 1e6:.3g} um {start} "
                             f"({getattr(p, f'{end}_relief_shape')})")
        for name, value in (("profile crowning", p.crowning), ("profile slope", p.slope),
                            ("lead crowning", q.crowning), ("helix slope", q.slope),
                            ("end relief face 1", q.end_relief_face1),
                            ("end relief face 2", q.end_relief_face2), ("twist", self.twist)):
            if value:
                parts.append(f"{name} {value * 1e6:.3g} um")
        if self.topography is not None:
            parts.append(f"topography {self.topography.source}")
        return ", ".join(parts)
