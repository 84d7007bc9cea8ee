"""Tooth-surface load maps: the unit load over the pinion and gear flanks for a whole mesh cycle.

Over one mesh cycle the tooth pairs in contact together sweep the whole plane
of action once (pair ``k`` covers ``[s_start + k p_bt, s_start + (k + 1) p_bt)``
at ``z = 0``), so the unit loads of all pairs at all positions of a
:class:`~pipeline.contact.results.LoadedMeshCycle` form the load one tooth sees
as it rolls through the mesh: every point of the flank is loaded once per cycle, so the
map is the envelope of the load over the cycle. :func:`flank_load_map` puts them on a
regular grid (roll coordinate ``s`` x face position ``z``, linear interpolation along
``s`` within each slice); :func:`flank_surface` maps the grid onto the 3D flank of the
pinion (involute at radius ``r1 = sqrt(s^2 + r_b1^2)``) or of an external gear (the
same contact point at ``r2 = sqrt((T1T2 - s)^2 + r_b2^2)``), swept along the helix by
rotating the transverse section through ``z tan(beta) / r_ref``. The flank drawn is the
one on the -x side of a tooth centred on +y, so that seen from outside the tooth with
the tip up the face position b_z runs from left to right, as in the 2D map (which flank
carries the load in service depends on the sense of rotation, which the contact
analysis does not need);
:func:`write_load_map_vtu` saves it for ParaView; :mod:`pipeline.viz.loadmap`
draws it (pyvista PNG, colour bar in N/mm, axes in mm, and a 2D matplotlib map).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.involute import inv
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at
from pipeline.io import atomic_write
from pipeline.validation import InputError, check_choice, check_int_range

MEMBERS = ("pinion", "gear")
"""The gears whose flanks a load map covers."""


@dataclass(frozen=True)
class FlankLoadMap:
    """Unit load on a regular (profile x face) grid of the plane of action.

    Attributes
    ----------
    s : (n_s,) roll coordinates from ``s_start`` to ``s_end``, m, widened to the tip-corner
        contacts beyond either end when the cycle has any.
    z : (n_z,) face positions from 0 to b, m.
    unit_load : (n_s, n_z) load per unit length of contact line, N/m, over the cycle.
    pinion_radius : (n_s,) radius of the contact point on the pinion, m (its tip radius
        where the pinion's tip corner touches, past the end of the path).
    gear_radius : (n_s,) radius of the contact point on the gear, m (its tip radius
        before the start of the path).
    """

    s: np.ndarray
    z: np.ndarray
    unit_load: np.ndarray
    pinion_radius: np.ndarray
    gear_radius: np.ndarray
    s_start: float = -np.inf
    s_end: float = np.inf

    def radius(self, member: str) -> np.ndarray:
        """Contact radius (n_s,) on ``member`` ("pinion" or "gear"), m."""
        check_choice("load map member", member, MEMBERS)
        return self.pinion_radius if member == "pinion" else self.gear_radius

    def tip_corner_load(self, member: str) -> np.ndarray:
        """(n_z,) largest unit load on ``member``'s tip corner over the cycle, N/m (the grid
        rows where it touches beyond the path of contact; 0 where it never does)."""
        check_choice("load map member", member, MEMBERS)
        tip = (self.s > self.s_end) if member == "pinion" else (self.s < self.s_start)
        return self.unit_load[tip].max(axis=0) if tip.any() else np.zeros(self.z.size)


def flank_load_map(cycle: LoadedMeshCycle, pair: GearPair,
                   profile_points: int = 80) -> FlankLoadMap:
    """Grid the point unit loads of a mesh cycle over the plane of action (module docstring).

    ``profile_points`` (>= 2) grid points along the path and the loaded tip-corner contacts
    beyond it; the face grid is the distinct face positions of the candidate points plus
    the two faces (nearest value).
    """
    check_int_range("contact.load_map_profile_points", profile_points, 2, 100_000)
    loaded = cycle.point_s[cycle.point_load > 0]
    lo = min(pair.s_start, float(loaded.min())) if loaded.size else pair.s_start
    hi = max(pair.s_end, float(loaded.max())) if loaded.size else pair.s_end
    s_grid = np.linspace(lo, hi, profile_points)
    zq = np.round(cycle.point_z, 9)
    z_in = np.unique(zq)
    cols = []
    for zj in z_in:
        sel = zq == zj
        order = np.argsort(cycle.point_s[sel])
        cols.append(np.interp(s_grid, cycle.point_s[sel][order],
                              cycle.point_unit_load[sel][order]))
    p = np.stack(cols, axis=1)
    b = pair.face_width
    z = z_in
    if z[0] > 0.0:
        z, p = np.concatenate([[0.0], z]), np.concatenate([p[:, :1], p], axis=1)
    if z[-1] < b:
        z, p = np.concatenate([z, [b]]), np.concatenate([p, p[:, -1:]], axis=1)
    r1, r2 = contact_radii_at(pair, s_grid)
    return FlankLoadMap(s_grid, z, p, np.asarray(r1), np.asarray(r2), pair.s_start, pair.s_end)


def _involute_flank(gear: GearSpec, r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Flank on the -x side (x <= 0) of an external tooth centred on +y at radii ``r`` (m)."""
    at = gear.transverse_pressure_angle
    psi_ref = gear.reference_tooth_thickness / (2.0 * gear.reference_radius)
    a = np.arccos(np.clip(gear.base_radius / r, -1.0, 1.0))
    psi = psi_ref + inv(at) - inv(a)
    return -r * np.sin(psi), r * np.cos(psi)


def _sweep(gear: GearSpec, x: np.ndarray, y: np.ndarray, z: np.ndarray) -> np.ndarray:
    """Transverse points (n,) swept over face positions (n_z,) -> (n, n_z, 3), m."""
    hand = {"right": 1.0, "left": -1.0}.get(gear.hand, 0.0)
    phi = hand * z * math.tan(gear.helix_angle) / gear.reference_radius
    c, s = np.cos(phi)[None, :], np.sin(phi)[None, :]
    X = x[:, None] * c - y[:, None] * s
    Y = x[:, None] * s + y[:, None] * c
    return np.stack([X, Y, np.broadcast_to(z[None, :], X.shape)], axis=-1)


def mapped_members(pair: GearPair) -> tuple[str, ...]:
    """The flanks a load map can be drawn on: the pinion's, and the gear's when external."""
    return MEMBERS[:1] if pair.gear.internal else MEMBERS


def flank_surface(pair: GearPair, load_map: FlankLoadMap, member: str = "pinion") -> np.ndarray:
    """3D points of ``member``'s flank under the grid, (n_s, n_z, 3), m (tooth centred on +y).

    ``member`` is "pinion" or "gear" (an external gear only: :func:`mapped_members`).
    """
    if member not in mapped_members(pair):
        raise InputError(f"load map member {member!r}: the flanks that can be mapped are "
                         f"{', '.join(mapped_members(pair))} (an internal gear's concave "
                         "flank is not drawn)")
    gear = pair.pinion if member == "pinion" else pair.gear
    x, y = _involute_flank(gear, load_map.radius(member))
    return _sweep(gear, x, y, load_map.z)


def _tooth_outline(gear: GearSpec, points: int = 40) -> np.ndarray:
    """Transverse outline of one tooth (m, 2), m: exact profile when available, else involutes."""
    try:
        from pipeline.geometry.profile import tooth_profile
    except ImportError:  # before the exact profile module exists: involute flanks + tip land
        r = np.linspace(max(gear.base_radius, gear.root_radius), gear.tip_radius_, points)
        x, y = _involute_flank(gear, r)
        right = np.stack([x, y], axis=1)  # root -> tip
        return np.concatenate([right * [-1.0, 1.0], right[::-1]])
    return np.asarray(tooth_profile(gear, points).outline(), dtype=float)


def _grid(pv, pts: np.ndarray):
    return pv.StructuredGrid(pts[..., 0], pts[..., 1], pts[..., 2])


def load_map_grid(pair: GearPair, load_map: FlankLoadMap, member: str = "pinion"):
    """pyvista StructuredGrid of ``member``'s loaded flank in mm with point data
    ``unit_load_N_per_mm`` and ``roll_coordinate_mm``."""
    import pyvista as pv

    pts = flank_surface(pair, load_map, member) * 1e3
    grid = _grid(pv, pts)
    # StructuredGrid point order is Fortran (first index fastest)
    grid.point_data["unit_load_N_per_mm"] = (load_map.unit_load * 1e-3).ravel(order="F")
    grid.point_data["roll_coordinate_mm"] = np.repeat(load_map.s[:, None] * 1e3,
                                                      load_map.z.size, 1).ravel(order="F")
    return grid


def tooth_body_grid(gear: GearSpec, z: np.ndarray):
    """pyvista StructuredGrid of one whole tooth of ``gear`` (transverse outline swept over
    the face positions ``z`` (m) along the helix), coordinates in mm."""
    import pyvista as pv

    outline = _tooth_outline(gear)
    return _grid(pv, _sweep(gear, outline[:, 0], outline[:, 1], z) * 1e3)


def write_load_map_vtu(pair: GearPair, load_map: FlankLoadMap, path: str | Path) -> Path:
    """Save the loaded pinion flank as an unstructured VTU of quads (coordinates in mm, point
    data ``unit_load_N_per_mm`` and ``roll_coordinate_mm``), atomically.

    Written with meshio (the same grid as :func:`load_map_grid` without importing pyvista,
    which costs seconds).
    """
    import meshio

    pts = flank_surface(pair, load_map) * 1e3  # (n_s, n_z, 3)
    n_s, n_z = pts.shape[:2]
    idx = np.arange(n_s * n_z).reshape(n_s, n_z)
    quads = np.stack([idx[:-1, :-1], idx[1:, :-1], idx[1:, 1:], idx[:-1, 1:]], axis=-1)
    data = {"unit_load_N_per_mm": (load_map.unit_load * 1e-3).reshape(-1),
            "roll_coordinate_mm": np.repeat(load_map.s[:, None] * 1e3, n_z, 1).reshape(-1)}
    mesh = meshio.Mesh(pts.reshape(-1, 3), [("quad", quads.reshape(-1, 4))], point_data=data)
    return atomic_write(path, lambda p: meshio.write(p, mesh, file_format="vtu"))
