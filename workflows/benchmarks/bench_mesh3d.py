"""Benchmark: the whole-gear 3D mesher (swept section, own P2 nodes) against the
OpenCASCADE loft it replaced, side by side in one run.

Cases: the helical test gear of tests/test_fem_source3d.py (z 30, m_n 3 mm, beta 15 deg,
b 12 mm, bore 30 mm; loaded teeth 13..16, refinement 1) and the gear of the pair of Yang
et al. (2026) (z 104, m_n 7.35 mm, b 130 mm; workflows/configs/traction_helical_pair.toml;
loaded teeth 51..54) at refinements 0.6 and 1. For each: the swept mesher's time split
into Gmsh (sweep, size field, linear tetrahedra) and the P2 node placement
(:func:`pipeline.fem.curved_p2.curve_p2`), the loft's time
(:func:`pipeline.fem.whole3d_loft.build_lofted_whole_gear_3d`), cells and nodes of both,
the boundary mid-edge nodes curved less (so as not to fold a cell), both mesh volumes
against the exact one (the section's polyline area times b) and the shape of the
cells (mean-ratio quality of their vertices). The machine is shared: compare the two
columns of one run. Prints the figures and writes results/benchmarks/mesh3d.json.

    python workflows/benchmarks/bench_mesh3d.py
"""

from __future__ import annotations

import math
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

from pipeline.fem.curved_p2 import SweptOutline, curve_p2
from pipeline.fem.gmsh_session import TetMeshData
from pipeline.fem.mesh_settings import SectorSettings3D, meshed_width
from pipeline.fem.outline2d import inner_radius
from pipeline.fem.whole3d import linear_whole_gear_mesh_3d, whole_gear_area
from pipeline.fem.whole3d_loft import build_lofted_whole_gear_3d
from pipeline.geometry import GearSpec
from pipeline.io import write_json
from pipeline.provenance import library_versions

HERE = Path(__file__).resolve().parents[1]


def _small_gear() -> GearSpec:
    return GearSpec(teeth=30, module=3e-3, pressure_angle=math.radians(20), bore_radius=0.03,
                    face_width=12e-3, helix_angle=math.radians(15), hand="right",
                    name="pinion")


def _yang_gear() -> GearSpec:
    from pipeline.config import load_gearbox

    return load_gearbox(HERE / "configs" / "traction_helical_pair.toml").pair.gear


def _volume_error(data: TetMeshData, gear: GearSpec, settings: SectorSettings3D) -> float:
    """Relative error of the P2 mesh volume against the exact section area x b."""
    from skfem import Basis, ElementTetP0

    from pipeline.fem.tetmesh import to_skfem

    volume = Basis(to_skfem(data).mesh, ElementTetP0(), intorder=4).dx.sum()
    exact = whole_gear_area(gear, settings.profile_points, inner_radius(gear, settings))
    return float(volume / (exact * meshed_width(gear)) - 1.0)


def cell_quality(data: TetMeshData) -> tuple[float, float]:
    """Smallest and 1st-percentile mean-ratio quality 12 (3 V)^(2/3) / sum(l^2) of the
    straight cells (their vertices; 1 for the regular tetrahedron, 0 for a flat one)."""
    v = data.points[:, data.cells[:4]]
    vol = np.abs(np.einsum("ic,ic->c", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0], axis=0),
                           v[:, 3] - v[:, 0])) / 6
    l2 = sum(np.sum((v[:, i] - v[:, j]) ** 2, axis=0)
             for i, j in ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)))
    q = 12 * (3 * vol) ** (2 / 3) / l2
    return float(q.min()), float(np.percentile(q, 1))


def off_surface_nodes(data: TetMeshData, boundary: SweptOutline) -> tuple[int, int]:
    """Boundary mid-edge nodes of the curved groups, and how many of them are off their
    exact surface (by more than 1e-9 m): those of cells curved less so as not to fold."""
    total = off = 0
    for g, name in enumerate(boundary.groups):
        nodes = np.unique(data.surfaces[name][3:])
        p = data.points[:, nodes]
        q = boundary.project(p, np.full(nodes.size, g))
        total += nodes.size
        off += int(np.sum(np.linalg.norm(q - p, axis=0) > 1e-9))
    return total, off


def bench_case(name: str, gear: GearSpec, loaded: tuple[int, ...], refinement: float
               ) -> dict:
    """Both meshers on ``gear``: times (s), sizes, nodes curved less, volumes, quality."""
    # every tooth kept: the loft models the whole outline
    settings = replace(SectorSettings3D.whole_gear(gear, loaded, refinement), reach=None)
    t0 = time.perf_counter()
    linear, boundary = linear_whole_gear_mesh_3d(gear, settings)
    t1 = time.perf_counter()
    swept = curve_p2(linear, boundary)
    t2 = time.perf_counter()
    lofted = build_lofted_whole_gear_3d(gear, settings)
    t3 = time.perf_counter()
    curved_nodes, off = off_surface_nodes(swept, boundary)
    return {"case": name, "teeth": gear.teeth, "loaded": list(loaded),
            "refinement": refinement,
            "swept": {"gmsh_linear_s": t1 - t0, "p2_nodes_s": t2 - t1, "total_s": t2 - t0,
                      "cells": int(swept.cells.shape[1]), "nodes": int(swept.points.shape[1]),
                      "boundary_mid_nodes": curved_nodes,
                      "boundary_mid_nodes_off_surface": off,
                      "volume_rel_error": _volume_error(swept, gear, settings),
                      "quality_min_p1": cell_quality(swept)},
            "lofted": {"total_s": t3 - t2, "cells": int(lofted.cells.shape[1]),
                       "nodes": int(lofted.points.shape[1]),
                       "volume_rel_error": _volume_error(lofted, gear, settings),
                       "quality_min_p1": cell_quality(lofted)},
            "speed_up": (t3 - t2) / (t2 - t0)}


def _print(r: dict) -> None:
    s, o = r["swept"], r["lofted"]
    print(f"{r['case']}: swept {s['total_s']:.2f} s (Gmsh {s['gmsh_linear_s']:.2f} s, "
          f"P2 nodes {s['p2_nodes_s']:.2f} s), {s['cells']} cells, {s['nodes']} nodes, "
          f"{s['boundary_mid_nodes_off_surface']} of {s['boundary_mid_nodes']} boundary mid "
          f"nodes curved less, volume {s['volume_rel_error']:+.1e}, quality min / 1 % "
          f"{s['quality_min_p1'][0]:.2f} / {s['quality_min_p1'][1]:.2f}; "
          f"lofted {o['total_s']:.2f} s, {o['cells']} cells, {o['nodes']} nodes, "
          f"volume {o['volume_rel_error']:+.1e}, quality {o['quality_min_p1'][0]:.2f} / "
          f"{o['quality_min_p1'][1]:.2f}; x{r['speed_up']:.1f}")


def main() -> dict:
    yang = _yang_gear()
    cases = [bench_case("z30 m3 beta15 b12, refinement 1", _small_gear(), (13, 14, 15, 16), 1.0)]
    for ref in (0.6, 1.0):
        cases.append(bench_case(f"Yang et al. (2026) gear z104 m7.35 b130, refinement {ref:g}",
                                yang, (51, 52, 53, 54), ref))
    for r in cases:
        _print(r)
    out = {"cases": cases, "versions": library_versions()}
    write_json(Path("results/benchmarks/mesh3d.json"), out)
    return out


if __name__ == "__main__":
    main()
