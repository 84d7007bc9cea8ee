"""A meshing pair: centre distance, operating pressure angle, contact ratios, path of contact.

The path of contact is described by the *roll coordinate* ``s`` (m): the distance
along the transverse line of action from T1, the point where it touches the
pinion's base circle. At a contact point at ``s`` the pinion's radius of
curvature is ``rho1 = s`` and the gear's is ``rho2 = T1T2 - s`` (external) or
``s + T1T2`` (internal), where ``T1T2 = a_w sin(alpha_wt)``.

When the pinion drives, contact starts at ``s_start`` (the gear's tip circle)
and moves towards ``s_end`` (the pinion's tip circle) at ``r_b1`` metres per
radian of pinion rotation, passing the pitch point ``s_pitch = r_b1 tan(alpha_wt)``.
Approach is ``s < s_pitch``, recess ``s > s_pitch`` (for either driver the
approach is the part before the pitch point in time: with the gear driving, ``s > s_pitch``).

For helical gears the plane of action is the rectangle ``[s_start, s_end] x [0, b]``
and the contact lines on it are inclined at the base helix angle: a tooth pair
whose transverse contact is at ``s0`` at face position ``z = 0`` touches at
``s0 + z tan(beta_b)`` across the face.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.involute import inv, inv_inverse
from pipeline.validation import InputError, check_range


@dataclass(frozen=True)
class GearPair:
    """Two gears in mesh; ``gear`` may be internal (ring), the pinion is always external.

    Attributes
    ----------
    pinion, gear : the two gears. They must share normal module, normal pressure
        angle and helix angle; external pairs have opposite hands, internal pairs
        the same hand.
    centre_distance : operating centre distance a_w in m; ``None`` takes the
        zero-backlash distance from the profile shifts (ISO 21771).
    """

    pinion: GearSpec
    gear: GearSpec
    centre_distance: float | None = None

    def __post_init__(self) -> None:
        p, g = self.pinion, self.gear
        if p.internal:
            raise InputError("pinion.internal = true: the pinion must be an external gear")
        for attr, unit in (("module", "m"), ("pressure_angle", "rad"), ("helix_angle", "rad")):
            if not math.isclose(getattr(p, attr), getattr(g, attr), rel_tol=1e-9, abs_tol=1e-15):
                raise InputError(
                    f"gear.{attr} = {getattr(g, attr):.6g} {unit} must equal "
                    f"pinion.{attr} = {getattr(p, attr):.6g} {unit} for the gears to mesh"
                )
        if p.is_helical:
            same = p.hand == g.hand
            if g.internal != same:
                need = "the same hand as" if g.internal else "the opposite hand to"
                raise InputError(f"gear.hand = {g.hand!r} must be {need} pinion.hand = {p.hand!r}")
        if p.herringbone != g.herringbone:
            raise InputError("pinion.herringbone and gear.herringbone must agree")
        if g.internal and g.teeth - p.teeth < 5:
            raise InputError(
                f"gear.teeth = {g.teeth} is outside the allowed range [{p.teeth + 5}, inf) for an "
                f"internal gear meshing with a {p.teeth}-tooth pinion (tip interference)"
            )
        a_min = (g.base_radius - p.base_radius) if g.internal else (p.base_radius + g.base_radius)
        if self.centre_distance is not None:
            a_ref = self.reference_centre_distance
            check_range("pair.centre_distance", self.centre_distance, a_min, a_ref * 1.2,
                        lo_open=True, unit="m")
        # Interference: contact must not run below either base circle (beyond T1 or T2).
        if self.s_start < 0.0:
            raise InputError(
                f"involute interference: the gear tip reaches past the pinion base circle "
                f"(start of contact {self.s_start * 1e3:.4g} mm before T1); increase "
                f"pinion.profile_shift = {p.profile_shift} or pinion.teeth = {p.teeth}"
            )
        if not g.internal and self.s_end > self.t1t2:
            raise InputError(
                f"involute interference: the pinion tip reaches past the gear base circle "
                f"(end of contact {(self.s_end - self.t1t2) * 1e3:.4g} mm beyond T2); increase "
                f"gear.profile_shift = {g.profile_shift} or gear.teeth = {g.teeth}"
            )
        if self.transverse_contact_ratio < 1.0 and self.overlap_ratio < 1.0:
            raise InputError(
                f"contact ratio {self.transverse_contact_ratio:.4g} is outside the allowed range "
                f"[1, inf): the gears lose contact between teeth (raise addendum_coef, teeth, or "
                f"the overlap ratio {self.overlap_ratio:.4g} above 1)"
            )

    # ---- centre distance and operating pressure angle -----------------------------------
    @property
    def sign(self) -> int:
        """+1 for an external pair, -1 for an internal pair."""
        return -1 if self.gear.internal else 1

    @cached_property
    def reference_centre_distance(self) -> float:
        """a = m_t (z2 +- z1) / 2 in m (unshifted gears, zero backlash)."""
        p, g = self.pinion, self.gear
        return p.transverse_module * (g.teeth + self.sign * p.teeth) / 2.0

    @cached_property
    def zero_backlash_pressure_angle(self) -> float:
        """alpha_wt of zero backlash from the profile shifts (ISO 21771), rad.

        ISO 21771 writes one relation for both kinds with a negative tooth count for an
        internal gear: ``inv(alpha_wt) = inv(alpha_t) + 2 tan(alpha_n) (x1 + x2) / (z1 + z2)``.
        With the tooth counts positive, as here, that is ``(x1 + x2) / (z2 + z1)`` for an
        external pair and ``-(x1 + x2) / (z2 - z1)`` for an internal one: a positive ring
        shift (ISO 21771: the ring's teeth move towards its axis and grow thicker on the
        reference circle) pulls the pinion's centre towards the ring's, like a negative
        shift of an external gear.
        """
        p, g = self.pinion, self.gear
        at = p.transverse_pressure_angle
        num = self.sign * (g.profile_shift + p.profile_shift)
        den = g.teeth + self.sign * p.teeth
        v = float(inv(at)) + 2.0 * math.tan(p.pressure_angle) * num / den
        if v <= 0:
            sense = "positive" if g.internal else "negative"
            raise InputError(
                f"profile shifts pinion.profile_shift = {p.profile_shift}, gear.profile_shift = "
                f"{g.profile_shift} give no operating pressure angle (their sum is too {sense}: "
                f"inv(alpha_wt) = {v:.4g} <= 0)"
            )
        return float(inv_inverse(v))

    @cached_property
    def operating_centre_distance(self) -> float:
        """a_w in m (given, or zero-backlash from the profile shifts)."""
        if self.centre_distance is not None:
            return self.centre_distance
        at = self.pinion.transverse_pressure_angle
        return self.reference_centre_distance * math.cos(at) / math.cos(
            self.zero_backlash_pressure_angle
        )

    @cached_property
    def operating_pressure_angle(self) -> float:
        """alpha_wt = acos((r_b2 +- r_b1) / a_w) in rad."""
        rb = self.gear.base_radius + self.sign * self.pinion.base_radius
        return math.acos(rb / self.operating_centre_distance)

    @cached_property
    def operating_pitch_radii(self) -> tuple[float, float]:
        """Operating pitch radii (r_w1, r_w2) in m."""
        a = math.cos(self.operating_pressure_angle)
        return self.pinion.base_radius / a, self.gear.base_radius / a

    @cached_property
    def circular_backlash(self) -> float:
        """Transverse circular backlash j_wt on the operating pitch circles, m.

        ``j_wt = p_wt - s_wt1 - s_wt2``: the operating transverse pitch ``2 pi r_w1 / z1`` less
        each gear's own arc tooth thickness on its operating pitch circle,
        ``s_wti = 2 r_wi psi_i(r_wi)`` (:meth:`GearSpec.half_tooth_angle`; for a ring its tooth,
        the metal between two spaces, whose space the pinion tooth fills). Zero at the
        zero-backlash centre distance; negative where the flanks would overlap (interference).
        """
        p, g = self.pinion, self.gear
        rw1, rw2 = self.operating_pitch_radii
        s1 = 2.0 * rw1 * float(p.half_tooth_angle(rw1))
        s2 = 2.0 * rw2 * float(g.half_tooth_angle(rw2))
        return 2.0 * math.pi * rw1 / p.teeth - s1 - s2

    @cached_property
    def gear_ratio(self) -> float:
        """u = z2 / z1."""
        return self.gear.teeth / self.pinion.teeth

    # ---- path of contact -----------------------------------------------------------------
    @cached_property
    def t1t2(self) -> float:
        """Length of the transverse line of action between the base tangent points, m."""
        return self.operating_centre_distance * math.sin(self.operating_pressure_angle)

    @cached_property
    def s_end(self) -> float:
        """Roll coordinate where the pinion's involute ends on the line of action, m: its tip
        circle, or the tangency point of its tip rounding (``active_tip_radius``)."""
        p = self.pinion
        return math.sqrt(p.active_tip_radius**2 - p.base_radius**2)

    @cached_property
    def s_start(self) -> float:
        """Roll coordinate where the gear's involute ends on the line of action, m: its tip
        circle, or the tangency point of its tip rounding (``active_tip_radius``)."""
        g = self.gear
        rho2 = math.sqrt(g.active_tip_radius**2 - g.base_radius**2)
        return rho2 - self.t1t2 if g.internal else self.t1t2 - rho2

    @cached_property
    def s_pitch(self) -> float:
        """Roll coordinate of the pitch point, m."""
        return self.pinion.base_radius * math.tan(self.operating_pressure_angle)

    @cached_property
    def path_length(self) -> float:
        """Length of the path of contact g_alpha in m."""
        return self.s_end - self.s_start

    @cached_property
    def base_pitch(self) -> float:
        """Transverse base pitch p_bt in m."""
        return self.pinion.transverse_base_pitch

    @cached_property
    def transverse_contact_ratio(self) -> float:
        """epsilon_alpha = g_alpha / p_bt."""
        return self.path_length / self.base_pitch

    @cached_property
    def face_width(self) -> float:
        """Common face width in m (of one helical half for herringbone gears)."""
        return min(self.pinion.half_width, self.gear.half_width)

    @cached_property
    def overlap_ratio(self) -> float:
        """epsilon_beta = b sin(beta) / (pi m_n) (per helical half for herringbone gears)."""
        return self.face_width * math.sin(self.pinion.helix_angle) / (math.pi * self.pinion.module)

    @cached_property
    def total_contact_ratio(self) -> float:
        """epsilon_gamma = epsilon_alpha + epsilon_beta."""
        return self.transverse_contact_ratio + self.overlap_ratio

    @cached_property
    def max_pairs(self) -> int:
        """Largest number of tooth pairs that can be in contact at once."""
        return int(math.ceil(self.total_contact_ratio)) + 1

    # ---- quantities along the path -------------------------------------------------------
    def curvature_radii(self, s: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Radii of curvature (rho1, rho2) of the flanks at roll coordinate ``s`` (m).

        ``rho2`` is negative for an internal gear (concave flank).
        """
        s = np.asarray(s, dtype=float)
        rho2 = self.t1t2 - s if not self.gear.internal else -(s + self.t1t2)
        return s, rho2

    def contact_radii(self, s: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Radii (R1, R2) of the contact point on each gear at roll coordinate ``s``, m."""
        rho1, rho2 = self.curvature_radii(s)
        return (
            np.hypot(rho1, self.pinion.base_radius),
            np.hypot(rho2, self.gear.base_radius),
        )

    def pressure_angles(self, s: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Profile pressure angles (alpha1, alpha2) = atan(|rho_i| / r_bi) at ``s``, rad."""
        rho1, rho2 = self.curvature_radii(s)
        return (
            np.arctan2(np.abs(rho1), self.pinion.base_radius),
            np.arctan2(np.abs(rho2), self.gear.base_radius),
        )

    def sliding_velocity(self, s: ArrayLike, pinion_speed: float) -> np.ndarray:
        """Sliding velocity ``u1 - u2`` of the pinion flank over the gear flank, m/s.

        ``u1 = omega1 rho1`` and ``u2 = omega2 |rho2|`` are the surface velocities
        along the common tangent; the difference is ``(omega1 +- omega2)(s - s_pitch)``
        (+ external, - internal): negative in approach, zero at the pitch point.
        ``pinion_speed`` in rad/s.
        """
        u1, u2 = self.rolling_velocities(s, pinion_speed)
        return u1 - u2

    def rolling_velocities(
        self, s: ArrayLike, pinion_speed: float
    ) -> tuple[np.ndarray, np.ndarray]:
        """Tangential (rolling) surface velocities u1 = omega1 rho1 and u2 = omega2 |rho2|, m/s."""
        rho1, rho2 = self.curvature_radii(s)
        return pinion_speed * rho1, pinion_speed / self.gear_ratio * np.abs(rho2)

    # ---- contacts over the mesh cycle ----------------------------------------------------
    def pair_indices(self, beyond: bool = True) -> np.ndarray:
        """Indices k of the tooth pairs ``s0 + k p_bt`` that can touch somewhere on the face.

        For helical gears pairs behind the leading one (k < 0) reach the path of
        contact through the far end of the face, where ``s = s0 + k p_bt + b tan(beta_b)``.
        With ``beyond`` (teeth touching beyond the path of contact,
        :mod:`pipeline.geometry.tip_contact`) one more pair behind them can touch before
        the path, at the gear's tip corner; the last index, ``max_pairs - 1``, can touch
        past the path's end at the pinion's tip corner.
        """
        reach = self.face_width * math.tan(self.pinion.base_helix_angle)
        return np.arange(-int(math.ceil(reach / self.base_pitch)) - int(beyond), self.max_pairs)

    def pair_positions(self, s0: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
        """Transverse (z = 0) roll coordinates of every tooth pair that may be in contact.

        Parameters
        ----------
        s0 : shape (m,) roll coordinate of the *leading* pair at z = 0, in
            ``[s_start, s_start + p_bt)`` for one mesh cycle.

        Returns
        -------
        s : shape (m, K) roll coordinates ``s0 + k p_bt`` for k in :meth:`pair_indices`.
        in_contact : shape (m, K) bool, ``s_start <= s <= s_end`` (at z = 0).
        """
        s0 = np.asarray(s0, dtype=float)[:, None]
        s = s0 + self.pair_indices()[None, :] * self.base_pitch
        return s, (s >= self.s_start) & (s <= self.s_end)

    def mesh_cycle(self, n: int) -> np.ndarray:
        """``n`` equally spaced roll coordinates of the leading pair over one mesh cycle, m."""
        return self.s_start + self.base_pitch * np.arange(n) / n

    def is_mesh_cycle(self, s0: ArrayLike) -> bool:
        """True when the roll coordinates ``s0`` (m) are :meth:`mesh_cycle` of their count
        (to 1e-9 of a base pitch)."""
        s0 = np.asarray(s0, dtype=float)
        return bool(np.allclose(s0, self.mesh_cycle(s0.size), rtol=0.0,
                                atol=1e-9 * self.base_pitch))

    def contact_line_lengths(self, s0: ArrayLike) -> np.ndarray:
        """Length of each tooth pair's contact line on the plane of action, m.

        For helical gears the line of pair k spans ``s0 + k p_bt + z tan(beta_b)`` for
        ``z`` in ``[0, b]``, clipped to ``[s_start, s_end]``; its length is the clipped
        z-range divided by ``cos(beta_b)``. Spur gears: ``b`` while in contact.

        Returns shape (m, K) for ``s0`` of shape (m,).
        """
        s, _ = self.pair_positions(s0)
        b = self.face_width
        tb = math.tan(self.pinion.base_helix_angle)
        if tb == 0.0:
            return np.where((s >= self.s_start) & (s <= self.s_end), b, 0.0)
        z_lo = np.clip((self.s_start - s) / tb, 0.0, b)
        z_hi = np.clip((self.s_end - s) / tb, 0.0, b)
        return (z_hi - z_lo) / math.cos(self.pinion.base_helix_angle)

    def contact_lines(self, s0: float) -> list[np.ndarray]:
        """End points of the contact lines on the plane of action at one mesh position.

        Returns a list of (2, 2) arrays ``[[s_a, z_a], [s_b, z_b]]`` (m), one per tooth
        pair in contact, with ``s`` the roll coordinate and ``z`` the face position.
        """
        s, _ = self.pair_positions(np.array([s0]))
        tb = math.tan(self.pinion.base_helix_angle)
        b = self.face_width
        out = []
        for sk in s[0]:
            if tb == 0.0:
                if self.s_start <= sk <= self.s_end:
                    out.append(np.array([[sk, 0.0], [sk, b]]))
                continue
            z_lo = min(max((self.s_start - sk) / tb, 0.0), b)
            z_hi = min(max((self.s_end - sk) / tb, 0.0), b)
            if z_hi > z_lo:
                out.append(np.array([[sk + z_lo * tb, z_lo], [sk + z_hi * tb, z_hi]]))
        return out

    def summary(self) -> dict[str, float]:
        """Key pair quantities for reports (SI units; keys carry the unit)."""
        return {
            "centre_distance_m": self.operating_centre_distance,
            "operating_pressure_angle_deg": math.degrees(self.operating_pressure_angle),
            "transverse_contact_ratio": self.transverse_contact_ratio,
            "overlap_ratio": self.overlap_ratio,
            "total_contact_ratio": self.total_contact_ratio,
            "base_pitch_m": self.base_pitch,
            "path_of_contact_m": self.path_length,
            "s_start_m": self.s_start,
            "s_pitch_m": self.s_pitch,
            "s_end_m": self.s_end,
            "line_of_action_T1T2_m": self.t1t2,
            "circular_backlash_m": self.circular_backlash,
            "gear_ratio": self.gear_ratio,
        }
