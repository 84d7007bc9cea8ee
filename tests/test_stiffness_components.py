"""Analytical stiffness building blocks: sections, foundation, friction, ISO 6336, Fourier."""

from __future__ import annotations

import math

import numpy as np
import pytest
from gearsets import spur

from pipeline.geometry import GearPair
from pipeline.signals import PeriodicSignal
from pipeline.stiffness.foundation import SAINSOT_TABLE, sainsot_polynomials
from pipeline.stiffness.friction import (
    ehl_friction_coefficient,
    friction_direction,
    hertz_line_pressure,
    load_components,
)
from pipeline.stiffness.iso6336 import contact_line_stiffness, iso_stiffness, q_prime
from pipeline.stiffness.sections import ToothSections
from pipeline.stiffness.tooth import classical_tooth_model, tooth_compliance
from pipeline.validation import InputError
from pipeline.verification.cases_compliance import closed_form_compliance

# Published ranges of the Sainsot coefficients over their fitted data (Sainsot et al. 2004).
PUBLISHED = {"L": (6.82, 6.94), "M": (1.08, 3.29), "P": (2.56, 13.47), "Q": (0.141, 0.62)}


@pytest.mark.parametrize("h_f", [2.0, 3.0, 4.0, 5.0, 6.0])
@pytest.mark.parametrize("theta_f", [0.08, 0.1, 0.15])
def test_sainsot_polynomials_in_published_ranges(h_f, theta_f):
    """Signs from the original paper: L*, M*, P*, Q* of typical gear bodies fall in its ranges.

    theta_f 0.08-0.15 rad covers standard teeth with 20-40 teeth (theta_f ~ pi/z for a
    full-radius root); at the corners of the fit (theta_f <= 0.05 with h_f >= 3) the polynomial
    for L* overshoots the published maximum 6.94 by up to 0.13 %, a property of the fit itself.
    """
    for name, value in zip("LMPQ", sainsot_polynomials(h_f, theta_f), strict=True):
        lo, hi = PUBLISHED[name]
        assert lo <= value <= hi, (name, value)


def test_sainsot_signs_matter():
    """The sign-stripped table (as the extracted paper text prints it) leaves Q* out of range."""
    b = np.array([1 / 0.06**2, 2.85**2, 2.85 / 0.06, 1 / 0.06, 2.85, 1.0])
    q_wrong = (np.abs(SAINSOT_TABLE) @ b)[3]
    assert not PUBLISHED["Q"][0] <= q_wrong <= PUBLISHED["Q"][1]


def test_section_integrals_exact_for_uniform_beam():
    """Uniform section h: int_0^c (c - e)^2 / I = c^3 / (3 I), int 1/A = c / A (exact)."""
    eta = np.linspace(0, 0.01, 2001)
    sec = ToothSections.from_half_thickness(eta, np.full_like(eta, 2e-3), clamp_radius=0.05)
    c = 0.007
    inertia = (4e-3) ** 3 / 12
    b2, b1, b0, a0 = sec.beam_integrals(c)
    assert b2 == pytest.approx(c**3 / (3 * inertia), rel=1e-6)
    assert b1 == pytest.approx(c**2 / (2 * inertia), rel=1e-6)
    assert b0 == pytest.approx(c / inertia, rel=1e-9)
    assert a0 == pytest.approx(c / 4e-3, rel=1e-9)


@pytest.mark.parametrize("a1", [0.05, 0.15, 0.3, 0.42])
@pytest.mark.parametrize("mu_lam", [0.0, 0.1, -0.1])
def test_classical_tooth_matches_closed_form(a1, mu_lam):
    """Base-circle-clamped involute tooth vs the closed-form integrals of Yang et al. (2026)
    (eqs. 11-13, 21-23; by quadrature in pipeline.verification.cases_compliance).

    The contact point with load angle a1 has tan(alpha_R) = a1 + a2 (a2: half base angle);
    friction enters as F_b = F(cos a1 - mu lam sin a1), F_a = F(sin a1 + mu lam cos a1).
    Relative tolerances with ``abs=0`` (the compliances are 1e-16 to 2e-11 m^2/N, below
    pytest's default absolute tolerance): 2e-5, and 5e-5 for bending at a1 = 0.05, whose
    error falls at second order with the section count (9.1e-5, 2.5e-5, 5.0e-6 at 2000,
    4000, 8000 sections; measured).
    """
    g = spur(50, "g")
    model = classical_tooth_model(g)
    a2 = g.half_tooth_angle(g.base_radius)
    r = g.base_radius / math.cos(math.atan(a1 + a2))
    c = tooth_compliance(model, r, mu=abs(mu_lam), lam=np.sign(mu_lam))
    bending, shear, axial = closed_form_compliance(g, a1, mu_lam)
    rel_bending = 5e-5 if a1 < 0.1 else 2e-5
    assert float(c.bending) == pytest.approx(bending, rel=rel_bending, abs=0)
    assert float(c.shear) == pytest.approx(shear, rel=2e-5, abs=0)
    assert float(c.axial) == pytest.approx(axial, rel=2e-5, abs=0)


def test_section_table_convergence():
    """Bending compliance converges at second order in the number of tabulated sections."""
    g = spur(50, "g")
    r = 0.5 * (g.base_radius + g.tip_radius_)
    ref = float(tooth_compliance(classical_tooth_model(g, 64000), r).bending)
    ns = np.array([250, 500, 1000, 2000])
    err = [abs(float(tooth_compliance(classical_tooth_model(g, n), r).bending) - ref) / ref
           for n in ns]
    rate = np.polyfit(np.log(1.0 / ns), np.log(err), 1)[0]
    assert rate > 1.8
    assert err[-1] < 1e-5


def test_friction_sign_convention():
    """lam = +1 in approach, -1 in recess, 0 at the pitch point; approach lowers F_b."""
    lam = friction_direction([0.01, 0.02, 0.03], s_pitch=0.02, driver="pinion")
    np.testing.assert_array_equal(lam, [1.0, 0.0, -1.0])
    np.testing.assert_array_equal(friction_direction([0.01, 0.03], 0.02, "gear"), [-1.0, 1.0])
    fb, fa = load_components(0.3, 0.1, 1.0)
    assert fb == pytest.approx(math.cos(0.3) - 0.1 * math.sin(0.3))
    assert fa == pytest.approx(math.sin(0.3) + 0.1 * math.cos(0.3))
    # |F|^2 grows by (1 + mu^2) whatever the direction
    assert fb**2 + fa**2 == pytest.approx(1.01)


def test_ehl_friction_formula_value():
    """Xu et al. (2007) regression evaluated by hand for P_h 1 GPa, SR 0.2, V_e 10 m/s, 10 mPa s,
    R 10 mm, S 0.5 um: f = -8.916465 - 0.354068*0.2 + 2.812084 e^-0.2 + 0.620305 e^0.5."""
    f = -8.916465 - 0.354068 * 0.2 + 2.812084 * math.exp(-0.2) + 0.620305 * math.exp(0.5)
    expect = math.exp(f) * 0.2**1.036077 * 10**-0.100601 * 10**0.752755 * 0.01**-0.390958
    mu = ehl_friction_coefficient(0.2, 1e9, 10.0, 0.01, 0.01, 0.5e-6)
    assert float(mu) == pytest.approx(expect, rel=1e-12)
    assert 0.005 < float(mu) < 0.08  # the usual EHL range
    assert float(ehl_friction_coefficient(0.0, 1e9, 10.0, 0.01, 0.01, 0.5e-6)) == 0.0
    rough = ehl_friction_coefficient(0.2, 1e9, 10.0, 0.01, 0.01, 0.9e-6)
    assert float(rough) > float(mu)
    with pytest.raises(InputError, match="viscosity"):
        ehl_friction_coefficient(0.2, 1e9, 10.0, -1.0, 0.01, 0.5e-6)


def test_hertz_line_pressure():
    """p0 = sqrt(w E* / (pi R)), E* = E / (2 (1 - nu^2)) for equal steels (Johnson eq. 4.45)."""
    e_prime = 2e11 / (1 - 0.09)
    p0 = hertz_line_pressure(2e5, 0.01, e_prime)
    assert float(p0) == pytest.approx(math.sqrt(2e5 * e_prime / 2 / (math.pi * 0.01)), rel=1e-14)


@pytest.mark.parametrize("z1,z2,x1,x2", [(20, 40, 0.0, 0.0), (17, 80, 0.3, -0.1),
                                         (31, 104, 0.27807, -0.59026), (50, 50, 0.0, 0.0)])
def test_iso_q_prime_formula(z1, z2, x1, x2):
    """ISO 6336-1 eq. (98) evaluated independently; c'_th = 1/q'."""
    expect = (0.04723 + 0.15551 / z1 + 0.25791 / z2 - 0.00635 * x1 - 0.11654 * x1 / z1
              - 0.00193 * x2 - 0.24188 * x2 / z2 + 0.00529 * x1**2 + 0.00182 * x2**2)
    assert q_prime(z1, z2, x1, x2) == pytest.approx(expect, rel=1e-14)
    pair = GearPair(spur(z1, "pinion", profile_shift=x1), spur(z2, "gear", profile_shift=x2))
    iso = iso_stiffness(pair)
    assert iso.c_th == pytest.approx(1e9 / expect, rel=1e-12)
    # standard basic rack (h_fP* = 1.25, 20 deg): C_B = 0.975; C_M 0.8, C_R 1
    assert iso.c_single == pytest.approx(1e9 / expect * 0.8 * 0.975, rel=1e-12)
    eps = pair.transverse_contact_ratio
    assert iso.c_gamma_alpha == pytest.approx(iso.c_single * (0.75 * eps + 0.25), rel=1e-12)


def test_iso_typical_value_and_load_correction():
    """ISO 6336-1: c' of standard solid steel gears is about 14 N/(mm um) (z around 30)."""
    pair = GearPair(spur(30, "pinion"), spur(30, "gear"))
    assert 12.5 < iso_stiffness(pair).c_single * 1e-9 < 14.5
    light = iso_stiffness(pair, tangential_load=50.0 * 20)  # 50 N/mm
    assert light.c_single / iso_stiffness(pair).c_single == pytest.approx(0.5**0.25, rel=1e-12)


def test_contact_line_method_follows_the_contact_length(helical_traction_pair):
    """k_m(t) = k_ym L(t): the stiffness follows the total contact line length, whose mean
    over a mesh cycle is eps_alpha b / cos(beta_b) (ISO 21771, the contact lines of a
    helical pair sweep the plane of action; 3.8e-7 off at 720 positions, 3.4e-9 at 7200:
    the sampling of the line ends), so that k_ym = c_gamma_alpha cos(beta_b) / eps_alpha
    with ISO 6336-1's c_gamma_alpha b as the mean."""
    pair = helical_traction_pair
    cl = contact_line_stiffness(pair, 720)
    np.testing.assert_allclose(cl.total / cl.contact_length, cl.k_per_length, rtol=1e-12)
    cos_b = math.cos(pair.pinion.base_helix_angle)
    mean_length = pair.transverse_contact_ratio * pair.face_width / cos_b
    assert cl.contact_length.mean() == pytest.approx(mean_length, rel=1e-6)
    assert cl.k_per_length == pytest.approx(
        cl.iso.mesh_stiffness / pair.face_width * cos_b / pair.transverse_contact_ratio,
        rel=1e-6)


def test_fourier_series_exact_for_trigonometric_signal():
    """A sampled trigonometric polynomial is reproduced exactly by its Fourier series."""
    tau = np.arange(64) / 64
    v = 5.0 + 2.0 * np.cos(2 * np.pi * tau + 0.3) + 0.5 * np.cos(6 * np.pi * tau - 1.1)
    fs = PeriodicSignal(v).fourier(5)
    assert fs.mean == pytest.approx(5.0)
    np.testing.assert_allclose(fs.amplitude[:3], [2.0, 0.0, 0.5], atol=1e-12)
    assert fs.phase[0] == pytest.approx(0.3)
    assert fs.phase[2] == pytest.approx(-1.1)
    np.testing.assert_allclose(fs(tau), v, atol=1e-12)
    with pytest.raises(InputError, match="n_harmonics"):
        PeriodicSignal(v).fourier(40)


def test_periodic_signal_shift_and_wrap():
    v = np.arange(8.0)
    sig = PeriodicSignal(v)
    assert float(sig(1.0)) == 0.0 and float(sig(0.0625)) == pytest.approx(0.5)
    np.testing.assert_allclose(sig.shifted(0.25).values, np.roll(v, 2))
