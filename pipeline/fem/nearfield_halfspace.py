"""The local (Boussinesq) near field of a flank load patch in 3D, for subtraction from FE.

This is the 3D analogue of :mod:`pipeline.fem.nearfield_halfplane`;
:func:`nearfield_halfspace` is the matrix ``H`` below for the points of a 3D sector. A load on a 3D
flank compresses the material right under it; the surface displacement of a
half-space under a point load grows like ``1/rho`` (Boussinesq), so an FE
compliance of a small load patch depends on the patch and the mesh and says
nothing about the real Hertzian contact. As in 2D, the FE is asked for the
*structural* compliance

    G_struct,ij = G_FE,ij - H_ij,

the approach of the point at depth ``h`` below flank point ``i`` (along the
inward normal) per unit load at ``j``. ``H_ij`` is the compression of an elastic
half-space between the surface and depth ``h``, averaged over patch ``i`` per
unit load spread over patch ``j`` - the analytical near field of the very load
the FE carried. The contact solver then adds back the local approach between
the surface and depth ``h`` with the actual contact width (Yang et al. 2026, eq. 24 per
slice, the same ``h``). ``H`` is applied to pairs on the same flank only.

Kernel (Johnson, Contact Mechanics, eq. 3.21a; shear modulus ``G``): a unit
normal point load on a half-space displaces the point at surface distance
``rho`` and depth ``z`` by ``u_z = [2 (1 - nu)/R + z^2 / R^3] / (4 pi G)``,
``R = sqrt(rho^2 + z^2)``, so the compression between the surface and depth ``h``
at surface distance ``rho`` is

    Delta(rho, h) = [2 (1 - nu) (1/rho - 1/R) - h^2 / R^3] / (4 pi G)     (m/N).

Its only singular part is ``A / rho`` with ``A = (1 - nu) / (2 pi G) =
(1 - nu^2) / (pi E)``; it decays like ``-nu h^2 / (2 pi G rho^3)``. Integrated
along an infinite line it gives the plane-strain kernel of the 2D module.

Patch. The FE load patch is ``q(t, w) = cos^2(pi t / 2c) cos^2(pi w / 2c)``
(``|t|, |w| < c``) in the two in-surface directions (profile, face) of
:mod:`pipeline.fem.flank_grid`, scaled to a unit resultant. ``H`` depends on the
separation ``s = (s_t, s_w)`` of the patch centres through the autocorrelation
``R(v) = R_1(v_t) R_1(v_w)`` of the patch, with the closed form (``u = |v|``,
``alpha = pi / c``)

    R_1(u) = [(2c - u)(1 + cos(alpha u) / 2) + 3 sin(alpha u) / (2 alpha)] / (4 c^2),

so ``H(s) = int R(v) Delta(|s - v|, h) dv``. The singular part is scale-free:
``int R(v) A / |s - v| dv = A f(s / c) / c``, with ``f`` tabulated once per call by
polar quadrature about ``s`` (the ``1/rho`` cancels the polar Jacobian) and
interpolated by bicubic splines (beyond ``|s| = 8 c``: a 24 x 24 Gauss rule);
the smooth rest is integrated with a 24 x 24 Gauss rule on the support.
The tests check ``R_1`` against a numerical convolution, ``H`` against a
brute-force quadrature, and ``H -> Delta(|s|)`` for ``|s| >> c``.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.interpolate import RectBivariateSpline

from pipeline.fem.flank import FlankPoints
from pipeline.geometry.gear import Material
from pipeline.validation import check_positive

TABLE_EXTENT = 8.0  # f(sigma) is tabulated for |sigma_t|, |sigma_w| <= 8 (units of c)


def halfspace_kernel(rho: np.ndarray, depth: np.ndarray, material: Material) -> np.ndarray:
    """Delta(rho, h): half-space compression surface -> depth per unit point load, m/N.

    ``rho`` (m, > 0) surface distance from the load, ``depth`` h (m); broadcast.
    """
    G = material.shear_modulus
    nu = material.poisson_ratio
    rho = np.asarray(rho, dtype=float)
    h2 = np.asarray(depth, dtype=float) ** 2
    R = np.sqrt(rho * rho + h2)
    return (2 * (1 - nu) * (1 / rho - 1 / R) - h2 / R**3) / (4 * math.pi * G)


def patch_autocorrelation_1d(u: np.ndarray, half_width: float) -> np.ndarray:
    """R_1(u) = int q(t) q(t + u) dt of the unit 1D cos^2 patch of half-width c, 1/m."""
    c = check_positive("patch.half_width", half_width, unit="m")
    a = np.minimum(np.abs(np.asarray(u, dtype=float)), 2 * c)
    al = math.pi / c
    return ((2 * c - a) * (1 + 0.5 * np.cos(al * a)) + 1.5 * np.sin(al * a) / al) / (4 * c * c)


def _gauss_box(n: int = 24) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Tensor Gauss-Legendre nodes (v_t, v_w) on [-2, 2]^2 and weights times R (c = 1)."""
    x, w = np.polynomial.legendre.leggauss(n)
    x, w = 2 * x, 2 * w
    vt, vw = np.meshgrid(x, x, indexing="ij")
    wt = np.outer(w, w) * patch_autocorrelation_1d(vt, 1.0) * patch_autocorrelation_1d(vw, 1.0)
    return vt.ravel(), vw.ravel(), wt.ravel()


def singular_integral(sigma_t: np.ndarray, sigma_w: np.ndarray, n_phi: int = 192,
                      n_rho: int = 40) -> np.ndarray:
    """f(sigma) = int R(v) / |sigma - v| dv for the c = 1 patch, by polar quadrature.

    About the point ``sigma``: ``int_0^2pi int R(sigma + rho e_phi) d rho d phi`` (the
    1/rho cancels the Jacobian), rho over the part of the ray inside the support
    [-2, 2]^2. Shapes broadcast; dimensionless.
    """
    st, sw = np.broadcast_arrays(np.asarray(sigma_t, float), np.asarray(sigma_w, float))
    shape = st.shape
    st, sw = st.reshape(-1, 1), sw.reshape(-1, 1)
    phi = (np.arange(n_phi) + 0.5) * 2 * math.pi / n_phi
    ex, ey = np.cos(phi)[None, :], np.sin(phi)[None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        # slab method: ray sigma + rho e against the box |v| <= 2
        t1x, t2x = (-2 - st) / ex, (2 - st) / ex
        t1y, t2y = (-2 - sw) / ey, (2 - sw) / ey
    lo = np.maximum(np.maximum(np.minimum(t1x, t2x), np.minimum(t1y, t2y)), 0.0)
    hi = np.minimum(np.maximum(t1x, t2x), np.maximum(t1y, t2y))
    length = np.where(hi > lo, hi - lo, 0.0)  # (m, n_phi)
    x, w = np.polynomial.legendre.leggauss(n_rho)
    out = np.zeros(st.shape[0])
    step = max(1, 400_000 // (n_phi * n_rho))
    for a in range(0, out.size, step):
        sl = slice(a, a + step)
        rho = lo[sl, :, None] + 0.5 * (x + 1) * length[sl, :, None]  # (m, phi, k)
        vt = st[sl, :, None] + rho * ex[:, :, None]
        vw = sw[sl, :, None] + rho * ey[:, :, None]
        val = patch_autocorrelation_1d(vt, 1.0) * patch_autocorrelation_1d(vw, 1.0)
        out[sl] = np.einsum("mpk,k,mp->m", val, 0.5 * w, length[sl]) * (2 * math.pi / n_phi)
    return out.reshape(shape)


def _singular_table(step: float = 0.2) -> RectBivariateSpline:
    """Bicubic spline of ``f`` on ``[0, TABLE_EXTENT]^2``: ``f`` is symmetric in its two
    arguments (the patch is the same along both), so one triangle is integrated, with 24
    radial points (5e-7 of the 40-point values, at 0.6 of the time)."""
    g = np.arange(0.0, TABLE_EXTENT + 0.5 * step, step)
    i, j = np.triu_indices(g.size)
    f = np.empty((g.size, g.size))
    f[i, j] = f[j, i] = singular_integral(g[i], g[j], n_rho=24)
    return RectBivariateSpline(g, g, f, kx=3, ky=3)


def patch_halfspace_compliance(sep_t: np.ndarray, sep_w: np.ndarray, depth: np.ndarray,
                               half_width: float, material: Material) -> np.ndarray:
    """H(s): half-space compression (surface -> depth h) averaged over a cos^2 x cos^2
    patch at separation ``s`` from a unit load spread over an equal patch, m/N.

    Parameters
    ----------
    sep_t, sep_w : separation of the patch centres along the profile and face
        directions, m (broadcast together with ``depth``).
    depth : h, m.
    half_width : c, patch half-width in both directions, m.
    material : elastic constants.
    """
    c = check_positive("patch.half_width", half_width, unit="m")
    st, sw, h = np.broadcast_arrays(np.asarray(sep_t, float), np.asarray(sep_w, float),
                                    np.asarray(depth, float))
    shape = st.shape
    st, sw, h = np.abs(st.ravel()) / c, np.abs(sw.ravel()) / c, h.ravel()
    A = (1 - material.poisson_ratio) / (2 * math.pi * material.shear_modulus)
    G, nu = material.shear_modulus, material.poisson_ratio
    vt, vw, wt = _gauss_box()
    near = (st <= TABLE_EXTENT) & (sw <= TABLE_EXTENT)
    sing = np.empty(st.size)
    if np.any(near):
        sing[near] = _singular_table().ev(st[near], sw[near])
    smooth = np.empty(st.size)
    step = max(1, 2_000_000 // wt.size)
    for a in range(0, st.size, step):
        sl = slice(a, a + step)
        rho = np.hypot(st[sl, None] - vt, sw[sl, None] - vw) * c  # m
        R = np.sqrt(rho * rho + h[sl, None] ** 2)
        rest = -(2 * (1 - nu) / R + h[sl, None] ** 2 / R**3) / (4 * math.pi * G)
        smooth[sl] = rest @ wt
        far = ~near[sl]
        if np.any(far):
            sing[sl][far] = (1.0 / (rho[far] / c)) @ wt
    return (A * sing / c + smooth).reshape(shape)


def nearfield_halfspace(points: FlankPoints, half_width: float, material: Material
                        ) -> np.ndarray:
    """(n, n) ``H`` of the 3D ``points`` (module docstring), m/N: same-flank pairs at the
    geometric mean of their depths; zero elsewhere."""
    H = np.zeros((len(points), len(points)))
    ii, jj = np.nonzero(np.triu(points.same_flank()))  # H is symmetric: one triangle
    d = points.position[ii] - points.position[jj]
    # separation in the frame of j (and of i, averaged: H is even in s, so symmetric)
    st = 0.5 * (np.abs(np.einsum("ij,ij->i", d, points.tangent[jj]))
                + np.abs(np.einsum("ij,ij->i", d, points.tangent[ii])))
    sw = 0.5 * (np.abs(np.einsum("ij,ij->i", d, points.tangent_face[jj]))
                + np.abs(np.einsum("ij,ij->i", d, points.tangent_face[ii])))
    h = np.sqrt(points.depth[ii] * points.depth[jj])
    H[ii, jj] = H[jj, ii] = patch_halfspace_compliance(st, sw, h, half_width, material)
    return H
