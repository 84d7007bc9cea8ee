"""Gmsh session, curved P2 meshes, surface integrals and the on-disk mesh cache.

Geometric references are exact: a cylinder of radius R and length L has volume
pi R^2 L, lateral area 2 pi R L and end area pi R^2. Quadratic (curved) cells
reproduce them to ~2e-5 here; straight-sided ones miss by the inscribed polygon
(~0.1-0.3 % at 16 elements per circle).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from skfem import Basis, ElementTetP2

from pipeline.cache import entries as cache
from pipeline.cache.folder import Cache
from pipeline.fem import mesh_cache
from pipeline.fem.gmsh_session import gmsh_session
from pipeline.fem.groove.body import CoaxialBody, Segment
from pipeline.fem.groove.mesh import MeshSettings, mesh_coaxial_body
from pipeline.fem.tetmesh import surface_mass, to_skfem

R, L, BORE = 0.05, 0.12, 0.02


@pytest.fixture(scope="module")
def tube():
    body = CoaxialBody((Segment("a", 0.0, 0.05, R), Segment("b", 0.05, L, R)), BORE)
    return body, mesh_coaxial_body(body, MeshSettings(0.03))


def test_session_always_finalises():
    import gmsh

    with pytest.raises(RuntimeError, match="boom"), gmsh_session():
        assert gmsh.isInitialized()
        raise RuntimeError("boom")
    assert not gmsh.isInitialized()


def test_curved_p2_volume_and_areas(tube):
    body, data = tube
    assert data.order == 2
    sk = to_skfem(data)
    exact = math.pi * (R**2 - BORE**2) * L
    vol = Basis(sk.mesh, ElementTetP2(), intorder=4).dx.sum()
    assert vol == pytest.approx(exact, rel=1e-4)
    # The same vertices with straight edges (inscribed polygons) miss by far more.
    from skfem import MeshTet1

    flat = MeshTet1(sk.mesh.p, sk.mesh.t)
    vol_flat = Basis(flat, ElementTetP2()).dx.sum()
    assert abs(vol_flat / exact - 1) > 20 * abs(vol / exact - 1)
    # Scalar P2 numbering of the mesh equals the basis numbering used by the models.
    b = Basis(sk.mesh, ElementTetP2())
    np.testing.assert_array_equal(b.doflocs, sk.mesh.doflocs)
    n = sk.mesh.doflocs.shape[1]
    for name, area in (("a:outer", 2 * math.pi * R * 0.05), ("b:outer", 2 * math.pi * R * 0.07),
                       ("end:left", math.pi * (R**2 - BORE**2))):
        M = surface_mass(sk.mesh.doflocs, sk.triangles[name], n)
        assert M.sum() == pytest.approx(area, rel=1e-4), name
    # Interface between the two segments is shared (conforming), not duplicated.
    assert sk.facets["a:outer"].size > 0 and "end:right" in sk.facets


def test_cache_hit_miss_and_atomic(tmp_path, tube):
    body, data = tube
    calls = []

    def build():
        calls.append(1)
        return data

    inputs = {"R": R, "L": L}
    d1, p1, hit1 = mesh_cache.cached_tet_mesh("t", inputs, build, cache=Cache(tmp_path))
    d2, p2, hit2 = mesh_cache.cached_tet_mesh("t", inputs, build, cache=Cache(tmp_path))
    assert (hit1, hit2) == (False, True) and p1 == p2 and len(calls) == 1
    np.testing.assert_array_equal(d2.cells, data.cells)
    np.testing.assert_array_equal(d2.surfaces["a:outer"], data.surfaces["a:outer"])
    # A changed input gives a new file.
    _, p3, hit3 = mesh_cache.cached_tet_mesh("t", {"R": R * 1.01, "L": L}, build,
                                             cache=Cache(tmp_path))
    assert not hit3 and p3 != p1
    # A truncated file is rebuilt, and no temporary files are left behind.
    p1.write_bytes(p1.read_bytes()[:100])
    with pytest.warns(cache.CacheWarning, match="deleted and rebuilt"):
        _, _, hit4 = mesh_cache.cached_tet_mesh("t", inputs, build, cache=Cache(tmp_path))
    assert not hit4 and len(calls) == 3
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([p1.name, p3.name])
