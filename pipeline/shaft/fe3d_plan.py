"""What the 3D shaft model meshes and condenses: the pieces, the reference nodes and their
bands, from a :class:`~pipeline.shaft.layout.ShaftLayout` and :class:`Fe3dSettings`.

The modelling choices are those of :mod:`pipeline.shaft.fe3d` (bands of bearings and the
torque point, rigid or integral seat, mesh sizes, sections). Lengths in m.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from pipeline.fem.settings import SOLVERS
from pipeline.fem.shaft_mesh import ShaftMeshSpec, ShaftPiece
from pipeline.shaft.layout import ShaftLayout
from pipeline.validation import InputError, check_choice, check_int_range, check_range

ELEMENTS_PER_DIAMETER = 4.0
"""Element edges across a segment's diameter at ``refinement = 1``."""
ELEMENTS_PER_LENGTH = 2.0
"""Element edges along a segment's length at ``refinement = 1`` (it governs a short, wide
segment: a disc bends and shears as a plate, through its length)."""
LARGE_STEP_RATIO = 2.0
"""Outer diameters this far apart (larger over smaller) make a large step (a pinion's body
on its journals)."""
LARGE_STEP_GRADING = 1.0
"""Growth of the edge away from a large step's shoulder circle, m per m (other shoulders
and a rigid hub's edges: 0.5)."""
TOL = 1e-9
"""Axial positions closer than this (m) are one."""


@dataclass(frozen=True)
class Fe3dSettings:
    """Mesh and coupling controls of the 3D shaft model (:mod:`pipeline.shaft.fe3d`).

    Attributes
    ----------
    refinement : divides the element edge (``d / 4`` at 1), > 0.
    shoulder_factor : edge at a shoulder circle over the smaller segment's edge, and at the
        edges of a rigid hub over the seat's edge.
    large_step_factor : the same at a large step (:data:`LARGE_STEP_RATIO`), whose corner
        decides more of the flexibility.
    band_factor : width of a bearing's or the torque point's band over the local outer
        diameter.
    seat_stations : reference nodes on an integral seat (``hub = "integral"``).
    section_spacing : largest distance between deflection-line sections, in local
        diameters.
    solver : :func:`pipeline.fem.solvers.solver_named` ("auto", "pardiso", "cholmod",
        "cholespy", "splu", "pmg-cg").
    """

    refinement: float = 1.0
    shoulder_factor: float = 0.35
    large_step_factor: float = 0.08
    band_factor: float = 0.25
    seat_stations: int = 5
    section_spacing: float = 0.5
    solver: str = "auto"

    def __post_init__(self) -> None:
        check_range("fe3d.refinement", self.refinement, 0.25, 8.0)
        check_range("fe3d.shoulder_factor", self.shoulder_factor, 0.05, 1.0)
        check_range("fe3d.large_step_factor", self.large_step_factor, 0.02, 1.0)
        check_range("fe3d.band_factor", self.band_factor, 0.02, 2.0)
        check_int_range("fe3d.seat_stations", self.seat_stations, 2, 40)
        check_range("fe3d.section_spacing", self.section_spacing, 0.05, 10.0)
        check_choice("fe3d.solver", self.solver, SOLVERS)


@dataclass(frozen=True)
class Fe3dPlan:
    """What is meshed and condensed: pieces, the seat's nodes and bands, the bearings'
    and the torque's nodes (index into the node list) and bands (m)."""

    mesh: ShaftMeshSpec
    rigid: bool
    nodes_z: tuple[float, ...]  # node 0 (anchor) first
    bands: tuple[tuple[float, float], ...]  # per node
    seat_nodes: tuple[int, ...]
    bearing_nodes: tuple[int, ...]
    torque_node: int


def _band(z: float, half: float, length: float, seat: tuple[float, float],
          others: Sequence[tuple[float, float]], what: str) -> tuple[float, float]:
    """``[z - half, z + half]`` clipped to the shaft, outside the seat and the ``others``."""
    lo, hi = max(0.0, z - half), min(length, z + half)
    for a, b in (seat, *others):
        if z <= a:
            hi = min(hi, a)
        elif z >= b:
            lo = max(lo, b)
    if hi - lo < 1e-6:
        raise InputError(f"{what} = {z * 1e3:.6g} mm leaves no room for its band on the shaft "
                         "(it meets the shaft's end, the seat or a neighbouring bearing)")
    return lo, hi


def plan_fe3d(layout: ShaftLayout, s: Fe3dSettings) -> Fe3dPlan:
    """The nodes, bands and pieces of ``layout`` (module docstring: modelling choices)."""
    n, L = layout.name, layout.length
    s0, s1 = layout.seat
    if s0 - TOL <= layout.torque_position <= s1 + TOL:
        raise InputError(f"{n}.torque_position_mm = {layout.torque_position * 1e3:.6g} mm lies "
                         f"on the gear's seat ({s0 * 1e3:.6g} to {s1 * 1e3:.6g} mm): the torque "
                         "must enter the shaft off the seat")
    rigid = layout.hub == "rigid"
    if rigid:
        nodes, bands, seat_nodes = [layout.gear_position], [(s0, s1)], (0,)
        edges_z = np.array([s0, s1])
    else:
        edges_z = np.linspace(s0, s1, s.seat_stations + 1)
        bands = list(zip(edges_z[:-1], edges_z[1:], strict=True))
        nodes = [0.5 * (a + b) for a, b in bands]
        seat_nodes = tuple(range(s.seat_stations))
    zb = sorted(b.position for b in layout.bearings)
    bearing_nodes = []
    for i, b in enumerate(layout.bearings):
        k = zb.index(b.position)
        if zb.count(b.position) > 1:
            raise InputError(f"{n}.bearings[{i}].position_mm = {b.position * 1e3:.6g} mm: "
                             "another bearing sits there; give one bearing per position")
        mids = [(0.5 * (zb[k - 1] + b.position),) * 2] if k > 0 else []
        mids += [(0.5 * (zb[k + 1] + b.position),) * 2] if k + 1 < len(zb) else []
        half = 0.5 * s.band_factor * layout.segment_at(b.position).outer_diameter
        bands.append(_band(b.position, half, L, (s0, s1), mids, f"{n}.bearings[{i}].position_mm"))
        nodes.append(b.position)
        bearing_nodes.append(len(nodes) - 1)
    zt = layout.torque_position
    inside = [j for j in bearing_nodes if bands[j][0] - TOL <= zt <= bands[j][1] + TOL]
    if inside:
        torque_node = inside[0]
    else:
        half = 0.5 * s.band_factor * layout.segment_at(zt).outer_diameter
        bands.append(_band(zt, half, L, (s0, s1), [bands[j] for j in bearing_nodes],
                           f"{n}.torque_position_mm"))
        nodes.append(zt)
        torque_node = len(nodes) - 1
    # an integral seat on a disc (a segment shorter than its diameter, a pinion's body):
    # cuts through it at the stations would slice it into thin full discs, each meshed
    # across the whole diameter; its stations' edges split only its surface (rings), and
    # their centres are not cut. A seat on a long segment is cut at both.
    seat_seg = layout.segment_at(layout.gear_position)
    disc = not rigid and seat_seg.end - seat_seg.start < seat_seg.outer_diameter
    rings = tuple(e for e in edges_z[1:-1] if seat_seg.start + TOL < e < seat_seg.end - TOL
                  ) if disc else ()
    cut_nodes = nodes[len(seat_nodes):] if disc else nodes
    cuts = {0.0, L, *cut_nodes, *(e for band in bands for e in band),
            *(seg.end for seg in layout.segments)}
    # a rigid hub's edges are corner singularities like the shoulders: refined alike
    r_seat = 0.5 * seat_seg.outer_diameter
    edges = ((s0, r_seat), (s1, r_seat)) if rigid else ()
    return Fe3dPlan(_pieces(layout, sorted(cuts), s, edges, rings), rigid, tuple(nodes),
                    tuple(bands), seat_nodes, tuple(bearing_nodes), torque_node)


def _pieces(layout: ShaftLayout, cuts: list[float], s: Fe3dSettings,
            edges: tuple[tuple[float, float], ...], rings: tuple[float, ...]) -> ShaftMeshSpec:
    """Pieces between the cuts (merged when closer than 1 nm), each split further so that
    sections are at most ``section_spacing`` diameters apart; the cuts at ``rings`` split
    the surface only."""
    z = [cuts[0]]
    for c in cuts[1:]:
        if c - z[-1] > TOL:
            z.append(c)
    pieces = []
    for a, b in zip(z[:-1], z[1:], strict=True):
        seg = layout.segment_at(0.5 * (a + b))
        ro, ri = 0.5 * seg.outer_diameter, 0.5 * seg.inner_diameter
        size = min(2 * ro / ELEMENTS_PER_DIAMETER, ro - ri,
                   (seg.end - seg.start) / ELEMENTS_PER_LENGTH) / s.refinement
        parts = max(1, math.ceil((b - a) / (s.section_spacing * 2 * ro) - 1e-9))
        ends = np.linspace(a, b, parts + 1)
        pieces += [ShaftPiece(float(p), float(q), ro, ri, size)
                   for p, q in zip(ends[:-1], ends[1:], strict=True)]
    ends = np.array(z)
    rings = tuple(float(ends[np.argmin(np.abs(ends - r))]) for r in rings)
    return ShaftMeshSpec(tuple(pieces), shoulder_factor=s.shoulder_factor,
                         large_step_ratio=LARGE_STEP_RATIO,
                         large_step_factor=s.large_step_factor,
                         large_step_grading=LARGE_STEP_GRADING, edges=edges, rings=rings)
