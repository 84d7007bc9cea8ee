"""Per-tooth manufacturing errors of both gears and the gaps they open at each tooth pair.

Each gear may carry single pitch deviations (one per tooth) and a runout given as the
eccentricity of its teeth about its axis of rotation. They act over a whole revolution
(:mod:`pipeline.contact.revolution`), unlike ``FlankModifications.pitch_errors``, which
offsets the tooth pairs of one mesh cycle.

Tooth numbering. The teeth of each gear are numbered 0, 1, ..., z - 1 in the order they
reach the start of the path of contact ``s_start`` as the roll coordinate grows (pinion
driving: the order they come into mesh). Tooth 0 of both gears forms the tooth pair
``k = 0`` at the first position of the revolution. Tooth pair ``k`` of mesh cycle ``c``
(:meth:`~pipeline.geometry.pair.GearPair.pair_indices`: pair ``k`` touches at
``s0 + k p_bt``) is the ``n = c - k``-th pair to mesh, made of pinion tooth ``n mod z1``
and gear tooth ``n mod z2`` (after one mesh cycle pair ``k`` has become pair ``k + 1``).

Sign. Every error is given for the loaded flanks, positive when it removes material: the
flank lies behind its nominal position, away from its mate, so its pair touches later
(the gap along the line of action grows), as for the initial separations of
:mod:`pipeline.contact.separations`.

Pitch deviations (ISO 1328-1). ``f_pt,i`` (tooth i, m) is the single pitch deviation: the
actual minus the theoretical transverse pitch, on the reference circle, between the
loaded flank of tooth ``i - 1`` and that of tooth ``i`` (tooth ``-1`` is tooth ``z - 1``);
positive: tooth ``i``'s flank lies further back. The cumulative pitch deviation of tooth
``i`` from tooth 0 is ``F_p,i = sum_{j=1..i} f_pt,j`` (ISO 1328-1's F_pk over ``i``
pitches). The deviations of a whole gear close the circle, ``sum_i f_pt,i = 0``; a list
that sums to more than :data:`CLOSURE_TOLERANCE` (rounding of measured values) is
refused, a smaller remainder is spread evenly over the teeth (its mean is subtracted).
A tooth displaced by ``F_p`` along the reference circle (radius ``r``) is the tooth turned
by ``F_p / r``, which moves its involute along its normal, the line of action, by
``r_b F_p / r = F_p cos(alpha_t)``: the gap of a tooth pair grows by
``(F_p,1(pinion tooth) + F_p,2(gear tooth)) cos(alpha_t)``, constant while the pair is
in mesh (a rigid offset of that pair).

Eccentricity. The teeth of a gear are centred ``e`` (m) away from its axis of rotation: a
rigid translation ``d`` of every tooth, which turns with the gear. An involute flank
moved by ``d`` moves along its normal by ``d . n``, and every flank point on the line of
action has the same normal ``n`` (the line of action's direction), so at an instant all
tooth pairs in mesh get the same gap ``d . n``; the component of ``d`` across the line of
action slides the flanks along themselves (no gap). Let ``n_g`` be the unit vector along
the line of action pointing from the mate's flank into gear ``g``'s loaded flank (the
"behind" direction) and ``u_g`` the vector ``n_g`` turned by 90 deg against the gear's
sense of rotation. The phase ``phi_g`` is the angle of the eccentricity (from the axis to
the centre of the teeth) from ``u_g`` at the first position, measured in the gear's sense
of rotation; after the gear has turned by ``theta_g`` the eccentricity lies at
``phi_g + theta_g`` from ``u_g`` and its projection on ``n_g`` (90 deg from ``u_g``) is
the gap

    g_g(theta_g) = e_g cos(phi_g + theta_g - 90 deg) = e_g sin(phi_g + theta_g),

with ``theta_1 = (s0 - s0_first) / r_b1`` and ``theta_2 = (s0 - s0_first) / r_b2`` for
the unrolled roll coordinate ``s0``. Angles, like the tooth numbers, grow with the roll
coordinate: with the pinion driving that is the sense of rotation in time; with the gear
driving the mesh runs through ``s`` backwards in time (the pair ``k = 0`` is the one about
to leave), so the revolution is read backwards and "the sense of rotation" above is the
one in which ``s`` grows. ``phi_g = 90 deg``: at the first position the teeth
of gear ``g`` lie ``e_g`` behind along the line of action (the gap is largest).

The same translation moves the gear's centre of teeth, and so the centre distance. In the
plane of the pinion-driving picture (pinion centre at the origin, gear centre at ``(0, a)``,
the line of action from ``T1 = r_b1 (sin alpha_wt, cos alpha_wt)`` towards the gear along
``t = (-cos alpha_wt, sin alpha_wt)``, the pinion turning counter-clockwise, the gear
clockwise): ``n_1 = -t``, ``n_2 = t``, ``u_1 = u_2 = (-sin alpha_wt, -cos alpha_wt)``, and
the centre distance grows by the eccentricity's component along the line of centres away
from the mate,

    delta_a_1 = e_1 cos(phi_1 + theta_1 - alpha_wt),
    delta_a_2 = -e_2 cos(phi_2 + theta_2 + alpha_wt)

(:func:`centre_distance_change`; check: ``phi_g + theta_g = 90 deg``, the teeth ``e_g``
behind along the line of action, gives ``delta_a_g = e_g sin(alpha_wt)``, the centre line's
share of that translation). With the gear driving the same holds in the mirror image in
which ``s`` grows. A changed centre distance ``a' = a + delta_a`` changes the operating
pressure angle (``cos alpha' = (r_b1 + r_b2) / a'``), the base tangent points and so the
path of contact (its ends, where the tip circles cut the line of action: ``s_end`` stays
``sqrt(r_a1^2 - r_b1^2)`` from ``T1``, ``T1 T2`` grows by about ``delta_a / sin(alpha_wt)``)
and the contact ratio (about ``-delta_a / (p_bt sin(alpha_wt))``: -0.33 % for 10 um on the
demo pair, ``p_bt = 8.86 mm``). It also turns ``T1`` about the pinion's axis by
``alpha' - alpha_wt``. The component of the translation across the line of centres,
``d_x`` in that picture (``d_1x = e_1 sin(phi_1 + theta_1 - alpha_wt)``, ``d_2x = -e_2
sin(phi_2 + theta_2 + alpha_wt)``), turns the line of centres, and the line of action with
it, by ``delta = (d_2x - d_1x) / a`` (:func:`centre_line_turn`), towards the side where
``T1`` lies for ``delta > 0``. At a given pinion angle the contact then lies
``r_b1 (delta + alpha' - alpha_wt)`` further along the path (:func:`roll_shift`, as
``AssembledPair.roll_offset`` of :mod:`pipeline.geometry.assembly_errors`): the pinion's
involute is where it was, its base tangent point has turned. Both the new path and this
shift modulate the mesh harmonics once per revolution: sidebands at the mesh orders +- 1
(:mod:`pipeline.contact.revolution` solves each mesh cycle on the pair at its centre
distance). The gap ``g_g`` above already holds the rigid part of both: with ``n_1 = (cos
alpha_wt, -sin alpha_wt)``, ``d . n_1 = d_x cos(alpha_wt) - d_y sin(alpha_wt)``, where
``-d_y sin(alpha_wt) = delta_a sin(alpha_wt)`` is the change of one flank's backlash
and (for the pinion) ``d_1x cos(alpha_wt) = -(r_b1 + r_b2) delta`` the gear's turn that
keeps the flanks together while both base tangent points turn with the line of centres.
The pair at ``a'`` at positions moved by the roll shift is thus the eccentric gear's
instantaneous geometry to first order in ``e``. A measured cumulative pitch deviation of
an eccentric gear already contains its eccentricity's sinusoid: give one or the other.

Beyond the path of contact a pair touches at a tip corner along the mate's flank normal
(:mod:`pipeline.geometry.tip_contact`), off the line of action: turning gear ``g`` by
``delta_g / r_bg`` closes that gap by ``a_g delta_g``, with ``a_g`` the distance of the
normal from gear ``g``'s centre over ``r_bg`` (``TipContact.lever_pinion``,
``lever_gear``; 1 on the path). Both errors of gear ``g`` enter a corner's gap as such a
turn, ``a_g`` times their gap on the path (for the eccentricity this leaves out the
component across the line of action, of first order in the angle between the corner's
normal and the line of action).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError, check_choice, check_range

SPANS = ("hunting", "pinion", "gear")
"""How far the full-revolution contact runs: the hunting cycle (LCM(z1, z2) mesh cycles,
every tooth of one gear against every tooth of the other it meets), or one revolution of
the pinion (z1 mesh cycles) or of the gear (z2)."""
CLOSURE_TOLERANCE = 0.5e-6
"""Largest |sum of the single pitch deviations| of a gear, m, accepted as rounding."""
_MAX_ERROR = 1e-3  # m: deviations above 1 mm are unit mistakes, not gears


@dataclass(frozen=True)
class GearErrors:
    """Manufacturing errors of one gear's teeth (SI; module docstring for the signs).

    Attributes
    ----------
    pitch_deviations : single pitch deviations f_pt of teeth 0 .. z - 1, m, each of
        magnitude <= 1e-3; empty: none. Summing to 0 within :data:`CLOSURE_TOLERANCE`.
    eccentricity : e, m, in [0, 1e-3].
    eccentricity_phase : phi, rad, in [-2 pi, 2 pi].
    name : the gear's role in messages ("pinion", "gear").
    """

    pitch_deviations: tuple[float, ...] = ()
    eccentricity: float = 0.0
    eccentricity_phase: float = 0.0
    name: str = "gear"

    def __post_init__(self) -> None:
        dev = tuple(float(v) for v in self.pitch_deviations)
        key = f"contact.errors.single_pitch_{self.name}"
        for i, v in enumerate(dev):
            check_range(f"{key}[{i}]", v, -_MAX_ERROR, _MAX_ERROR, unit="m")
        total = sum(dev)
        if abs(total) > CLOSURE_TOLERANCE:
            raise InputError(f"{key} sums to {total * 1e6:.4g} um: the single pitch deviations "
                             "of a gear close its circle and sum to 0 (ISO 1328-1); allowed "
                             f"|sum| <= {CLOSURE_TOLERANCE * 1e6:g} um (rounding)")
        object.__setattr__(self, "pitch_deviations", dev)
        check_range(f"contact.errors.eccentricity_{self.name}", self.eccentricity, 0.0,
                    _MAX_ERROR, unit="m")
        check_range(f"contact.errors.eccentricity_phase_{self.name}", self.eccentricity_phase,
                    -2.0 * math.pi, 2.0 * math.pi, unit="rad")

    def check_teeth(self, teeth: int) -> None:
        """Refuse a list of pitch deviations whose length is not the gear's tooth count."""
        n = len(self.pitch_deviations)
        if n and n != teeth:
            raise InputError(f"contact.errors.single_pitch_{self.name} has {n} entries; "
                             f"the {self.name} has {teeth} teeth (one deviation per tooth)")

    @property
    def is_zero(self) -> bool:
        return not (any(self.pitch_deviations) or self.eccentricity)

    def cumulative(self, teeth: int) -> np.ndarray:
        """F_p of teeth 0 .. z - 1 from tooth 0, m, along the reference circle (module
        docstring: the mean of f_pt removed); zeros without pitch deviations."""
        if not self.pitch_deviations:
            return np.zeros(teeth)
        self.check_teeth(teeth)
        f = np.asarray(self.pitch_deviations)
        f = f - f.mean()
        return np.concatenate(([0.0], np.cumsum(f[1:])))

    def runout_gap(self, theta: np.ndarray) -> np.ndarray:
        """``e sin(phi + theta)``, m: the gap the eccentricity opens at rotation ``theta``
        (rad) of the gear from the first position."""
        return self.eccentricity * np.sin(self.eccentricity_phase + np.asarray(theta))


@dataclass(frozen=True)
class ToothErrors:
    """Errors of both gears and how far the full-revolution contact runs.

    Attributes
    ----------
    pinion, gear : each gear's errors.
    span : one of :data:`SPANS`.
    """

    pinion: GearErrors = field(default_factory=lambda: GearErrors(name="pinion"))
    gear: GearErrors = field(default_factory=lambda: GearErrors(name="gear"))
    span: str = "hunting"

    def __post_init__(self) -> None:
        check_choice("contact.errors.span", self.span, SPANS)

    @property
    def is_zero(self) -> bool:
        return self.pinion.is_zero and self.gear.is_zero

    def check_pair(self, pair: GearPair) -> None:
        """Refuse pitch deviation lists that do not have one entry per tooth of ``pair``."""
        self.pinion.check_teeth(pair.pinion.teeth)
        self.gear.check_teeth(pair.gear.teeth)

    def mesh_cycles(self, pair: GearPair) -> int:
        """Mesh cycles of the span: LCM(z1, z2), z1 or z2."""
        z1, z2 = pair.pinion.teeth, pair.gear.teeth
        return {"hunting": math.lcm(z1, z2), "pinion": z1, "gear": z2}[self.span]


def pair_teeth(pair: GearPair, cycle: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Pinion and gear tooth of tooth pair ``k`` in mesh cycle ``cycle`` (module docstring:
    the ``n = cycle - k``-th pair to mesh), int arrays of the broadcast shape."""
    n = np.asarray(cycle) - np.asarray(k)
    return np.mod(n, pair.pinion.teeth), np.mod(n, pair.gear.teeth)


def tooth_offsets(pair: GearPair, errors: ToothErrors) -> tuple[np.ndarray, np.ndarray]:
    """Gap along the line of action of each pinion tooth and each gear tooth from its
    cumulative pitch deviation, m, shapes (z1,) and (z2,): ``F_p cos(alpha_t)`` (module
    docstring)."""
    cos_at = pair.pinion.base_radius / pair.pinion.reference_radius
    return (errors.pinion.cumulative(pair.pinion.teeth) * cos_at,
            errors.gear.cumulative(pair.gear.teeth) * cos_at)


def pitch_gaps(pair: GearPair, errors: ToothErrors, cycle: int | np.ndarray,
               k: np.ndarray, offsets: tuple[np.ndarray, np.ndarray] | None = None
               ) -> tuple[np.ndarray, np.ndarray]:
    """Gaps along the line of action of tooth pair ``k`` in mesh cycle ``cycle`` from the
    cumulative pitch deviations of its pinion tooth and of its gear tooth, m
    (``offsets``: :func:`tooth_offsets`, computed when None)."""
    i1, i2 = pair_teeth(pair, cycle, k)
    o1, o2 = tooth_offsets(pair, errors) if offsets is None else offsets
    return o1[i1], o2[i2]


def runout_gaps(pair: GearPair, errors: ToothErrors,
                roll: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Gaps along the line of action from the pinion's and the gear's eccentricity at the
    unrolled roll distance ``roll`` (m) from the first position, m (the same for every
    pair on the line of action at an instant; module docstring)."""
    roll = np.asarray(roll, dtype=float)
    return (errors.pinion.runout_gap(roll / pair.pinion.base_radius),
            errors.gear.runout_gap(roll / pair.gear.base_radius))


def centre_distance_change(pair: GearPair, errors: ToothErrors,
                           roll: np.ndarray) -> np.ndarray:
    """Change of the centre distance from both eccentricities at the unrolled roll distance
    ``roll`` (m) from the first position, m: ``e_1 cos(phi_1 + theta_1 - alpha_wt) - e_2
    cos(phi_2 + theta_2 + alpha_wt)`` (module docstring)."""
    roll = np.asarray(roll, dtype=float)
    alpha = pair.operating_pressure_angle
    p, g = errors.pinion, errors.gear
    return (p.eccentricity * np.cos(p.eccentricity_phase + roll / pair.pinion.base_radius - alpha)
            - g.eccentricity * np.cos(g.eccentricity_phase + roll / pair.gear.base_radius
                                      + alpha))


def centre_line_turn(pair: GearPair, errors: ToothErrors, roll: np.ndarray) -> np.ndarray:
    """Turn of the line of centres from both eccentricities at the unrolled roll distance
    ``roll`` (m) from the first position, rad, positive in the sense in which ``T1`` lies
    from the line of centres: ``(d_2x - d_1x) / a`` with ``d_1x = e_1 sin(phi_1 + theta_1 -
    alpha_wt)`` and ``d_2x = -e_2 sin(phi_2 + theta_2 + alpha_wt)`` (module docstring)."""
    roll = np.asarray(roll, dtype=float)
    alpha = pair.operating_pressure_angle
    p, g = errors.pinion, errors.gear
    d1 = p.eccentricity * np.sin(p.eccentricity_phase + roll / pair.pinion.base_radius - alpha)
    d2 = -g.eccentricity * np.sin(g.eccentricity_phase + roll / pair.gear.base_radius + alpha)
    return (d2 - d1) / pair.operating_centre_distance


def roll_shift(nominal: GearPair, actual: GearPair, turn: float = 0.0) -> float:
    """How much further along the path of contact ``actual`` (the pair at another centre
    distance, its line of centres turned by ``turn``, rad, :func:`centre_line_turn`) touches
    than ``nominal`` at the same pinion angle, m: ``r_b1 (turn + alpha' - alpha_wt)``, the
    turn of the base tangent point ``T1`` (module docstring)."""
    return nominal.pinion.base_radius * (turn + actual.operating_pressure_angle
                                         - nominal.operating_pressure_angle)
