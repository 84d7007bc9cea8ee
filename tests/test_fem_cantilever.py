"""Exact-solution rungs of the 2D elasticity layer: the Timoshenko cantilever.

Reference: Timoshenko & Goodier, *Theory of Elasticity* (3rd ed., 1970), section 21,
in the form of Augarde & Deeks, Finite Elem. Anal. Des. 44 (2008) 595-600: a beam
0 <= x <= L, |y| <= D/2, unit thickness, end shear P with parabolic distribution at
x = L, plane stress,

    u_x = -P y / (6 E I) [(6 L - 3 x) x + (2 + nu) (y^2 - D^2/4)]
    u_y =  P / (6 E I) [3 nu y^2 (L - x) + (4 + 5 nu) D^2 x / 4 + (3 L - x) x^2]
    s_xx = -P (L - x) y / I,  s_yy = 0,  t_xy = P / (2 I) (D^2/4 - y^2),

plane strain with E -> E / (1 - nu^2), nu -> nu / (1 - nu). The tip deflection is
u_y(L, 0) = P L^3 / (3 E I) + (4 + 5 nu) P D^2 L / (24 E I); a Timoshenko beam with
shear coefficient 5/6 gives P L^3 / (3 E I) + P L / (5/6 G A), which differs from
the elasticity value by about 0.1 % at L/D = 10 (the shear terms differ by the end
condition only). The exact solution and the FE cantilever are
:mod:`pipeline.verification.cases_elasticity`'s.
"""

from __future__ import annotations

import numpy as np
import pytest

from pipeline.verification.cases_elasticity import (
    CANTILEVER,
    cantilever_constants,
    cantilever_exact_tip,
    cantilever_fe,
    cantilever_l2_error,
    cantilever_tip,
)

L, D, P = (CANTILEVER[k] for k in ("length_m", "depth_m", "load_N"))


@pytest.mark.parametrize("kind", ["plane_stress", "plane_strain"])
def test_tip_deflection_exact_and_timoshenko(kind):
    """P2 triangles, 40 x 4 cells: tip deflection within 1 % of the exact value.

    Also within 1 % of the Timoshenko beam formula with shear (kappa = 5/6).
    """
    basis, u, sol = cantilever_fe(40, 4, kind)
    tip = cantilever_tip(basis, u)
    exact = cantilever_exact_tip(kind)
    assert tip == pytest.approx(exact, rel=1e-3)
    E, nu = cantilever_constants(kind)
    G = E / (2 * (1 + nu))
    timo = P * L**3 / (3 * E * D**3 / 12) + P * L / (5 / 6 * G * D)
    assert tip == pytest.approx(timo, rel=1e-2)
    # The reactions on the clamp carry the whole end load.
    assert sol.reactions[1::2].sum() == pytest.approx(-P, rel=1e-9)


def test_l2_convergence_rate_p2():
    """L2 displacement error of P2 falls at least as h^3 (order p + 1), fitted on 3 meshes.

    On these structured meshes the cubic exact solution is approximated slightly
    better than the a-priori rate (measured 3.6), so the check is a bracket.
    """
    hs, errs, tips = [], [], []
    for n in (2, 4, 8):
        basis, u, _ = cantilever_fe(10 * n, n, "plane_stress")
        hs.append(D / n)
        errs.append(cantilever_l2_error(basis, u, "plane_stress"))
        tips.append(abs(cantilever_tip(basis, u) / cantilever_exact_tip("plane_stress") - 1.0))
    rate = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert 2.9 < rate < 4.2
    tip_rate = np.polyfit(np.log(hs), np.log(tips), 1)[0]
    assert tip_rate > 2.9


def test_l2_convergence_rate_p1():
    """P1 converges at h^2 in L2 (same exact solution), a check that the rate test can fail."""
    hs, errs = [], []
    for n in (4, 8, 16):
        basis, u, _ = cantilever_fe(10 * n, n, "plane_stress", order=1)
        hs.append(D / n)
        errs.append(cantilever_l2_error(basis, u, "plane_stress"))
    rate = np.polyfit(np.log(hs), np.log(errs), 1)[0]
    assert rate == pytest.approx(2.0, abs=0.3)
