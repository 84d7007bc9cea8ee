"""The 3D shaft model (``model = "fe3d"``) against beam theory and 3D elasticity's exact
solutions.

References:

* Timoshenko beam, simply supported, central load F over the span L: deflection
  ``F L^3 / (48 E I) + F L / (4 kappa G A)`` (Timoshenko & Gere, *Mechanics of Materials*;
  the shear term by the unit-load method); stepped shafts by the unit-load method,
  ``delta = int M m / (E I) dz + int V v / (kappa G A) dz``, segment by segment.
* The shear coefficient of a solid circle ``kappa = 6 (1 + nu) / (7 + 6 nu)`` (Cowper,
  J. Appl. Mech. 33 (1966) 335-340), derived with the section's mean displacement and
  mean rotation (the least-squares fit that reads the 3D model's sections): with it the
  beam's curvature ``M / (E I)`` and shear strain ``V / (kappa G A)`` are those of the
  Saint-Venant flexure solution of 3D elasticity, exact between the load and the
  supports away from their Saint-Venant zones (about one diameter).
* Torsion of a round shaft: ``dtheta/dz = T / (G J)``, ``J = pi d^4 / 32``, exact in 3D
  elasticity (Saint-Venant); a stepped shaft in series, ``sum L_i / (G J_i)``, plus a local
  compliance at each shoulder that the series sum lacks (the stress spreads from the small
  into the large section over a zone of the order of the step height; bounded by it).
* A rigid hub over the seat: the beam with a rigid segment over the seat is the stiff
  bound (it holds every section under the hub); the 3D hub holds only the shaft's
  surface, so the core under the hub's edges still bends - as if the beam's built-in
  points lay a little inside the hub. The beam without a hub (a point load) is the soft
  bound.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import numpy as np
import pytest

from pipeline.cache.folder import Cache
from pipeline.geometry.gear import Material
from pipeline.shaft.fe3d import Fe3dShaft
from pipeline.shaft.fe3d_plan import Fe3dSettings
from pipeline.shaft.layout import Bearing, ShaftLayout, ShaftSegment
from pipeline.shaft.model import PointLoad
from pipeline.validation import InputError

MAT = Material()
E, G, NU = MAT.youngs_modulus, MAT.shear_modulus, MAT.poisson_ratio
KAPPA = 6 * (1 + NU) / (7 + 6 * NU)  # Cowper (1966), solid circle
D, SPAN, SEAT = 0.04, 0.2, 0.02  # diameter, bearing span, seat width (m)


def _I(d):
    return math.pi * d**4 / 64


def _A(d):
    return math.pi * d**2 / 4


def plain(hub="rigid", d=D, torque=0.23, **bearing):
    """A plain shaft 240 mm long, bearings at 20 and 220 mm, the seat at mid-span."""
    return ShaftLayout((ShaftSegment(0.0, 0.24, d),), 0.12, SEAT,
                       (Bearing(0.02, axial=True, **bearing), Bearing(0.22, **bearing)),
                       torque, hub=hub)


def stepped(hub="integral", d=0.03, body=0.045):
    """Journals d (0-40 and 200-240 mm) either side of a body of diameter ``body``."""
    segs = (ShaftSegment(0.0, 0.04, d), ShaftSegment(0.04, 0.2, body),
            ShaftSegment(0.2, 0.24, d))
    return ShaftLayout(segs, 0.12, SEAT, (Bearing(0.02, axial=True), Bearing(0.22)), 0.23,
                       hub=hub)


def timoshenko_central(span, d, rigid_length=0.0):
    """Central deflection per unit load (m/N) of a simply supported Timoshenko beam, with a
    rigid segment ``rigid_length`` at mid-span: each elastic half is a cantilever of length
    a = (span - rigid_length) / 2 built in at the rigid segment, with tip load 1/2."""
    a = 0.5 * (span - rigid_length)
    return 0.5 * a**3 / (3 * E * _I(d)) + 0.5 * a / (KAPPA * G * _A(d))


@pytest.fixture(scope="module")
def coarse():
    """The plain shaft with a rigid hub at the coarsest mesh (about 13k unknowns)."""
    return Fe3dShaft(plain(), Fe3dSettings(refinement=0.75), cache=Cache.off())


def test_coarse_rigid_hub_between_the_beam_bounds(coarse):
    """Rigid hub: the 3D seat deflection lies between the beam with a rigid segment over
    the seat (5.20 um/kN) and the beam with a point load (7.00 um/kN); measured 5.48 um/kN
    (+5.2 %), as if each built-in point lay 1.6 mm (0.04 d) inside the hub (refinement 1:
    5.50; the refinement series converges to 5.57, slow test)."""
    c = coarse.flexibility(np.array([0.12]))[1, 1]
    stiff, soft = timoshenko_central(SPAN, D, SEAT), timoshenko_central(SPAN, D)
    assert stiff < c < soft
    assert c / stiff == pytest.approx(1.053, abs=0.01)
    # the built-in point inside the hub that makes the beam as flexible as the 3D shaft
    shift = _built_in_shift(c)
    assert 0.0 < shift < 0.1 * D


def _built_in_shift(c):
    lo, hi = 0.0, SEAT / 2
    for _ in range(60):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if timoshenko_central(SPAN, D, SEAT - 2 * mid) < c else (lo, mid)
    return 0.5 * (lo + hi)


@pytest.fixture(scope="module")
def long_coarse():
    """A plain shaft twice as long (bearings at 20 and 460 mm, rigid hub at 240 mm), coarse
    (about 19k unknowns): five diameters between the bearing and the hub."""
    layout = ShaftLayout((ShaftSegment(0.0, 0.48, D),), 0.24, SEAT,
                         (Bearing(0.02, axial=True), Bearing(0.46)), 0.47)
    return Fe3dShaft(layout, Fe3dSettings(refinement=0.75), cache=Cache.off())


def _sections(sol, zs):
    idx = [int(np.argmin(np.abs(sol.z - z))) for z in zs]
    assert np.allclose(sol.z[idx], zs, atol=1e-4)
    return idx


def test_saint_venant_zone_is_the_beam_exactly(long_coarse):
    """More than one diameter from the bearing band and from the hub (sections at 62, 118
    and 174 mm, equally spaced) the sections' rotation grows by int M / (E I) dz and the
    deflection by the rotation integral plus the shear strain V / (kappa G A) with Cowper's
    kappa: exact 3D elasticity (Saint-Venant flexure), so only discretisation error is left
    (measured 1.4e-4 and 5e-3 of the shear part, which is 10 % of the deflection; 4e-5 and
    1.7e-3 at refinement 1)."""
    F = 1000.0
    sol = long_coarse.solve([PointLoad(0.24, (0.0, F, 0.0))])
    idx = _sections(sol, (0.0622727, 0.1181818, 0.1740909))
    z, uy, tx = sol.z[idx], sol.displacement[idx, 1], sol.rotation[idx, 0]
    V = F / 2  # shear force between the bearing at 20 mm and the hub
    # u_y = -theta_x z for a small rotation about x: theta_x = -du_y/dz, and
    # d theta_x / dz = M / (E I) with M(z) = V (z - 0.02) sagging
    curvature_integral = V / (E * _I(D)) * ((z[2] - 0.02) ** 2 - (z[0] - 0.02) ** 2) / 2
    assert tx[2] - tx[0] == pytest.approx(curvature_integral, rel=1e-3)
    h = z[1] - z[0]
    rotation_integral = h / 3 * (tx[0] + 4 * tx[1] + tx[2])  # Simpson: exact, theta quadratic
    shear = (uy[2] - uy[0]) + rotation_integral
    assert shear == pytest.approx(V * (z[2] - z[0]) / (KAPPA * G * _A(D)), rel=1e-2)


def test_torsion_gradient_is_exact(long_coarse):
    """Between the hub and the torque point, more than 1.5 diameters from both, the twist
    per length is T / (G J): exact in 3D elasticity (measured 4e-4 low; 1.7e-4 at
    refinement 1)."""
    T = 100.0
    sol = long_coarse.solve([PointLoad(0.24, (0.0, 0.0, 0.0), (0.0, 0.0, T))])
    J = math.pi * D**4 / 32
    inner = (sol.z > 0.25 + 1.5 * D) & (sol.z < 0.465 - 1.5 * D)
    assert inner.sum() >= 4
    slope = np.polyfit(sol.z[inner], sol.rotation[inner, 2], 1)[0]
    assert -slope == pytest.approx(T / (G * J), rel=1e-3)


def test_hollow_shaft_saint_venant_zone():
    """A bored shaft (40 mm, bore 24 mm, integral seat, coarse): the twist per length
    T / (G J) with J = pi (d^4 - d_i^4) / 32 and the curvature M / (E I) with the bore
    (measured 4.7e-4 and 1.2e-4)."""
    do, di = 0.04, 0.024
    layout = ShaftLayout((ShaftSegment(0.0, 0.48, do, di),), 0.24, SEAT,
                         (Bearing(0.02, axial=True), Bearing(0.46)), 0.47, hub="integral")
    m = Fe3dShaft(layout, Fe3dSettings(refinement=0.75), cache=Cache.off())
    T, F = 100.0, 1000.0
    sol = m.solve([PointLoad(0.24, (0.0, 0.0, 0.0), (0.0, 0.0, T))])
    inner = (sol.z > 0.25 + 1.5 * do) & (sol.z < 0.465 - 1.5 * do)
    slope = np.polyfit(sol.z[inner], sol.rotation[inner, 2], 1)[0]
    assert -slope == pytest.approx(T / (G * math.pi * (do**4 - di**4) / 32), rel=1e-3)
    sol = m.solve([PointLoad(0.24, (0.0, F, 0.0))])
    idx = _sections(sol, (0.0622727, 0.1181818, 0.1740909))
    z, tx = sol.z[idx], sol.rotation[idx, 0]
    moment_area = F / 2 * ((z[2] - 0.02) ** 2 - (z[0] - 0.02) ** 2) / 2
    I = math.pi * (do**4 - di**4) / 64  # noqa: E741
    assert tx[2] - tx[0] == pytest.approx(moment_area / (E * I), rel=1e-3)


def test_overhung_seat_on_one_clamping_bearing(tmp_path):
    """Overhung: one bearing rigid in translation and tilt at 20 mm (its band held as a
    whole), the torque held there too (the torque point inside its band shares its node),
    an integral seat at 200 mm. The seat deflects as a Timoshenko cantilever of 180 mm,
    F a^3 / (3 E I) + F a / (kappa G A), within 1 % (measured -0.39 %; -1.4 % and -0.08 %
    at refinements 0.5 and 1: the discretisation, converging on the beam) and twists by
    T a / (G J) within 1 % (+0.26 %); the bearing takes the force and the moment F a. A
    tilting stiffness k instead of the rigid one adds a^2 / k exactly (springs in series)."""
    layout = ShaftLayout((ShaftSegment(0.0, 0.24, D),), 0.2, SEAT,
                         (Bearing(0.02, tilting_stiffness=math.inf, axial=True),), 0.02,
                         hub="integral")
    m = Fe3dShaft(layout, Fe3dSettings(refinement=0.75), cache=Cache(tmp_path))
    a, F, T = 0.18, 1000.0, 100.0
    c = m.flexibility([0.2])
    assert c[1, 1] == pytest.approx(a**3 / (3 * E * _I(D)) + a / (KAPPA * G * _A(D)), rel=0.01)
    assert c[5, 5] == pytest.approx(a / (G * math.pi * D**4 / 32), rel=0.01)
    sol = m.solve([PointLoad(0.2, (0.0, F, 0.0), (0.0, 0.0, T))])
    np.testing.assert_allclose(sol.reactions[0], [0, -F, 0, F * a, 0, 0], atol=1e-6 * F)
    assert sol.torque_reaction == pytest.approx(-T, rel=1e-9)
    # an elastic tilting stiffness k in series: + a^2 / k at the seat (same superelement)
    k = 1e6
    tilting = replace(layout, bearings=(replace(layout.bearings[0], tilting_stiffness=k),))
    soft = Fe3dShaft(tilting, Fe3dSettings(refinement=0.75), cache=Cache(tmp_path))
    assert soft.cached
    assert soft.flexibility([0.2])[1, 1] - c[1, 1] == pytest.approx(a**2 / k, rel=1e-6)


def test_coarse_reactions_and_torque_balance_the_load(coarse):
    """Bearing reactions and the torque point's moment balance the seat's load."""
    F = np.array([300.0, -1000.0, 200.0])
    M = np.array([0.0, 0.0, 50.0])
    sol = coarse.solve([PointLoad(0.125, tuple(F), tuple(M))])
    R = sol.reactions
    assert R[:, :3].sum(axis=0) == pytest.approx(-F, abs=1e-6 * np.abs(F).max())
    assert sol.torque_reaction == pytest.approx(-M[2], rel=1e-9)
    assert abs(R[1, 2]) < 1e-9 * abs(F[2])  # only the locating bearing takes the axial force
    # moment about x at the first bearing: F_y lever 105 mm, reaction of the second 200 mm
    assert 0.105 * F[1] + 0.2 * R[1, 1] == pytest.approx(0.0, abs=1e-6 * abs(F[1]))


def test_coarse_flexibility_symmetric_and_seat_stiffness_its_inverse(coarse):
    """Maxwell-Betti: the condensed flexibility is symmetric to solver precision (measured
    asymmetry 2e-15 before symmetrising); the seat stiffness is the inverse of the
    flexibility at the seat's centre; a rigid hub moves rigidly between seat points."""
    assert coarse.superelement.asymmetry < 1e-10
    z = np.array([0.111, 0.12, 0.129])
    C = coarse.flexibility(z)
    assert C.shape == (18, 18)
    np.testing.assert_allclose(C, C.T, atol=1e-12 * np.abs(C).max())
    K = coarse.seat_stiffness()
    np.testing.assert_allclose(K @ C[6:12, 6:12], np.eye(6), atol=1e-8)
    assert np.all(np.linalg.eigvalsh(K) > 0)
    # u_y at 129 mm under F_y at 111 mm: u_y - 9 mm theta_x at the centre (u + theta x r)
    assert C[12 + 1, 1] == pytest.approx(C[6 + 1, 1] - 0.009 * C[6 + 3, 1], rel=1e-9)


def test_coarse_seat_twist_against_g_j_over_l(coarse):
    """The seat's twist against the torque point is T L / (G J) over the free length
    L = 100 mm from the hub's edge (130 mm) to the torque band's centre (230 mm), within
    3 % and above it (measured +1.8 %; +1.9 % at refinement 1): the core under the hub
    still twists, the torque enters the surface band over a Saint-Venant zone."""
    J = math.pi * D**4 / 32
    twist = coarse.flexibility(np.array([0.12]))[5, 5]
    assert twist == pytest.approx((0.23 - 0.13) / (G * J), rel=0.03)
    assert twist > (0.23 - 0.13) / (G * J)


def test_cache_reads_the_superelement_and_follows_the_layout(tmp_path):
    """A second build of the same layout reads the cache (faster); a bearing stiffness
    changes no cached matrix (applied to the condensed one); a diameter does."""
    cache = Cache(tmp_path)
    s = Fe3dSettings(refinement=0.5)
    t0 = time.perf_counter()
    cold = Fe3dShaft(plain(), s, cache=cache)
    t_cold = time.perf_counter() - t0
    t0 = time.perf_counter()
    warm = Fe3dShaft(plain(), s, cache=cache)
    t_warm = time.perf_counter() - t0
    print(f"cold {t_cold:.3f} s, warm {t_warm:.3f} s")
    assert not cold.cached and warm.cached
    assert t_warm < t_cold
    np.testing.assert_array_equal(cold.flexibility([0.12]), warm.flexibility([0.12]))
    soft = Fe3dShaft(plain(radial_stiffness=1e8), s, cache=cache)
    assert soft.cached
    # the bearings in series: + (1/2)^2 / k per bearing at mid-span for u_y
    extra = soft.flexibility([0.12])[1, 1] - cold.flexibility([0.12])[1, 1]
    assert extra == pytest.approx(2 * 0.25 / 1e8, rel=1e-6)
    other = Fe3dShaft(plain(d=0.041), s, cache=cache)
    assert not other.cached
    assert len(list(tmp_path.glob("shaftfe3d-*.npz"))) == 2


def test_bad_inputs_are_one_line_errors():
    """A torque point on the seat and two bearings at one place (refused by the layout
    itself) and bad settings name the key."""
    with pytest.raises(InputError, match=r"shaft.torque_position_mm = 120 mm lies inside "
                                         r"the gear's seat"):
        Fe3dShaft(plain(torque=0.12), cache=Cache.off())
    with pytest.raises(InputError, match=r"shaft.bearings\[1\].position_mm = 20 mm is that "
                                         r"of bearings\[0\]"):
        ShaftLayout((ShaftSegment(0.0, 0.24, D),), 0.12, SEAT,
                    (Bearing(0.02, axial=True), Bearing(0.02)), 0.23)
    with pytest.raises(InputError, match=r"fe3d.refinement = 20 is outside"):
        Fe3dSettings(refinement=20)
    with pytest.raises(InputError, match=r"fe3d.seat_stations = 1 is outside"):
        Fe3dSettings(seat_stations=1)
    with pytest.raises(InputError, match=r"fe3d.solver = 'lu' is not one of"):
        Fe3dSettings(solver="lu")


def test_load_off_the_seat_is_refused(coarse):
    with pytest.raises(InputError, match=r"z = 140 mm lies off the gear's seat \(110 to 130"):
        coarse.solve([PointLoad(0.14, (0.0, 1.0, 0.0))])


# -- slow: refinement series, integral seats, stepped shafts --------------------------------

def _series(hub, refinements):
    c = []
    for r in refinements:
        m = Fe3dShaft(plain(hub), Fe3dSettings(refinement=r), cache=Cache.off())
        c.append(m.flexibility(np.array([0.12]))[1, 1])
    return np.array(c)


def _rate(h, c):
    """Extrapolated value and observed rate: c(h) = c_inf - C h^p fitted to the series,
    then p from np.polyfit(log h, log |c_inf - c|)."""
    from scipy.optimize import curve_fit

    scale = c[-1]
    (a, k, p), _ = curve_fit(lambda h, a, k, p: a - k * h**p, h / h[0], c / scale,
                             p0=(1.01, 0.05, 1.5), maxfev=20000)
    c_inf = a * scale
    slope = np.polyfit(np.log(h), np.log(np.abs(c_inf - c)), 1)[0]
    return c_inf, slope


@pytest.mark.slow
def test_integral_seat_converges_to_timoshenko():
    """Integral seat, central load on the middle station: the series 0.5-1.5 (5k-46k
    unknowns) converges at the rate h^2.2 to 7.024 um/kN, 0.27 % above Timoshenko's
    7.005 (the bearing bands and the loaded ring, 10 and 4 mm wide, are not points);
    Euler-Bernoulli alone (6.44) is 8 % low."""
    refinements = np.array([0.5, 0.75, 1.0, 1.25, 1.5])
    c = _series("integral", refinements)
    assert np.all(np.diff(c) > 0)  # monotone: a displacement model is too stiff
    c_inf, p = _rate(D / 4 / refinements, c)
    print(f"integral: {c} -> {c_inf:.6g} m/N, rate {p:.2f}")
    assert 1.5 < p < 3.0
    assert c_inf == pytest.approx(timoshenko_central(SPAN, D), rel=5e-3)
    assert c[-1] == pytest.approx(c_inf, rel=1e-3)


@pytest.mark.slow
def test_rigid_hub_converges():
    """Rigid hub: the series 0.5-1.5 (6k-48k unknowns) converges at about h^1.4, slower
    than the integral seat: the edges of a rigid ring bonded to the surface are corner
    singularities (refined like the shoulders); extrapolated 5.57 um/kN, 7 % above the
    beam with a rigid segment over the seat (built-in points 2.3 mm = 0.06 d inside the
    hub), below the beam without a hub."""
    refinements = np.array([0.5, 0.75, 1.0, 1.25, 1.5])
    c = _series("rigid", refinements)
    c_inf, p = _rate(D / 4 / refinements, c)
    print(f"rigid: {c} -> {c_inf:.6g} m/N, rate {p:.2f}")
    assert 0.8 < p < 2.2
    assert timoshenko_central(SPAN, D, SEAT) < c_inf < timoshenko_central(SPAN, D)
    assert 0.0 < _built_in_shift(c_inf) < 0.1 * D


def beam_stepped_central(d, body):
    """Central deflection per unit load (m/N) of :func:`stepped` as a Timoshenko beam (the
    unit-load method over the half-span: journal d for 20 mm from the bearing, then the
    body to mid-span)."""
    out = 0.0
    for x1, x2, dia in ((0.0, 0.02, d), (0.02, 0.10, body)):
        out += 2 * ((x2**3 - x1**3) / (12 * E * _I(dia))
                    + (x2 - x1) / (4 * KAPPA * G * _A(dia)))
    return out


@pytest.mark.parametrize("refinement, bend, bend_length, twist, twist_length", [
    (0.75, 0.0204, 0.164, 0.0476, 0.073),
    pytest.param(1.5, 0.0244, 0.195, 0.0546, 0.083, marks=pytest.mark.slow),
])
def test_stepped_shaft_against_the_beam(refinement, bend, bend_length, twist, twist_length):
    """Stepped shaft (journals 30 mm, body 45 mm, integral seat), central load and torque.

    Bending: 3D is 2.0 % (refinement 0.75; 2.4 % at 1.5) more flexible than the Timoshenko
    beam, against 0.27 % on the plain shaft: the shoulders' local flexibility. As an extra
    length l_e of journal at each shoulder it is 0.16 d (0.195 d at 1.5, converging upwards
    as the corner is resolved): the large section is not fully effective next to the step.
    Torsion: 4.8 % (5.5 %) above the series sum; at the one shoulder between the seat and
    the torque point 0.073 d (0.083 d) of extra journal, of the order of the 0.097 d the
    groove body gives for D/d = 1.67 (``tests/test_groove_shafts.py``) and below the step
    height 0.25 d that bounds the Saint-Venant zone; the loaded bands add about 0.01 d."""
    d, body = 0.03, 0.045
    m = Fe3dShaft(stepped(), Fe3dSettings(refinement=refinement), cache=Cache.off())
    c = m.flexibility(np.array([0.12]))
    beam = beam_stepped_central(d, body)
    assert c[1, 1] / beam - 1 == pytest.approx(bend, abs=0.004)
    # the excess as extra journal at the two shoulders, 20 mm from the bearings
    l_e = (c[1, 1] - beam) / (2 * 0.02**2 / 4 * (1 / (E * _I(d)) - 1 / (E * _I(body))))
    assert l_e / d == pytest.approx(bend_length, abs=0.03)
    assert 0 < l_e < 0.5 * d
    J = math.pi * np.array([d, body]) ** 4 / 32
    series = (0.2 - 0.12) / (G * J[1]) + (0.23 - 0.2) / (G * J[0])
    assert c[5, 5] / series - 1 == pytest.approx(twist, abs=0.005)
    dl = (c[5, 5] - series) * G * J[0]
    assert dl / d == pytest.approx(twist_length, abs=0.01)
    assert 0 < dl < (body - d) / 2


def test_integral_seat_flexibility_between_stations():
    """Integral seat (five stations, 112 to 128 mm): the flexibility between seat points is
    symmetric, the deflection under a load falls away from mid-span, also between stations
    (hat weights), and is symmetric about it to 2 % (the torque band breaks the symmetry
    only in torsion; measured 0.2 %)."""
    m = Fe3dShaft(plain("integral"), Fe3dSettings(refinement=0.5), cache=Cache.off())
    z = np.array([0.112, 0.116, 0.12, 0.122, 0.128])  # stations at 112, 116, ... 128 mm
    C = m.flexibility(z)
    np.testing.assert_allclose(C, C.T, atol=1e-12 * np.abs(C).max())
    uy = np.diag(C)[1::6]
    assert uy[2] > uy[3] > uy[4] and uy[2] > uy[1] > uy[0]
    assert uy[0] == pytest.approx(uy[4], rel=2e-2)  # symmetric span


def test_shaft_mesh_volume_and_sections():
    """The Gmsh shaft (curved P2 cells): the volume of a stepped, partly bored shaft within
    1e-4 of the exact value (measured 8e-6) and the area of every named cross-section (the
    smaller disc at a shoulder, the shared annulus where the bore starts, the end faces)
    within 1e-3 (measured 6e-6 at the refined shoulder to 3.2e-4 at an end face meshed
    at 2/3 of its radius)."""
    from skfem import Basis, ElementTetP2

    from pipeline.fem.shaft_mesh import ShaftMeshSpec, ShaftPiece, mesh_shaft
    from pipeline.fem.tetmesh import surface_mass, to_skfem

    pieces = (ShaftPiece(0.0, 0.03, 0.015, 0.0, 0.01), ShaftPiece(0.03, 0.08, 0.025, 0.0, 0.012),
              ShaftPiece(0.08, 0.11, 0.025, 0.01, 0.01))
    spec = ShaftMeshSpec(pieces)
    assert [s[:2] for s in spec.shoulders()] == [(0.03, 0.015)]
    sk = to_skfem(mesh_shaft(spec))
    volume = Basis(sk.mesh, ElementTetP2()).dx.sum()
    exact = sum(math.pi * (p.outer_radius**2 - p.inner_radius**2) * (p.z1 - p.z0)
                for p in pieces)
    assert volume == pytest.approx(exact, rel=1e-4)
    # at 80 mm only the annulus is shared: the disc inside the bore is the solid's free end
    annulus = math.pi * (0.025**2 - 0.01**2)
    areas = {0: math.pi * 0.015**2, 1: math.pi * 0.015**2, 2: annulus, 3: annulus}
    nodes = sk.mesh.doflocs
    for k, area in areas.items():
        tri = sk.triangles[f"section:{k}"]
        got = surface_mass(nodes, tri, nodes.shape[1]).sum()
        assert got == pytest.approx(area, rel=1e-3), k
        assert np.allclose(nodes[2, np.unique(tri)], spec.cuts[k])


def _straddle_pinion():
    """The pinion shaft of workflows/configs/shaft_straddle_pinion.toml: 35 mm journals, the
    pinion's 142.5 mm body 70-90 mm (integral seat), bearings at 40 and 140 mm."""
    from pathlib import Path

    from pipeline.config import load_gearbox

    path = Path(__file__).parents[1] / "workflows" / "configs" / "shaft_straddle_pinion.toml"
    return load_gearbox(path).shafts["pinion"][1]


def test_straddle_pinion_body_is_one_solid_with_seat_rings():
    """A seat on a disc (20 mm long, 142.5 mm across): its four inner station edges split
    only its surface (rings), so the body is one solid with cross-sections at its faces
    only; the journals keep their sections. Its shoulders are a large step (142.5 / 35):
    their circles are meshed at 0.08 of the journal's 8.75 mm edge, growing 1 m/m; the
    stepped shaft's (45 / 30) at 0.35 of 7.5 mm, growing 0.5 m/m; the body at its length
    over 2 (10 mm, not 142.5 / 4)."""
    from pipeline.shaft.fe3d_plan import plan_fe3d

    plan = plan_fe3d(_straddle_pinion(), Fe3dSettings())
    for z, (zs, r, hs, h, g) in zip((0.07, 0.09), plan.mesh.shoulders(), strict=True):
        assert (zs, r, h, g) == pytest.approx((z, 0.0175, 0.00875, 1.0))
        assert hs == pytest.approx(0.08 * 0.00875)
    body = [p for p in plan.mesh.pieces if p.outer_radius > 0.07]
    assert [p.size for p in body] == pytest.approx([0.01] * len(body))
    for _, _, hs, h, g in plan_fe3d(stepped(), Fe3dSettings()).mesh.shoulders():
        assert (hs, h, g) == pytest.approx((0.35 * 0.0075, 0.0075, 0.5))
    assert np.allclose(plan.mesh.rings, [0.074, 0.078, 0.082, 0.086])
    cuts = plan.mesh.section_cuts
    assert not np.any((cuts > 0.0701) & (cuts < 0.0899))
    assert np.any(np.isclose(cuts, 0.07)) and np.any(np.isclose(cuts, 0.09))
    # the seat of the stepped test shaft lies on a long segment: cut, no rings
    assert plan_fe3d(stepped(), Fe3dSettings()).mesh.rings == ()


@pytest.mark.slow
def test_straddle_pinion_graded_mesh_against_a_finer_one():
    """The straddle-mounted pinion's seat compliance (centre of the 142.5 mm body on 35 mm
    journals; the bearings rigid) at the default mesh (64k unknowns; the large step's
    shoulder circles at 0.08 of the journal's edge, growing 1 m/m; the body at its length
    over 2, split by rings) agrees with the
    same mesh refined 1.5 times (121k unknowns) within 0.5 % in u_x, u_y, u_z and the
    twist (measured -0.41, -0.38, -0.47 and -0.16 %), and lies below it (a displacement
    model is too stiff). Against the earlier sizing (shoulder circles at 0.35 growing
    0.5 m/m, the seat cut into slabs at its stations) refined to 2 (121k unknowns; its own
    series 1, 1.25, 1.5, 2 rises by 0.45, 0.15, 0.29 % in u_x) the default differs by
    -0.17, -0.16, -0.24 and -0.20 % (workflows/benchmarks/bench_shaft_fe3d.py)."""
    layout = _straddle_pinion()
    z = np.array([layout.gear_position])
    coarse = Fe3dShaft(layout, cache=Cache.off()).flexibility(z)
    fine = Fe3dShaft(layout, Fe3dSettings(refinement=1.5), cache=Cache.off()).flexibility(z)
    for k in (0, 1, 2, 5):  # u_x, u_y, u_z, theta_z
        assert coarse[k, k] == pytest.approx(fine[k, k], rel=5e-3), k
        assert coarse[k, k] < fine[k, k], k
