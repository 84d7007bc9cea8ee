"""Zero backlash of external and internal pairs (ISO 21771), the carrier radius of planetary
sets with profile shifts, and ISO 6336-1's gear numbering whatever order the gears come in.

The ladder: exact (the circular backlash from each gear's own tooth thickness on its operating
pitch circle is zero at the zero-backlash distance; the rack-generated external profile gives
the same thickness as ISO 21771's formula), a published planetary set (Ljubljana LECAD,
"Analysis of Planetary Transmissions", test run: sun 21, planet 43, ring 108, m_n 1.75 mm,
x 0.4380 / 0.0426 / 0, a = 56.8 mm), and ISO 6336-1 eq. (98) evaluated by hand with the
standard's numbering.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import STEEL, spur

from pipeline.config import gearbox_from_text
from pipeline.geometry import GearPair, GearSpec
from pipeline.geometry.involute import inv
from pipeline.geometry.planetary import BACKLASH_TOLERANCE, PlanetarySet
from pipeline.geometry.profile import INVOLUTE, tooth_profile
from pipeline.stiffness.iso6336 import iso_gears, iso_stiffness
from pipeline.validation import InputError

D = math.radians


def ring(z: int, x: float, module: float = 3e-3, beta: float = 0.0, hand: str = "none",
         alpha: float = 20.0) -> GearSpec:
    rf = z * module / (2 * math.cos(beta)) + module * (1.25 - x)
    return GearSpec(teeth=z, module=module, pressure_angle=D(alpha), face_width=0.02,
                    helix_angle=beta, hand=hand, profile_shift=x, internal=True,
                    bore_radius=rf + 4 * module, material=STEEL, name="ring")


def iso21771_thickness(g: GearSpec, r_w: float, alpha_wt: float) -> float:
    """Transverse arc tooth thickness on the circle of radius r_w (ISO 21771), m:
    ``s_w = d_w (s / d + inv(alpha_t) - inv(alpha_wt))`` with z, d, d_w and s/d negative for an
    internal gear (so its tooth grows towards its root)."""
    sign = -1.0 if g.internal else 1.0
    s = g.transverse_module * (math.pi / 2 + 2 * g.profile_shift * math.tan(g.pressure_angle))
    d, d_w = sign * 2 * g.reference_radius, sign * 2 * r_w
    return d_w * (s / d + inv(g.transverse_pressure_angle) - inv(alpha_wt))


def profile_thickness(g: GearSpec, r: float) -> float:
    """Arc tooth thickness at radius r measured on the rack-generated profile points, m."""
    p = tooth_profile(g, points=2000)
    inv_part = p.kind == INVOLUTE
    radius = np.hypot(p.x, p.y)[inv_part]
    half = np.arctan2(p.x, p.y)[inv_part]
    return 2 * r * float(np.interp(r, radius, half))


SHIFTS = [(0.0, 0.0), (0.3, 0.2), (0.3, -0.2), (-0.2, 0.3), (0.0, 0.5), (0.4, -0.4)]


@pytest.mark.parametrize("internal", [False, True])
@pytest.mark.parametrize("helical", [False, True])
@pytest.mark.parametrize(("x1", "x2"), SHIFTS)
def test_backlash_is_zero_at_the_zero_backlash_distance(internal, helical, x1, x2):
    """ISO 21771 with a negative tooth count for the ring: at the zero-backlash distance the
    operating transverse pitch is exactly filled by the two gears' own tooth thicknesses on
    their operating pitch circles, j_wt = p_wt - s_w1 - s_w2 = 0 to 1e-9 m, for shifts of both
    signs on either gear. (With the ring's shift taken with the wrong sign, as before, the
    (0.3, 0.2) planet-ring pair had a_w 1.34 mm too large and j_wt = -0.87 mm.)"""
    beta, h1, h2 = (D(12.0), "right", "right" if internal else "left") if helical else \
        (0.0, "none", "none")
    pinion = spur(30, "planet", profile_shift=x1, bore_radius=0.01, helix_angle=beta, hand=h1)
    gear = ring(80, x2, beta=beta, hand=h2) if internal else \
        spur(45, "gear", profile_shift=x2, helix_angle=beta, hand=h2)
    pair = GearPair(pinion, gear)
    rw1, rw2 = pair.operating_pitch_radii
    awt = pair.operating_pressure_angle
    s1, s2 = iso21771_thickness(pinion, rw1, awt), iso21771_thickness(gear, rw2, awt)
    assert 2 * math.pi * rw1 / pinion.teeth - s1 - s2 == pytest.approx(0.0, abs=1e-9)
    assert pair.circular_backlash == pytest.approx(0.0, abs=1e-9)
    # the rack-generated external flank has ISO 21771's thickness (interpolated on 2000 points)
    assert profile_thickness(pinion, rw1) == pytest.approx(s1, abs=1e-8)
    # a_w moves with the shift sum: apart for an external pair, together for an internal one
    a_ref = pair.reference_centre_distance
    moved = (pair.operating_centre_distance - a_ref) * (-1.0 if internal else 1.0)
    if x1 + x2 == 0.0:
        assert moved == pytest.approx(0.0, abs=1e-15)
    else:
        assert math.copysign(1.0, moved) == math.copysign(1.0, x1 + x2)


@pytest.mark.parametrize("internal", [False, True])
def test_backlash_grows_the_right_way_off_the_zero_backlash_distance(internal):
    """Away from zero backlash, j_wt follows the involute relation exactly: at a_w with
    ``cos(alpha_wt) = a cos(alpha_t) / a_w`` the backlash is
    ``j_wt = d_w1 (inv(alpha_wt) - inv(alpha_wt0)) (z1 +- z2) / z1`` (+ external, - internal).
    Pulling an external pinion out, or pushing one deeper into a ring, opens backlash."""
    pinion = spur(30, "planet", profile_shift=0.2, bore_radius=0.01)
    gear = ring(80, 0.1) if internal else spur(45, "gear", profile_shift=0.1)
    zero = GearPair(pinion, gear)
    a0 = zero.operating_centre_distance
    da = 50e-6 * (-1.0 if internal else 1.0)
    moved = GearPair(pinion, gear, a0 + da)
    z1, z2 = pinion.teeth, gear.teeth * (-1 if internal else 1)
    d_w1 = 2 * moved.operating_pitch_radii[0]
    expect = d_w1 * (inv(moved.operating_pressure_angle) - inv(zero.operating_pressure_angle)) \
        * (z1 + z2) / z1
    assert moved.circular_backlash == pytest.approx(expect, rel=1e-9)
    assert moved.circular_backlash > 0.0


LECAD = """
name = "lecad_planetary"
[sun]
teeth = 21
module_mm = 1.75
pressure_angle_deg = 20.0
face_width_mm = 38.0
profile_shift = 0.4380
[planet]
teeth = 43
module_mm = 1.75
pressure_angle_deg = 20.0
face_width_mm = 38.0
profile_shift = 0.0426
bore_radius_mm = 15.0
[ring]
teeth = 108
module_mm = 1.75
pressure_angle_deg = 20.0
face_width_mm = 38.0
internal = true
rim_outer_radius_mm = 102.0
[carrier]
mass_kg = 1.0
inertia_kgm2 = 0.01
[planetary]
planets = 3
{extra}
"""


def test_published_planetary_set_with_shifts():
    """The LECAD test run (header): shifts printed to 4 decimals give sun-planet and
    planet-ring zero-backlash distances 56.79992 and 56.80008 mm, 2.7e-6 apart (refused
    before as a mismatch). Both round to the published a = 56.8 mm, the carrier radius is
    their mean, and each mesh's backlash there is far inside the stated tolerance."""
    box = gearbox_from_text(LECAD.format(extra=""))
    ps = box.planetary
    a_sp, a_pr = ps.zero_backlash_distances
    assert round(a_sp * 1e3, 1) == 56.8 and round(a_pr * 1e3, 1) == 56.8
    assert a_sp == pytest.approx(56.79992e-3, abs=1e-8)
    assert a_pr == pytest.approx(56.80008e-3, abs=1e-8)
    assert ps.carrier_radius == pytest.approx(0.5 * (a_sp + a_pr), rel=1e-15)
    for pair in (ps.sun_planet, ps.planet_ring):
        assert abs(pair.circular_backlash) < 0.1e-6  # measured 0.062 um
    # the published carrier radius given in the file: each mesh's own operating pressure angle
    given = gearbox_from_text(LECAD.format(extra="centre_distance_mm = 56.8")).planetary
    assert given.carrier_radius == pytest.approx(56.8e-3, rel=1e-15)
    sp, pr = given.sun_planet, given.planet_ring
    assert math.degrees(sp.operating_pressure_angle) == pytest.approx(
        math.degrees(math.acos(1.75 * 64 / 2 * math.cos(D(20)) / 56.8)), abs=1e-12)
    assert math.degrees(pr.operating_pressure_angle) == pytest.approx(
        math.degrees(math.acos(1.75 * 65 / 2 * math.cos(D(20)) / 56.8)), abs=1e-12)
    for pair in (sp, pr):
        rw1, rw2 = pair.operating_pitch_radii
        awt = pair.operating_pressure_angle
        j = 2 * math.pi * rw1 / pair.pinion.teeth - iso21771_thickness(pair.pinion, rw1, awt) \
            - iso21771_thickness(pair.gear, rw2, awt)
        assert pair.circular_backlash == pytest.approx(j, abs=1e-12)
        assert 0.0 < j < 0.1e-6  # measured 0.062 and 0.055 um
    summary = given.summary()
    assert summary["sun_planet_backlash_m"] == sp.circular_backlash


@pytest.mark.parametrize(("a_mm", "mesh", "advice"), [(56.79, "sun-planet", "enlarge"),
                                                      (56.81, "planet-ring", "reduce")])
def test_planetary_interference_is_refused_naming_the_mesh(a_mm, mesh, advice):
    """10 um off the published carrier radius one mesh interferes by about 2 x 10 um x
    tan(alpha_wt) (7-8 um), far beyond the 0.35 um allowed at m_n 1.75 mm: one line naming the
    mesh, its backlash in um, the shifts and which way to move the carrier radius."""
    with pytest.raises(InputError) as err:
        gearbox_from_text(LECAD.format(extra=f"centre_distance_mm = {a_mm}"))
    text = str(err.value)
    assert "\n" not in text
    assert text.startswith(f"[planetary]: {mesh} mesh: circular backlash -")
    j_um = float(text.split("circular backlash ")[1].split(" um")[0])
    assert -9.0 < j_um < -6.0
    assert f"beyond the allowed {BACKLASH_TOLERANCE * 1.75e3:.3g} um" in text
    assert "0.438" in text or "0.0426" in text
    assert f"{advice} planetary.centre_distance_mm" in text


def test_mismatched_ring_without_carrier_radius_is_refused():
    """Unshifted 21/43/108 cannot share a carrier radius at zero backlash (56.0 against
    56.875 mm): without centre_distance_mm the file is refused in one line that says so."""
    text = LECAD.format(extra="").replace("profile_shift = 0.4380", "profile_shift = 0.0") \
        .replace("profile_shift = 0.0426", "profile_shift = 0.0")
    with pytest.raises(InputError, match=r"sun-planet zero-backlash centre distance 56 mm "
                                         r"differs from planet-ring 56.875 mm.*"
                                         r"planetary.centre_distance_mm"):
        gearbox_from_text(text)


# ---- ISO 6336-1 numbering -------------------------------------------------------------------

def q_by_hand(z1, z2, x1, x2):
    """ISO 6336-1 eq. (98), q' in mm um/N, gear 1 the one with fewer teeth."""
    i2 = 0.0 if math.isinf(z2) else 1 / z2
    return (0.04723 + 0.15551 / z1 + 0.25791 * i2 - 0.00635 * x1 - 0.11654 * x1 / z1
            - 0.00193 * x2 - 0.24188 * x2 * i2 + 0.00529 * x1**2 + 0.00182 * x2**2)


def test_iso_numbering_does_not_follow_the_pair_order():
    """A sun of 40 teeth with 20-tooth planets (ring 80, shifts sun 0.2, planet 0.1, ring -0.4:
    both meshes at one zero-backlash distance): ISO 6336-1 numbers the planet gear 1. q' is
    eq. (98) with z_n1 = 20, x1 = 0.1, whichever gear the pair lists first; taking the sun as
    gear 1 gives a q' 3.8 % different (the error the numbering removes)."""
    sun = spur(40, "sun", profile_shift=0.2)
    planet = spur(20, "planet", profile_shift=0.1, bore_radius=0.01)
    ps = PlanetarySet(sun, planet, ring(80, -0.4), 3)
    assert ps.zero_backlash_distances[0] == pytest.approx(ps.zero_backlash_distances[1],
                                                          rel=1e-14)
    sp = ps.sun_planet
    assert [g.name for g in iso_gears(sp)] == ["planet", "sun"]
    iso = iso_stiffness(sp)
    assert iso.gear_1 == "planet"
    assert iso.q_prime * 1e9 == pytest.approx(q_by_hand(20, 40, 0.1, 0.2), rel=1e-14)
    swapped = iso_stiffness(GearPair(planet, sun, sp.operating_centre_distance))
    assert swapped.c_gamma_alpha == pytest.approx(iso.c_gamma_alpha, rel=1e-14)
    wrong = q_by_hand(40, 20, 0.2, 0.1)
    assert abs(wrong / (iso.q_prime * 1e9) - 1) == pytest.approx(0.0378, abs=0.0005)
    # the planet-ring mesh: the ring is gear 2 with z_n2 = inf
    pr = iso_stiffness(ps.planet_ring)
    assert pr.gear_1 == "planet"
    assert pr.q_prime * 1e9 == pytest.approx(q_by_hand(20, math.inf, 0.1, -0.4), rel=1e-14)


def test_basic_rack_factor_is_the_mean_of_both_racks():
    """C_B = (C_B1 + C_B2) / 2 with C_Bi = (1 + 0.5 (1.2 - h_fPi*)) (1 - 0.02 (20 - alpha_n)):
    h_f* 1.25 and 1.4 at 20 deg give (0.975 + 0.9) / 2 = 0.9375 in either order."""
    a, b = spur(25, "a"), spur(31, "b", dedendum_coef=1.4)
    for pair in (GearPair(a, b), GearPair(b, a)):
        assert iso_stiffness(pair).factors["C_B"] == pytest.approx(0.9375, rel=1e-14)


def test_carrier_radius_out_of_range_names_the_key():
    """A carrier radius at or below the sun and planet base radii together is refused in the
    file's key and unit."""
    with pytest.raises(InputError, match=r"planetary.centre_distance_mm = -5 mm is outside the "
                                         r"allowed range \(52.6228, 67.2\] mm"):
        gearbox_from_text(LECAD.format(extra="centre_distance_mm = -5"))
