"""Points on the involute flanks of a sector: position, normal, roll/arc coordinate, depth.

:class:`FlankPoints` holds flank points of a 2D sector (:func:`flank_points` here) or
of a 3D one (the profile x face grids of :func:`pipeline.fem.flank_grid.flank_grid`);
the influence routine (:mod:`pipeline.fem.influence`) takes either.

A flank point is given by its tooth ``k`` of the sector, its side (``"right"``:
the clockwise flank, x >= 0 in the tooth frame; ``"left"``) and its radius ``r``
(m) on the involute. In the tooth frame (centre line along +y) the right flank
point is ``r (sin psi, cos psi)`` with ``psi = gear.half_tooth_angle(r)``; the
outward normal (out of the tooth material) is perpendicular to the involute and
tangent to the base circle. The *arc coordinate* along the involute from the
base circle is ``t = (r^2 - r_b^2) / (2 r_b)`` (the roll length squared over
``2 r_b``), the *depth* ``h`` is the distance from the point along the inward
normal to the tooth centre line (h_k of Yang et al. 2026, eq. 24, Weber-Banaschek).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError, check_choice

SIDES = ("right", "left")


@dataclass(frozen=True, eq=False)
class FlankPoints:
    """``n`` candidate contact points on the flanks of a 2D or 3D sector (``dim`` 2 or 3).

    Attributes
    ----------
    tooth : (n,) int, sector tooth index.
    side : (n,) int, +1 right flank, -1 left flank.
    radius : (n,) radius on the involute, m.
    position : (n, dim) coordinates, m.
    normal : (n, dim) outward unit normal (out of the tooth material).
    tangent : (n, dim) unit tangent along the transverse profile, towards the tip.
    arc : (n,) arc coordinate along the involute from the base circle, m.
    depth : (n,) transverse distance along the inward normal to the tooth centre line, m
        (h of Yang et al. 2026, eq. 24; in 3D the 2D depth of the same point).
    z : 3D only, else None: (n,) axial position, m (0 .. face width).
    tangent_face : 3D only, else None: (n, 3) unit in-surface tangent ``normal x tangent``
        (z component >= 0).
    shape : 3D only, else None: (n_teeth, n_face, n_profile) of the grid.
    """

    tooth: np.ndarray
    side: np.ndarray
    radius: np.ndarray
    position: np.ndarray
    normal: np.ndarray
    tangent: np.ndarray
    arc: np.ndarray
    depth: np.ndarray
    z: np.ndarray | None = None
    tangent_face: np.ndarray | None = None
    shape: tuple[int, int, int] | None = None

    def __len__(self) -> int:
        return int(self.radius.size)

    @property
    def dim(self) -> int:
        """2 (points of a 2D sector) or 3."""
        return int(self.position.shape[1])

    def same_flank(self) -> np.ndarray:
        """(n, n) bool: points i and j lie on the same flank (tooth and side)."""
        return (self.tooth[:, None] == self.tooth[None, :]) & (self.side[:, None] == self.side)

    def subset(self, index: np.ndarray) -> FlankPoints:
        """The points ``index`` (a grid's ``shape`` is dropped: a subset is no grid)."""
        def take(a):
            return None if a is None else a[index]

        return FlankPoints(self.tooth[index], self.side[index], self.radius[index],
                           self.position[index], self.normal[index], self.tangent[index],
                           self.arc[index], self.depth[index], take(self.z),
                           take(self.tangent_face))


def flank_points(gear: GearSpec, teeth: int, tooth: ArrayLike, radius: ArrayLike,
                 side: str = "right") -> FlankPoints:
    """Geometry of involute points of a ``teeth``-tooth sector (tooth angles as in sector2d).

    Parameters
    ----------
    gear : the gear.
    teeth : number of teeth of the sector.
    tooth : (n,) sector tooth indices in ``[0, teeth)``.
    radius : (n,) radii on the involute, m, between the base and tip circles.
    side : "right" or "left" (all points).
    """
    check_choice("flank.side", side, SIDES)
    k = np.asarray(tooth, dtype=int).reshape(-1)
    r = np.asarray(radius, dtype=float).reshape(-1)
    if k.size != r.size:
        raise InputError(f"flank points: {k.size} tooth indices but {r.size} radii")
    if np.any((k < 0) | (k >= teeth)):
        raise InputError(f"flank points: tooth index outside [0, {teeth - 1}]")
    rb, ra = gear.base_radius, gear.active_tip_radius  # the involute's end
    lo, hi = (rb, ra) if not gear.internal else (max(rb, ra), gear.root_radius)
    if np.any((r < lo * (1 - 1e-12)) | (r > hi * (1 + 1e-12))):
        raise InputError(f"flank radius outside the involute [{lo:.6g}, {hi:.6g}] m: "
                         f"{r.min():.6g} .. {r.max():.6g} m")
    psi = np.array([gear.half_tooth_angle(float(v)) for v in r])
    dpsi = np.sqrt(np.maximum(r * r - rb * rb, 0.0)) / (rb * r)  # tan(alpha)/r
    dpsi = dpsi if gear.internal else -dpsi
    x, y = r * np.sin(psi), r * np.cos(psi)
    tx, ty = np.sin(psi) + r * np.cos(psi) * dpsi, np.cos(psi) - r * np.sin(psi) * dpsi
    nrm = np.hypot(tx, ty)
    tx, ty = tx / nrm, ty / nrm
    if gear.internal:  # radius decreases towards the tip
        tx, ty = -tx, -ty
    nx, ny = ty, -tx
    flip = nx < 0
    nx, ny = np.where(flip, -nx, nx), np.where(flip, -ny, ny)
    depth = x / nx
    sgn = 1.0 if side == "right" else -1.0
    loc_p = np.column_stack([sgn * x, y])
    loc_n = np.column_stack([sgn * nx, ny])
    loc_t = np.column_stack([sgn * tx, ty])
    ang = (k - (teeth - 1) / 2.0) * 2.0 * math.pi / gear.teeth
    c, s = np.cos(ang), np.sin(ang)

    def rot(v: np.ndarray) -> np.ndarray:
        return np.column_stack([c * v[:, 0] - s * v[:, 1], s * v[:, 0] + c * v[:, 1]])

    arc = (r * r - rb * rb) / (2.0 * rb)
    return FlankPoints(k, np.full(k.size, int(sgn)), r, rot(loc_p), rot(loc_n), rot(loc_t),
                       arc, depth)


def active_radii(gear: GearSpec, n: int, lo: float | None = None, hi: float | None = None,
                 margin: float | None = None) -> np.ndarray:
    """``n`` radii (m) equally spaced in roll length between ``lo`` and ``hi``.

    Defaults: ``lo`` the larger of the base radius and ``root + 1.1 m_n`` (external;
    internal: the tip radius), ``hi`` the tip radius (internal: ``root - 1.1 m_n``);
    the end points are kept ``margin`` (m of arc length, default 0.15 m_n, i.e.
    1.5 load-patch half-widths) inside, so no load patch crosses the tip corner (the end of
    the involute: :attr:`GearSpec.active_tip_radius` with a tip rounding).
    """
    rb, ra = gear.base_radius, gear.active_tip_radius
    if gear.internal:
        lo = lo if lo is not None else max(ra, rb)
        hi = hi if hi is not None else gear.root_radius - 1.1 * gear.module
    else:
        lo = lo if lo is not None else max(rb, gear.root_radius + 1.1 * gear.module)
        hi = hi if hi is not None else ra
    margin = 0.15 * gear.module if margin is None else margin
    a0 = (lo * lo - rb * rb) / (2 * rb) + margin
    a1 = (hi * hi - rb * rb) / (2 * rb) - margin
    if a1 <= a0:
        raise InputError(f"no involute left between {lo:.6g} m and {hi:.6g} m after margins")
    arcs = np.linspace(a0, a1, n)
    return np.sqrt(2 * rb * arcs + rb * rb)


def table_radii(gear: GearSpec, n: int, patch: float = 0.1) -> np.ndarray:
    """``n`` tabulated involute radii (m), ascending: as close to both ends of the involute
    as the load patch of half-width ``patch`` m_n allows (1.1 patch of arc inside)."""
    from pipeline.geometry.profile import tooth_profile

    form = tooth_profile(gear).form_radius
    margin = 1.1 * patch * gear.module
    if gear.internal:
        return active_radii(gear, n, hi=min(form, gear.root_radius), margin=margin)
    return active_radii(gear, n, lo=max(form, gear.base_radius), margin=margin)
