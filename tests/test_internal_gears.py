"""Internal (ring) gears through geometry, analytical stiffness and loaded contact.

The ladder: exact geometry (the ring's fillet limit in closed form against the profile
construction), exact section integrals (pure-involute ring tooth against an independent
quadrature, the exact profile against a quadrature of its own flank), the load and
friction directions derived by hand from rigid-body kinematics, limits (z -> inf: the
internal and the external pair close in on the pinion-rack pair from both sides),
published references (ISO 6336-1 and the whole-ring FE fit of the body term), and every
ring tried end to end through the command line.
"""

from __future__ import annotations

import dataclasses
import json
import math
from pathlib import Path

import numpy as np
import pytest
from gearsets import STEEL, spur
from scipy.integrate import quad

from pipeline.cli import main
from pipeline.config import load_gearbox
from pipeline.contact import ContactOptions, analyse_contact, analytical_compliance
from pipeline.contact.analysis import line_of_action_load
from pipeline.geometry import GearPair, GearSpec
from pipeline.geometry.analysis import analyse_geometry
from pipeline.geometry.profile import tooth_profile
from pipeline.operation import OperatingPoint
from pipeline.stiffness import StiffnessOptions, analyse_stiffness
from pipeline.stiffness.foundation import FoundationCoefficients
from pipeline.stiffness.friction import friction_direction, load_components
from pipeline.stiffness.iso6336 import iso_stiffness
from pipeline.stiffness.mesh import FrictionModel, PairModel, mesh_stiffness, stiffness_at
from pipeline.stiffness.ring_body import RING_TABLE, ring_coefficients
from pipeline.stiffness.sections import exact_sections
from pipeline.stiffness.tooth import (
    classical_tooth_model,
    load_geometry,
    tooth_compliance,
    tooth_model,
)
from pipeline.validation import InputError

D = math.radians
CONFIGS = Path(__file__).parents[1] / "workflows" / "configs"


def ring(z: int, module: float = 3e-3, alpha_deg: float = 20.0, rim_modules: float = 4.0,
         **kw) -> GearSpec:
    """A ring with a rim ``rim_modules`` m_n thick below its root circle."""
    beta = kw.get("helix_angle", 0.0)
    shift = kw.get("profile_shift", 0.0)
    rf = z * module / (2 * math.cos(beta)) + module * (kw.get("dedendum_coef", 1.25) - shift)
    kw.setdefault("face_width", 0.02)
    kw.setdefault("material", STEEL)
    return GearSpec(teeth=z, module=module, pressure_angle=D(alpha_deg), internal=True,
                    bore_radius=rf + rim_modules * module, name="ring", **kw)


def planet_ring(z_ring: int = 80, z_planet: int = 30) -> GearPair:
    """Planet 30 / ring 80 of workflows/configs/planet_ring_pair.toml (m 3 mm, 20 deg, b 20 mm)."""
    return GearPair(spur(z_planet, "planet", bore_radius=0.45 * z_planet * 1e-3), ring(z_ring))


# ---- geometry: the ring's fillet ------------------------------------------------------------

@pytest.mark.parametrize(("z", "alpha", "limit"), [(40, 25.0, 0.2415), (95, 25.0, 0.2866),
                                                   (120, 25.0, 0.2932), (80, 20.0, 0.4419)])
def test_ring_fillet_limit_is_where_the_fillets_meet(z, alpha, limit):
    """The closed-form fillet limit (GearSpec.ring_fillet_limit) puts the fillet centre at
    the middle of the tooth space: the profile built with it has a root land of zero length
    (its root-circle points at polar angle pi/z to 1e-9), and any larger radius is refused.

    The rack default 0.318 m_n of 25 deg rack cutters does not fit a 25-deg ring (its space
    is narrower at the root than the rack's); the ring default is the limit then.
    Reference values: the limit over m_n measured when the test was written (4 digits).
    """
    g = ring(z, alpha_deg=alpha)
    assert g.ring_fillet_limit / g.module == pytest.approx(limit, abs=1e-4)
    at_limit = dataclasses.replace(g, cutter_tip_radius_coef=g.ring_fillet_limit / g.module)
    p = tooth_profile(at_limit, points=200)
    on_root = np.abs(p.radius - g.root_radius) <= 1e-9 * g.root_radius
    angles = np.arctan2(p.x[on_root], p.y[on_root])
    assert np.ptp(angles) <= 1e-9
    assert angles[0] == pytest.approx(math.pi / z, abs=1e-9)
    if alpha == 25.0:
        assert g.cutter_tip_radius_coef == pytest.approx(g.ring_fillet_limit / g.module, rel=1e-12)
    with pytest.raises(InputError, match="ring.cutter_tip_radius_coef"):
        dataclasses.replace(g, cutter_tip_radius_coef=1.01 * g.ring_fillet_limit / g.module)


def test_ring_fillet_limit_tends_to_the_rack():
    """z -> inf: the ring's tooth space becomes the rack's, and its fillet limit the rack's
    e cos(a) / (1 - sin a) with e = (pi/4 - h_f* tan a) m_n (0.3179 at 25 deg), from below
    and like 1/z (slope of log gap against log z: -1 within 0.05)."""
    a = D(25.0)
    rack = (math.pi / 4 - 1.25 * math.tan(a)) * math.cos(a) / (1 - math.sin(a))
    gaps = np.array([rack - ring(z, alpha_deg=25.0).ring_fillet_limit / 3e-3
                     for z in (500, 1000, 2000, 4000)])
    assert np.all(gaps > 0)
    assert np.polyfit(np.log([500, 1000, 2000, 4000]), np.log(gaps), 1)[0] == pytest.approx(
        -1.0, abs=0.05)
    assert gaps[-1] / rack < 3e-3  # measured 2.3e-3 at z = 4000


def test_spaces_closing_before_the_root_are_refused():
    """A ring whose involutes meet below its root circle has no tooth space there: one line."""
    with pytest.raises(InputError, match="tooth spaces of the internal gear close"):
        ring(30, alpha_deg=30.0, dedendum_coef=2.0, addendum_coef=0.8)


# ---- section integrals ---------------------------------------------------------------------

def _ring_quadrature(g: GearSpec, radius: float, mu_lam: float, clamp_r: float,
                     psi: callable) -> tuple[float, float, float]:
    """Bending, shear and axial compliance (m^2/N) of a ring tooth loaded at ``radius``,
    integrated over the flank radius R' from the load point to the clamp (scipy quad).

    Section at R': centre-line coordinate y = R' cos psi(R'), half thickness h = R' sin psi;
    dy = y'(R') dR'. Load at (h_c, y_c) with load angle a = alpha + psi (tooth.load_geometry
    derives it); moment at a section y: F_b (y - y_c) - F_a h_c (unit load).
    """
    E, G = g.material.youngs_modulus, g.material.shear_modulus
    rb = g.base_radius
    a = math.acos(rb / radius) + psi(radius)
    fb, fa = math.cos(a) - mu_lam * math.sin(a), math.sin(a) + mu_lam * math.cos(a)
    y_c, h_c = radius * math.cos(psi(radius)), radius * math.sin(psi(radius))

    def geo(r):
        p = psi(r)
        dp = math.sqrt(r * r - rb * rb) / (rb * r)  # d psi / dR' on a ring involute
        return r * math.cos(p), r * math.sin(p), math.cos(p) - r * math.sin(p) * dp

    def bend(r):
        y, h, dy = geo(r)
        return (fb * (y - y_c) - fa * h_c) ** 2 / (E * (2 * h) ** 3 / 12) * dy

    def shear(r):
        y, h, dy = geo(r)
        return 1.2 * fb**2 / (G * 2 * h) * dy

    def axial(r):
        y, h, dy = geo(r)
        return fa**2 / (E * 2 * h) * dy

    return tuple(quad(f, radius, clamp_r, limit=400, epsabs=0, epsrel=1e-11)[0]
                 for f in (bend, shear, axial))


@pytest.mark.parametrize("z", [60, 120])
@pytest.mark.parametrize("where", [0.02, 0.4, 0.9])
@pytest.mark.parametrize("mu_lam", [0.0, 0.1, -0.1])
def test_ring_tooth_integrals_match_quadrature(z, where, mu_lam):
    """Pure-involute ring tooth clamped at the chord of its root-circle points (the classical
    internal tooth): the tabulated integrals equal an independent quadrature over the flank.

    ``where`` places the load between the tip (0) and the root circle (1). 2e-5 is the error
    of the 4000 tabulated sections (second order, as for the external classical model).
    """
    g = ring(z)
    model = classical_tooth_model(g)
    r = g.tip_radius_ + where * (g.root_radius - g.tip_radius_)
    c = tooth_compliance(model, r, mu=abs(mu_lam), lam=np.sign(mu_lam))
    ref = _ring_quadrature(g, r, mu_lam, g.root_radius, g.half_tooth_angle)
    assert float(c.bending) == pytest.approx(ref[0], rel=2e-5)
    assert float(c.shear) == pytest.approx(ref[1], rel=2e-5)
    assert float(c.axial) == pytest.approx(ref[2], rel=2e-5)


@pytest.mark.parametrize("z", [60, 95])
def test_exact_ring_sections_match_profile_quadrature(z):
    """Exact profile (involute + circular fillet): the tooth model's bending, shear and axial
    compliance equal a quadrature of the same beam integrals written on the profile itself
    (adaptive quad of the flank polyline between the load point and the clamp chord, its
    fillet arc included), within 1e-4 (the 3000 graded sections of the table)."""
    g = ring(z, alpha_deg=25.0 if z == 95 else 20.0)
    model = tooth_model(g)
    prof = tooth_profile(g)
    top = int(np.argmax(prof.y))
    yb, xb = prof.y[top:][::-1], prof.x[top:][::-1]
    y0 = model.sections.clamp_radius
    E, G = g.material.youngs_modulus, g.material.shear_modulus
    breaks = yb[(yb > yb[0]) & (yb < y0)]
    for r in np.linspace(g.tip_radius_ * 1.0005, g.root_radius - 1.2 * g.module, 4):
        a, h_c, y_c = (float(v) for v in load_geometry(g, r))
        fb, fa = load_components(a, 0.0, 0.0)

        def integrands(y, fb=fb, fa=fa, h_c=h_c, y_c=y_c):
            h = float(np.interp(y, yb, xb))
            return ((fb * (y - y_c) - fa * h_c) ** 2 / (E * (2 * h) ** 3 / 12),
                    1.2 * fb**2 / (G * 2 * h), fa**2 / (E * 2 * h))

        pts = breaks[(breaks > y_c)]
        kw = dict(points=pts if pts.size < 50 else None, limit=2000, epsrel=1e-10)
        bend, shear, axial = (quad(lambda y, k=k: integrands(y)[k], y_c, y0, **kw)[0]
                              for k in range(3))
        c = tooth_compliance(model, r)
        assert float(c.bending) == pytest.approx(bend, rel=1e-4)
        assert float(c.shear) == pytest.approx(shear, rel=1e-4)
        assert float(c.axial) == pytest.approx(axial, rel=1e-4)


def test_exact_ring_sections_clamp_at_the_root_chord():
    """The table starts on the chord through the fillets' root-circle points and ends at the
    tip corner; its half thickness there is the profile's (checked against the polyline)."""
    g = ring(80)
    prof = tooth_profile(g)
    model = tooth_model(g)
    theta_f = model.foundation.theta_f
    sec = model.sections
    assert sec.internal
    assert sec.clamp_radius == pytest.approx(g.root_radius * math.cos(theta_f), rel=1e-15)
    assert sec.eta[-1] == pytest.approx(sec.clamp_radius - prof.y[-1], rel=1e-12)
    assert sec.half_thickness[-1] == pytest.approx(prof.x[-1], rel=1e-9)
    # the same table from the function itself, and a ring tooth widens towards its root
    again = exact_sections(prof, theta_f, 3000)
    np.testing.assert_array_equal(again.J2, sec.J2)
    assert np.all(np.diff(sec.half_thickness) <= 1e-15)


# ---- load and friction directions, by hand ----------------------------------------------------

def test_ring_load_and_friction_split_from_vectors():
    """Hand derivation in the ring tooth's frame (centre line +y, root at larger y, loaded
    flank at x > 0): the involute point at radius R, its tangent by differentiating the
    involute, the normal load pointing into the tooth and the friction force mu F along the
    tangent towards the root (the approach, see the next test). Bending is the component
    along -x, compression the one along +y (towards the root). load_components(load_geometry)
    must give the same split: load angle alpha + psi, lam = +1 in approach.
    """
    g = ring(80)
    mu = 0.1
    for r in np.linspace(g.tip_radius_ * 1.001, g.root_radius - 1.3 * g.module, 5):
        psi = g.half_tooth_angle(r)
        eps = 1e-7 * r
        p0 = np.array([r * math.sin(psi), r * math.cos(psi)])
        q = r + eps
        p1 = np.array([q * math.sin(g.half_tooth_angle(q)), q * math.cos(g.half_tooth_angle(q))])
        to_root = (p1 - p0) / np.linalg.norm(p1 - p0)  # along the flank, radius growing
        normal_in = np.array([to_root[1], -to_root[0]])  # the tangent turned clockwise
        if normal_in[0] > 0:  # must point into the tooth (towards the centre line, -x)
            normal_in = -normal_in
        force = normal_in + mu * to_root
        fb, fa = -force[0], force[1]
        a, h_c, y_c = (float(v) for v in load_geometry(g, r))
        assert a == pytest.approx(math.acos(g.base_radius / r) + psi, rel=1e-12)
        assert (h_c, y_c) == pytest.approx((p0[0], p0[1]), rel=1e-12)
        ref_b, ref_a = load_components(a, mu, 1.0)
        assert fb == pytest.approx(float(ref_b), abs=2e-6)
        assert fa == pytest.approx(float(ref_a), abs=2e-6)


@pytest.mark.parametrize("driver", ["pinion", "gear"])
def test_friction_points_to_both_roots_in_approach_internal(driver):
    """Friction sign of an internal mesh, derived from rigid-body kinematics.

    Frame: line of action along +y, base tangent points T1 = O1 + r_b1 x and T2 = O2 + r_b2 x
    on the *same* side (internal pair), T2 = T1 - T1T2 y, contact P = T1 + s y. Both gears
    turn counter-clockwise (w2 = w1 z1/z2), so the contact runs from s_start to s_end with
    the pinion driving. Sliding velocity of the pinion over the ring (v1 - v2) . x =
    -(w1 - w2)(s - s_pitch): positive before the pitch point. Friction on the pinion opposes
    it (along -x there), which lowers |P - O1|: towards the pinion's root; its reaction on the
    ring (along +x) raises |P - O2|: towards the ring's root. So in the approach both
    frictions point to their tooth's root, as in an external mesh, and
    ``friction_direction`` must return +1 exactly there (with the ring driving the contact
    runs backwards, and approach and recess swap). The same construction checks the pair's
    contact radii |P - O1|, |P - O2| (``rho2 = -(s + T1T2)`` of an internal pair).
    """
    pair = planet_ring()
    w1 = 100.0 * (1.0 if driver == "pinion" else -1.0)  # the driver turns the mesh forwards
    w2 = w1 * pair.pinion.teeth / pair.gear.teeth
    rb1, rb2 = pair.pinion.base_radius, pair.gear.base_radius
    o1 = np.zeros(2)
    t1 = np.array([rb1, 0.0])
    o2 = t1 - np.array([0.0, pair.t1t2]) - np.array([rb2, 0.0])
    assert np.linalg.norm(o2 - o1) == pytest.approx(pair.operating_centre_distance, rel=1e-12)
    s = np.linspace(pair.s_start, pair.s_end, 41)
    s = s[np.abs(s - pair.s_pitch) > 1e-6]
    lam = friction_direction(s, pair.s_pitch, driver)
    r1, r2 = pair.contact_radii(s)
    for si, li, r1i, r2i in zip(s, lam, r1, r2, strict=True):
        p = t1 + np.array([0.0, si])
        # the pair's contact radii and roll coordinate are those of this construction
        assert np.linalg.norm(p - o1) == pytest.approx(r1i, rel=1e-12)
        assert np.linalg.norm(p - o2) == pytest.approx(r2i, rel=1e-12)
        v1 = w1 * np.array([-(p - o1)[1], (p - o1)[0]])
        v2 = w2 * np.array([-(p - o2)[1], (p - o2)[0]])
        assert v1[1] == pytest.approx(v2[1], rel=1e-12)  # no approach along the normal
        slide = (v1 - v2)[0]
        f_pinion = -np.sign(slide) * np.array([1.0, 0.0])
        towards_pinion_root = f_pinion @ (p - o1) < 0
        towards_ring_root = -f_pinion @ (p - o2) > 0
        assert towards_pinion_root == towards_ring_root
        assert towards_pinion_root == (li > 0)


def test_friction_stiffens_approach_softens_recess_internal():
    """Consequence for the ring pair (as Yang et al. 2026 figs. 6-7 for external pairs): a tooth
    pair with friction is stiffer than without in the approach and softer in the recess, and
    the ring tooth alone follows the same sign."""
    pair = planet_ring()
    model = PairModel.build(pair)
    j = list(pair.pair_indices()).index(0)
    s = np.linspace(pair.s_start + 1e-5, pair.s_end - 1e-5, 41)
    k0 = stiffness_at(model, s).pairs[:, j]
    k1 = stiffness_at(model, s, friction=FrictionModel(mu=0.1)).pairs[:, j]
    approach, recess = s < pair.s_pitch, s > pair.s_pitch
    assert np.all(k1[approach] > k0[approach])
    assert np.all(k1[recess] < k0[recess])
    r2 = pair.contact_radii(s)[1]
    dry = tooth_compliance(model.gear, r2).tooth
    wet = tooth_compliance(model.gear, r2, 0.1, friction_direction(s, pair.s_pitch)).tooth
    assert np.all(wet[approach] < dry[approach]) and np.all(wet[recess] > dry[recess])


# ---- body term ----------------------------------------------------------------------------------

def test_ring_body_term_values_and_thin_rim_refused():
    """Ring body term (ring_body): P = P0 + P1 ln(t_R / S_f) grows with the rim (as a
    half-plane's displacement against a support at depth t_R does), L and M are the fit's,
    the fit ranges are reported, and a rim thinner than S_f / 2 is one clear error."""
    g = ring(80)
    model = tooth_model(g)
    coef = model.foundation
    s_f = model.root_thickness
    L, M, P0, P1 = RING_TABLE
    assert (coef.L, coef.M, coef.Q) == (L, M, 0.0)
    assert coef.P == pytest.approx(P0 + P1 * math.log(4 * 3e-3 / s_f), rel=1e-12)
    assert coef.in_fit_range
    thick = ring_coefficients(ring(80, rim_modules=10.0), coef.theta_f)
    assert thick.P > coef.P
    assert not ring_coefficients(ring(80, rim_modules=20.0), coef.theta_f).in_fit_range
    with pytest.raises(InputError, match="ring.rim_outer_radius .* outside the allowed range"):
        tooth_model(ring(80, rim_modules=0.8))


def test_assembly_errors_of_an_internal_pair_are_refused_in_one_line(tmp_path):
    """Centre displacements are modelled for external pairs (the assembly-error paper): an
    internal pair file with them is one InputError line from the command, exit status 2."""
    text = (CONFIGS / "planet_ring_pair.toml").read_text() + (
        "\n[pair]\nassembly_error_gear_um = [10.0, 10.0]\n")
    path = tmp_path / "ring_errors.toml"
    path.write_text(text)
    with pytest.raises(InputError, match="assembly errors are modelled for external pairs"):
        load_gearbox(path)
    assert main(["stiffness", str(path), "--out", str(tmp_path / "out")]) == 2


# ---- ISO 6336 and the external pair with the same planet --------------------------------------

@pytest.mark.parametrize(("z_planet", "z_ring", "measured"), [
    (30, 80, (1.134, 1.500, 1.141, 1.163)), (24, 60, (1.164, 1.557, 1.199, 1.229)),
    (25, 100, (1.145, 1.472, 1.110, 1.127)), (30, 104, (1.127, 1.469, 1.105, 1.122)),
    (20, 120, (1.161, 1.454, 1.090, 1.104))])
def test_internal_pair_against_iso_and_the_external_pair(z_planet, z_ring, measured):
    """Mean mesh stiffness of a planet-ring pair (m 3 mm, 20 deg, b 20 mm, rim 4 m_n) against
    ISO 6336-1 method B and against the external pair with the same planet (bore 0.45 z m).

    ISO 6336-1 treats an internal gear by z_n2 = inf in q' (the ring tooth counts as a rack
    tooth) and its larger contact ratio in c_gamma_alpha = c' (0.75 eps_a + 0.25); its bodies
    are solid discs (C_R = 1). Measured (``measured`` = int/ISO, int/ext, int/ext without the
    big gear's body term, ISO int/ext), e.g. 30/80: internal 5.75e8 N/m = 1.134 x ISO (5.07e8),
    external 3.83e8 N/m = 0.879 x ISO; the internal mesh is 1.50 x the external one where ISO
    says 1.163. The difference is the body: at the pitch point the ring's body term is
    6.6e-12 m^2/N against 28.1e-12 for the external 80-tooth gear (Sainsot's term includes
    the torsion of the body between root circle and bore, which a ring clamped 4 m_n behind
    its teeth does not have); the ring tooth itself is 12 % stiffer (9.6 vs 10.9e-12, it
    widens towards its root) and the contact ratio 11 % larger (1.938 vs 1.740). Without
    the big gear's body term the model's internal/external ratio is within 3 % of ISO's.

    Tolerances: 0.5 % on the measured ratios (regression; the model is deterministic, the
    margin covers library round-off), and the stated physics as bounds: the internal pair
    above the external one by more than ISO says, and above ISO itself by 5-25 %.
    """
    p = spur(z_planet, "planet", bore_radius=0.45 * z_planet * 1e-3)
    internal = GearPair(p, ring(z_ring))
    external = GearPair(p, spur(z_ring, "gear", bore_radius=0.45 * z_ring * 1e-3))
    mi, me = PairModel.build(internal), PairModel.build(external)
    ki, ke = mesh_stiffness(mi, 720).mean, mesh_stiffness(me, 720).mean
    iso_i, iso_e = iso_stiffness(internal).mesh_stiffness, iso_stiffness(external).mesh_stiffness

    def no_gear_body(model):
        zero = FoundationCoefficients(0.0, 0.0, 0.0, 0.0, 1.0, 0.1, True)
        return dataclasses.replace(model, gear=dataclasses.replace(model.gear, foundation=zero))

    bare = (mesh_stiffness(no_gear_body(mi), 720).mean
            / mesh_stiffness(no_gear_body(me), 720).mean)
    got = (ki / iso_i, ki / ke, bare, iso_i / iso_e)
    assert got == pytest.approx(measured, rel=5e-3)
    assert 1.05 < ki / iso_i < 1.25
    assert ki / ke > iso_i / iso_e > 1.0
    assert bare == pytest.approx(iso_i / iso_e, rel=0.03)


# ---- the rack limit --------------------------------------------------------------------------

def test_internal_and_external_pairs_close_in_on_the_rack():
    """z -> inf: a ring and an external gear both become the rack, so with the same planet the
    internal and the external pair tend to the pinion-rack pair, from either side, like 1/z.

    Exact limit: the pinion-rack path of contact g = sqrt(r_a1^2 - r_b1^2) - r_b1 tan a +
    h_a* m / sin a (contact ratio 1.8172 here). The tooth compliance of the big gear at the
    same roll distance from the pitch point, and the mesh stiffness with the big gear's body
    term left out (the two bodies have no common limit: a rim clamped behind the teeth vs an
    annulus clamped at a bore), differ between ring and external gear by O(1/z): the fitted
    slopes of log(difference) against log(z) are -1 within 0.1 (measured: -1.0 contact
    ratio, -1.0 tooth, -1.0 +- 0.1 mesh), and at z = 2000 the pairs are 0.55 % apart.
    """
    m, a = 3e-3, D(20.0)
    p = spur(30, "planet", bore_radius=0.45 * 30 * 1e-3)
    g_rack = (math.sqrt(p.tip_radius_**2 - p.base_radius**2) - p.base_radius * math.tan(a)
              + m / math.sin(a))
    eps_rack = g_rack / (math.pi * m * math.cos(a))
    zero = FoundationCoefficients(0.0, 0.0, 0.0, 0.0, 1.0, 0.1, True)
    zs = np.array([250, 500, 1000, 2000])
    d_eps, d_tooth, d_mesh = [], [], []
    for z in zs:
        pairs = (GearPair(p, ring(int(z))), GearPair(p, spur(int(z), "gear",
                                                             bore_radius=0.45 * z * 1e-3)))
        eps_i, eps_e = (q.transverse_contact_ratio for q in pairs)
        assert eps_e < eps_rack < eps_i
        d_eps.append(eps_i - eps_e)
        models = [PairModel.build(q) for q in pairs]
        d = np.linspace(-0.004, 0.004, 5)
        ct = [tooth_compliance(mo.gear, q.contact_radii(q.s_pitch + d)[1]).tooth
              for mo, q in zip(models, pairs, strict=True)]
        d_tooth.append(np.max(np.abs(ct[0] / ct[1] - 1)))
        k = [mesh_stiffness(dataclasses.replace(mo, gear=dataclasses.replace(
            mo.gear, foundation=zero)), 3600).mean for mo in models]
        assert k[0] > k[1]
        d_mesh.append(k[0] / k[1] - 1)
    for diff, tol in ((d_eps, 0.05), (d_tooth, 0.05), (d_mesh, 0.1)):
        assert np.polyfit(np.log(zs), np.log(diff), 1)[0] == pytest.approx(-1.0, abs=tol)
    assert d_mesh[-1] < 0.006


# ---- loaded contact ----------------------------------------------------------------------------

@pytest.fixture(scope="module")
def example_box():
    return load_gearbox(CONFIGS / "planet_ring_pair.toml")


def test_loaded_cycle_internal_linear_equals_slice_method(example_box):
    """With the constant Hertz term, independent slices and no friction, the loaded contact
    analysis of the ring pair on the nominal path equals the analytical slice method at every
    position (the identity k = sum 1/G_ii, see pipeline.contact.ltca), and its loads sum to
    P."""
    box = example_box
    op = box.operation
    dry = StiffnessOptions(friction=0.0)
    src = analytical_compliance(box.pair, op, ContactOptions(tip_contact=False), dry)
    cyc = analyse_contact(src, op, ContactOptions(positions=24, local_contact="linear"))
    ref = stiffness_at(src.model, cyc.s0, 1, FrictionModel(), op)
    np.testing.assert_allclose(cyc.mesh_stiffness_secant, ref.total, rtol=1e-9)
    np.testing.assert_allclose(cyc.pair_loads.sum(axis=1), cyc.load, rtol=1e-12)


def test_loaded_cycle_internal_weber_and_friction(example_box):
    """The ring pair's loaded cycle on the nominal path with the Weber-Banaschek local
    contact (Yang et al. 2026, eq. 24) and friction 0.05 at 150 N m:

    * the pair loads sum to P = T / r_b1 at every position (to the solver's tolerance);
    * secant stiffness: mean 0.832 x the slice method's (measured; the local approach of
      eq. 24 is softer than the constant Hertz term of the slice method, as for external
      pairs, where it costs 10-14 %); asserted within 0.80-0.90;
    * friction moves load towards the tooth pair in approach: where one pair touches before
      the pitch point and the other after it (29 of the 36 positions), the pair in approach
      carries more with mu = 0.05 than without, the pair in recess less (friction stiffens
      approach and softens recess; see test_friction_points_to_both_roots_in_approach_internal
      for the sign). When both pairs are in approach both stiffen and the shift is not signed.
    """
    box = example_box
    op = box.operation
    opts = ContactOptions(positions=36, tip_contact=False)
    wet = analyse_contact(analytical_compliance(box.pair, op, opts, box.stiffness), op, opts)
    dry = analyse_contact(analytical_compliance(box.pair, op, opts, StiffnessOptions()), op,
                          opts)
    p = line_of_action_load(box.pair, op)
    assert p == pytest.approx(150.0 / box.pair.pinion.base_radius, rel=1e-14)
    np.testing.assert_allclose(wet.pair_loads.sum(axis=1), p, rtol=1e-9)
    ref = stiffness_at(PairModel.build(box.pair), wet.s0, 1, box.stiffness.friction_model, op)
    ratio = wet.mesh_stiffness_secant.mean() / ref.mean
    assert ratio == pytest.approx(0.832, abs=0.005)
    assert 0.80 < ratio < 0.90
    s_pairs = wet.s0[:, None] + wet.pair_index[None, :] * box.pair.base_pitch
    loaded = wet.pair_loads > 0
    approach = (s_pairs < box.pair.s_pitch) & loaded
    recess = (s_pairs > box.pair.s_pitch) & loaded
    mixed = approach.any(axis=1) & recess.any(axis=1)  # one pair each side of the pitch point
    approach, recess = approach & mixed[:, None], recess & mixed[:, None]
    assert mixed.sum() >= 20
    assert np.all(wet.pair_loads[approach] > dry.pair_loads[approach])
    assert np.all(wet.pair_loads[recess] < dry.pair_loads[recess])


# ---- every ring end to end ---------------------------------------------------------------------

RINGS = [  # (ring teeth, planet teeth, m_n mm, alpha_n deg, helix deg of the helical variant)
    (60, 21, 2.0, 20.0, 10.0),
    (80, 30, 3.0, 20.0, 12.0),
    (95, 37, 15.0, 25.0, 8.0),   # Xu et al. (2020), one helical half
    (100, 31, 4.0, 20.0, 15.0),
    (104, 31, 7.35, 20.0, 4.0),  # the gear module of Yang et al. (2026)
    (120, 35, 2.5, 25.0, 20.0),
]


def _pair_file(tmp: Path, z_ring, z_planet, m, alpha, beta) -> Path:
    rim = z_ring * m / (2 * math.cos(D(beta))) + 1.25 * m + 4 * m
    helix = f'helix_angle_deg = {beta}\nhand = "left"\n' if beta else ""
    text = f"""
[pinion]
teeth = {z_planet}
module_mm = {m}
pressure_angle_deg = {alpha}
face_width_mm = {8 * m}
bore_radius_mm = {0.3 * z_planet * m:.4f}
{helix}
[gear]
teeth = {z_ring}
module_mm = {m}
pressure_angle_deg = {alpha}
face_width_mm = {8 * m}
internal = true
rim_outer_radius_mm = {rim:.4f}
{helix}
[operation]
torque_Nm = {0.8 * z_planet * m * m:.2f}  # 200 N/mm of face at the reference circle
speed_rpm = 1000.0
[stiffness]
friction = 0.05
positions = 48
slices = 24
[contact]
positions = 6
slices = 12
load_map_profile_points = 12
render = false
"""
    path = tmp / f"ring{z_ring}_{'helical' if beta else 'spur'}.toml"
    path.write_text(text)
    return path


CASES = [(r, helical) for r in RINGS for helical in (False, True)]
CLI_DEFAULT = {(80, False), (95, True)}  # the rest of the matrix runs with -m slow


@pytest.mark.parametrize(("case", "helical"), CASES,
                         ids=[f"{r[0]}-{'helical' if h else 'spur'}" for r, h in CASES])
def test_every_ring_through_the_analytical_stages(tmp_path, case, helical):
    """Geometry, stiffness and loaded contact of each ring (spur and helical, same hand as
    the planet) from its pair file: stiffness positive everywhere, and the physics of
    test_internal_pair_against_iso_and_the_external_pair for every ring: the internal pair
    stiffer than ISO 6336-1 method B and stiffer than the external pair with the same planet
    and a gear of the ring's tooth count (same module, bore 0.3 z m like the planet, the
    opposite hand) by more than ISO's own internal/external ratio, which exceeds 1 (ISO:
    z_n2 = inf and the larger contact ratio; the model adds the ring's stiffer body).
    Measured: internal / ISO 1.31-1.45, internal / external 1.33-1.44 against ISO's
    1.06-1.23. The contact ratio of the geometry stage is the stiffness stage's, pair
    loads sum to the load."""
    z_ring, z_planet, m, alpha, beta = case
    box = load_gearbox(_pair_file(tmp_path, z_ring, z_planet, m, alpha, beta if helical else 0))
    geo = analyse_geometry(box.pair)
    res = analyse_stiffness(box.pair, box.operation, box.stiffness)
    assert np.all(res.mesh.total > 0)
    g = box.pair.gear
    hand = {"right": "left", "left": "right"}.get(g.hand, g.hand)
    external = GearPair(box.pair.pinion, dataclasses.replace(
        g, internal=False, bore_radius=0.3 * z_ring * m * 1e-3, hand=hand))
    ext = analyse_stiffness(external, box.operation, box.stiffness)
    iso_ratio = res.iso.mesh_stiffness / ext.iso.mesh_stiffness
    assert res.mesh.mean > res.iso.mesh_stiffness
    assert res.mesh.mean / ext.mesh.mean > iso_ratio > 1.0
    assert geo.summary()["transverse_contact_ratio"] == res.actual.transverse_contact_ratio
    opts = dataclasses.replace(box.contact, positions=3)
    cyc = analyse_contact(analytical_compliance(box.pair, box.operation, opts, box.stiffness),
                          box.operation, opts)
    np.testing.assert_allclose(cyc.pair_loads.sum(axis=1), cyc.load, rtol=1e-9)
    assert np.all(cyc.mesh_stiffness_secant > 0)


@pytest.mark.parametrize(("case", "helical"), [
    pytest.param(r, h, marks=() if (r[0], h) in CLI_DEFAULT else pytest.mark.slow)
    for r, h in CASES], ids=[f"{r[0]}-{'helical' if h else 'spur'}" for r, h in CASES])
def test_rings_through_the_command_line(tmp_path, capsys, case, helical):
    """gearpipe geometry, stiffness and contact on a pair file with an internal gear: exit 0,
    their files written, and the printed JSON summaries agree with the Python API (two
    rings by default, all twelve with -m slow: each command plots, about 1.5 s a call)."""
    z_ring, z_planet, m, alpha, beta = case
    path = _pair_file(tmp_path, z_ring, z_planet, m, alpha, beta if helical else 0)
    summaries = {}
    for cmd in ("geometry", "stiffness", "contact"):
        assert main([cmd, str(path), "--out", str(tmp_path / cmd), "--json"]) == 0
        summaries[cmd] = json.loads(capsys.readouterr().out)
    for cmd, name in (("geometry", "geometry.json"), ("stiffness", "mesh_stiffness.csv"),
                      ("contact", "contact_cycle.csv")):
        assert (tmp_path / cmd / name).is_file()
    box = load_gearbox(path)
    res = analyse_stiffness(box.pair, box.operation, box.stiffness)
    assert summaries["stiffness"]["potential_energy"]["mean_N_per_m"] == pytest.approx(
        res.mesh.mean, rel=1e-12)
    assert summaries["geometry"]["transverse_contact_ratio"] == pytest.approx(
        box.pair.transverse_contact_ratio, rel=1e-12)
    assert summaries["contact"]["load_N"] == pytest.approx(
        line_of_action_load(box.pair, box.operation), rel=1e-12)


def test_planetary_ring_mesh_and_herringbone_halves():
    """The planet-ring mesh of Xu et al. (2020)'s herringbone stage: analyse_stiffness runs on
    it (both helical halves in line: exactly twice one half), and the contact stage takes
    one helical half (the herringbone pair itself is refused with one line, as for
    external pairs)."""
    box = load_gearbox(CONFIGS / "wind_turbine_herringbone_planetary.toml")
    pr = box.planetary.planet_ring
    op = OperatingPoint(1000.0, 10.0)
    opts = StiffnessOptions(positions=60, slices=40)
    both = analyse_stiffness(pr, op, opts)
    p = dataclasses.replace(pr.pinion, herringbone=False, groove_width=0.0,
                            face_width=pr.face_width)
    g = dataclasses.replace(pr.gear, herringbone=False, groove_width=0.0,
                            face_width=pr.gear.half_width)
    half_pair = GearPair(p, g)
    half = analyse_stiffness(half_pair, op, opts)
    np.testing.assert_allclose(both.mesh.total, 2.0 * half.mesh.total, rtol=1e-12)
    with pytest.raises(InputError, match="herringbone pairs are not supported"):
        analytical_compliance(pr, op)
    cyc = analyse_contact(analytical_compliance(half_pair, op, ContactOptions(slices=20)), op,
                          ContactOptions(positions=4, slices=20))
    np.testing.assert_allclose(cyc.pair_loads.sum(axis=1), cyc.load, rtol=1e-9)


@pytest.mark.slow
@pytest.mark.parametrize(("z", "alpha", "rim"), [(80, 20.0, 4.0), (95, 25.0, 4.1),
                                               (50, 20.0, 3.0)])
def test_ring_tooth_and_body_against_whole_ring_fe(z, alpha, rim):
    """Tooth + ring body term against a 2D FE of the whole ring (P2, plane stress, outer rim
    surface clamped, Hertz near field removed; refinement 1.0, within 2 % of refinement 2.0
    at the root end), at 9 flank points from tip to root. The body term was fitted on such
    rings (workflows/ring_body_fit.py); 50 teeth and the 4.1-module rim of Xu et al. (2020)'s
    ring are not among the fitted rings. Tolerance: the fit's largest error over its 288
    points was 10.7 % (RMS 2.9 %); measured here -4.6 to +2.6 %, RMS 1.6-2.3 %. Sainsot's
    external formula mapped to h_f = r_rim / r_f is far off (measured +23 % at the tip to
    +220 % at the root; asserted > 25 % somewhere): the reason for the ring fit."""
    from pipeline.contact.fe2d_source import gear_table
    from pipeline.fem.settings import FE2DSettings
    from pipeline.stiffness.foundation import foundation_coefficients

    g = ring(z, alpha_deg=alpha, rim_modules=rim)
    tab, _ = gear_table(g, FE2DSettings(teeth=None, points=9, refinement=1.0,
                                        kind="plane_stress"), np.array([0]))
    fe = np.diag(tab.structural)
    model = tooth_model(g)
    c = tooth_compliance(model, tab.points.radius)
    err = (c.tooth + c.foundation) / fe - 1.0
    assert np.max(np.abs(err)) < 0.11
    assert np.sqrt(np.mean(err**2)) < 0.05
    sainsot = dataclasses.replace(model, foundation=foundation_coefficients(
        g.root_radius, g.bore_radius, model.foundation.theta_f))
    old = tooth_compliance(sainsot, tab.points.radius)
    assert np.max(np.abs((old.tooth + old.foundation) / fe - 1.0)) > 0.25


@pytest.mark.slow
def test_ring_body_fit_workflow_coarse(tmp_path):
    """workflows/ring_body_fit.py, coarse (8 rings, refinement 0.5): its fit reproduces the
    whole-ring FE flank compliance within 4 % RMS (measured 2.8 %), the translation term grows
    with ln(t_R/S_f) at about the Flamant rate 2/pi = 0.64 (measured 0.68), and its
    coefficients are those of the shipped full fit within the coarse mesh's error (L, M,
    P0 within 25 %: measured L 3.47 vs 3.30, M 1.30 vs 1.31, P0 0.58 vs 0.70)."""
    import importlib.util

    path = Path(__file__).parents[1] / "workflows" / "ring_body_fit.py"
    spec = importlib.util.spec_from_file_location("ring_body_fit", path)
    wf = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(wf)
    assert wf.main(["--out", str(tmp_path)]) == 0
    fit = json.loads((tmp_path / "fit.json").read_text())
    assert fit["total_compliance_error_rms"] < 0.04
    assert 0.55 < fit["P1"] < 0.8
    for got, shipped in zip((fit["L"], fit["M"], fit["P0"]), RING_TABLE[:3], strict=True):
        assert got == pytest.approx(shipped, rel=0.25)
