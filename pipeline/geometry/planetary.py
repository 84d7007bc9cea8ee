"""Planetary sets: planet positions, assembly condition and meshing phases (Xu et al. 2020).

Phases are fractions of one mesh period ``T_m = 2 pi / ((omega_s - omega_c) z_s)``
(Xu et al. 2020, eq. 7), in [0, 1):

* ``lambda_sn = dec(+- z_s psi_n / 2 pi)`` - sun-planet mesh n relative to mesh 1 (eq. 10a);
* ``lambda_rn = dec(+- z_r psi_n / 2 pi)`` - ring-planet mesh n relative to mesh 1 (eq. 10b);
* ``lambda_rs`` - ring-planet mesh relative to the sun-planet mesh of the same planet
  (eq. 10c), see :meth:`PlanetarySet.ring_sun_phase`;
* ``lambda_LR = dec(z_s phi_LR / 2 pi)`` - right sun-planet mesh relative to the left one of a
  herringbone sun twisted by ``phi_LR`` across its relief groove (eq. 11).

``dec`` is the fractional part. The sign is ``+`` when the sun turns
counter-clockwise relative to the carrier (planet angles ``psi_n`` counted
counter-clockwise from planet 1) and ``-`` otherwise (``direction`` below).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import cached_property

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError, check_int_range, check_range

BACKLASH_TOLERANCE = 2e-4
"""Interference a planetary mesh may have, over m_n: what rounding the profile shifts to
4 decimals changes the tooth thicknesses by (2 tan(alpha_n) x 1e-4 m_n for the two gears of a
mesh, at most 1.4e-4 m_n up to alpha_n = 35 deg), with a margin: 0.6 um at m_n = 3 mm."""


def dec(x: np.ndarray | float) -> np.ndarray:
    """Fractional part in [0, 1) (robust to round-off just below an integer)."""
    f = np.mod(np.asarray(x, dtype=float), 1.0)
    return np.where(np.isclose(f, 1.0, atol=1e-12), 0.0, f)


@dataclass(frozen=True)
class PlanetarySet:
    """Sun, N identical planets and a ring.

    Attributes
    ----------
    sun, planet, ring : the gears (ring internal). Normal module, pressure and helix
        angle must agree; the sun-planet and planet-ring centre distances must match.
    n_planets : N (>= 1).
    planet_angles : optional angles psi_n of the planets (rad, planet 1 at 0);
        default: equally spaced.
    direction : +1 when the sun turns counter-clockwise relative to the carrier, -1 otherwise.
    centre_distance : the carrier radius a_w in m, the operating centre distance of both
        meshes, from which each mesh's operating pressure angle and backlash follow; ``None``
        takes the mean of the two meshes' zero-backlash distances (ISO 21771), allowed only
        when they agree to within :data:`BACKLASH_TOLERANCE` of backlash.

    Either way each mesh's circular backlash (:attr:`GearPair.circular_backlash`) is at least
    ``-BACKLASH_TOLERANCE m_n``: interference beyond it is refused, naming the mesh.
    """

    sun: GearSpec
    planet: GearSpec
    ring: GearSpec
    n_planets: int
    planet_angles: tuple[float, ...] | None = None
    direction: int = 1
    centre_distance: float | None = None

    def __post_init__(self) -> None:
        check_int_range("planetary.n_planets", self.n_planets, 1, 64)
        if not self.ring.internal:
            raise InputError("ring.internal = false: the ring of a planetary set must be internal")
        if self.sun.internal or self.planet.internal:
            raise InputError("sun and planet must be external gears")
        if self.direction not in (1, -1):
            raise InputError(f"planetary.direction = {self.direction!r} is not one of +1, -1")
        if self.centre_distance is None:
            self._check_zero_backlash_distances()
        for name, pair, fix in (("sun-planet", self.sun_planet, "enlarge"),
                                ("planet-ring", self.planet_ring, "reduce")):
            j = pair.circular_backlash
            if j < -BACKLASH_TOLERANCE * self.sun.module:
                raise InputError(
                    f"{name} mesh: circular backlash {j * 1e6:.4g} um at the carrier radius "
                    f"{self.carrier_radius * 1e3:.6g} mm is an interference beyond the allowed "
                    f"{BACKLASH_TOLERANCE * self.sun.module * 1e6:.3g} um (profile shifts "
                    f"{pair.pinion.name} {pair.pinion.profile_shift}, {pair.gear.name} "
                    f"{pair.gear.profile_shift}); {fix} planetary.centre_distance_mm or "
                    "change the shifts"
                )
        ang = self.angles
        if len(ang) != self.n_planets:
            raise InputError(
                f"planetary.planet_angles has {len(ang)} values: give one per planet "
                f"(planetary.n_planets = {self.n_planets})"
            )
        for i, a in enumerate(ang):  # within one turn either way
            check_range(f"planetary.planet_angles[{i}]", a, -2 * math.pi, 2 * math.pi,
                        unit="rad")
        turns = (self.sun.teeth + self.ring.teeth) * ang / (2 * math.pi)
        bad = np.abs(turns - np.round(turns)) > 1e-6
        if np.any(bad):
            n = int(np.argmax(bad))
            raise InputError(
                f"planet {n + 1} at {math.degrees(ang[n]):.6g} deg cannot be assembled: "
                f"(z_s + z_r) psi / 360 deg = {turns[n]:.6g} must be a whole number "
                f"(z_s + z_r = {self.sun.teeth + self.ring.teeth}, n_planets = {self.n_planets})"
            )
        # planets must not overlap: tip circles closer than the centre spacing
        if self.n_planets > 1:
            gaps = np.diff(np.concatenate([np.sort(ang), [np.sort(ang)[0] + 2 * math.pi]]))
            chord = 2 * self.carrier_radius * math.sin(gaps.min() / 2)
            if chord <= 2 * self.planet.tip_radius_:
                raise InputError(
                    f"planets overlap: neighbouring planet centres are {chord * 1e3:.4g} mm "
                    "apart, "
                    f"less than the planet tip diameter {2e3 * self.planet.tip_radius_:.4g} mm "
                    + (f"(n_planets = {self.n_planets} is too many)" if self.planet_angles is None
                       else "(planet_angles put neighbours too close)")
                )

    def _check_zero_backlash_distances(self) -> None:
        """Without a carrier radius the two meshes' zero-backlash distances must agree."""
        a_sp, a_pr = self.zero_backlash_distances
        mean = 0.5 * (a_sp + a_pr)
        backlash = (GearPair(self.sun, self.planet, mean).circular_backlash,
                    GearPair(self.planet, self.ring, mean).circular_backlash)
        if max(abs(j) for j in backlash) > BACKLASH_TOLERANCE * self.sun.module:
            raise InputError(
                f"sun-planet zero-backlash centre distance {a_sp * 1e3:.6g} mm differs from "
                f"planet-ring {a_pr * 1e3:.6g} mm (ISO 21771, from the profile shifts sun "
                f"{self.sun.profile_shift}, planet {self.planet.profile_shift}, ring "
                f"{self.ring.profile_shift}): give the carrier radius as "
                "planetary.centre_distance_mm, or with no profile shifts make ring.teeth = "
                f"sun.teeth + 2 planet.teeth = {self.sun.teeth + 2 * self.planet.teeth} "
                f"(ring.teeth = {self.ring.teeth})"
            )

    @cached_property
    def zero_backlash_distances(self) -> tuple[float, float]:
        """Zero-backlash centre distances (sun-planet, planet-ring) of the shifts, m."""
        return (GearPair(self.sun, self.planet).operating_centre_distance,
                GearPair(self.planet, self.ring).operating_centre_distance)

    @cached_property
    def sun_planet(self) -> GearPair:
        return GearPair(self.sun, self.planet, self.carrier_radius)

    @cached_property
    def planet_ring(self) -> GearPair:
        return GearPair(self.planet, self.ring, self.carrier_radius)

    @cached_property
    def angles(self) -> np.ndarray:
        """Planet angles psi_n, shape (N,), rad."""
        if self.planet_angles is None:
            return 2 * math.pi * np.arange(self.n_planets) / self.n_planets
        return np.asarray(self.planet_angles, dtype=float)

    @cached_property
    def carrier_radius(self) -> float:
        """Planet centre radius r_c = a_w of both meshes, m (given, or the mean of the two
        zero-backlash distances)."""
        if self.centre_distance is not None:
            return self.centre_distance
        return 0.5 * sum(self.zero_backlash_distances)

    def mesh_period(self, sun_speed: float, carrier_speed: float = 0.0) -> float:
        """T_m = 2 pi / ((omega_s - omega_c) z_s) in s (Xu et al. 2020, eq. 7); speeds in rad/s."""
        rel = abs(sun_speed - carrier_speed)
        if rel == 0:
            raise InputError("sun and carrier speeds are equal: there is no meshing")
        return 2 * math.pi / (rel * self.sun.teeth)

    @cached_property
    def sun_phases(self) -> np.ndarray:
        """lambda_sn, shape (N,) (Xu et al. 2020, eq. 10a)."""
        return dec(self.direction * self.sun.teeth * self.angles / (2 * math.pi))

    @cached_property
    def ring_phases(self) -> np.ndarray:
        """lambda_rn, shape (N,) (Xu et al. 2020, eq. 10b)."""
        return dec(self.direction * self.ring.teeth * self.angles / (2 * math.pi))

    @cached_property
    def ring_sun_phase(self) -> float:
        """lambda_rs: ring-planet mesh relative to the sun-planet mesh of the same planet.

        Both meshes are referenced to the instant a tooth pair passes its pitch
        point. The sun loads one flank of a planet tooth and the ring the other,
        on opposite sides of the planet; with ``psi_ws``, ``psi_wr`` the planet's half
        tooth angles on its two operating pitch circles, a planet tooth turns by
        ``pi - psi_ws - psi_wr`` (modulo the angular pitch) between the two pitch
        crossings, so ``lambda_rs = dec(+- z_p (psi_ws + psi_wr - pi) / 2 pi)``.
        For unshifted gears this is 0 for an odd and 1/2 for an even planet tooth count.
        """
        p = self.planet
        psi_s = p.half_tooth_angle(self.sun_planet.operating_pitch_radii[1])
        psi_r = p.half_tooth_angle(self.planet_ring.operating_pitch_radii[0])
        return float(dec(self.direction * p.teeth * (psi_s + psi_r - math.pi) / (2 * math.pi)))

    def start_of_contact_offsets(self) -> tuple[float, float]:
        """Fraction of a mesh period from start of contact to the pitch point, (s-p, r-p).

        The pipeline's stiffness curves start at the start of contact; add these to
        phases referenced to pitch-point crossings.
        """
        sp, pr = self.sun_planet, self.planet_ring
        return ((sp.s_pitch - sp.s_start) / sp.base_pitch,
                (pr.s_pitch - pr.s_start) / pr.base_pitch)

    def left_right_phase(self, twist: float) -> float:
        """lambda_LR = dec(z_s phi_LR / 2 pi) for a relative twist ``phi_LR`` (rad), eq. 11."""
        return float(dec(self.sun.teeth * twist / (2 * math.pi)))

    def summary(self) -> dict[str, object]:
        return {
            "teeth_sun_planet_ring": [self.sun.teeth, self.planet.teeth, self.ring.teeth],
            "n_planets": self.n_planets,
            "planet_angles_deg": np.degrees(self.angles).tolist(),
            "carrier_radius_m": self.carrier_radius,
            "sun_planet_backlash_m": self.sun_planet.circular_backlash,
            "planet_ring_backlash_m": self.planet_ring.circular_backlash,
            "sun_planet_contact_ratio": self.sun_planet.total_contact_ratio,
            "planet_ring_contact_ratio": self.planet_ring.total_contact_ratio,
            "lambda_sn": self.sun_phases.tolist(),
            "lambda_rn": self.ring_phases.tolist(),
            "lambda_rs": self.ring_sun_phase,
        }
