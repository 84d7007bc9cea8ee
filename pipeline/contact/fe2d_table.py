"""Structural flank tables of one gear's 2D model (for the 2D FE compliance source).

The tables of :class:`~pipeline.contact.fe2d_source.FE2DCompliance`: for each gear one
structural influence matrix (:func:`pipeline.fem.influence.influence_matrix`, FE minus
the half-plane near field, m^2/N per unit face width) on ``radii`` points of the right
flank of every tooth that a tooth pair in contact can reach, from one factorisation.

Profile points are equally spaced in the arc coordinate of the involute between the
form (or base) circle and the tip, ``1.1 c`` of arc inside both ends (the load patch,
half-width ``c = settings.patch`` m_n, 0.1 by default, stays on the involute).

A whole gear looks the same from each of its teeth (all teeth alike, the bore - or a ring's
rim circle - clamped all round), so the table of ``n`` consecutive teeth does not depend on
where they sit: it is solved on the teeth ``z // 2 - n // 2 ..`` (:func:`solved_teeth`,
the mesh graded from them) and read on the teeth asked for. The pinion's and the gear's
tables of a pair of equal gears (their tooth-pair ranges ``mid - k`` and ``mid + k`` are
shifted by a tooth or two when the pairs that can touch are not symmetric about ``k =
0``) are then one model: solved once, then read from the cache (``--no-cache``: solved
twice). A sector (``fe.teeth`` set) is clamped at its cuts: its table is solved on the
teeth asked for.
Measured on the demo pair (z 50/50, tabulated teeth 23-26 and 24-27): the gear's table
solved on 23-26 instead of 24-27 (another mesh of the same model) moves the mesh stiffness
mean, min and max by +0.004, -0.006 and +0.007 % and the TE p-p by +0.03 % (the
discretisation error of the default mesh is 0.3 %, :mod:`pipeline.contact.fe2d_source`).

Tables are cached on disk by a content hash of the gear, the mesh settings, the points
and the boundary conditions (``meshes/fe2dtable-<hash>.npz``, written atomically by
:func:`pipeline.cache.entries.cached_file`; an unreadable file is rebuilt), so a warm build
reads one or two small files and neither meshes nor solves.
"""

from __future__ import annotations

import time
from dataclasses import asdict, replace
from typing import TYPE_CHECKING

import numpy as np

from pipeline.cache.entries import cached_file, unlabelled
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.flank import FlankPoints, flank_points, table_radii
from pipeline.fem.mesh_cache import MESH_CODE
from pipeline.fem.mesh_settings import SectorSettings
from pipeline.fem.sector2d import sector_mesh_2d
from pipeline.fem.settings import check_table_points
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError

if TYPE_CHECKING:
    from pipeline.fem.influence import InfluenceMatrix
    from pipeline.fem.settings import FE2DSettings

TABLE_CODE = (*MESH_CODE, "pipeline.contact.fe2d_table")
"""The code the 2D tables depend on (part of their cache key)."""
_TIMING_KEYS = ("mesh", "assembly", "loads", "factor", "solve", "nearfield", "total")


def sector_teeth(gear: GearSpec, settings: FE2DSettings) -> int:
    """Teeth of the meshed model: ``settings.teeth``, or z (the whole gear)."""
    return gear.teeth if settings.teeth is None else settings.teeth


def sector_settings(gear: GearSpec, settings: FE2DSettings, loaded: np.ndarray
                    ) -> SectorSettings:
    """Mesh settings of ``gear``'s model: graded from the ``loaded`` sector teeth, or
    uniform (every tooth at the flank size) for ``settings.mesh = "uniform"``."""
    n = sector_teeth(gear, settings)
    if settings.mesh == "uniform":
        return SectorSettings.for_gear(gear, n, settings.refinement)
    return SectorSettings.graded(gear, n, tuple(int(k) for k in loaded), settings.refinement,
                                   tooth=settings.tooth_size, body=settings.body_size,
                                   growth=settings.growth)


def solved_teeth(gear: GearSpec, settings: FE2DSettings, teeth: np.ndarray) -> np.ndarray:
    """The teeth a table of ``teeth`` (consecutive, ascending) is solved on: for a whole gear
    the same number of teeth from ``z // 2 - n // 2`` (module docstring), for a sector
    ``teeth`` themselves."""
    teeth = np.asarray(teeth, dtype=int)
    if settings.teeth is not None and settings.teeth != gear.teeth:
        return teeth
    if teeth.size and np.any(np.diff(teeth) != 1):
        raise ValueError(f"table teeth must be consecutive and ascending, got {teeth.tolist()}")
    return teeth - teeth[0] + gear.teeth // 2 - teeth.size // 2


def table_points(gear: GearSpec, settings: FE2DSettings, teeth: np.ndarray) -> FlankPoints:
    """Right-flank points: ``settings.points`` radii on each of ``teeth`` (ascending)."""
    r = table_radii(gear, settings.points, settings.patch)
    return flank_points(gear, sector_teeth(gear, settings), np.repeat(teeth, r.size),
                        np.tile(r, teeth.size))


def table_jobs(pair: GearPair, settings: FE2DSettings, tip_contact: bool = True
               ) -> list[tuple[str, GearSpec, np.ndarray]]:
    """The tables :meth:`~pipeline.contact.fe2d_source.FE2DCompliance.build` reads or
    builds: (role, gear, sector teeth) of the pinion and the gear, the teeth of every tooth
    pair that can touch (:meth:`GearPair.pair_indices` with ``beyond = tip_contact``; the
    tooth mapping of :mod:`pipeline.contact.fe2d_source`: pinion tooth ``mid - k``, gear
    tooth ``mid + k``)."""
    if pair.pinion.herringbone:
        raise InputError("fe source: analyse one helical half of a herringbone pair")
    k = pair.pair_indices(tip_contact)
    mid = min(sector_teeth(pair.pinion, settings), sector_teeth(pair.gear, settings)) // 2
    if np.abs(k).max() > mid:
        raise InputError(f"fe.teeth = {settings.teeth} does not cover tooth pairs "
                         f"{k.min()}..{k.max()}: use at least {2 * np.abs(k).max() + 1}")
    return [("pinion", pair.pinion, np.sort(sector_teeth(pair.pinion, settings) // 2 - k)),
            ("gear", pair.gear, np.sort(sector_teeth(pair.gear, settings) // 2 + k))]


def _table_arrays(G: InfluenceMatrix) -> dict[str, object]:
    return {"fe": G.fe, "local": G.local, "patch_half_width": G.patch_half_width,
            "kind": G.kind, "n_dof": G.n_dof, "n_free": G.n_free, "method": G.method,
            "timings": np.array([G.timings.get(k, 0.0) for k in _TIMING_KEYS])}


def _table_from_arrays(z: dict[str, np.ndarray], points: FlankPoints) -> InfluenceMatrix:
    from pipeline.fem.influence import InfluenceMatrix  # the FE side: on use only

    n = len(points)
    if z["fe"].shape != (n, n) or z["local"].shape != (n, n):
        raise ValueError(f"table of shape {z['fe'].shape}, expected {(n, n)}")
    return InfluenceMatrix(points, z["fe"], z["local"], float(z["patch_half_width"]),
                           str(z["kind"]), int(z["n_dof"]), int(z["n_free"]),
                           str(z["method"]), 0,
                           dict(zip(_TIMING_KEYS, z["timings"].tolist(), strict=True)))


def _table_inputs(gear: GearSpec, settings: FE2DSettings, teeth: np.ndarray
                  ) -> tuple[dict, FlankPoints, SectorSettings]:
    """The cache key data of a table (every input it depends on), its points and its mesh
    settings."""
    ss = sector_settings(gear, settings, teeth)
    check_table_points(settings.points * teeth.size,
                       f"fe.points x loaded teeth = {settings.points} x {teeth.size}",
                       "lower fe.points")
    pts = table_points(gear, settings, teeth)
    inputs = {"gear": unlabelled(gear), "sector": asdict(ss), "radii": pts.radius.tolist(),
              "teeth": teeth.tolist(), "kind": settings.kind, "cuts": settings.cuts,
              "patch": settings.patch}
    return inputs, pts, ss


def gear_table(gear: GearSpec, settings: FE2DSettings, teeth: np.ndarray, *,
               cache: Cache = DEFAULT_CACHE
               ) -> tuple[InfluenceMatrix, dict]:
    """Influence matrix of the right-flank points of the sector teeth ``teeth`` (consecutive
    indices, ascending) of ``gear``, from the cache or built (mesh, FE, near field) on the
    teeth :func:`solved_teeth` (a whole gear's, moved round the gear; the same matrix).

    Returns the matrix (``timings`` of the build that made it, s, with ``"mesh"``) and an
    ``info`` dict: ``cached`` (read from the cache), ``seconds`` (wall time of this call),
    ``dof``, ``free_dof``, ``solver``, ``sector`` (mesh settings).
    """
    t0 = time.perf_counter()
    teeth = np.asarray(teeth, dtype=int)
    inputs, pts, ss = _table_inputs(gear, settings, solved_teeth(gear, settings, teeth))

    def build() -> InfluenceMatrix:
        from pipeline.fem.influence import influence_matrix

        t = time.perf_counter()
        sec = sector_mesh_2d(gear, ss, cache=cache)
        t_mesh = time.perf_counter() - t
        G = influence_matrix(sec, pts, settings.patch * gear.module, kind=settings.kind,
                             cuts=settings.cuts)
        G.timings["mesh"] = t_mesh
        G.timings["total"] += t_mesh
        return G

    G, _, hit = cached_file("fe2dtable", inputs, build, _table_arrays,
                            lambda z: _table_from_arrays(z, pts), code=TABLE_CODE,
                            cache=cache)
    G = replace(G, points=table_points(gear, settings, teeth))  # the teeth asked for
    info = {"cached": hit, "seconds": time.perf_counter() - t0, "dof": G.n_dof,
            "free_dof": G.n_free, "solver": G.method, "sector": asdict(ss)}
    return G, info
