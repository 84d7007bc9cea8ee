"""The gap the shafts open across the face (pipeline.shaft.misalignment), on the beam model,
against closed forms written here (Euler-Bernoulli with Timoshenko shear where it enters,
the section rotation for a rigid seat); a helical mesh's loads against the statics of the
pair (Newton's third law and the torques, exact)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from pipeline.geometry.gear import Material
from pipeline.shaft.beam import BeamShaft
from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
from pipeline.shaft.misalignment import HelicalMesh, seat_loads, shaft_gap, unit_loads
from pipeline.validation import InputError
from pipeline.verification.cases_shaft_loads import (  # the helical mesh of the statics case
    BETA_B,
    RB2,
    ROLL,
    T1T2,
    W_SLOPED,
    global_loads,
)

E, NU = 206e9, 0.3
G = E / (2 * (1 + NU))
D = 0.040
I_ = math.pi * D**4 / 64
J = 2 * I_
B = 0.020   # face width
RB = 0.0705  # base radius
Z = (np.arange(10) + 0.5) * B / 10  # slice centres
W = np.full(10, 2.3e5)  # N/m: F = 4600 N
F = float(W.sum() * B / 10)


def _layout(gear_position, bearings, torque_position=0.0, hub="rigid", length=0.3):
    return ShaftLayout((ShaftSegment(0.0, length, D),), gear_position, B, bearings,
                       torque_position, hub, Material(E, NU))


def test_straddle_mounted_rigid_seat_opens_no_misalignment():
    """A rigid seat at mid-span between two rigid bearings, under a uniform line load, moves
    without tilting: the gap is the same at every face point (to 1e-12 of its size); its
    twist part is r_b^2 F L_t / (G J) with L_t the shaft from the torque point to the seat."""
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)))
    gap, (ret,) = shaft_gap([BeamShaft(lay)], [RB], Z, W)
    assert np.ptp(gap) <= 1e-12 * abs(gap).max()
    l_t = 0.15 - B / 2
    assert ret.twist == pytest.approx(np.full(10, RB**2 * F * l_t / (G * J)), rel=1e-9)


def test_overhung_rigid_seat_tilts_by_its_section_rotation():
    """A rigid seat overhung beyond the second bearing: the gap grows linearly across the
    face (second differences 0 to 1e-12 of the range), its slope the section rotation at the
    seat: F c^2 / (2 E I) + F (b / 2) c / (E I) from the overhang's bending, and the span's
    rotation at the bearing under the overhang's moment M = F (c + b / 2), M a / (3 E I) +
    M / (kappa G A a) with its shear (Cowper's kappa of a solid section, 6 (1 + nu) / (7 + 6
    nu)); a the span, c the flexible overhang to the seat's start (the shear strain of the
    overhang does not turn the rigid seat; a free stub beyond the seat carries nothing). The
    twist is uniform over a rigid seat."""
    a, c = 0.2, 0.03
    lay = _layout(a + c + B / 2, (Bearing(0.0, axial=True), Bearing(a)),
                  length=a + c + B + 0.01)
    gap, (ret,) = shaft_gap([BeamShaft(lay)], [RB], Z, W)
    d2 = np.diff(ret.translation, 2)
    assert np.abs(d2).max() <= 1e-12 * np.ptp(ret.translation)
    kappa, area = 6 * (1 + NU) / (7 + 6 * NU), math.pi * D**2 / 4
    slope = (F * c**2 / (2 * E * I_) + F * (B / 2) * c / (E * I_)
             + F * (c + B / 2) * (a / (3 * E * I_) + 1 / (kappa * G * area * a)))
    assert np.diff(ret.translation).mean() / (B / 10) == pytest.approx(slope, rel=1e-9)
    assert np.ptp(ret.twist) <= 1e-12 * abs(ret.twist).max()


def test_integral_seat_twists_across_the_face():
    """A pinion cut on its shaft (integral seat), torque held at the shaft's first end: the
    flank's twist grows across the face as the torque carried through each section, r_b
    theta(z) = r_b^2 / (G J) [ F L_0 + integral of the torque still to come ], L_0 the shaft
    up to the face; checked at every slice centre by the discrete sum."""
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)), hub="integral")
    gap, (ret,) = shaft_gap([BeamShaft(lay)], [RB], Z, W)
    start = 0.15 - B / 2
    dz = B / 10
    # the torque through the section at z: the slices beyond z (each F_j r_b at its centre)
    want = []
    for zj in Z:
        theta = F * RB * start / (G * J)
        beyond = [(zk, W[k] * dz) for k, zk in enumerate(Z)]
        theta += sum(fk * RB * min(zk, zj) for zk, fk in beyond) / (G * J)
        want.append(RB * theta)
    assert ret.twist == pytest.approx(want, rel=1e-9)
    assert ret.twist[-1] > ret.twist[0]


def test_helical_needs_its_mesh():
    """A helix angle without the mesh's hand and levers: one line, not a spur answer."""
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)))
    with pytest.raises(InputError, match="need its HelicalMesh"):
        shaft_gap([BeamShaft(lay)], [RB], Z, W, helix_angle=0.2)


def _mesh(hand, beta_b=BETA_B, roll=ROLL):
    return HelicalMesh(beta_b, hand, T1T2, roll)


@pytest.mark.parametrize("hand", ["right", "left"])
def test_helical_loads_are_equal_and_opposite_and_give_the_torques(hand):
    """Newton's third law and the torques, exact: the pinion's and the gear's slice loads,
    each in its mesh frame, taken to one global frame (the pinion's: its axis at the origin,
    T1 at (r_b1, 0), the line of action along -y, so T2 = (r_b1, -T1T2) and the gear's axis
    at (r_b1 + r_b2, -T1T2), the gear's frame turned 180 deg about z) sum to zero force and
    zero moment (to 1e-12 of F and F r_b2): the two act at one contact point. The moment
    about each axis is P r_b of that gear (the driving torque P r_b1 on the pinion, P r_b2
    = P r_b1 u on the gear), the axial force -h tan(beta_b) P on the pinion (h = +1 right
    hand), and the slices' transverse loads sum to P."""
    mesh = _mesh(hand)
    p_tot = float(W_SLOPED.sum() * B / 10)
    h = 1.0 if hand == "right" else -1.0
    lp = seat_loads(Z, W_SLOPED, B, 0.15, RB, unit_loads(RB, 10, mesh, 0))
    lg = seat_loads(Z, W_SLOPED, B, 0.40, RB2, unit_loads(RB2, 10, mesh, 1))
    fp, mp = global_loads(lp, 1.0, (0.0, 0.0), 0.15 - B / 2)
    fg, mg = global_loads(lg, -1.0, (RB + RB2, -T1T2), 0.40 - B / 2)
    assert np.abs(fp.sum(0) + fg.sum(0)).max() <= 1e-12 * p_tot
    assert np.abs(mp.sum(0) + mg.sum(0)).max() <= 1e-12 * p_tot * RB2
    assert sum(ld.moment[2] for ld in lp) == pytest.approx(p_tot * RB, rel=1e-12)
    assert sum(ld.moment[2] for ld in lg) == pytest.approx(p_tot * RB2, rel=1e-12)
    assert fp.sum(0)[2] == pytest.approx(-h * math.tan(BETA_B) * p_tot, rel=1e-12)
    assert fp.sum(0)[1] == pytest.approx(p_tot, rel=1e-12)


def test_reversing_the_hand_reverses_the_axial_force_and_its_tilt():
    """Right against left hand (the same face load, uniform, so the right hand's face
    running against the shaft moves nothing): the axial force and the moments about x and y
    change sign, the transverse force and the torque do not (exact); the shaft's rotations
    and axial displacement from the axial force (the solution less the spur one) change
    sign (to 1e-12 of the whole solution's size, its round-off)."""
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)))
    roll = np.full(10, 0.0274)
    loads = {hand: seat_loads(Z, W, B, 0.15, RB, unit_loads(RB, 10, _mesh(hand, roll=roll)))
             for hand in ("right", "left")}
    for r, ll in zip(loads["right"], loads["left"], strict=True):
        assert (r.force[2], r.moment[0], r.moment[1]) == (-ll.force[2], -ll.moment[0],
                                                          -ll.moment[1])
        assert (r.force[1], r.moment[2]) == (ll.force[1], ll.moment[2])
        assert r.force[2] != 0.0 and r.moment[0] != 0.0
    beam = BeamShaft(lay)
    spur = beam.solve(seat_loads(Z, W, B, 0.15, RB))
    right, left = (beam.solve(loads[h]) for h in ("right", "left"))
    for part in ("rotation", "displacement"):
        d_r = getattr(right, part) - getattr(spur, part)
        d_l = getattr(left, part) - getattr(spur, part)
        assert np.abs(d_r).max() > 1e-3 * np.abs(getattr(right, part)).max()
        assert np.abs(d_r + d_l).max() <= 1e-12 * np.abs(getattr(right, part)).max()


@pytest.mark.parametrize("hand", ["right", "left"])
def test_the_force_is_normal_to_the_contact_lines(hand):
    """The project's own contact lines (GearPair.contact_lines, z 20/40, m_n 3 mm, beta 15
    deg), taken into each gear's mesh frame (pinion: y = -s; gear: y = +s; the face point on
    the shaft at zeta, or b - zeta for a right-hand pinion): the force per unit transverse
    load (0, 1, a) is perpendicular to every contact line (to 1e-12), its transverse part
    pushes each gear away from its mate (+y), and a = -+tan(beta_b) (pinion, right/left
    hand) as the module docstring derives: |a| = tan(beta_b) to 1e-12."""
    from pipeline.geometry.gear import GearSpec
    from pipeline.geometry.pair import GearPair

    other = "left" if hand == "right" else "right"
    kw = dict(module=0.003, pressure_angle=math.radians(20.0), face_width=0.02,
              helix_angle=math.radians(15.0))
    pair = GearPair(GearSpec(20, hand=hand, name="pinion", **kw),
                    GearSpec(40, hand=other, name="gear", **kw))
    mesh = HelicalMesh.of(pair, np.full(10, pair.s_pitch))
    b = pair.face_width
    lines = [ln for s0 in np.linspace(pair.s_start, pair.s_start + pair.base_pitch, 7)
             for ln in pair.contact_lines(s0)]
    assert lines
    for role, (sign, rb) in enumerate(((-1.0, pair.pinion.base_radius),
                                       (1.0, pair.gear.base_radius))):
        unit = unit_loads(rb, 10, mesh, role)[0]
        for (s_a, z_a), (s_b, z_b) in lines:
            zs = (b - np.array([z_a, z_b])) if mesh.reversed else np.array([z_a, z_b])
            dy, dz = sign * (s_b - s_a), zs[1] - zs[0]
            assert abs(unit[1] * dy + unit[2] * dz) <= 1e-12 * math.hypot(dy, dz)
        assert unit[1] == 1.0
        want = -math.tan(pair.pinion.base_helix_angle) * (1 if hand == "right" else -1)
        assert unit[2] == pytest.approx(want if role == 0 else -want, rel=1e-12)


def test_herringbone_and_helical_internal_pairs_refused():
    """Shaft loads are built for external spur and helical pairs: a herringbone pair (the
    contact takes one half, whose axial force the other half cancels) and a helical internal
    pair (its ring's frame differs) are one line each."""
    from pipeline.geometry.gear import GearSpec
    from pipeline.geometry.pair import GearPair

    kw = dict(module=0.003, pressure_angle=math.radians(20.0), face_width=0.04,
              helix_angle=math.radians(15.0))
    herring = GearPair(GearSpec(20, hand="right", herringbone=True, name="pinion", **kw),
                       GearSpec(40, hand="left", herringbone=True, name="gear", **kw))
    with pytest.raises(InputError, match="herringbone pair's two halves"):
        HelicalMesh.of(herring, np.zeros(10))
    ring = GearPair(GearSpec(20, hand="right", name="pinion", **kw),
                    GearSpec(60, hand="right", internal=True, bore_radius=0.12, name="gear",
                             **kw))
    with pytest.raises(InputError, match="helical internal pair"):
        HelicalMesh.of(ring, np.zeros(10))


def _k_tilt(span, seat):
    """The tilting stiffness (N m/rad) of a rigid seat of width ``seat`` at mid-span between
    two pinned supports ``span`` apart: each flexible piece, length l = (span - seat) / 2, is
    a Timoshenko cantilever clamped in the seat, its tip held by the support; a seat
    rotation psi moves the support by psi (l + seat / 2) relative to the seat's line, which
    takes the tip force psi (l + seat / 2) / (l^3 / (3 E I) + l / (kappa G A)), whose moment
    about the seat's centre is that force times (l + seat / 2); two pieces."""
    ell = (span - seat) / 2
    kappa, area = 6 * (1 + NU) / (7 + 6 * NU), math.pi * D**2 / 4
    return 2 * (ell + seat / 2) ** 2 / (ell**3 / (3 * E * I_) + ell / (kappa * G * area))


@pytest.mark.parametrize("hand", ["right", "left"])
def test_helical_straddle_mounted_rigid_seat_tilts_by_the_axial_force(hand):
    """A rigid seat at mid-span between two pinned bearings (0.02 and 0.28 m; axial at the
    first) under a uniform helical line load: by symmetry the transverse load only moves the
    seat, so the misalignment is the axial force's moment about x, M_x = -a F d (a = -h
    tan(beta_b), d the contact's distance from T1), tilting the seat by theta_x = M_x / k
    (k of :func:`_k_tilt`); the gap grows linearly across the face, slope -theta_x along the
    shaft, i.e. tan(beta_b) F d / k along the contact's face for either hand (a right-hand
    pinion's face runs against the shaft) - to 1e-9 on the beam. The axial terms are uniform
    over the rigid seat: a (u_z - d theta_x - r_b theta_y) = a^2 F (L / (E A) + (d^2 + r_b^2)
    / k), L = 0.12 m the shaft from the axial bearing to the seat, theta_y = -a F r_b / k the
    tilt across the line of action (same k). A spur mesh on the same seat opens no
    misalignment (test_straddle_mounted_rigid_seat_opens_no_misalignment)."""
    lay = _layout(0.15, (Bearing(0.02, axial=True), Bearing(0.28)))
    d = 0.0274
    mesh = _mesh(hand, roll=np.full(10, d))
    gap, (ret,) = shaft_gap([BeamShaft(lay)], [RB], Z, W, helix_angle=0.26, mesh=mesh)
    k = _k_tilt(0.26, B)
    tb = math.tan(BETA_B)
    slope = np.diff(gap) / (B / 10)
    assert slope == pytest.approx(np.full(9, tb * F * d / k), rel=1e-9)
    area = math.pi * D**2 / 4
    want = tb**2 * F * (0.12 / (E * area) + (d**2 + RB**2) / k)
    assert ret.axial == pytest.approx(np.full(10, want), rel=1e-9)
    assert ret.twist == pytest.approx(np.full(10, RB**2 * F * (0.15 - B / 2) / (G * J)),
                                      rel=1e-9)


def test_the_hands_mirror_each_other():
    """Reversing the hand is the gearbox turned end for end (module docstring): a right-hand
    pinion on a shaft (integral seat, so the twist varies across the face with the torque
    point's side; axial bearing at 0.02 m, torque held at 0) and a left-hand one on the
    mirror image of that shaft (z -> 0.3 m - z: axial bearing at 0.28 m, torque at 0.3 m)
    open the same gap along the contact's face under a sloped line load and a sloped roll
    coordinate (to 1e-12 of its size): the right hand's face runs against the shaft and its
    axial force is reversed, and only both together leave the answer unchanged. On the
    same, unmirrored shaft the two hands differ."""
    def shaft(axial_at, torque_at):
        bearings = tuple(Bearing(p, axial=(p == axial_at)) for p in (0.02, 0.28))
        return BeamShaft(_layout(0.15, bearings, torque_position=torque_at, hub="integral"))

    g_r, _ = shaft_gap([shaft(0.02, 0.0)], [RB], Z, W_SLOPED, 0.26, mesh=_mesh("right"))
    g_l, _ = shaft_gap([shaft(0.28, 0.3)], [RB], Z, W_SLOPED, 0.26, mesh=_mesh("left"))
    assert np.abs(g_r - g_l).max() <= 1e-12 * np.abs(g_r).max()
    g_l0, _ = shaft_gap([shaft(0.02, 0.0)], [RB], Z, W_SLOPED, 0.26, mesh=_mesh("left"))
    assert np.ptp(g_r - g_l0) > 0.1 * np.ptp(g_r)


@pytest.mark.parametrize("hand", ["left", "none"])
def test_zero_helix_is_the_spur_result(hand):
    """beta_b = 0 with a left hand (the contact's face runs with the shaft) or none: the
    spur gap and retreats exactly (bit for bit) under a sloped line load on an overhung
    seat; the axial terms are 0."""
    a, c = 0.2, 0.03
    lay = _layout(a + c + B / 2, (Bearing(0.0, axial=True), Bearing(a)), length=a + c + B + 0.01)
    beam = BeamShaft(lay)
    spur, (rs,) = shaft_gap([beam], [RB], Z, W_SLOPED)
    hel, (rh,) = shaft_gap([beam], [RB], Z, W_SLOPED, mesh=_mesh(hand, beta_b=0.0))
    assert np.array_equal(spur, hel)
    assert np.array_equal(rs.translation, rh.translation)
    assert not np.any(rh.axial)
