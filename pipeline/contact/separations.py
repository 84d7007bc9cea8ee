"""Initial separations ``eps`` of the candidate contact points from flank modifications and errors.

``eps_i`` (m) is the gap at point ``i`` before load, measured along the
transverse line of action (for an involute the normal to the transverse profile)
and relative to the unmodified, error-free flanks, for which ``eps = 0``
everywhere. Positive ``eps`` means material removed (the point touches later).
Contributions add up:

* **each gear's flank modifications** (:mod:`pipeline.contact.modifications`): tip and
  root relief, profile crowning and slope, lead crowning, end reliefs, helix slope, twist
  and a topography grid, given per gear (``[pinion.modifications]``,
  ``[gear.modifications]``), each evaluated at the gear's own roll length and face
  position of the point and summed.
* The **short form** of ``[contact]`` is read into the same per-gear model: ``tip relief``
  of the pinion (at the end of the path, ``s_end``) and of the gear (at its start,
  ``s_start``): amount ``C_a`` at the tip, falling to zero over the roll length ``L_a``
  along the path (``s``), linearly or parabolically: ``C_a ((s - (s_end - L_a)) /
  L_a)^e`` with ``e = 1`` or 2 (pinion; mirrored for the gear). Pinion driving or not,
  the pinion tip is at ``s_end``. **Lead crowning** ``C_b`` (the sum of both gears, given
  to the pinion): ``C_b (2 z / b - 1)^2``, zero at mid face, ``C_b`` at both faces.
  **Helix slope deviation / misalignment** ``f_Hb`` over the face width (the pinion's):
  ``f_Hb (z / b - 1/2)``, positive when the gap opens towards ``z = b``; both over the
  mesh's common face width ``b``.
* **pitch errors**: a constant offset per tooth pair, ``pitch_errors[j]`` for the
  tooth pair with index ``k = j`` (``k = 0`` is the pair that enters contact at
  the start of the analysed mesh cycle (pinion driving; with the gear driving it
  is the pair about to leave), ``k = 1`` the one a base pitch further along ``s``;
  see :meth:`GearPair.pair_indices`); pairs without an entry get 0. Positive: the
  flank lies behind its nominal position. Only the first :func:`meshing_pairs` entries
  can act: the later pairs never touch during the analysed cycle.

Beyond the path of contact (the tip zones of
:func:`pipeline.contact.source.candidate_zone`) a pair touches at a tip corner: its gap
is the rigid gap of the corner to the mate's flank
(:func:`pipeline.geometry.tip_contact.tip_contact`, along the contact normal) plus the
corner gear's tip relief at its tip (the full amount ``C_a``) and the lead and pitch terms
above; the mate's flank point there lies near its root, where no tip relief acts.

Centre-distance assembly errors do not appear here: an involute pair stays
conjugate when its centres move in the plane, so they change the path of contact
(use the actual pair of :class:`pipeline.geometry.assembly_errors.AssembledPair`
for the compliance source) and shift the cycle's phase, not the gaps. Profile
shift acts the same way, through the gear geometry.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from pipeline.contact.modifications import (
    GearModification,
    LeadModification,
    ProfileModification,
    flank_frames,
    modification_gap,
)
from pipeline.contact.source import ContactPoints, candidate_range
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import tip_contact
from pipeline.validation import InputError, check_choice, check_range

_MAX_MOD = 1e-3  # m: modifications above 1 mm are input mistakes (units), not designs


@dataclass(frozen=True)
class FlankModifications:
    """Flank modifications and errors that open initial gaps (all SI, m).

    Attributes
    ----------
    tip_relief_pinion, tip_relief_gear : C_a at the tip, m, in [0, 1e-3].
    relief_length_pinion, relief_length_gear : L_a, roll length along the path of
        contact over which the relief acts, m; > 0 when the amount is > 0 and at
        most the path length (checked against the pair in :func:`initial_separations`).
    relief_shape : "linear" or "parabolic".
    crowning : lead crowning C_b, m, in [0, 1e-3].
    slope_deviation : helix slope deviation / misalignment f_Hb across the face, m,
        in [-1e-3, 1e-3].
    pitch_errors : offsets of tooth pairs k = 0, 1, 2, ..., m, each in [-1e-3, 1e-3].
    lead_gap : a gap across the face tabulated as ((z_0, g_0), (z_1, g_1), ...), z in m from
        the face's first end (ascending), g in m (magnitude <= 1e-3), linear between points
        and constant beyond them: the relative displacement of the flanks along the line of
        action that the shafts' deflection causes (:mod:`pipeline.shaft`); empty: none.
    pinion_flank, gear_flank : each gear's modifications
        (:class:`~pipeline.contact.modifications.GearModification`), or None; not together
        with the short form above (tip reliefs, crowning, slope deviation).
    """

    tip_relief_pinion: float = 0.0
    relief_length_pinion: float = 0.0
    tip_relief_gear: float = 0.0
    relief_length_gear: float = 0.0
    relief_shape: str = "linear"
    crowning: float = 0.0
    slope_deviation: float = 0.0
    pitch_errors: tuple[float, ...] = ()
    lead_gap: tuple[tuple[float, float], ...] = ()
    pinion_flank: GearModification | None = None
    gear_flank: GearModification | None = None

    def __post_init__(self) -> None:
        for who in ("pinion", "gear"):
            amount = getattr(self, f"tip_relief_{who}")
            length = getattr(self, f"relief_length_{who}")
            check_range(f"contact.tip_relief_{who}", amount, 0.0, _MAX_MOD, unit="m")
            # at most the path of contact: checked against the pair (check_fits)
            check_range(f"contact.relief_length_{who}", length, 0.0, math.inf, unit="m")
            if amount > 0.0 and length == 0.0:
                raise InputError(f"contact.relief_length_{who} = 0 m: contact.tip_relief_{who} "
                                 f"= {amount:.6g} m needs a relief length > 0 m")
        check_choice("contact.relief_shape", self.relief_shape, ("linear", "parabolic"))
        check_range("contact.crowning", self.crowning, 0.0, _MAX_MOD, unit="m")
        check_range("contact.slope_deviation", self.slope_deviation, -_MAX_MOD, _MAX_MOD, unit="m")
        errs = tuple(float(e) for e in self.pitch_errors)
        for j, e in enumerate(errs):
            check_range(f"contact.pitch_errors[{j}]", e, -_MAX_MOD, _MAX_MOD, unit="m")
        object.__setattr__(self, "pitch_errors", errs)
        table = tuple((float(z), float(g)) for z, g in self.lead_gap)
        for j, (z, g) in enumerate(table):
            check_range(f"contact.lead_gap[{j}]", g, -_MAX_MOD, _MAX_MOD, unit="m")
            if j and z <= table[j - 1][0]:
                raise InputError(f"contact.lead_gap[{j}]: face positions must ascend "
                                 f"({z:.6g} m after {table[j - 1][0]:.6g} m)")
        object.__setattr__(self, "lead_gap", table)
        if self.has_short_form and (self.pinion_flank is not None
                                    or self.gear_flank is not None):
            raise InputError("contact.tip_relief_*, contact.crowning and contact."
                             "slope_deviation are the short form of the gears' modifications: "
                             "give them there (pinion.modifications, gear.modifications) "
                             "instead")

    @property
    def has_short_form(self) -> bool:
        """The tip reliefs, crowning or slope deviation of the short form are given."""
        return bool(self.tip_relief_pinion or self.tip_relief_gear or self.crowning
                    or self.slope_deviation)

    @cached_property
    def flanks(self) -> tuple[GearModification, GearModification]:
        """The pinion's and the gear's modifications: given, or read from the short form
        (tip reliefs by roll length; crowning and slope deviation on the pinion)."""
        if not self.has_short_form:
            return (self.pinion_flank or GearModification(),
                    self.gear_flank or GearModification())
        out = []
        for who in ("pinion", "gear"):
            amount = getattr(self, f"tip_relief_{who}")
            length = getattr(self, f"relief_length_{who}") if amount else None
            profile = ProfileModification(tip_relief=amount, tip_relief_length=length,
                                          tip_relief_shape=self.relief_shape)
            lead = (LeadModification(crowning=self.crowning, slope=self.slope_deviation,
                                     common_width=True)
                    if who == "pinion" else LeadModification())
            out.append(GearModification(profile=profile, lead=lead))
        return out[0], out[1]

    def check_fits(self, pair: GearPair, mesh: str = "") -> None:
        """Refuse a relief length longer than the path of contact of ``pair`` (named
        ``mesh`` in the message when given), and each gear's modifications outside its
        active flank or face (:meth:`GearModification.check_fits`)."""
        where = f" of the {mesh} mesh" if mesh else ""
        for who in ("pinion", "gear"):
            check_range(f"contact.relief_length_{who}", getattr(self, f"relief_length_{who}"),
                        0.0, pair.path_length, unit="m", note=f"the path of contact{where}")
        for mod, frame in zip(self.flanks, flank_frames(pair), strict=True):
            mod.check_fits(frame, mesh)

    @property
    def varies_across_face(self) -> bool:
        """A lead modification, a twist, a topography varying along the face or a lead gap:
        the gap changes along the face, so even a spur pair's line load does (the solve
        needs slices across the face)."""
        return bool(any(m.varies_across_face for m in self.flanks)
                    or (self.lead_gap and len({g for _, g in self.lead_gap}) > 1))

    @property
    def is_zero(self) -> bool:
        return not (any(not m.is_zero for m in self.flanks) or any(self.pitch_errors)
                    or any(g for _, g in self.lead_gap))

    def describe(self, gears: tuple[str, str] = ("pinion", "gear")) -> str:
        """One line for titles and reports, in the gearbox file's units (um, mm), e.g.
        ``"tip relief pinion 15 um over 8.1 mm (linear), crowning 8 um"``, or ``"none"``;
        ``gears`` names the pinion's and the gear's flanks (a planetary mesh: its gears)."""
        given = [f"{who}: {text}" for who, m in zip(gears, self.flanks, strict=True)
                 if not self.has_short_form and (text := m.describe())]
        parts = ["; ".join(given)] if given else []
        parts += [f"tip relief {who} {amount * 1e6:.3g} um over {length * 1e3:.3g} mm "
                 f"({self.relief_shape})"
                 for who, amount, length in (
                     ("pinion", self.tip_relief_pinion, self.relief_length_pinion),
                     ("gear", self.tip_relief_gear, self.relief_length_gear)) if amount]
        if self.crowning:
            parts.append(f"crowning {self.crowning * 1e6:.3g} um")
        if self.slope_deviation:
            parts.append(f"helix slope deviation {self.slope_deviation * 1e6:.3g} um")
        if any(self.pitch_errors):
            parts.append("pitch errors " + "/".join(f"{e * 1e6:.3g}" for e in self.pitch_errors)
                         + " um")
        if any(g for _, g in self.lead_gap):
            gaps = [g for _, g in self.lead_gap]
            parts.append(f"shaft misalignment {min(gaps) * 1e6:.3g} to {max(gaps) * 1e6:.3g} um "
                         "across the face")
        return ", ".join(parts) or "none"


def meshing_pairs(pair: GearPair, tip_contact: bool = True) -> int:
    """Number of tooth pairs k = 0, 1, ... that can touch during the analysed mesh cycle.

    Over the cycle the leading pair's roll coordinate at z = 0 runs through
    ``s0 in [s_start, s_start + p_bt)``, and pair k lies at ``s0 + k p_bt + z tan(beta_b)``
    for z in [0, b], so its smallest roll coordinate is ``s_start + k p_bt``: it meets the
    path of contact ``[s_start, s_end]`` exactly when ``k p_bt < g_alpha``, i.e.
    ``k < epsilon_alpha``, for spur and helical pairs alike; with ``tip_contact`` it can
    touch at the pinion's tip corner up to the end of the tip zone ``s_hi``
    (:func:`pipeline.contact.source.candidate_range`), i.e. when ``k p_bt < s_hi -
    s_start`` (:func:`reach_in_pitches`). The entries of ``FlankModifications.pitch_errors``
    from there on change nothing. (Pairs k < 0, a helical pair's through the far face end
    and the pair touching at the gear's tip corner before the path, have no entry and get
    0.)
    """
    return max(1, math.ceil(reach_in_pitches(pair, tip_contact) - 1e-9))


def reach_in_pitches(pair: GearPair, tip_contact: bool = True) -> float:
    """How far a tooth pair can touch beyond the start of the path of contact, in base
    pitches: the transverse contact ratio, or with ``tip_contact`` the path and the tip
    zone past its end over ``p_bt``."""
    hi = candidate_range(pair, tip_contact)[1]
    return (hi - pair.s_start) / pair.base_pitch


def initial_separations(pair: GearPair, points: ContactPoints, mods: FlankModifications,
                        zone: tuple[float, float] | None = None) -> np.ndarray:
    """Initial gaps ``eps`` (m, shape (n,)) of the candidate points (module docstring).

    Points beyond the path of contact are tip corners (module docstring): their rigid
    corner gap is added; points outside ``[s_lo, s_hi]`` (``zone``, the path itself when
    None) get ``+inf`` (out of mesh).
    """
    mods.check_fits(pair)
    s, z = points.s, points.z
    on_path = np.clip(s, pair.s_start, pair.s_end)  # a corner has its tip's relief
    eps = modification_gap(pair, on_path, z, mods.flanks)
    if mods.lead_gap:
        zs, gs = np.array(mods.lead_gap).T
        eps = eps + np.interp(z, zs, gs)
    if mods.pitch_errors:
        table = np.asarray(mods.pitch_errors)
        k = points.pair
        ok = (k >= 0) & (k < table.size)
        eps = eps + np.where(ok, table[np.clip(k, 0, table.size - 1)], 0.0)
    tol = 1e-12 * max(abs(pair.s_end), 1.0)
    lo, hi = (pair.s_start, pair.s_end) if zone is None else zone
    beyond = (s < pair.s_start - tol) | (s > pair.s_end + tol)
    if beyond.any():
        eps = eps + np.where(beyond, tip_contact(pair, s).gap, 0.0)
    inside = (s >= lo - tol) & (s <= hi + tol)
    return np.where(inside, eps, np.inf)
