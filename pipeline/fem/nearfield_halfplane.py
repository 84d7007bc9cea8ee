"""The local (Hertzian) near field of a 2D flank load patch, for subtraction from FE.

:func:`nearfield_halfplane` is the matrix ``H`` below for the points of a 2D sector;
:mod:`pipeline.fem.influence` subtracts it.

The problem. A load on the flank compresses the material right under it: in
2D the surface displacement of a half-plane grows like ``ln(1/a)`` as the load
width ``a`` shrinks, so an FE compliance of a (nearly) concentrated load depends
on the mesh and on the load patch and says nothing about the real Hertzian
contact, whose width follows from the load and the curvatures.

The method (Weber & Banaschek's split, as used by Andersson & Vedmar, J. Mech.
Des. 125 (2003) 524-534, for FE/half-plane hybrids). The approach of a flank
point is the displacement of a reference point *inside* the tooth, the point
at depth ``h`` on the tooth centre line along the contact normal, plus the
compression of the material between that point and the surface. The second
part is local: Weber and Banaschek take it from the half-plane, which gives
Yang et al. (2026), eq. (24) (:class:`pipeline.contact.hertz.HertzLineContact`, added by
the contact solver with the actual Hertz half-width). So the FE must deliver
the first part: the *structural* compliance

    G_struct,ij = G_FE,ij - H_ij,

where ``G_FE,ij`` is the FE approach at patch ``i`` (the same patch weights as
the load, which keeps the matrix symmetric, Maxwell-Betti) per unit load on
patch ``j``, and ``H_ij`` the same quantity for the elastic half-plane measured
relative to the depth ``h`` under the measuring point: the analytical near field
of the very load the FE carried. ``H`` is applied to pairs on the same flank
(for other flanks/teeth the half-plane is not a model of the near field and the
FE far field is exact). The FE patch ``q(t) = cos^2(pi t / (2 c)) / c`` (``|t| < c``,
``t`` the arc coordinate) has a fixed physical half-width ``c``, so the FE part
converges under mesh refinement, and the difference is independent of ``c`` up
to ``O(c^2/h^2)`` (tests check both).

Half-plane kernel. For a unit line load (N/m) on a half-plane, the normal
compression between the surface point at distance ``u`` from the load and the
point at depth ``h`` below it is the integral of the Flamant strain
(Johnson, Contact Mechanics, eq. 2.15):

    plane strain : Delta(u) = (1 + nu)/(pi E) [(1 - nu) ln(1 + h^2/u^2) - h^2/(u^2 + h^2)]
    plane stress : Delta(u) = 1/(pi E) [ln(1 + h^2/u^2) - (1 + nu) h^2/(u^2 + h^2)]

(m^2/N). Averaged over a semi-elliptical Hertz pressure at ``u = 0`` it gives
Weber's ``2 (1 - nu^2)/(pi E) (ln(2 h / a) - nu / (2 (1 - nu)))`` to
``O(a^2/h^2)`` (tests), i.e. eq. (24) per body. ``H_ij`` is this kernel
convolved with the autocorrelation of the patch, evaluated by product
integration against the closed-form antiderivative of the kernel.

For a 3D model the analogue is the Boussinesq half-space near field of the same
kind of patch (:mod:`pipeline.fem.nearfield_halfspace`); integrated along a line,
its kernel is the plane-strain kernel below (tested).
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.fem.flank import FlankPoints
from pipeline.geometry.gear import Material
from pipeline.validation import check_choice, check_positive


def _coefficients(material: Material, kind: str) -> tuple[float, float]:
    check_choice("nearfield_halfplane.kind", kind, ("plane_strain", "plane_stress", "3d"))
    E, nu = material.youngs_modulus, material.poisson_ratio
    if kind == "plane_stress":
        return 1.0 / (math.pi * E), (1.0 + nu) / (math.pi * E)
    return (1.0 - nu * nu) / (math.pi * E), (1.0 + nu) / (math.pi * E)


def halfplane_kernel(u: np.ndarray, depth: np.ndarray, material: Material,
                     kind: str = "plane_strain") -> np.ndarray:
    """Delta(u): compression surface -> depth of a half-plane per unit line load, m^2/N.

    ``u`` (m, != 0) distance from the load along the surface, ``depth`` h (m), broadcast.
    """
    A, B = _coefficients(material, kind)
    u2 = np.asarray(u, dtype=float) ** 2
    h2 = np.asarray(depth, dtype=float) ** 2
    return A * np.log1p(h2 / u2) - B * h2 / (u2 + h2)


def _kernel_antiderivative(u: np.ndarray, h: np.ndarray, A: float, B: float) -> np.ndarray:
    """Odd antiderivative of Delta in u (zero at u = 0)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        t = np.where(u == 0.0, 0.0, u * np.log1p(h * h / np.where(u == 0.0, 1.0, u * u)))
    at = np.arctan(u / h)
    return A * (t + 2.0 * h * at) - B * h * at


def patch_autocorrelation(half_width: float, panels: int = 800) -> tuple[np.ndarray, np.ndarray]:
    """Panel edges (K+1,) and panel values (K,) of the autocorrelation of the cos^2 patch.

    The patch ``q(t) = cos^2(pi t / (2 c)) / c`` on ``|t| < c`` has unit integral; its
    autocorrelation ``R(v) = int q(t) q(t + v) dt`` (1/m, support ``|v| < 2 c``) too.
    """
    c = check_positive("patch.half_width", half_width, unit="m")
    n = 4001
    t = np.linspace(-c, c, n)
    dt = t[1] - t[0]
    q = np.cos(0.5 * math.pi * t / c) ** 2 / c
    R = np.convolve(q, q[::-1]) * dt  # at v = (k - (n-1)) dt
    v = (np.arange(R.size) - (n - 1)) * dt
    edges = np.linspace(-2 * c, 2 * c, panels + 1)
    mid = 0.5 * (edges[1:] + edges[:-1])
    vals = np.interp(mid, v, R)
    return edges, vals / np.sum(vals * np.diff(edges))


def patch_halfplane_compliance(separation: np.ndarray, depth: np.ndarray, half_width: float,
                               material: Material, kind: str = "plane_strain",
                               panels: int = 800) -> np.ndarray:
    """H(s): half-plane compression (surface -> depth ``h``) averaged over a cos^2 patch
    at distance ``s`` from a unit load spread over an equal patch, m^2/N (shape of ``s``).

    Parameters
    ----------
    separation : s, distance between the patch centres along the surface, m.
    depth : h, reference depth, m (broadcast with ``s``).
    half_width : c, patch half-width, m.
    material, kind : elastic constants; "plane_strain" (also used for "3d") or "plane_stress".
    panels : product-integration panels over the autocorrelation support.
    """
    A, B = _coefficients(material, kind)
    s, h = np.broadcast_arrays(np.asarray(separation, dtype=float), np.asarray(depth, dtype=float))
    edges, vals = patch_autocorrelation(half_width, panels)
    flat_s, flat_h = s.reshape(-1, 1), h.reshape(-1, 1)
    out = np.empty(flat_s.shape[0])
    step = max(1, 2_000_000 // edges.size)
    for a in range(0, out.size, step):  # bounded temporary memory
        ss, hh = flat_s[a:a + step], flat_h[a:a + step]
        F = _kernel_antiderivative(ss - edges[None, :], hh, A, B)
        out[a:a + step] = -(np.diff(F, axis=1) * vals[None, :]).sum(axis=1)
    return out.reshape(s.shape)


def nearfield_halfplane(points: FlankPoints, half_width: float, material: Material,
                        kind: str = "plane_strain", panels: int = 200) -> np.ndarray:
    """(n, n) ``H`` of the 2D ``points`` (module docstring), m^2/N: same-flank pairs, separated
    by their arc coordinates, at the geometric mean of their depths; zero elsewhere.

    ``panels`` of the product integration: 200 differ from 800 by 2e-5 of the largest
    entry (30 points per flank, 0.1 m_n patches; measured), far below the FE error, at a
    quarter of the cost.
    """
    H = np.zeros((len(points), len(points)))
    ii, jj = np.nonzero(points.same_flank())
    h = np.sqrt(points.depth[ii] * points.depth[jj])
    H[ii, jj] = patch_halfplane_compliance(points.arc[ii] - points.arc[jj], h, half_width,
                                           material, kind, panels)
    return H


def weber_halfplane(load_half_width: float, depth: float, material: Material) -> float:
    """Weber-Banaschek compression of one body per unit line load (plane strain), m^2/N:
    ``2 (1 - nu^2)/(pi E) (ln(2 h / a) - nu / (2 (1 - nu)))`` (one body of Yang et al. 2026, eq.
    24)."""
    E, nu = material.youngs_modulus, material.poisson_ratio
    return 2 * (1 - nu * nu) / (math.pi * E) * (math.log(2 * depth / load_half_width)
                                                 - nu / (2 * (1 - nu)))
