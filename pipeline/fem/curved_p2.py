"""Curved quadratic tetrahedra from a linear mesh: mid-edge nodes on the exact surfaces.

:func:`curve_p2` turns a linear (4-node) tetrahedral mesh into a 10-node one, as Gmsh's
``setOrder(2)`` with CAD projection would, in a few vectorised steps. Every edge gets its
straight midpoint; then the nodes of the curved boundary groups are put on their exact
surfaces (a :class:`CurvedBoundary`; :class:`SweptOutline` for the tooth sides and bore
of a swept gear body): the vertices are projected (they were on Gmsh's approximate
geometry), and the mid-edge node of a boundary edge is the surface point at the middle of
its end points' surface parameters (the mid-parameter placement of isoparametric
meshes: for an edge on a strongly curved fillet it balances the parabola, where the
nearest point to the chord's midpoint would not). Groups that are not curved (plane end
faces) keep straight edges.

Folded cells. Curving a coarse cell whose face lies on a strongly curved fillet can fold
it (det J <= 0), which a factorisation would report only as "not positive definite". The
check is det J at the quadrature points of the assembly of curved P2 cells (order 4,
:func:`pipeline.fem.elasticity.default_intorder`, those of
``pipeline.fem.sector3d._check_cells``), required above :data:`MIN_DET_RATIO` of the
straight cell's. The curving of a folded cell's edges is halved up to
:data:`UNFOLD_STEPS` - 1 times, then dropped (the cell kept straight). Measured on the
whole gears of :mod:`pipeline.fem.whole3d`: a few cells of the coarse far teeth (33 of
6100 boundary mid-edge nodes of a z 30 gear), none on the loaded teeth.

The exact surface of a swept outline. A gear body swept along its helix has the tooth
side ``{R(theta(z)) c(u), z}``: the transverse curve ``c`` (a piece of the outline at
mid-face, :func:`pipeline.fem.outline2d.outline_pieces`) turned by
``theta(z) = rate (z - b/2)``. A point ``(x, y, z)`` is projected by turning it back by
``-theta(z)``, finding the nearest point of ``c`` (nearest dense sample, then Newton steps
on the curve parameter) and turning that by ``theta(z)``: exact for the helicoid, since
the rotation keeps ``z``. ``c`` is the cubic spline (not-a-knot ends, chord-length parameter)
through all the outline points of each piece, the curve the lofted model interpolates too.
The bore is the cylinder of radius ``r_in``: radial projection. Lengths in m.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Protocol

import numpy as np
from scipy.interpolate import CubicSpline, PPoly
from scipy.spatial import cKDTree

from pipeline.fem.gmsh_session import TetMeshData

MIN_DET_RATIO = 0.05
"""A curved cell is kept only if det J stays above this share of its straight cell's
determinant at every quadrature point (a well-shaped curved cell stays near 1)."""
UNFOLD_STEPS = 4
"""Tries for a folded cell: its edges' curving halved (1/2, 1/4, 1/8), then dropped."""

# scikit-fem MeshTet2 edge order, and the triangle edges (0,1) (1,2) (2,0)
TET_EDGES = np.array([[0, 1], [1, 2], [0, 2], [0, 3], [1, 3], [2, 3]])
TRI_EDGES = np.array([[0, 1], [1, 2], [2, 0]])
_NEWTON_STEPS = 4
_SAMPLES_PER_SEGMENT = 3


class CurvedBoundary(Protocol):
    """The exact surfaces of a mesh's curved boundary groups (lengths in m).

    ``groups`` names them; ``group`` arguments are (n,) indices into it.
    """

    groups: tuple[str, ...]

    def project(self, p: np.ndarray, group: np.ndarray) -> np.ndarray:
        """The nearest points (3, n) of the surfaces ``group`` to ``p`` (3, n)."""

    def midpoint(self, a: np.ndarray, b: np.ndarray, group: np.ndarray) -> np.ndarray:
        """Mid-edge nodes (3, n) of the edges from ``a`` to ``b`` (3, n, points of the
        surfaces ``group``): the surface point at the middle of their parameters."""


@dataclass(frozen=True, eq=False)
class SweptOutline:
    """The tooth sides and bore of a gear section swept along its helix (module docstring).

    Attributes
    ----------
    pieces : (group name, (m, 2) points at mid-face, m) outline pieces.
    inner_radius : bore radius, m.
    width : meshed face width b, m.
    twist_rate : d theta / d z, rad/m.
    groups : the outline group names in their order of appearance, then ``"bore"``.
    """

    pieces: list[tuple[str, np.ndarray]]
    inner_radius: float
    width: float
    twist_rate: float
    groups: tuple[str, ...] = field(init=False)
    _curve: PPoly = field(init=False, repr=False)
    _bounds: np.ndarray = field(init=False, repr=False)
    _tree: cKDTree = field(init=False, repr=False)
    _samples: tuple = field(init=False, repr=False)
    _lift: float = field(init=False, repr=False)

    def __post_init__(self) -> None:
        names = tuple(dict.fromkeys(name for name, _ in self.pieces))
        index = {name: i for i, name in enumerate(names)}
        # all pieces on one parameter u: piece i spans [u_i, u_i + length_i]
        knots, coefs, bounds, pts, owner, params = [], [], [], [], [], []
        start = 0.0
        lift = 10.0 * max(float(np.abs(seg).max()) for _, seg in self.pieces)
        for i, (name, seg) in enumerate(self.pieces):
            u = start + np.r_[0.0, np.cumsum(np.hypot(*np.diff(seg, axis=0).T))]
            spline = CubicSpline(u, seg)
            knots.append(u if i == 0 else u[1:])
            coefs.append(spline.c)
            bounds.append((u[0], u[-1]))
            s = np.linspace(u[0], u[-1], _SAMPLES_PER_SEGMENT * (u.size - 1) + 1)
            xy = spline(s)
            # a third coordinate keeps each group's samples apart in one tree
            pts.append(np.column_stack([xy, np.full(s.size, lift * index[name])]))
            owner.append(np.full(s.size, i))
            params.append(s)
            start = u[-1]
        set_ = object.__setattr__
        set_(self, "groups", (*names, "bore"))
        set_(self, "_curve", PPoly(np.concatenate(coefs, axis=1), np.concatenate(knots)))
        set_(self, "_bounds", np.array(bounds))
        set_(self, "_tree", cKDTree(np.vstack(pts)))
        set_(self, "_samples", (np.concatenate(owner), np.concatenate(params)))
        set_(self, "_lift", lift)

    def theta(self, z: np.ndarray) -> np.ndarray:
        """Turn (rad) of the section at axial position ``z`` (m)."""
        return self.twist_rate * (z - 0.5 * self.width)

    def _locate(self, p: np.ndarray, group: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Piece (n,) and curve parameter u (n,) of the nearest points of the outline
        groups ``group`` to ``p`` (3, n) turned back to mid-face."""
        xy = _turned(p[:2], -self.theta(p[2]))
        _, idx = self._tree.query(np.column_stack([xy.T, self._lift * group]))
        piece, u = self._samples[0][idx], self._samples[1][idx]
        lo, hi = self._bounds[piece].T
        c = self._curve
        for _ in range(_NEWTON_STEPS):  # minimise |c(u) - q|^2 over u
            d, d1, d2 = c(u) - xy.T, c(u, 1), c(u, 2)
            g, h = np.sum(d * d1, axis=1), np.sum(d1 * d1, axis=1)
            h2 = h + np.sum(d * d2, axis=1)
            u = np.clip(u - g / np.where(h2 > 0.0, h2, h), lo, hi)
        return piece, u

    def _point(self, u: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Surface points (3, n) at curve parameter ``u`` and height ``z`` (m)."""
        return np.vstack([_turned(self._curve(u).T, self.theta(z)), z])

    def _bore(self, p: np.ndarray) -> np.ndarray:
        return np.vstack([p[:2] * (self.inner_radius / np.hypot(p[0], p[1])), p[2]])

    def project(self, p: np.ndarray, group: np.ndarray) -> np.ndarray:
        """Nearest points (3, n) of the surfaces ``group`` (indices into ``groups``)."""
        out = np.empty_like(p)
        bore = group == len(self.groups) - 1
        out[:, bore] = self._bore(p[:, bore])
        side = ~bore
        out[:, side] = self._point(self._locate(p[:, side], group[side])[1], p[2, side])
        return out

    def midpoint(self, a: np.ndarray, b: np.ndarray, group: np.ndarray) -> np.ndarray:
        """Mid-edge nodes (3, n): middle curve parameter and height on a tooth side whose
        ends lie on one piece (else the nearest point to the chord's middle); on the bore
        the middle angle and height (the radial projection of the chord's middle)."""
        out = self.project(0.5 * (a + b), group)
        side = np.flatnonzero(group != len(self.groups) - 1)
        pa, ua = self._locate(a[:, side], group[side])
        pb, ub = self._locate(b[:, side], group[side])
        same = pa == pb
        out[:, side[same]] = self._point(0.5 * (ua + ub)[same],
                                         0.5 * (a[2] + b[2])[side[same]])
        return out


def _turned(xy: np.ndarray, th: np.ndarray) -> np.ndarray:
    """``xy`` (2, n) turned by ``th`` (rad) about the axis."""
    c, s = np.cos(th), np.sin(th)
    return np.array([c * xy[0] - s * xy[1], s * xy[0] + c * xy[1]])


def curve_p2(data: TetMeshData, boundary: CurvedBoundary) -> TetMeshData:
    """The 10-node mesh of the linear ``data``, boundary nodes on their exact surfaces.

    Parameters
    ----------
    data : linear tetrahedral mesh (order 1) with its named surface groups.
    boundary : the exact surfaces of the curved groups (``boundary.groups``); other
        groups (plane faces) keep straight edges. A node or edge shared by two curved
        groups (the edge between two tooth sides) is placed by the later group in
        ``boundary.groups``, which lands on their common curve.

    Returns
    -------
    :class:`~pipeline.fem.gmsh_session.TetMeshData` of order 2: vertices first (the
    projected ``data.points``), then one node per edge; cells in scikit-fem ``MeshTet2``
    order, surfaces (6, n). Cells that curving would fold are curved less or kept
    straight (module docstring).
    """
    if data.order != 1:
        raise ValueError("curve_p2 needs a linear (4-node) mesh")
    n_v = data.points.shape[1]
    edges, tet_edge = _unique_edges(data.cells, n_v)
    key = edges[:, 0] * n_v + edges[:, 1]
    tri_edges = {}
    for name, tri in data.surfaces.items():
        pairs = np.sort(tri.T[:, TRI_EDGES], axis=2)
        tri_edges[name] = np.searchsorted(key, pairs[..., 0] * n_v + pairs[..., 1]).T
    node_owner = np.full(n_v, -1)
    edge_owner = np.full(edges.shape[0], -1)
    for g, name in enumerate(boundary.groups):
        if name in data.surfaces:
            node_owner[data.surfaces[name]] = g
            edge_owner[tri_edges[name]] = g
    vertices = data.points.copy()
    on = np.flatnonzero(node_owner >= 0)
    vertices[:, on] = boundary.project(vertices[:, on], node_owner[on])
    straight = 0.5 * (vertices[:, edges[:, 0]] + vertices[:, edges[:, 1]])
    bent = np.flatnonzero(edge_owner >= 0)
    shift = np.zeros_like(straight)
    shift[:, bent] = boundary.midpoint(vertices[:, edges[bent, 0]], vertices[:, edges[bent, 1]],
                                       edge_owner[bent]) - straight[:, bent]
    cells = np.vstack([data.cells, n_v + tet_edge.T])
    share = (edge_owner >= 0).astype(float)  # of each edge's curving kept
    check = np.flatnonzero((node_owner[data.cells] >= 0).any(axis=0))  # cells that moved
    for step in range(UNFOLD_STEPS + 1):
        points = np.hstack([vertices, straight + share * shift])
        bad = check[folded_cells(points, cells[:, check])]
        if bad.size == 0:
            break
        e = np.unique(tet_edge[bad])
        share[e] = 0.0 if step >= UNFOLD_STEPS - 1 else 0.5 * share[e]
    else:
        raise RuntimeError("curve_p2: cells fold even with straight edges")
    surfaces = {name: np.vstack([tri, n_v + tri_edges[name]])
                for name, tri in data.surfaces.items()}
    return TetMeshData(points, cells, surfaces, dict(data.volumes))


def _unique_edges(cells: np.ndarray, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(n_edges, 2) sorted vertex pairs, in increasing ``a n + b``, and the (n_cells, 6)
    edge index of each cell edge (:data:`TET_EDGES` order) of the (4, n_cells) ``cells``."""
    pairs = np.sort(cells.T[:, TET_EDGES], axis=2)
    keys, inverse = np.unique(pairs[..., 0] * n + pairs[..., 1], return_inverse=True)
    return np.column_stack([keys // n, keys % n]), inverse.reshape(-1, 6)


def _p2_gradients(X: np.ndarray) -> np.ndarray:
    """Reference gradients (10, 3, nq) of the P2 tetrahedron's shape functions (MeshTet2
    node order) at reference points ``X`` (3, nq)."""
    lam = np.vstack([1.0 - X.sum(axis=0), X])  # barycentric (4, nq)
    dlam = np.array([[-1.0, -1.0, -1.0], [1, 0, 0], [0, 1, 0], [0, 0, 1]])  # (4, 3)
    grads = [(4 * lam[i] - 1)[None, :] * dlam[i][:, None] for i in range(4)]
    grads += [4 * (lam[i][None, :] * dlam[j][:, None] + lam[j][None, :] * dlam[i][:, None])
              for i, j in TET_EDGES]
    return np.array(grads)


def assembly_points() -> np.ndarray:
    """Reference points (3, nq) of the assembly's quadrature on curved P2 cells (order 4,
    :func:`pipeline.fem.elasticity.default_intorder`)."""
    from skfem.quadrature import get_quadrature
    from skfem.refdom import RefTet

    return get_quadrature(RefTet, 4)[0]


def folded_cells(points: np.ndarray, cells: np.ndarray) -> np.ndarray:
    """(n_cells,) True where the P2 cell's det J falls to :data:`MIN_DET_RATIO` of its
    straight (vertex) cell's, or changes sign, at a quadrature point of the assembly, or
    where the straight cell itself is inverted (negative volume).

    ``points`` (3, n) in m, ``cells`` (10, n_cells) in MeshTet2 order.
    """
    dN = _p2_gradients(assembly_points())
    J = np.einsum("inc,njq->ijcq", points[:, cells], dN)  # (3, 3, nc, nq)
    det = (J[0, 0] * (J[1, 1] * J[2, 2] - J[1, 2] * J[2, 1])
           - J[0, 1] * (J[1, 0] * J[2, 2] - J[1, 2] * J[2, 0])
           + J[0, 2] * (J[1, 0] * J[2, 1] - J[1, 1] * J[2, 0]))
    v = points[:, cells[:4]]
    lin = np.einsum("ic,ic->c", np.cross(v[:, 1] - v[:, 0], v[:, 2] - v[:, 0], axis=0),
                    v[:, 3] - v[:, 0])
    return (lin <= 0.0) | ((det / lin[:, None]).min(axis=1) <= MIN_DET_RATIO)
