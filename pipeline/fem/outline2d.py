"""The outline of a 2D gear sector (or whole gear) as polyline pieces, and its inner radius.

Shared by the 2D meshes (:mod:`pipeline.fem.sector2d`) and the 3D sectors lofted from the
same outline (:mod:`pipeline.fem.sector3d`). Pieces run counter-clockwise, one group per
flank (``right{k}`` / ``left{k}``: from the middle of the tooth space over the fillet and
involute to the middle of the tip land), split at sharp corners so that splines through
them do not overshoot.

Gears whose cutter tip round fills the tooth space (h_f* = 1.55 on the helical pair of Yang
et al. 2026) have a zero-length root circle; the outline merges the repeated points
(:data:`MERGE_TOL`).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError

if TYPE_CHECKING:
    from pipeline.fem.mesh_settings import SectorSettings, SectorSettings3D

CORNER_DEG = 12.0  # outline turns sharper than this split the spline (tip corners)
# outline points closer than this (times m_n) are one point: Gmsh cannot mesh a zero-length curve
MERGE_TOL = 1e-6


def inner_radius(gear: GearSpec, settings: SectorSettings | SectorSettings3D) -> float:
    """Radius of the sector's inner (external gear) or outer (internal gear) boundary, m.

    ``settings.inner_radius`` if given, else ``gear.bore_radius`` if > 0, else (solid
    external gear) a hub at ``max(0.25 r_f, r_f - 6 m_n)``: a solid gear has no
    bore, and a sector cannot reach the centre.
    """
    if settings.inner_radius is not None:
        r = settings.inner_radius
    elif gear.bore_radius > 0:
        r = gear.bore_radius
    else:
        r = max(0.25 * gear.root_radius, gear.root_radius - 6.0 * gear.module)
    rf = gear.root_radius
    if gear.internal and r <= rf * 1.001:
        raise InputError(f"sector rim radius {r:.6g} m must exceed the root radius {rf:.6g} m")
    if not gear.internal and r >= rf * 0.999:
        raise InputError(f"sector bore radius {r:.6g} m must be below the root radius {rf:.6g} m")
    return float(r)


def _drop_repeated(pts: np.ndarray, tol: float) -> np.ndarray:
    """``pts`` (m, 2) without the points closer than ``tol`` (m) to their predecessor.

    The profile repeats points where a feature has zero length: when the cutter tip
    round fills the whole rack tooth space (e.g. h_f* = 1.55 with the largest
    rho_a0*), the root circle land shrinks to the middle of the tooth space, and its
    ``max(4, n // 6)`` points (twice, from both flanks) coincide. Splines and lines
    through such points have zero length, which Gmsh cannot mesh (it hangs on the
    whole gear with "Impossible to recover edge", or returns no triangles).
    """
    step = np.hypot(*np.diff(pts, axis=0).T)
    return pts[np.r_[True, step > tol]]


def outline_pieces(gear: GearSpec, teeth: int, points: int) -> list[tuple[str, np.ndarray]]:
    """The outline as (group name, (m, 2) polyline) pieces, CCW, split at flank ends/corners."""
    from pipeline.geometry.profile import gear_outline

    pts = _drop_repeated(gear_outline(gear, teeth=teeth, points=points),
                         MERGE_TOL * gear.module)
    z = gear.teeth
    ang = np.unwrap(np.arctan2(pts[:, 1], pts[:, 0]))
    cuts = [0]
    names = []
    for k in range(teeth):
        centre = math.pi / 2 + (k - (teeth - 1) / 2.0) * 2.0 * math.pi / z
        i_tip = int(np.argmin(np.abs(ang - centre)))
        i_end = int(np.argmin(np.abs(ang - (centre + math.pi / z))))
        cuts += [i_tip, i_end]
        names += [f"right{k}", f"left{k}"]
    pieces = []
    for (a, b), name in zip(zip(cuts[:-1], cuts[1:], strict=True), names, strict=True):
        seg = pts[a:b + 1]
        # split further at sharp corners (tip corner) so splines do not overshoot
        d = np.diff(seg, axis=0)
        turn = np.abs(np.degrees(np.diff(np.unwrap(np.arctan2(d[:, 1], d[:, 0])))))
        corners = [0, *(np.flatnonzero(turn > CORNER_DEG) + 1).tolist(), len(seg) - 1]
        for c0, c1 in zip(corners[:-1], corners[1:], strict=True):
            if c1 > c0:
                pieces.append((name, seg[c0:c1 + 1]))
    return pieces
