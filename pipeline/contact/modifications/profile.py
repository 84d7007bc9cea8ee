"""Profile modifications of one gear's flank: tip and root relief, profile crowning and slope.

All act along the profile, the same at every face position, and are evaluated at a
contact point's roll coordinate ``s`` of a mesh through the gear's
:class:`~pipeline.contact.modifications.frame.FlankFrame` (roll length along the path of
contact; ``u`` below is the distance from the gear's start of active profile towards its
tip, ``L_AE`` the active flank's length, both m):

* **tip relief** ``C_a`` from a start towards the tip, given as the roll length ``L_a``
  measured from the active tip down the flank (ISO 21771's length of tip relief along the
  path of contact) or as the start diameter ``d_Ca``; shape linear, parabolic or arc
  (:mod:`.shapes`), ``C_a`` reached at the active tip;
* **root relief** ``C_f``, the same towards the root: a roll length ``L_f`` measured from
  the start of active profile up the flank, or the start diameter ``d_Cf``; ``C_f`` reached
  at the start of active profile (the lowest point this mesh touches);
* **profile crowning** ``C_alpha``: ``C_alpha (2 u / L_AE - 1)^2``, ``C_alpha`` at both ends of
  the active flank, 0 in its middle;
* **profile slope** ``f_Halpha``: ``f_Halpha (u / L_AE - 1/2)``, positive when more material is
  removed towards the tip (a sign by material, not ISO 1328's by pressure angle).

Positive values remove material. Which flank is active depends on the mesh, so starts are
checked against it (:meth:`ProfileModification.check_fits`): inside the active flank, and
a root relief ending below where the tip relief starts.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.contact.modifications import shapes
from pipeline.contact.modifications.frame import FlankFrame
from pipeline.validation import InputError, check_choice, check_range

MAX_AMOUNT = 1e-3
"""m: a modification above 1 mm is an input mistake (units), not a design."""


@dataclass(frozen=True)
class ProfileModification:
    """One gear's profile modifications (module docstring; SI, m).

    Attributes
    ----------
    tip_relief, root_relief : amounts C_a, C_f, m, in [0, 1e-3].
    tip_relief_length, root_relief_length : roll lengths L_a (from the active tip) and L_f
        (from the start of active profile), m, > 0; or None.
    tip_relief_diameter, root_relief_diameter : start diameters d_Ca, d_Cf, m; or None.
        A relief with an amount needs exactly one of its length and its diameter.
    tip_relief_shape, root_relief_shape : "linear", "parabolic" or "arc".
    crowning : profile crowning C_alpha, m, in [0, 1e-3].
    slope : profile slope f_Halpha, m, in [-1e-3, 1e-3].
    """

    tip_relief: float = 0.0
    tip_relief_length: float | None = None
    tip_relief_diameter: float | None = None
    tip_relief_shape: str = "linear"
    root_relief: float = 0.0
    root_relief_length: float | None = None
    root_relief_diameter: float | None = None
    root_relief_shape: str = "linear"
    crowning: float = 0.0
    slope: float = 0.0

    def __post_init__(self) -> None:
        for end in ("tip", "root"):
            amount = check_range(f"modifications.{end}_relief", getattr(self, f"{end}_relief"),
                                 0.0, MAX_AMOUNT, unit="m")
            length = getattr(self, f"{end}_relief_length")
            diameter = getattr(self, f"{end}_relief_diameter")
            check_choice(f"modifications.{end}_relief_shape",
                         getattr(self, f"{end}_relief_shape"), shapes.RELIEF_SHAPES)
            if length is not None:
                check_range(f"modifications.{end}_relief_length", length, 0.0, math.inf,
                            unit="m")
            if diameter is not None:  # its range is the active flank's (check_fits)
                check_range(f"modifications.{end}_relief_diameter", diameter, -math.inf,
                            math.inf, unit="m")
            given = [n for n, v in (("length", length), ("diameter", diameter))
                     if v is not None]
            if amount > 0.0 and len(given) != 1:
                what = "both" if given else "neither"
                raise InputError(f"modifications.{end}_relief = {amount:.6g} m needs its start: "
                                 f"modifications.{end}_relief_length or modifications."
                                 f"{end}_relief_diameter (one of them; {what} given)")
            if amount > 0.0 and length == 0.0:
                raise InputError(f"modifications.{end}_relief_length = 0 m: modifications."
                                 f"{end}_relief = {amount:.6g} m needs a relief length > 0 m")
            if amount == 0.0 and given:
                raise InputError(f"modifications.{end}_relief_{given[0]} = "
                                 f"{length if length is not None else diameter:.6g} m changes "
                                 f"nothing without an amount modifications.{end}_relief")
        check_range("modifications.profile_crowning", self.crowning, 0.0, MAX_AMOUNT, unit="m")
        check_range("modifications.profile_slope", self.slope, -MAX_AMOUNT, MAX_AMOUNT, unit="m")

    @property
    def is_zero(self) -> bool:
        return not (self.tip_relief or self.root_relief or self.crowning or self.slope)

    def tip_start(self, frame: FlankFrame) -> float:
        """The roll coordinate s (m) of the mesh where the tip relief starts."""
        if self.tip_relief_length is not None:
            return frame.tip_s - frame.toward_tip * self.tip_relief_length
        return frame.s_at_diameter(self.tip_relief_diameter)

    def root_start(self, frame: FlankFrame) -> float:
        """The roll coordinate s (m) of the mesh where the root relief starts."""
        if self.root_relief_length is not None:
            return frame.root_s + frame.toward_tip * self.root_relief_length
        return frame.s_at_diameter(self.root_relief_diameter)

    def terms(self, frame: FlankFrame, s: np.ndarray) -> dict[str, np.ndarray]:
        """Material removed (m) at roll coordinates ``s`` (m) by each modification given,
        by name, in the order they are summed."""
        out = {}
        if self.tip_relief:
            start = self.tip_start(frame)
            length = (self.tip_relief_length if self.tip_relief_length is not None
                      else float(frame.into(frame.tip_s, start)))
            out["tip_relief"] = shapes.relief(frame.into(s, start), self.tip_relief, length,
                                              self.tip_relief_shape)
        if self.root_relief:
            start = self.root_start(frame)
            length = (self.root_relief_length if self.root_relief_length is not None
                      else float(frame.into(start, frame.root_s)))
            out["root_relief"] = shapes.relief(-frame.into(s, start), self.root_relief, length,
                                               self.root_relief_shape)
        if self.crowning:
            out["profile_crowning"] = shapes.crowning(frame.into(s, frame.root_s),
                                                      self.crowning, frame.active_length)
        if self.slope:
            out["profile_slope"] = shapes.slope(frame.into(s, frame.root_s), self.slope,
                                                frame.active_length)
        return out

    def check_fits(self, frame: FlankFrame, mesh: str = "") -> None:
        """Refuse a relief start outside ``frame``'s active flank, and a root relief reaching
        past the start of the tip relief (``mesh`` names the mesh in the message)."""
        where = f" of the {mesh} mesh" if mesh else ""
        note = f"the {frame.role}'s active flank{where}"
        lo, hi = frame.active_diameter
        for end in ("tip", "root"):
            if not getattr(self, f"{end}_relief"):
                continue
            length = getattr(self, f"{end}_relief_length")
            if length is not None:
                check_range(f"modifications.{end}_relief_length", length, 0.0,
                            frame.active_length, unit="m", note=note)
            else:
                check_range(f"modifications.{end}_relief_diameter",
                            getattr(self, f"{end}_relief_diameter"), lo, hi, unit="m",
                            note=note)
        if self.tip_relief and self.root_relief:
            overlap = float(frame.into(self.root_start(frame), self.tip_start(frame)))
            if overlap > 0.0:
                raise InputError(
                    f"modifications.root_relief overlaps modifications.tip_relief by "
                    f"{overlap * 1e3:.4g} mm of roll length on the {frame.role}'s flank{where}: "
                    "the root relief must end below where the tip relief starts")
