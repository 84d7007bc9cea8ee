"""Hertz line contact and the Weber-Banaschek local approach (pipeline.contact.hertz)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import integrate

from pipeline.contact import (
    HertzLineContact,
    LinearLocalCompliance,
    contact_modulus,
    effective_radius,
    hertz_half_width,
    hertz_max_pressure,
)
from pipeline.geometry import Material
from pipeline.validation import InputError
from pipeline.verification.cases_contact import half_plane_approach

STEEL = Material(youngs_modulus=2.07e11, poisson_ratio=0.3)


def test_two_steel_cylinders_against_textbook():
    """Two steel cylinders, F = 250 N over l = 20 mm, radii 10 mm and 15 mm, E = 207 GPa, nu 0.3.

    Reference: the cylinder-contact formulas in the diameter form of Shigley's
    Mechanical Engineering Design (Budynas & Nisbett), section "Contact stresses":
    ``b = sqrt(2F/(pi l) [(1-nu1^2)/E1 + (1-nu2^2)/E2] / (1/d1 + 1/d2))`` and
    ``p_max = 2F/(pi b l)``. By hand: b = 0.028976 mm, p_max = 274.65 MPa.
    """
    F, length, d1, d2 = 250.0, 0.02, 0.02, 0.03
    E, nu = 2.07e11, 0.3
    b_ref = math.sqrt(2 * F / (math.pi * length) * (2 * (1 - nu**2) / E) / (1 / d1 + 1 / d2))
    p_ref = 2 * F / (math.pi * b_ref * length)
    R = effective_radius(d1 / 2, d2 / 2)
    Es = contact_modulus(STEEL, STEEL)
    a = hertz_half_width(F / length, R, Es)
    p0 = hertz_max_pressure(F / length, R, Es)
    assert a == pytest.approx(b_ref, rel=1e-13)
    assert p0 == pytest.approx(p_ref, rel=1e-13)
    assert a == pytest.approx(2.8976e-5, rel=1e-4)
    assert p0 == pytest.approx(274.65e6, rel=1e-4)
    assert Es == pytest.approx(E / (2 * (1 - nu**2)), rel=1e-15)


def test_semi_elliptic_pressure_carries_the_load():
    """Johnson eq. 4.45: p0 = 2 w / (pi a), i.e. the Hertz pressure
    p0 sqrt(1 - x^2/a^2) integrates to the load per length w (equilibrium)."""
    w, R = 2.5e5, 0.012
    Es = contact_modulus(STEEL, Material(1.1e11, 0.34))  # steel on bronze
    a = float(hertz_half_width(w, R, Es))
    p0 = float(hertz_max_pressure(w, R, Es))
    total, _ = integrate.quad(lambda x: p0 * math.sqrt(1 - (x / a) ** 2), -a, a)
    assert total == pytest.approx(w, rel=1e-9)


def test_weber_approach_is_the_half_plane_solution():
    """Weber-Banaschek per-body approach ``2w(1-nu^2)/(pi E) (ln(2h/a) - nu/(2(1-nu)))``
    against an independent quadrature of half-plane elasticity (Flamant kernel) for
    h/a = 10..160. The formula is the leading term: expanding the exact on-axis
    result, model - exact = -(a/h)^2 (1/4 + nu/(8(1-nu))) in units of
    2w(1-nu^2)/(pi E). So the fitted order must be 2 and the coefficient 0.3036."""
    E, nu, w, R = STEEL.youngs_modulus, STEEL.poisson_ratio, 3.0e5, 0.02
    es = contact_modulus(STEEL, STEEL)
    a = float(hertz_half_width(w, R, es))
    unit = 2 * w * (1 - nu**2) / (math.pi * E)
    ratios = np.array([10.0, 20.0, 40.0, 80.0, 160.0])
    errs = []
    for r in ratios:
        h = r * a
        # one body of a symmetric pair: the model's u_c for h1 = h2 = h is twice this
        model = HertzLineContact(1.0, 2 * R, 2 * R, h, h, STEEL, STEEL)
        errs.append((float(model.approach(w)) / 2 - half_plane_approach(w, a, h, E, nu)) / unit)
    errs = np.array(errs)
    order = np.polyfit(np.log(1 / ratios), np.log(np.abs(errs)), 1)[0]
    assert order == pytest.approx(2.0, abs=0.01)
    coef = 0.25 + nu / (8 * (1 - nu))
    # the next term is O((a/h)^4): 0.4 % of the coefficient at h/a = 10, < 0.1 % from 20 on
    np.testing.assert_allclose(errs[1:] * ratios[1:] ** 2, -coef, rtol=1e-3)


def test_equal_materials_reduce_to_yang2026_eq24():
    """Yang et al. (2026), eq. (24) written out literally for equal materials:
    u = 4F(1-nu^2)/(pi E b) (ln(2 sqrt(k1 k2)/a) - nu/(2(1-nu))),
    a = sqrt(8 F rho1 rho2/(rho1+rho2) (1-nu^2)/(pi E b))."""
    E, nu = STEEL.youngs_modulus, STEEL.poisson_ratio
    F = np.array([10.0, 1e3, 3e4])
    b, r1, r2, k1, k2 = 4e-3, 0.021, 0.065, 5.5e-3, 7.0e-3
    a = np.sqrt(8 * F / b * r1 * r2 / (r1 + r2) * (1 - nu**2) / (math.pi * E))
    u_seed = 4 * F * (1 - nu**2) / (math.pi * E * b) * (
        np.log(2 * math.sqrt(k1 * k2) / a) - nu / (2 * (1 - nu)))
    model = HertzLineContact(b, r1, r2, k1, k2, STEEL, STEEL)
    np.testing.assert_allclose(model.half_width(F), a, rtol=1e-14)
    np.testing.assert_allclose(model.approach(F), u_seed, rtol=1e-13)


def test_dissimilar_materials_sum_per_body_terms():
    """Two materials: u_c is the sum of each body's Weber term with its own E, nu and h."""
    bronze = Material(1.1e11, 0.34)
    F, b, r1, r2, h1, h2 = 2e3, 5e-3, 0.03, 0.08, 6e-3, 4e-3
    model = HertzLineContact(b, r1, r2, h1, h2, STEEL, bronze)
    a = float(model.half_width(F))

    def body(m, h):
        return 2 * F * (1 - m.poisson_ratio**2) / (math.pi * m.youngs_modulus * b) * (
            math.log(2 * h / a) - m.poisson_ratio / (2 * (1 - m.poisson_ratio)))

    assert float(model.approach(F)) == pytest.approx(body(STEEL, h1) + body(bronze, h2),
                                                     rel=1e-13)


@pytest.fixture
def slices() -> HertzLineContact:
    """Three slices of a mesh like Yang et al. (2026)'s (4.3 mm wide, rho 20-60 mm, depths 5-8
    mm)."""
    return HertzLineContact(4.3e-3, [0.02, 0.035, 0.05], [0.06, 0.045, 0.03],
                            [8e-3, 6.5e-3, 5e-3], [5e-3, 6.5e-3, 8e-3], STEEL, STEEL)


def test_approach_is_monotone_concave_with_right_limits(slices):
    """u_c(0) = 0; u_c increasing and concave in F; secant compliance u_c/F grows
    without bound as F -> 0 (logarithmically); positive below max_valid_load."""
    F = np.geomspace(1e-6, 1e5, 200)[:, None] * np.ones(3)
    u = slices.approach(F)
    assert np.all(slices.approach(np.zeros(3)) == 0.0)
    assert np.all(u > 0)
    assert np.all(np.diff(u, axis=0) > 0)
    Fl = np.linspace(1.0, 1e5, 300)[:, None] * np.ones(3)
    assert np.all(np.diff(slices.approach(Fl), 2, axis=0) < 0)
    sec = u / F
    assert np.all(np.diff(sec, axis=0) < 0)
    # the secant compliance grows like -C/2 ln F: doubling per ~ e^(2 u/F / C) decades
    C = 2 / (math.pi * 4.3e-3) * 2 / STEEL.plane_strain_modulus
    slope = np.polyfit(np.log(F[:50, 0]), sec[:50, 0], 1)[0]
    assert slope == pytest.approx(-C / 2, rel=1e-9)


def test_tangent_matches_finite_difference_and_vanishes_at_validity_limit(slices):
    """du_c/dF against a central difference (h = 1e-5 F, truncation ~1e-10), +inf at 0,
    and exactly zero at max_valid_load (closed form)."""
    F = np.array([3.0, 2e3, 4e4])
    h = 1e-5 * F
    fd = (slices.approach(F + h) - slices.approach(F - h)) / (2 * h)
    np.testing.assert_allclose(slices.tangent(F), fd, rtol=1e-8)
    assert np.all(np.isinf(slices.tangent(np.zeros(3))))
    fmax = slices.max_valid_load()
    assert np.all(fmax > 1e5)  # far above gear slice loads
    np.testing.assert_allclose(slices.tangent(fmax) * fmax, 0.0,
                               atol=1e-12 * slices.approach(fmax).max())
    assert np.all(slices.tangent(0.99 * fmax) > 0) and np.all(slices.tangent(1.01 * fmax) < 0)


def test_positions_split_and_validation():
    """(m, n) arrays split per position; bad geometry names the field and index."""
    hz = HertzLineContact(4e-3, np.full((2, 3), 0.02), 0.05, np.full((2, 3), 6e-3), 6e-3)
    assert hz.n_positions == 2 and hz.for_position(1).shape == (3,)
    np.testing.assert_array_equal(hz.for_position(1).approach(np.ones(3)),
                                  hz.approach(np.ones((2, 3)))[1])
    with pytest.raises(InputError, match=r"hertz.radius_1\[1\] = -0.01"):
        HertzLineContact(4e-3, [0.02, -0.01], 0.05, 6e-3, 6e-3)
    with pytest.raises(InputError, match="do not broadcast"):
        HertzLineContact(4e-3, [0.02, 0.01], [0.05, 0.05, 0.05], 6e-3, 6e-3)
    with pytest.raises(InputError, match="local compliance"):
        LinearLocalCompliance([-1e-9])
