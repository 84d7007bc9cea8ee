"""2D gear sector meshes: exact-profile area, boundary groups, cache behaviour.

Reference: the sector area is exact from the profile, ``teeth * A_tooth`` (polygon of
:meth:`ToothProfile.area`, teeth above the root circle) plus the annular sector
between the root and the bore circle, ``(n 2 pi / z) / 2 |r_f^2 - r_bore^2|``.
Curved P2 cells on splines through the profile points reproduce it to ~1e-5
(the polygon area itself differs from the spline by that order).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from skfem import Basis, ElementTriP2, Functional

from pipeline.cache.folder import Cache
from pipeline.fem.mesh_settings import SectorSettings
from pipeline.fem.sector2d import build_sector_mesh_2d, outline_pieces, sector_mesh_2d
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.profile import tooth_profile
from pipeline.validation import InputError

EXT = GearSpec(teeth=30, module=3e-3, pressure_angle=math.radians(20), face_width=0.02,
               bore_radius=0.03)
INT = GearSpec(teeth=80, module=3e-3, pressure_angle=math.radians(20), face_width=0.02,
               internal=True, bore_radius=0.135)


def _area(mesh) -> float:
    return float(Functional(lambda w: 1.0 + 0.0 * w.x[0]).assemble(
        Basis(mesh, ElementTriP2(), intorder=4)))


@pytest.mark.parametrize("gear", [EXT, INT], ids=["external", "internal"])
def test_sector_area_matches_profile(gear, tmp_path):
    """Mesh area vs n * tooth area + annular sector, relative difference < 5e-5."""
    sec = sector_mesh_2d(gear, SectorSettings.for_gear(gear, teeth=3), cache=Cache(tmp_path))
    n, z = 3, gear.teeth
    ring = 0.5 * (n * 2 * math.pi / z) * abs(gear.root_radius**2 - gear.bore_radius**2)
    exact = n * tooth_profile(gear).area() + ring
    assert _area(sec.mesh) == pytest.approx(exact, rel=5e-5)
    names = {f"{s}{k}" for s in ("right", "left") for k in range(3)} | {
        "bore", "cut_left", "cut_right"}
    assert names == set(sec.facets)
    # the bore group lies on the bore circle, every flank group on the tooth outline
    p = sec.mesh.p[:, sec.mesh.facets[:, sec.facets["bore"]].ravel()]
    assert np.hypot(*p) == pytest.approx(gear.bore_radius, rel=1e-9)
    for k in range(3):
        p = sec.mesh.p[:, sec.mesh.facets[:, sec.facets[f"right{k}"]].ravel()]
        r = np.hypot(*p)
        assert r.min() >= min(gear.root_radius, gear.tip_radius_) * (1 - 1e-9)
        assert r.max() <= max(gear.root_radius, gear.tip_radius_) * (1 + 1e-9)


def test_flank_refinement():
    """Edges on the flanks are about ``size_flank`` long, bore edges about ``size_body``."""
    s = SectorSettings.for_gear(EXT, teeth=3, refinement=1.0)
    data = build_sector_mesh_2d(EXT, s)
    pts = data.points

    def mean_len(name):
        e = data.surfaces[name]
        return float(np.mean(np.hypot(*(pts[:, e[0]] - pts[:, e[1]]))))

    assert mean_len("right1") == pytest.approx(s.size_flank, rel=0.3)
    assert mean_len("bore") == pytest.approx(s.size_body, rel=0.3)


def test_cache_hit_and_new_key(tmp_path):
    """A second call reads the cached file (same arrays); a changed setting makes a new file."""
    s = SectorSettings.for_gear(EXT, teeth=3, refinement=0.5)
    a = sector_mesh_2d(EXT, s, cache=Cache(tmp_path))
    b = sector_mesh_2d(EXT, s, cache=Cache(tmp_path))
    assert np.array_equal(a.mesh.doflocs, b.mesh.doflocs)
    assert len(list(tmp_path.glob("sector2d-*.npz"))) == 1
    sector_mesh_2d(EXT, SectorSettings.for_gear(EXT, teeth=5, refinement=0.5),
                   cache=Cache(tmp_path))
    assert len(list(tmp_path.glob("sector2d-*.npz"))) == 2


def test_rejects_too_many_teeth():
    """A sector must span less than half the gear."""
    with pytest.raises(InputError, match="sector.teeth"):
        build_sector_mesh_2d(EXT, SectorSettings(teeth=15))


def test_whole_gear_with_full_round_root(helical_traction_pair, tmp_path):
    """Yang et al. (2026)'s 31-tooth pinion as a whole gear (regression: Gmsh hung on it).

    With h_f* = 1.55 the largest cutter tip radius fills the rack tooth space, so the
    root circle land has zero length and the profile repeats its points there. The
    outline given to Gmsh must have no curve shorter than the tip half-lands
    (0.22 m_n here; the bound 0.1 m_n leaves room for other gears), four pieces per
    tooth (flank with fillet, two tip halves, flank), and the mesh must reproduce the
    exact area, z A_tooth + pi (r_f^2 - r_bore^2), within 5e-5 (as for the sectors).
    """
    gear = helical_traction_pair.pinion
    assert np.all(np.hypot(*np.diff(tooth_profile(gear).outline()[:10], axis=0).T) == 0.0)
    s = SectorSettings.for_gear(gear, teeth=gear.teeth, refinement=0.3)
    pieces = outline_pieces(gear, gear.teeth, s.profile_points)
    length = [np.hypot(*np.diff(seg, axis=0).T).sum() for _, seg in pieces]
    assert min(length) > 0.1 * gear.module
    assert len(pieces) == 4 * gear.teeth
    sec = sector_mesh_2d(gear, s, cache=Cache(tmp_path))
    exact = (gear.teeth * tooth_profile(gear).area()
             + math.pi * (gear.root_radius**2 - gear.bore_radius**2))
    assert _area(sec.mesh) == pytest.approx(exact, rel=5e-5)
    assert {"right0", f"left{gear.teeth - 1}", "bore"} <= set(sec.facets)
    # the 3-tooth sector of the same gear came back empty (no triangles) before the fix
    assert build_sector_mesh_2d(gear, SectorSettings.for_gear(gear, 3, 0.3)).cells.shape[1] > 500
