"""Line contact across a curvature jump: a rounded tip near its tangency with the involute.

A tip rounded by design (``tip_rounding_mm``, :attr:`GearSpec.tip_rounding`) meets its
involute at the active tip radius with a jump of curvature, from the involute's
``1/rho_inv`` to the rounding's ``1/rho_r``. Hertz of one curvature holds where the
contact patch lies on one side of the tangency; within about a half-width of it the patch
spans both, and taking either curvature alone is wrong by up to the whole difference
(the demo pair with 0.3 mm roundings at 100 N m: the loaded TE stepped by 2.4 % within
0.01 mm of roll where the contact point crossed the tangency).

Model. Two elastic half-planes (plane strain, contact modulus ``E*`` of
:mod:`pipeline.contact.hertz`) pressed together by ``w`` per unit length, with the gap
of the two profiles near the rigid contact point ``x = 0``: ``x^2 / (2 R_near)`` on its
side of the tangency, continued beyond the tangency at ``x = e`` with the same value and
slope and curvature ``1 / R_far``. ``R_i`` and ``R_r`` are the effective radii of the mate's
flank with the involute and with the rounding. The pressure is piecewise constant on a
graded grid of collocation elements (the half-plane's logarithmic influence in closed
form), the contact set found by active-set iteration. The approach differs from Hertz of
``R_i`` by

    du = w / (pi E*) * Phi(q, xi),   q = R_r / R_i,

where ``xi = e_r / b_r`` when the rigid contact point lies on the rounding, ``e_r >= 0``
past the tangency (``b_r`` the Hertz half-width with ``R_r``), and ``xi = e_r / b_i`` on the
involute, ``e_r < 0``: the log kernel's constant is the same for both problems at the same
``w`` and cancels, so ``du`` is the correction to Weber's approach of ``R_i``
(:class:`~pipeline.contact.hertz.HertzLineContact`) measured at the same depths. Exact
limits: ``Phi = 0`` for ``xi <= -1`` (the involute's Hertz patch ends before the tangency
and the rounding beyond it only opens the gap) and ``Phi = ln(1/q)``, Hertz of the
rounding, for ``xi >= 1`` (measured: within 2e-4 of it there). ``Phi`` depends on the load
through ``xi`` (``b ~ sqrt(w)``), so the model's tangent is
``(Phi - xi dPhi/dxi / 2) / (pi b E*)`` per slice width ``b``.

``Phi`` is tabulated over ``q`` in ``[Q_MIN, 1]`` (log-spaced) and ``xi`` in ``[-1, 1]``
(:func:`phi_table`, computed once per process, about a second) and interpolated: cubic
splines in ``xi`` on each side of the tangency, linear in ``ln q``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

import numpy as np
from numpy.typing import ArrayLike

from pipeline.validation import InputError

Q_MIN = 1e-4
"""Smallest ratio R_r / R_i tabulated (a 0.002 m_n rounding against flanks of 20 m_n
effective radius)."""
Q = np.logspace(math.log10(Q_MIN), 0.0, 17)
"""Tabulated ratios q."""
XI_INVOLUTE = np.linspace(-1.0, 0.0, 21)
"""Tabulated xi on the involute side."""
T_ROUNDING = np.linspace(0.0, 1.0, 41)
"""Tabulated ``t = sqrt(xi)`` on the rounding side: a step ``e_r`` onto the rounding turns
its surface by ``e_r / rho_r`` and tilts the involute behind it away, so ``Phi`` rises
steeply from ``xi = 0`` for a small ``q`` (0.0025 of ``b_r`` raises it by 16 % at
``q = 0.001``)."""
TABLE = Path(__file__).with_name("tangency_table.npz")
"""The committed table (``python workflows/tangency_table.py`` writes it)."""


def _influence(centres: np.ndarray, edges: np.ndarray) -> np.ndarray:
    """Surface approach at ``centres`` per unit pressure on each element between ``edges``
    (half-planes with E* = 1): ``-(2 / pi) int ln|x - s| ds``."""

    def primitive(t: np.ndarray) -> np.ndarray:
        a = np.abs(t)
        return np.where(a > 0.0, t * np.log(np.where(a > 0.0, a, 1.0)) - t, 0.0)

    return -(2.0 / math.pi) * (primitive(centres[:, None] - edges[None, :-1])
                               - primitive(centres[:, None] - edges[None, 1:]))


def line_contact(gap: np.ndarray, edges: np.ndarray, load: float = 1.0,
                 max_iter: int = 200) -> tuple[float, np.ndarray]:
    """Approach and element pressures of two half-planes (E* = 1) pressed by ``load`` per
    unit length with the initial ``gap`` at the element centres (collocation, active set)."""
    centres = 0.5 * (edges[:-1] + edges[1:])
    width = np.diff(edges)
    A = _influence(centres, edges)
    n = centres.size
    active = gap <= np.sort(gap)[min(n - 1, 3)]
    for _ in range(max_iter):
        idx = np.flatnonzero(active)
        m = idx.size
        M = np.zeros((m + 1, m + 1))
        M[:m, :m] = A[np.ix_(idx, idx)]
        M[:m, m] = -1.0
        M[m, :m] = width[idx]
        sol = np.linalg.solve(M, np.concatenate([-gap[idx], [load]]))
        p = np.zeros(n)
        p[idx] = sol[:m]
        approach = float(sol[m])
        clearance = A @ p + gap - approach
        dropped = p < 0.0
        added = ~active & (clearance < -1e-12 * max(1.0, abs(approach)))
        if not (dropped.any() or added.any()):
            return approach, p
        active = (active & ~dropped) | added
    raise RuntimeError("line contact: the active set did not settle")


def _gap(x: np.ndarray, x_t: float, r_near: float, r_far: float, near_left: bool
         ) -> np.ndarray:
    """Gap with its minimum 0 at x = 0, curvature 1/r_near on the contact point's side of
    the tangency ``x_t`` (the left side if ``near_left``), continued with the same value
    and slope and curvature 1/r_far beyond it."""
    far = x > x_t if near_left else x < x_t
    beyond = (x_t * x_t / (2.0 * r_near) + x_t / r_near * (x - x_t)
              + (x - x_t) ** 2 / (2.0 * r_far))
    return np.where(far, beyond, x * x / (2.0 * r_near))


def _edges(lo: float, hi: float, x_t: float, fine: float, coarse: float,
           ratio: float = 1.06) -> np.ndarray:
    """Element edges from lo to hi: ``fine`` within 3 fine-zone widths of the tangency
    ``x_t``, growing by ``ratio`` per element away from it up to ``coarse``."""
    out = [x_t]
    for sign, end in ((1.0, hi), (-1.0, lo)):
        x, h = x_t, fine
        while sign * (end - x) > 0.0:
            near = abs(x - x_t) < 40.0 * fine
            h = fine if near else min(coarse, h * ratio)
            x = x + sign * h
            out.append(x)
    return np.unique(np.array(out))


def phi(q: float, xi: float) -> float:
    """``Phi(q, xi)`` (module docstring): the exact limits outside ``(-1, 1)`` and for
    ``q = 1``, else :func:`solved_phi`."""
    if not 0.0 < q <= 1.0:
        raise InputError(f"tangency: radius ratio q = {q!r} must lie in (0, 1]")
    if xi <= -1.0 or q == 1.0:
        return 0.0
    if xi >= 1.0:
        return math.log(1.0 / q)
    return solved_phi(q, xi)


def solved_phi(q: float, xi: float) -> float:
    """``Phi(q, xi)`` by the numerical contact solution (any ``xi``)."""
    b_i = math.sqrt(4.0 / math.pi)  # R_i = 1, w = 1, E* = 1
    b_r = b_i * math.sqrt(q)
    # the involute left of the tangency x_t, the rounding right of it
    if xi < 0.0:  # the contact point on the involute, the tangency ahead
        x_t, r_near, r_far, near_left = -xi * b_i, 1.0, q, True
    else:  # on the rounding, the involute behind
        x_t, r_near, r_far, near_left = -xi * b_r, q, 1.0, False
    lo = min(0.0, x_t) - 1.6 * b_i
    hi = max(0.0, x_t) + 3.0 * b_r
    edges = _edges(lo, hi, x_t, b_r / 40.0, b_i / 60.0)
    centres = 0.5 * (edges[:-1] + edges[1:])
    gap = _gap(centres, x_t, r_near, r_far, near_left)
    u, _ = line_contact(gap, edges)
    return (u - hertz_approach(b_i)) * math.pi


def hertz_approach(b: float) -> float:
    """Approach of the Hertz pressure of half-width ``b`` and unit load on half-planes with
    E* = 1 in the kernel of :func:`line_contact`: ``-(2 / pi) int p ln|s| ds =
    -(2 / pi) (ln(b / 2) - 1 / 2)``."""
    return -(2.0 / math.pi) * (math.log(b / 2.0) - 0.5)


def compute_table() -> np.ndarray:
    """``Phi`` at ``Q`` x (``XI_INVOLUTE``, ``T_ROUNDING**2``), shape (17, 21 + 41), by
    :func:`phi` (about 30 s)."""
    xi = np.concatenate([XI_INVOLUTE, T_ROUNDING**2])
    return np.array([[phi(float(q), float(x)) for x in xi] for q in Q])


@lru_cache(maxsize=1)
def phi_table() -> np.ndarray:
    """The committed table (:data:`TABLE`), checked against the grids it was made on (to
    1e-12: NumPy releases can differ in the last bit of ``logspace``; NumPy 2.4.6 gives
    q = 1e-3 7e-18 away from the committed grid's)."""
    with np.load(TABLE) as z:
        for name, grid in (("q", Q), ("xi_involute", XI_INVOLUTE), ("t_rounding", T_ROUNDING)):
            if z[name].shape != grid.shape or not np.allclose(z[name], grid, rtol=1e-12,
                                                              atol=0.0):
                raise RuntimeError(f"{TABLE}: grid {name!r} differs from the code's; "
                                   "regenerate it with python workflows/tangency_table.py")
        return np.array(z["phi"])


@lru_cache(maxsize=1)
def _splines() -> tuple[list, list]:
    """Per tabulated q: a cubic spline in xi (involute side) and one in t = sqrt(xi)
    (rounding side), both flat at the exact limits xi = -1 and xi = 1."""
    from scipy.interpolate import CubicSpline  # imported where a tip rounding is met only

    values = phi_table()
    k = XI_INVOLUTE.size
    left = [CubicSpline(XI_INVOLUTE, v[:k], bc_type=((1, 0.0), "not-a-knot")) for v in values]
    right = [CubicSpline(T_ROUNDING, v[k:], bc_type=((1, 0.0), (1, 0.0))) for v in values]
    return left, right


def phi_interp(q: ArrayLike, xi: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """``Phi`` and ``xi dPhi/dxi`` interpolated from the table (the broadcast shape of the
    inputs): cubic in ``xi`` (involute side) or ``sqrt(xi)`` (rounding side), linear in
    ``ln q``; the exact limits outside ``[-1, 1]``. ``q`` outside ``[Q_MIN, 1]`` is
    refused."""
    q, xi = np.broadcast_arrays(np.asarray(q, dtype=float), np.asarray(xi, dtype=float))
    if (q < Q_MIN * (1 - 1e-12)).any() or (q > 1.0 + 1e-12).any():
        raise InputError(f"tangency: radius ratio R_r / R_i = {q.min():.4g} outside the "
                         f"tabulated [{Q_MIN:g}, 1]")
    left, right = _splines()
    x = np.clip(xi, -1.0, 1.0)
    t = np.sqrt(np.maximum(x, 0.0))
    lq = np.log(np.clip(q, Q_MIN, 1.0))
    grid = np.log(Q)
    j = np.clip(np.searchsorted(grid, lq) - 1, 0, grid.size - 2)
    w = (lq - grid[j]) / (grid[j + 1] - grid[j])
    val = np.zeros(q.shape)
    slope = np.zeros(q.shape)  # xi dPhi/dxi: on the rounding side (t / 2) dPhi/dt
    for shift, wgt in ((0, 1.0 - w), (1, w)):
        col = j + shift
        for c in np.unique(col):
            neg = (col == c) & (x <= 0.0)
            pos = (col == c) & (x > 0.0)
            val[neg] += wgt[neg] * left[c](x[neg])
            slope[neg] += wgt[neg] * x[neg] * left[c](x[neg], 1)
            val[pos] += wgt[pos] * right[c](t[pos])
            slope[pos] += wgt[pos] * 0.5 * t[pos] * right[c](t[pos], 1)
    val = np.where(xi >= 1.0, np.log(1.0 / q), np.where(xi <= -1.0, 0.0, val))
    return val, np.where(np.abs(xi) >= 1.0, 0.0, slope)


@dataclass(frozen=True)
class TangencyContact:
    """A local contact model with the rounding's tangency correction (module docstring):
    ``u(F) = base.approach(F) + F / (pi b E*) Phi(q, xi(F))``.

    Attributes
    ----------
    base : Weber's model with the involute-side radii (:class:`~pipeline.contact.hertz.
        HertzLineContact`, shape (n,)).
    ratio : (n,) ``q = R_r / R_i`` (1 where no rounding is near: no correction).
    offset : (n,) ``e_r``, m: the rigid contact point's arc distance past the tangency (on
        the rounding, >= 0) or before it (on the involute, < 0).
    """

    base: object
    ratio: np.ndarray
    offset: np.ndarray

    def _phi(self, loads: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """``Phi`` and ``xi dPhi/dxi`` at slice loads F (N)."""
        F = np.maximum(np.asarray(loads, dtype=float), 1e-300)
        b_i = self.base.half_width(F)
        scale = np.where(self.offset >= 0.0, b_i * np.sqrt(self.ratio), b_i)
        return phi_interp(self.ratio, self.offset / scale)

    def _factor(self) -> np.ndarray:
        return 1.0 / (math.pi * self.base.slice_width * self.base.contact_modulus)

    def approach(self, loads: np.ndarray) -> np.ndarray:
        F = np.asarray(loads, dtype=float)
        val, _ = self._phi(F)
        return self.base.approach(F) + np.where(F > 0.0, F * self._factor() * val, 0.0)

    def tangent(self, loads: np.ndarray) -> np.ndarray:
        # Phi depends on F through xi ~ F^(-1/2): d(F Phi)/dF = Phi - (xi dPhi/dxi) / 2
        val, slope = self._phi(loads)
        return self.base.tangent(loads) + self._factor() * (val - 0.5 * slope)

    def max_valid_load(self) -> np.ndarray:
        return self.base.max_valid_load()

