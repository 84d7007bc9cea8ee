"""Case of line contact across a rounded tip's tangency with its involute
(:mod:`pipeline.contact.tangency`): the collocation solver against Hertz (Johnson 1985).

Two half-planes (E* = 1, unit load per unit length) with a quadratic gap of radius R give
Hertz's half-width b = sqrt(4 R / pi), peak pressure 2 / (pi b) and, in the solver's
logarithmic kernel, an approach whose difference from radius 1's is ln(1 / R) / pi (Johnson
1985, eqs. 4.43 and 4.45 with the half-plane's logarithmic displacement). Across a
tangency the correction Phi(q, xi) (q the rounding's radius over the involute's, xi where
the contact point lies in Hertz half-widths from the tangency) has exact limits: 0 where the
involute's Hertz patch ends at the tangency (xi = -1), ln(1 / q) where the rounding's patch
starts there (xi = 1); both are solved here without the shortcut that :func:`phi` takes
beyond them.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.verification.context import Context
from pipeline.verification.model import Outcome, Quantity

HERTZ_RATIOS = (0.5, 0.01)
"""Radii R (with R = 1 the unit) of the plain Hertz comparison."""
LIMIT_RATIOS = (0.001, 0.05, 0.3)
"""Radius ratios q of the limits of the tangency correction."""


def case_tangency_hertz_limits(context: Context) -> Outcome:
    """The solver's approach and peak pressure against Hertz; the tangency correction at
    xi = -1 and xi = 1 against its exact limits 0 and ln(1 / q)."""
    from pipeline.contact import tangency as T

    b_1 = math.sqrt(4.0 / math.pi)
    q = []
    for r in HERTZ_RATIOS:
        b = b_1 * math.sqrt(r)
        edges = np.linspace(-1.6 * b, 1.6 * b, 193)  # elements of b / 60
        centres = 0.5 * (edges[:-1] + edges[1:])
        u, p = T.line_contact(centres**2 / (2.0 * r), edges)
        q += [Quantity(f"approach difference pi (u(R) - u(1)), R = {r:g}", "-",
                       math.log(1.0 / r), (u - T.hertz_approach(b_1)) * math.pi, "absolute",
                       2e-4, "the collocation's error (1.2e-4 on the tests' graded grid, "
                             "5.2e-5 on elements of b / 60); the tests hold 2e-4"),
              Quantity(f"peak pressure 2 w / (pi b), R = {r:g}", "-", 2.0 / (math.pi * b),
                       float(p.max()), "relative", 5e-3,
                       "the element at the centre averages the pressure's peak (the tests "
                       "hold 0.5 %; measured 3.6e-5 on elements of b / 60)")]
    for r in LIMIT_RATIOS:
        q += [Quantity(f"tangency correction Phi at xi = -1, q = {r:g}", "-", 0.0,
                       T.solved_phi(r, -1.0), "absolute", 2e-4,
                       "the collocation's error (as Hertz's approach, 2e-4)"),
              Quantity(f"tangency correction Phi at xi = 1, q = {r:g}", "-", math.log(1.0 / r),
                       T.solved_phi(r, 1.0), "absolute", 2e-3,
                       "the collocation's error where the curvature changes at the patch's "
                       "edge (measured up to 7e-4 in a correction of up to 6.9); the tests "
                       "hold 2e-3")]
    inputs = (("units", "non-dimensional: E* = 1, load w = 1 per unit length, radii in "
                        "units of the involute's (or the reference) radius"),
              ("model", "two elastic half-planes, "
                        "piecewise-constant pressure, collocation with an active set"),
              ("Hertz radii R", ", ".join(f"{r:g}" for r in HERTZ_RATIOS)
               + " (uniform elements of b / 60 over +-1.6 b)"),
              ("tangency ratios q", ", ".join(f"{r:g}" for r in LIMIT_RATIOS)))
    return Outcome("Hertz line contact, Johnson (1985), Contact Mechanics, eqs. 4.43 and 4.45; "
                   "the tangency correction's limits by construction", inputs, tuple(q))
