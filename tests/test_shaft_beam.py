"""The Timoshenko beam shaft model against exact solutions.

Exact solutions are written here independently of the FE code: closed forms of elementary
strength of materials (Timoshenko & Gere, *Mechanics of Materials*; Roark's *Formulas for
Stress and Strain*, 8th ed., Table 8.1) with the Timoshenko shear term, and the unit-load
(Castigliano) method for stepped shafts,

    delta = int M m / (E I) dz + int V v / (kappa G A) dz,

integrated piece by piece with Simpson's rule, which is exact because M and m are linear
and V and v constant on each piece. The shear coefficient kappa is Cowper's (1966) for a
hollow round section, itself checked against Cowper's Table 1 limits.

The element is the exact (static condensation of the exact solution) Timoshenko element,
so nodal values are exact for loads at nodes; the tolerances are round-off (1e-9 to 1e-12
relative), tighter than the 1e-6 asked of the model.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.optimize as so
import scipy.sparse.linalg as spla

from pipeline.geometry.gear import Material
from pipeline.shaft.beam import BeamShaft, Disc
from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
from pipeline.shaft.model import PointLoad
from pipeline.shaft.timoshenko import (
    Sections,
    bending_mass,
    bending_stiffness,
    shape_functions,
    shear_coefficient,
)
from pipeline.validation import InputError

MAT = Material()
E, G, NU, RHO = MAT.youngs_modulus, MAT.shear_modulus, MAT.poisson_ratio, MAT.density


def _section(outer, inner=0.0):
    """(E I, kappa G A, G J, E A) of a hollow round section (J = 2 I)."""
    i = math.pi / 64.0 * (outer**4 - inner**4)
    a = math.pi / 4.0 * (outer**2 - inner**2)
    kappa = float(shear_coefficient(NU, outer, inner))
    return E * i, kappa * G * a, G * 2.0 * i, E * a


def _layout(segments, *, gear, width, bearings, torque, hub="integral"):
    segs, start = [], 0.0
    for length, outer, inner in segments:
        segs.append(ShaftSegment(start, start + length, outer, inner))
        start += length
    return ShaftLayout(segments=tuple(segs), gear_position=gear, seat_width=width,
                       bearings=tuple(bearings), torque_position=torque, hub=hub,
                       material=MAT)


def _unit_load(pieces, length, a, b):
    """Deflection at ``b`` of a beam simply supported at 0 and ``length`` under a unit
    load at ``a`` (unit-load method). ``pieces``: (z0, z1, EI, kGA); inf = rigid."""

    def moment(z, p):
        return np.where(z <= p, z * (length - p), p * (length - z)) / length

    def shear(z, p):
        return np.where(z < p, (length - p) / length, -p / length)

    cuts = sorted({a, b, *(q for pc in pieces for q in pc[:2])})
    total = 0.0
    for z0, z1 in zip(cuts[:-1], cuts[1:], strict=False):
        if z1 - z0 <= 0.0:
            continue
        zm = 0.5 * (z0 + z1)
        ei, kga = next((pc[2], pc[3]) for pc in pieces if pc[0] <= zm <= pc[1])
        zs = np.array([z0, zm, z1])
        simpson = (z1 - z0) / 6.0 * np.dot([1.0, 4.0, 1.0], moment(zs, a) * moment(zs, b))
        total += simpson / ei + (z1 - z0) * shear(zm, a) * shear(zm, b) / kga
    return total


def _rel(a, b):
    return abs(a - b) / abs(b)


# -- the shear coefficient and the element ------------------------------------------------

def test_cowper_shear_coefficient_limits():
    """Cowper (1966) Table 1: solid circle 6 (1 + nu) / (7 + 6 nu) = 0.886364 and thin
    circular tube 2 (1 + nu) / (4 + 3 nu) = 0.530612 at nu = 0.3."""
    assert shear_coefficient(0.3, 0.05, 0.0) == pytest.approx(0.8863636364, rel=1e-10)
    assert shear_coefficient(0.3, 1.0, 1.0 - 1e-7) == pytest.approx(0.5306122449, rel=1e-6)


def _one_element(phi):
    length, area, second = np.array([0.3]), np.array([2e-3]), np.array([4e-7])
    kappa = 12.0 * E * second / (phi * G * area * length**2)
    return Sections(length, area, second, kappa, E, G, RHO)


def test_consistent_mass_is_przemieniecki():
    """The IIE mass (quadrature of the shape functions) equals the closed-form Timoshenko
    consistent mass of Przemieniecki (1968, Theory of Matrix Structural Analysis, ch. 11),
    translational + rotary, at Phi = 0.7; at Phi -> 0 the translational part is Archer's
    (1963) rho A L / 420 [156, 22L, 54, -13L; ...]."""
    s = _one_element(0.7)
    p, L = float(s.phi[0]), float(s.length[0])
    m11, m13 = 13 / 35 + 7 / 10 * p + p**2 / 3, 9 / 70 + 3 / 10 * p + p**2 / 6
    m12 = (11 / 210 + 11 / 120 * p + p**2 / 24) * L
    m14 = -(13 / 420 + 3 / 40 * p + p**2 / 24) * L
    m22 = (1 / 105 + p / 60 + p**2 / 120) * L**2
    m24 = -(1 / 140 + p / 60 + p**2 / 120) * L**2
    trans = RHO * s.area[0] * L / (1 + p) ** 2 * np.array([
        [m11, m12, m13, m14], [m12, m22, -m14, m24],
        [m13, -m14, m11, -m12], [m14, m24, -m12, m22]])
    r12, r22 = (1 / 10 - p / 2) * L, (2 / 15 + p / 6 + p**2 / 3) * L**2
    r24 = (-1 / 30 - p / 6 + p**2 / 6) * L**2
    rot = RHO * s.second_moment[0] / ((1 + p) ** 2 * L) * np.array([
        [6 / 5, r12, -6 / 5, r12], [r12, r22, -r12, r24],
        [-6 / 5, -r12, 6 / 5, -r12], [r12, r24, -r12, r22]])
    m = bending_mass(s)[0]
    np.testing.assert_allclose(m, trans + rot, rtol=0, atol=1e-13 * np.abs(m).max())
    e0 = Sections(s.length, s.area, np.array([1e-30]), np.array([1.0]), E, G, RHO)
    archer = RHO * s.area[0] * L / 420 * np.array([
        [156, 22 * L, 54, -13 * L], [22 * L, 4 * L**2, 13 * L, -3 * L**2],
        [54, 13 * L, 156, -22 * L], [-13 * L, -3 * L**2, -22 * L, 4 * L**2]])
    np.testing.assert_allclose(bending_mass(e0)[0], archer, rtol=1e-12, atol=1e-15)


def test_shape_functions_give_the_stiffness():
    """The same IIE shape functions, put into the Timoshenko energy
    int E I theta'^2 + kappa G A (v' - theta)^2 dz (derivatives by complex step, exact for
    polynomials), give the closed-form element stiffness: mass and stiffness are of one
    element."""
    s = _one_element(0.7)
    L, h = float(s.length[0]), 1e-30
    xg, wg = np.polynomial.legendre.leggauss(4)
    xi, w = 0.5 * (xg + 1.0), 0.5 * wg
    nv, nt = shape_functions(xi, s.length, s.phi)
    dv, dt = (f.imag / h / L for f in shape_functions(xi + 1j * h, s.length, s.phi))
    k = L * (E * s.second_moment[0] * np.einsum("q,qi,qj->ij", w, dt[0], dt[0])
             + s.shear_coefficient[0] * G * s.area[0]
             * np.einsum("q,qi,qj->ij", w, dv[0] - nt[0], dv[0] - nt[0]))
    kb = bending_stiffness(s)[0]
    np.testing.assert_allclose(k, kb, rtol=0, atol=1e-12 * np.abs(kb).max())


# -- 1. simply supported, central load ----------------------------------------------------

def test_simply_supported_central_load_both_planes():
    """delta = F L^3 / (48 E I) + F L / (4 kappa G A) (Timoshenko & Gere; shear term by
    the unit-load method), in x and in y, for a hollow shaft."""
    L, D, d = 0.4, 0.06, 0.03
    lay = _layout([(L, D, d)], gear=L / 2, width=0.04, torque=L,
                  bearings=[Bearing(0.0, axial=True), Bearing(L)])
    ei, kga, _, _ = _section(D, d)
    fx, fy = 2000.0, -3000.0
    sol = BeamShaft(lay).solve([PointLoad(L / 2, (fx, fy, 0.0))])
    i = int(np.argmin(np.abs(sol.z - L / 2)))
    unit = L**3 / (48 * ei) + L / (4 * kga)
    assert _rel(sol.displacement[i, 0], fx * unit) < 1e-9
    assert _rel(sol.displacement[i, 1], fy * unit) < 1e-9
    np.testing.assert_allclose(sol.reactions[:, :2], [[-fx / 2, -fy / 2]] * 2, rtol=1e-12)


# -- 2. overhung load ---------------------------------------------------------------------

def test_overhung_load_tip_and_reactions():
    """Load F at z = a + c beyond the second bearing (at a): tip deflection
    F c^2 (a + c) / (3 E I) + F c (a + c) / (a kappa G A) (Roark Table 8.1 case 1e with the
    unit-load shear term); reactions by statics R_B = -F (a + c) / a, R_A = F c / a."""
    a, c, D = 0.3, 0.12, 0.05
    lay = _layout([(a + c, D, 0.0)], gear=a + c - 0.02, width=0.04, torque=0.0,
                  bearings=[Bearing(0.0, axial=True), Bearing(a)])
    ei, kga, _, _ = _section(D)
    f = np.array([1500.0, -800.0])
    sol = BeamShaft(lay).solve([PointLoad(a + c, (f[0], f[1], 0.0))])
    tip = c**2 * (a + c) / (3 * ei) + c * (a + c) / (a * kga)
    np.testing.assert_allclose(sol.displacement[-1, :2], f * tip, rtol=1e-9)
    np.testing.assert_allclose(sol.reactions[0, :2], f * c / a, rtol=1e-12)
    np.testing.assert_allclose(sol.reactions[1, :2], -f * (a + c) / a, rtol=1e-12)


# -- 3. stepped shaft ---------------------------------------------------------------------

@pytest.mark.parametrize("hub", ["integral", "rigid"])
def test_stepped_shaft_unit_load_method(hub):
    """Simply supported stepped shaft (D 60 mm over 150 mm, then D 40 mm bore 15 mm over
    250 mm), load off centre: the deflections under the load and at a second point by the
    unit-load method (module docstring). A rigid seat is the same beam with E I and
    kappa G A infinite over the seat."""
    L1, L2, L = 0.15, 0.25, 0.40
    seat = (0.07, 0.11)
    lay = _layout([(L1, 0.06, 0.0), (L2, 0.04, 0.015)], gear=0.09, width=0.04, torque=L,
                  bearings=[Bearing(0.0, axial=True), Bearing(L)], hub=hub)
    s1, s2 = _section(0.06), _section(0.04, 0.015)
    pieces = [(0.0, L1, s1[0], s1[1]), (L1, L, s2[0], s2[1])]
    if hub == "rigid":
        pieces = [(0.0, seat[0], s1[0], s1[1]), (*seat, math.inf, math.inf),
                  (seat[1], L1, s1[0], s1[1]), (L1, L, s2[0], s2[1])]
    a, b, F = 0.09, 0.27, 4000.0
    sol = BeamShaft(lay).solve([PointLoad(a, (0.0, F, 0.0)), PointLoad(b, (0.0, 0.0, 0.0))])
    for p in (a, b):
        i = int(np.argmin(np.abs(sol.z - p)))
        assert _rel(sol.displacement[i, 1], F * _unit_load(pieces, L, a, p)) < 1e-9


# -- 4. torsion, 5. axial -----------------------------------------------------------------

def test_torsion_hollow_and_stepped():
    """Twist between the seat's centre and the torque point: T L / (G J),
    J = pi (D^4 - d^4) / 32, summed over the segments between them (Timoshenko, Strength
    of Materials I, ch. IX); a rigid seat twists only from its end; the torque point
    takes -T."""
    segs = [(0.1, 0.05, 0.02), (0.15, 0.06, 0.02), (0.2, 0.045, 0.0)]
    T = 350.0
    for hub, start in (("integral", 0.05), ("rigid", 0.07)):
        lay = _layout(segs, gear=0.05, width=0.04, torque=0.45, hub=hub,
                      bearings=[Bearing(0.0, axial=True), Bearing(0.45)])
        expect = T * ((0.1 - start) / _section(0.05, 0.02)[2] + 0.15 / _section(0.06, 0.02)[2]
                      + 0.2 / _section(0.045)[2])
        sol = BeamShaft(lay).solve([PointLoad(0.05, (0.0, 0.0, 0.0), (0.0, 0.0, T))])
        i = int(np.argmin(np.abs(sol.z - 0.05)))
        assert _rel(sol.rotation[i, 2] - sol.rotation[-1, 2], expect) < 1e-10
        assert sol.torque_reaction == pytest.approx(-T, rel=1e-12)


def test_axial_load():
    """u_z at the load = F L / (E A) over the length to the axial bearing (at the far
    end), summed over the hollow and the solid segment; the axial bearing takes -F."""
    lay = _layout([(0.2, 0.05, 0.02), (0.2, 0.04, 0.0)], gear=0.1, width=0.04, torque=0.0,
                  hub="integral", bearings=[Bearing(0.0), Bearing(0.4, axial=True)])
    F = 12000.0
    sol = BeamShaft(lay).solve([PointLoad(0.1, (0.0, 0.0, F))])
    i = int(np.argmin(np.abs(sol.z - 0.1)))
    expect = F * (0.1 / _section(0.05, 0.02)[3] + 0.2 / _section(0.04)[3])
    assert _rel(sol.displacement[i, 2], expect) < 1e-10  # pushed towards the bearing
    assert sol.reactions[1, 2] == pytest.approx(-F, rel=1e-12)
    assert sol.reactions[0, 2] == 0.0


# -- 6. elastic bearings ------------------------------------------------------------------

def test_elastic_bearings_add_their_compliance():
    """Radial stiffness k at both bearings of the symmetric case adds F / (2 k) at
    mid-span; a single bearing clamping with tilting stiffness k_t (an overhung shaft)
    adds F L^2 / k_t at the tip to F L^3 / (3 E I) + F L / (kappa G A) (Roark Table 8.1
    case 1a, shear by the unit-load method; the clamp rotates by F L / k_t)."""
    L, D, F, k = 0.4, 0.05, 1000.0, 2.0e8
    ei, kga, _, _ = _section(D)
    lay = _layout([(L, D, 0.0)], gear=L / 2, width=0.04, torque=L,
                  bearings=[Bearing(0.0, k, axial=True), Bearing(L, k)])
    sol = BeamShaft(lay).solve([PointLoad(L / 2, (F, 0.0, 0.0))])
    i = int(np.argmin(np.abs(sol.z - L / 2)))
    expect = F * (L**3 / (48 * ei) + L / (4 * kga)) + F / (2 * k)
    assert _rel(sol.displacement[i, 0], expect) < 1e-9
    assert _rel(sol.displacement[0, 0], F / (2 * k)) < 1e-9
    for kt in (3.0e5, math.inf):
        lay = _layout([(L, D, 0.0)], gear=L - 0.02, width=0.04, torque=0.0,
                      bearings=[Bearing(0.0, tilting_stiffness=kt, axial=True)])
        sol = BeamShaft(lay).solve([PointLoad(L, (0.0, F, 0.0))])
        expect = F * (L**3 / (3 * ei) + L / kga + L**2 / kt)
        assert _rel(sol.displacement[-1, 1], expect) < 1e-9
        # M_x = +F L (u_y' = -theta_x); from the residual at the clamp: round-off 1e-11
        assert _rel(sol.reactions[0, 3], F * L) < 1e-10


# -- 7. rigid hub -------------------------------------------------------------------------

def _rigid_motion(sol, centre, lo, hi):
    """The largest deviation of the seat's nodes from the rigid motion of its centre."""
    on = (sol.z >= lo - 1e-12) & (sol.z <= hi + 1e-12)
    c = int(np.argmin(np.abs(sol.z - centre)))
    d = sol.z[on] - sol.z[c]
    ux, uy, uz = sol.displacement[c]
    tx, ty, _ = sol.rotation[c]
    rigid = np.column_stack([ux + d * ty, uy - d * tx, np.full(d.size, uz)])
    return max(np.abs(sol.displacement[on] - rigid).max(),
               np.abs(sol.rotation[on] - sol.rotation[c]).max())


def test_rigid_hub_moves_as_a_rigid_body_and_is_stiffer():
    """A rigid seat (bearings elastic, one at the seat's end) under a line load across the
    seat given as point loads with moments: every seat node's six displacements are one
    rigid motion of the centre to 1e-12 of the largest displacement; the centre deflects
    less than on the integral seat."""
    kw = dict(gear=0.14, width=0.06, torque=0.4,
              bearings=[Bearing(0.0, 3e8, axial=True), Bearing(0.17, 5e8, 1e4),
                        Bearing(0.4, 4e8)])
    segs = [(0.1, 0.05, 0.0), (0.1, 0.07, 0.0), (0.2, 0.05, 0.0)]
    zs = np.linspace(0.11, 0.17, 7)
    loads = [PointLoad(z, (300.0 * (1 + z), -500.0, 80.0), (3.0, -2.0, 40.0)) for z in zs]
    sols = {hub: BeamShaft(_layout(segs, hub=hub, **kw)).solve(loads)
            for hub in ("rigid", "integral")}
    scale = np.abs(sols["rigid"].displacement).max()
    assert _rigid_motion(sols["rigid"], 0.14, 0.11, 0.17) < 1e-12 * scale
    assert _rigid_motion(sols["integral"], 0.14, 0.11, 0.17) > 1e-3 * scale  # it does bend
    c = int(np.argmin(np.abs(sols["rigid"].z - 0.14)))
    for axis in (0, 1):
        assert abs(sols["rigid"].displacement[c, axis]) < abs(
            sols["integral"].displacement[c, axis])


# -- equilibrium --------------------------------------------------------------------------

@pytest.mark.parametrize("hub", ["integral", "rigid"])
def test_equilibrium_to_round_off(hub):
    """Forces and moments about the origin of the loads, the bearing reactions and the
    torque reaction sum to zero (1e-12 of the loads), with rigid and elastic bearings,
    tilting stiffness, a bearing at the seat's end and loads off the nodes."""
    lay = _layout([(0.08, 0.04, 0.0), (0.12, 0.06, 0.02), (0.15, 0.045, 0.0)],
                  gear=0.12, width=0.05, torque=0.33, hub=hub,
                  bearings=[Bearing(0.02, axial=True), Bearing(0.145, math.inf, 2e5),
                            Bearing(0.3, 2e8, math.inf)])
    rng = np.random.default_rng(7)
    loads = [PointLoad(float(z), tuple(rng.normal(0, 1e3, 3)), tuple(rng.normal(0, 50, 3)))
             for z in rng.uniform(0.0, 0.35, 6)]
    sol = BeamShaft(lay).solve(loads)
    pos = np.array([b.position for b in lay.bearings])

    def moment_about_origin(z, f, m):
        return np.column_stack([-z * f[:, 1], z * f[:, 0], np.zeros(len(z))]) + m

    f = np.array([ld.force for ld in loads])
    m = np.array([ld.moment for ld in loads])
    zl = np.array([ld.z for ld in loads])
    force = f.sum(0) + sol.reactions[:, :3].sum(0)
    moment = (moment_about_origin(zl, f, m).sum(0)
              + moment_about_origin(pos, sol.reactions[:, :3], sol.reactions[:, 3:]).sum(0)
              + [0.0, 0.0, sol.torque_reaction])
    assert np.abs(force).max() < 1e-12 * np.abs(f).max()
    assert np.abs(moment).max() < 1e-12 * np.abs(f).max() * 0.35
    assert np.all(sol.reactions[:, 5] == 0.0)


# -- 8. flexibility -----------------------------------------------------------------------

@pytest.mark.parametrize("hub", ["integral", "rigid"])
def test_flexibility_reciprocal_and_inverse_of_seat_stiffness(hub):
    """Maxwell-Betti reciprocity: the flexibility over five seat points (off the mesh) is
    symmetric to 1e-10; its columns are the solutions under unit loads; seat_stiffness is
    the inverse of the flexibility at the centre (K G = I to 1e-10)."""
    lay = _layout([(0.1, 0.05, 0.0), (0.1, 0.07, 0.03), (0.2, 0.05, 0.0)], gear=0.15,
                  width=0.06, torque=0.4, hub=hub,
                  bearings=[Bearing(0.0, 3e8, axial=True), Bearing(0.4, 4e8, 2e4)])
    model = BeamShaft(lay)
    zs = np.array([0.1213, 0.135, 0.15, 0.1611, 0.1799])
    g = model.flexibility(zs)
    assert g.shape == (30, 30)
    assert np.abs(g - g.T).max() < 1e-10 * np.abs(g).max()
    sol = model.solve([PointLoad(zs[3], (0.0, 1.0, 0.0))])
    i = int(np.argmin(np.abs(sol.z - zs[1])))
    col = np.concatenate([sol.displacement[i], sol.rotation[i]])
    np.testing.assert_allclose(g[6:12, 3 * 6 + 1], col, rtol=0, atol=1e-12 * np.abs(g).max())
    k = model.seat_stiffness()
    g0 = model.flexibility(np.array([0.15]))
    np.testing.assert_allclose(k @ g0, np.eye(6), rtol=0, atol=1e-10)
    np.testing.assert_allclose(g[12:18, 12:18], g0, rtol=1e-10, atol=0)  # other nodes


def test_flexibility_off_node_is_exact():
    """At an off-mesh point a of a simply supported uniform beam, the direct flexibility is
    a^2 b^2 / (3 E I L) + a b / (kappa G A L), b = L - a (Roark Table 8.1 case 2e plus the
    shear term); the model adds a node there instead of interpolating."""
    L, D = 0.4, 0.05
    lay = _layout([(L, D, 0.0)], gear=0.2, width=0.04, torque=L,
                  bearings=[Bearing(0.0, axial=True), Bearing(L)])
    model = BeamShaft(lay)
    a = 0.1234567
    assert np.min(np.abs(model.z - a)) > 1e-4
    ei, kga, _, _ = _section(D)
    b = L - a
    g = model.flexibility(np.array([a]))
    assert _rel(g[0, 0], a**2 * b**2 / (3 * ei * L) + a * b / (kga * L)) < 1e-9


def test_seat_stiffness_refuses_a_rigidly_held_centre():
    """The axial bearing at a rigid seat's end holds the centre rigidly in u_z: the seat's
    stiffness is infinite and asked for, a one-line error names the DOF."""
    lay = _layout([(0.4, 0.05, 0.0)], gear=0.2, width=0.04, torque=0.4, hub="rigid",
                  bearings=[Bearing(0.0), Bearing(0.22, axial=True)])
    with pytest.raises(ValueError, match="u_z"):
        BeamShaft(lay).seat_stiffness()


# -- 9. mesh independence -----------------------------------------------------------------

def test_refining_does_not_change_nodal_results():
    """The element is exact at its nodes for loads at nodes (the stiffness is the static
    condensation of the exact Timoshenko solution; Friedman & Kosmatka 1993), so nodal
    results at the key points, the reactions and the seat's flexibility agree to 1e-10
    between the default mesh and one 10 times finer. (What differs is round-off, which
    grows with the condition number, about as n^2: 1e-11 here, 1e-10 at 30 times finer.)"""
    lay = _layout([(0.1, 0.05, 0.0), (0.12, 0.07, 0.03), (0.18, 0.05, 0.0)], gear=0.15,
                  width=0.06, torque=0.4, hub="integral",
                  bearings=[Bearing(0.0, 3e8, axial=True), Bearing(0.4, 4e8, 2e4)])
    loads = [PointLoad(0.13, (900.0, -400.0, 200.0), (5.0, 0.0, 60.0)),
             PointLoad(0.17, (300.0, 700.0, 0.0), (0.0, -4.0, 20.0))]
    coarse = BeamShaft(lay, extra_nodes=(0.13, 0.17))
    fine = BeamShaft(lay, element_length=0.4 / 300, extra_nodes=(0.13, 0.17))
    assert fine.z.size > 9 * coarse.z.size
    sc, sf = coarse.solve(loads), fine.solve(loads)
    key = np.array([0.0, 0.1, 0.12, 0.13, 0.15, 0.17, 0.18, 0.22, 0.4])
    ic, jf = coarse.node(key), fine.node(key)
    for a, b in ((sc.displacement, sf.displacement), (sc.rotation, sf.rotation)):
        assert np.abs(a[ic] - b[jf]).max() < 1e-10 * np.abs(a).max()
    assert np.abs(sc.reactions - sf.reactions).max() < 1e-10 * np.abs(sc.reactions).max()
    zs = np.array([0.125, 0.15, 0.175])
    gc, gf = coarse.flexibility(zs), fine.flexibility(zs)
    assert np.abs(gc - gf).max() < 1e-10 * np.abs(gc).max()


# -- 10. torsional dynamics ---------------------------------------------------------------

def _torsional_frequency(model, discs, near):
    """The natural frequency (rad/s) nearest ``near`` of a torsion-dominated mode, with the
    torque point free; shift-invert Lanczos on the whole reduced 3D model (a dense
    eigensolver's round-off on the stiff axial and shear modes would reach 1e-8)."""
    b = model.basis(hold_torque=False)
    k = (b.T @ model.stiffness_matrix() @ b).tocsc()
    m = (b.T @ model.mass_matrix(discs) @ b).tocsc()
    w2, v = spla.eigsh(k, 6, m, sigma=near**2)
    shapes = (b @ v).reshape(-1, 6, v.shape[1])
    twist = np.linalg.norm(shapes[:, 5, :], axis=0) / np.linalg.norm(shapes, axis=(0, 1))
    torsion = np.flatnonzero(twist > 0.99)
    return math.sqrt(w2[torsion[np.argmin(np.abs(w2[torsion] - near**2))]])


def test_two_inertia_torsional_frequency():
    """Two discs (J1 0.5, J2 1.0 kg m^2) at the ends of a 0.5 m shaft of D 30 mm (its own
    polar inertia 3.1e-4 kg m^2): omega = sqrt(k_t (J1 + J2) / (J1 J2)), k_t = G J / L, to
    1e-3 (den Hartog, Mechanical Vibrations, sec. 5.2; the shaft's inertia is what
    separates them, 5.2e-5), and to 1e-10 the exact continuous root of
    (a b - 1) sin(kL) = (a + b) cos(kL), k = omega sqrt(rho / G),
    a = omega^2 J1 / (G J k), b likewise with J2 (the shaft as a torsional wave guide
    between the discs). Consistent mass; 30 elements."""
    L, D, j1, j2 = 0.5, 0.03, 0.5, 1.0
    lay = _layout([(L, D, 0.0)], gear=0.02, width=0.04, torque=L,
                  bearings=[Bearing(0.1, axial=True), Bearing(0.4)])
    model = BeamShaft(lay, element_length=L / 30)
    gj = _section(D)[2]
    w0 = math.sqrt(gj / L * (j1 + j2) / (j1 * j2))
    discs = [Disc(0.0, polar_inertia=j1), Disc(L, polar_inertia=j2)]
    w = _torsional_frequency(model, discs, near=w0)
    assert _rel(w, w0) < 1e-3

    def residual(om):
        kk = om * math.sqrt(RHO / G)
        a, b = om**2 * j1 / (gj * kk), om**2 * j2 / (gj * kk)
        return (a * b - 1) * math.sin(kk * L) - (a + b) * math.cos(kk * L)

    exact = so.brentq(residual, 0.9 * w0, 1.1 * w0, xtol=1e-14, rtol=1e-15)
    assert _rel(w, exact) < 1e-10
    assert _rel(w, w0) > 1e-5  # the shaft's inertia shows: 5.2e-5


def test_torsional_frequency_converges_at_second_order():
    """Linear twist elements with consistent mass converge at O(h^2) in frequency
    (Strang & Fix 1973, ch. 6): the fitted rate of the error of the first free-free
    torsional mode of a bare shaft, omega = pi sqrt(G / rho) / L, on uniform meshes of
    32, 64 and 96 elements is 2 within 0.01 (measured 2.0001; errors 4.0e-4 to 4.5e-5)."""
    L, D = 0.5, 0.03
    lay = _layout([(L, D, 0.0)], gear=L / 16, width=L / 8, torque=L,
                  bearings=[Bearing(L / 4, axial=True), Bearing(3 * L / 4)])
    exact = math.pi * math.sqrt(G / RHO) / L
    hs, errs = [], []
    for n in (32, 64, 96):
        model = BeamShaft(lay, element_length=L / n)
        assert np.ptp(np.diff(model.z)) < 1e-12  # uniform
        hs.append(L / n)
        errs.append(_rel(_torsional_frequency(model, [], near=exact), exact))
    rate = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert rate == pytest.approx(2.0, abs=0.01)


def test_shaft_mass_is_exact():
    """The consistent mass moves the whole shaft's mass in a rigid translation,
    rho A L summed over the segments, and its polar inertia rho J L in a rigid rotation."""
    lay = _layout([(0.1, 0.05, 0.02), (0.2, 0.06, 0.0)], gear=0.05, width=0.04, torque=0.3,
                  bearings=[Bearing(0.0, axial=True), Bearing(0.3)])
    model = BeamShaft(lay)
    m = model.mass_matrix()
    for dof in (0, 1, 2):
        r = np.zeros((model.z.size, 6))
        r[:, dof] = 1.0
        mass = RHO * (math.pi / 4 * ((0.05**2 - 0.02**2) * 0.1 + 0.06**2 * 0.2))
        assert _rel(r.ravel() @ m @ r.ravel(), mass) < 1e-12
    r = np.zeros((model.z.size, 6))
    r[:, 5] = 1.0
    polar = RHO * math.pi / 32 * ((0.05**4 - 0.02**4) * 0.1 + 0.06**4 * 0.2)
    assert _rel(r.ravel() @ m @ r.ravel(), polar) < 1e-12


# -- inputs -------------------------------------------------------------------------------

def test_inputs_refused_in_one_line():
    """A bad element length, a point off the shaft, a disc off the nodes, two bearings at
    one position, the torque point inside the seat: one-line errors naming the key."""
    lay = _layout([(0.4, 0.05, 0.0)], gear=0.2, width=0.04, torque=0.4,
                  bearings=[Bearing(0.0, axial=True), Bearing(0.4)])
    with pytest.raises(InputError, match=r"shaft\.element_length_mm = 0 mm"):
        BeamShaft(lay, element_length=0.0)
    with pytest.raises(InputError, match="z_mm = 450 mm"):
        BeamShaft(lay).flexibility(np.array([0.45]))
    with pytest.raises(ValueError, match="not a node"):
        BeamShaft(lay).mass_matrix([Disc(0.123456, 1.0)])
    with pytest.raises(InputError, match=r"bearings\[1\]\.position_mm = 0 mm is that of"):
        _layout([(0.4, 0.05, 0.0)], gear=0.2, width=0.04, torque=0.4,
                bearings=[Bearing(0.0, axial=True), Bearing(0.0), Bearing(0.4)])
    with pytest.raises(InputError, match="torque_position_mm = 210 mm lies inside"):
        _layout([(0.4, 0.05, 0.0)], gear=0.2, width=0.04, torque=0.21,
                bearings=[Bearing(0.0, axial=True), Bearing(0.4)])
    assert Bearing(0.1).radial_stiffness == math.inf  # the rigid default is accepted
