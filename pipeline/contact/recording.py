"""Recording a loaded contact over the positions of a mesh cycle into a
:class:`~pipeline.contact.results.LoadedMeshCycle`.

The single-mesh loaded contact (:func:`pipeline.contact.ltca.loaded_mesh_cycle`) and each
helical half of a herringbone mesh (:func:`pipeline.contact.herringbone.herringbone_mesh_cycle`)
keep the same per-position and per-point record, with the mesh stiffnesses of
:func:`pipeline.contact.complementarity.mesh_stiffnesses` (one definition for both).
"""

from __future__ import annotations

import numpy as np

from pipeline.contact.hertz import contact_pressures
from pipeline.contact.results import LoadedMeshCycle
from pipeline.contact.source import ContactPoints
from pipeline.geometry.pair import GearPair

_PER_POSITION = ("x", "k_t", "k_s", "k_m", "res", "tol", "newton", "pmax")


class CycleRecorder:
    """Accumulates the state of each position of one mesh cycle (a local working object:
    filled by one solve loop, then turned into a :class:`LoadedMeshCycle`).

    Parameters
    ----------
    pair : the pair; its :meth:`GearPair.pair_indices` order the tooth-pair loads.
    positions : number m of positions of the cycle.
    tip_contact : the candidate points reach beyond the path of contact (the tooth pairs
        :meth:`GearPair.pair_indices` lists with ``beyond``).
    """

    def __init__(self, pair: GearPair, positions: int, tip_contact: bool = True) -> None:
        self.pair = pair
        self.pair_index = pair.pair_indices(tip_contact)
        self.per_position = {name: np.zeros(positions) for name in _PER_POSITION}
        self.pair_loads = np.zeros((positions, self.pair_index.size))
        self.rows: list[tuple] = []

    def add(self, i: int, points: ContactPoints, loads: np.ndarray, separations: np.ndarray,
            deformation: np.ndarray, approach: float,
            stiffnesses: tuple[float, float, float],
            stats: tuple[float, float, int], lever: np.ndarray | None = None) -> None:
        """Position ``i``: candidate points, their loads along the line of action (N),
        initial separations and local contact deformations (m), the approach x (m), the
        (tangent, secant, pointwise) mesh stiffnesses (N/m), the solver's (residual m,
        tolerance m, Newton iterations) and the points' lever factors ``a`` (a tip
        corner's normal force is ``load / a``; default 1)."""
        pair = self.pair
        lever = np.ones(len(points)) if lever is None else np.asarray(lever, dtype=float)
        unit = loads / lever / points.width
        corner = np.where(points.s > pair.s_end, 1, np.where(points.s < pair.s_start, 2, 0))
        values = (approach, *stiffnesses, *stats, float(unit.max()))
        for name, v in zip(_PER_POSITION, values, strict=True):
            self.per_position[name][i] = v
        np.add.at(self.pair_loads[i], np.searchsorted(self.pair_index, points.pair), loads)
        self.rows.append((np.full(len(points), i), points.s, points.z, points.pair,
                          points.width, loads, unit, separations, deformation, lever, corner,
                          contact_pressures(pair, points.s, unit)))

    def cycle(self, s0: np.ndarray, load: float, local: str) -> LoadedMeshCycle:
        """The recorded cycle at positions ``s0`` (m) under the load ``load`` (N)."""
        cols = [np.concatenate(c) for c in zip(*self.rows, strict=True)]
        a = self.per_position
        return LoadedMeshCycle(
            s0=s0, pinion_angle=(s0 - s0[0]) / self.pair.pinion.base_radius,
            transmission_error=a["x"], mesh_stiffness=a["k_t"], mesh_stiffness_secant=a["k_s"],
            mesh_stiffness_pointwise=a["k_m"], residual=a["res"], tolerance=a["tol"],
            newton_iterations=a["newton"].astype(int), max_unit_load=a["pmax"],
            pair_index=self.pair_index, pair_loads=self.pair_loads,
            point_position=cols[0].astype(int), point_s=cols[1], point_z=cols[2],
            point_pair=cols[3].astype(int), point_width=cols[4], point_load=cols[5],
            point_unit_load=cols[6], point_separation=cols[7],
            point_contact_deformation=cols[8], point_lever=cols[9],
            point_corner=cols[10].astype(int), point_pressure=cols[11], load=float(load),
            local_contact=local,
        )
