"""The one place where Gmsh's process-global state is opened and closed.

Gmsh keeps a single global model per process. Every meshing module in
``pipeline.fem`` builds its geometry inside :func:`gmsh_session` and converts the
result with :func:`extract_tet_mesh` before the session closes, so what leaves
this package is a scikit-fem mesh plus plain dictionaries of tags; nothing
Gmsh-specific leaks out.
"""

from __future__ import annotations

import threading
from collections.abc import Iterator
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

# Gmsh is not re-entrant: one session at a time per process.
_LOCK = threading.Lock()

# Gmsh 10-node tetrahedron -> scikit-fem MeshTet2 node order. Gmsh numbers the
# edges (0,1) (1,2) (0,2) (0,3) (2,3) (1,3); scikit-fem (like VTK) (0,1) (1,2)
# (0,2) (0,3) (1,3) (2,3).
_GMSH_TET10_TO_SKFEM = np.array([0, 1, 2, 3, 4, 5, 6, 7, 9, 8])
_ELEMENT_TYPE = {1: (4, 2), 2: (11, 9)}  # order -> (Gmsh tet type, Gmsh triangle type)


@contextmanager
def gmsh_session(verbosity: int = 0, threads: int = 1) -> Iterator[object]:
    """Initialise Gmsh, yield the ``gmsh`` module, and always finalise it.

    Parameters
    ----------
    verbosity : Gmsh ``General.Verbosity`` (0 silent ... 5 debug).
    threads : threads Gmsh may use for 3D meshing (``General.NumThreads``).

    Yields
    ------
    The imported ``gmsh`` module with a fresh, empty model.
    """
    import gmsh

    with _LOCK:
        # Gmsh installs a SIGINT handler when it initialises; keep Python's.
        gmsh.initialize(interruptible=False)
        try:
            gmsh.option.setNumber("General.Verbosity", verbosity)
            gmsh.option.setNumber("General.Terminal", 1 if verbosity > 0 else 0)
            gmsh.option.setNumber("General.NumThreads", threads)
            gmsh.model.add("gearpipe")
            yield gmsh
        finally:
            gmsh.finalize()



def size_from_fields(gmsh, fields: list[int]) -> None:
    """Make the smallest of the size ``fields`` the element size everywhere: they become
    the background mesh (through a ``Min`` field if there are several), and the sizes
    Gmsh would take from boundaries, points and curvature are switched off."""
    fld = gmsh.model.mesh.field
    if len(fields) > 1:
        smallest = fld.add("Min")
        fld.setNumbers(smallest, "FieldsList", fields)
        fields = [smallest]
    fld.setAsBackgroundMesh(fields[0])
    for opt in ("MeshSizeExtendFromBoundary", "MeshSizeFromPoints", "MeshSizeFromCurvature"):
        gmsh.option.setNumber(f"Mesh.{opt}", 0)

@dataclass(frozen=True)
class TetMeshData:
    """A tetrahedral mesh taken out of Gmsh, free of Gmsh types.

    Attributes
    ----------
    points : (3, n_nodes) node coordinates in m.
    cells : (n_cell_nodes, n_cells) node indices; 4 rows (linear) or 10 rows
        (quadratic, scikit-fem MeshTet2 order: vertices then edges (0,1) (1,2)
        (0,2) (0,3) (1,3) (2,3)).
    surfaces : name -> (3, n_faces) or, for quadratic meshes, (6, n_faces) node
        indices of the boundary triangles of a named surface group (vertices, then
        the mid-edge nodes of edges (0,1) (1,2) (2,0)).
    volumes : name -> (n,) indices into the columns of ``cells``.
    """

    points: np.ndarray
    cells: np.ndarray
    surfaces: dict[str, np.ndarray] = field(default_factory=dict)
    volumes: dict[str, np.ndarray] = field(default_factory=dict)

    @property
    def order(self) -> int:
        """Geometric order of the elements (1 or 2)."""
        return 2 if self.cells.shape[0] == 10 else 1


def extract_tet_mesh(
    gmsh, order: int, surface_groups: dict[str, list[int]], volume_groups: dict[str, list[int]]
) -> TetMeshData:
    """Read the current Gmsh mesh into a :class:`TetMeshData`; call inside a session.

    Parameters
    ----------
    gmsh : the module yielded by :func:`gmsh_session`, after ``mesh.generate(3)``.
    order : element order the mesh was generated with (1 or 2).
    surface_groups : name -> list of Gmsh surface entity tags.
    volume_groups : name -> list of Gmsh volume entity tags.
    """
    tet_type, tri_type = _ELEMENT_TYPE[order]
    node_tags, coords, _ = gmsh.model.mesh.getNodes()
    # Gmsh tags are arbitrary positive integers: map them to 0..n-1.
    lookup = np.zeros(int(node_tags.max()) + 1, dtype=np.int64)
    lookup[node_tags.astype(np.int64)] = np.arange(node_tags.size)
    points = coords.reshape(-1, 3).T.copy()

    nper = 10 if order == 2 else 4
    tet_blocks, tet_owner = [], {}
    start = 0
    for _, vol in gmsh.model.getEntities(3):
        _, nodes = gmsh.model.mesh.getElementsByType(tet_type, vol)
        conn = lookup[nodes.astype(np.int64)].reshape(-1, nper)
        tet_blocks.append(conn)
        tet_owner[vol] = np.arange(start, start + conn.shape[0])
        start += conn.shape[0]
    cells = np.vstack(tet_blocks)
    if order == 2:
        cells = cells[:, _GMSH_TET10_TO_SKFEM]
    cells = np.ascontiguousarray(cells.T)

    # Keep only nodes that belong to volume elements (drops geometry-only nodes).
    used = np.unique(cells)
    renum = -np.ones(points.shape[1], dtype=np.int64)
    renum[used] = np.arange(used.size)
    points = np.ascontiguousarray(points[:, used])
    cells = renum[cells]

    surfaces = {}
    for name, tags in surface_groups.items():
        faces = []
        for s in tags:
            _, nodes = gmsh.model.mesh.getElementsByType(tri_type, s)
            nn = 6 if order == 2 else 3
            faces.append(renum[lookup[nodes.astype(np.int64)].reshape(-1, nn)])
        surfaces[name] = (np.ascontiguousarray(np.vstack(faces).T) if faces
                          else np.zeros((6 if order == 2 else 3, 0), dtype=np.int64))
    volumes = {
        name: np.concatenate([tet_owner[v] for v in tags]) for name, tags in volume_groups.items()
    }
    return TetMeshData(points=points, cells=cells, surfaces=surfaces, volumes=volumes)
