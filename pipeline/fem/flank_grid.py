"""Grids of points on the helical flanks of a 3D sector: profile x face width, with normals.

The grid is a :class:`~pipeline.fem.flank.FlankPoints` with ``z``, ``tangent_face`` and
``shape`` set.

A grid point is given by its sector tooth ``k``, its side, its radius ``r`` on the
involute and its axial position ``z`` (0 <= z <= b). At mid-face (z = b/2) it is
the 2D flank point of :func:`pipeline.fem.flank.flank_points` (same tooth angles,
sides, arc coordinate and depth); at ``z`` it is that point turned about the
gear axis by the section twist ``theta(z)`` of the sector
(:meth:`pipeline.fem.sector3d.SectorMesh3D.twist`).

Frames. With ``p(r)`` the transverse point and ``t2`` its transverse profile
tangent, the flank is ``P(s, z) = R(theta(z)) p + z e_z``; its tangents are
``dP/ds = R t2`` and ``dP/dz = theta' e_z x P + e_z``. The outward unit normal is
their cross product, oriented out of the tooth (it tilts out of the transverse
plane by the base helix angle on the base cylinder and by the helix angle at
radius ``r``, ``tan beta_r = r theta'``, elsewhere). ``tangent`` is
``R t2`` (towards the tip), ``tangent_face = normal x tangent`` (the
in-surface direction across the profile, with a positive z component). These
two in-surface directions are the local coordinates of the load patches
(:mod:`pipeline.fem.patch_loads`).

Ordering: points run over teeth (outer), face positions, then radii (inner), so
``values.reshape(n_teeth, n_face, n_profile)`` gives the grid of each tooth.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from pipeline.fem.flank import SIDES, FlankPoints, flank_points
from pipeline.fem.sector3d import SectorMesh3D
from pipeline.validation import InputError, check_choice, check_int_range, check_range


def face_positions(width: float, n: int, margin: float) -> np.ndarray:
    """``n`` axial positions (m) equally spaced from ``margin`` to ``width - margin``."""
    check_int_range("flank_grid.n_face", n, 1, 10000)
    check_range("flank_grid.face_margin", margin, 0.0, 0.5 * width, hi_open=n > 1, unit="m")
    return np.array([0.5 * width]) if n == 1 else np.linspace(margin, width - margin, n)


def flank_grid(sector: SectorMesh3D, teeth: ArrayLike, radii: ArrayLike, z: ArrayLike,
               side: str = "right") -> FlankPoints:
    """The grid ``teeth x z x radii`` on one side of the teeth of ``sector``.

    Parameters
    ----------
    sector : the 3D sector.
    teeth : (n_teeth,) sector tooth indices.
    radii : (n_profile,) involute radii, m (e.g. :func:`pipeline.fem.flank.active_radii`).
    z : (n_face,) axial positions in ``[0, b]``, m (e.g. :func:`face_positions`).
    side : "right" or "left".
    """
    check_choice("flank_grid.side", side, SIDES)
    k = np.asarray(teeth, dtype=int).reshape(-1)
    r = np.asarray(radii, dtype=float).reshape(-1)
    zz = np.asarray(z, dtype=float).reshape(-1)
    b = sector.width
    if np.any((zz < 0) | (zz > b)):
        raise InputError(f"flank_grid.z outside the face width [0, {b:.6g}] m: "
                         f"{zz.min():.6g} .. {zz.max():.6g} m")
    shape = (k.size, zz.size, r.size)
    kk = np.repeat(k, zz.size * r.size)
    zg = np.tile(np.repeat(zz, r.size), k.size)
    rg = np.tile(r, k.size * zz.size)
    p2 = flank_points(sector.gear, sector.settings.teeth, kk, rg, side)
    th = sector.twist(zg)
    c, s = np.cos(th), np.sin(th)

    def turn(v: np.ndarray) -> np.ndarray:
        return np.column_stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1],
                                np.zeros(len(v))])

    pos = turn(p2.position)
    pos[:, 2] = zg
    t1 = turn(p2.tangent)
    dz = np.column_stack([-sector.twist_rate * pos[:, 1], sector.twist_rate * pos[:, 0],
                          np.ones(zg.size)])  # theta' e_z x P + e_z
    nrm = np.cross(t1, dz)
    nrm /= np.linalg.norm(nrm, axis=1)[:, None]
    flip = np.einsum("ij,ij->i", nrm, turn(p2.normal)) < 0
    nrm[flip] *= -1.0
    t2 = np.cross(nrm, t1)
    t2[t2[:, 2] < 0] *= -1.0
    return FlankPoints(kk, p2.side, rg, pos, nrm, t1, p2.arc, p2.depth, zg, t2, shape)
