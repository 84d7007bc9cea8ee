"""The largest Hertz pressure over the mesh cycle at every point of the flanks.

:func:`pressure_envelope` gathers the Hertz pressure of every loaded point of a
:class:`~pipeline.contact.results.LoadedMeshCycle` (:attr:`LoadDistribution.hertz_pressure`)
onto an (s, z) grid of the plane of action: ``s`` the roll coordinate along the path of
contact (equally spaced from its start to its end), ``z`` the face position of the slices,
extended to the face ends 0 and b (:func:`to_face_ends`). The same pressure acts on both
flanks, at the pinion radius ``r_1(s)`` and the gear radius ``r_2(s)``
(:meth:`GearPair.contact_radii`). The mesh positions sample the path at the cycle's spacing:
between two samples of one slice the pressure is interpolated linearly, and the nearest
sample holds up to the ends of the path (no sample falls on them). Points on the path of
contact only: a tip corner touching beyond it presses on the mate's flank below its active
profile, edge loading given apart (:attr:`LoadDistribution.tip_corner_max`).

The contact pressure figure of the report (:func:`pipeline.viz.distribution.plot_contact_pressure`)
and the local pitting safety (:mod:`pipeline.rating.local_safety`) both read this one grid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.contact.distribution import LoadDistribution
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.pair import GearPair


@dataclass(frozen=True)
class PressureEnvelope:
    """Largest Hertz pressure over the cycle on the plane of action.

    Attributes
    ----------
    s : (n_s,) roll coordinate along the path of contact, from its start to its end, m.
    z : (n_z,) face position, 0 .. b (the slice centres and both face ends), m.
    pressure : (n_s, n_z) largest p_H over the cycle, Pa; 0 where the flank carries no load
        on the path of contact.
    """

    s: np.ndarray
    z: np.ndarray
    pressure: np.ndarray


def to_face_ends(z: np.ndarray, values: np.ndarray, face_width: float
                 ) -> tuple[np.ndarray, np.ndarray]:
    """Slice-centre values (columns of ``values`` at face positions ``z``, m) extended to the
    face ends z = 0 and b (m): each slice carries a uniform load over its width, so the end
    slice's value holds up to its face end, the slice model's own shape there."""
    if z.size == 0:
        return z, values
    if z[0] > 0.0:
        z, values = np.concatenate(([0.0], z)), np.concatenate((values[:, :1], values), axis=1)
    if z[-1] < face_width:
        z = np.concatenate((z, [face_width]))
        values = np.concatenate((values, values[:, -1:]), axis=1)
    return z, values


def pressure_envelope(cycle: LoadedMeshCycle, dist: LoadDistribution, pair: GearPair,
                      n_s: int) -> PressureEnvelope:
    """Largest p_H over ``cycle`` on an (``n_s`` roll points) x (slices and face ends) grid
    of the plane of action (module docstring); ``dist`` is the cycle's load distribution
    (its Hertz pressure per point), ``pair`` the pair the cycle was solved on."""
    s_grid = np.linspace(pair.s_start, pair.s_end, n_s)
    zq = np.round(cycle.point_z, 12)
    z = np.unique(zq)
    env = np.zeros((n_s, z.size))
    idx = np.clip(np.round((cycle.point_s - pair.s_start) / (pair.s_end - pair.s_start)
                           * (n_s - 1)).astype(int), 0, n_s - 1)
    iz = np.searchsorted(z, zq)
    np.maximum.at(env, (idx, iz), np.where(cycle.point_corner > 0, 0.0, dist.hertz_pressure))
    filled = env.copy()
    for j in range(z.size):
        col = env[:, j]
        hit = np.flatnonzero(col > 0)
        if hit.size >= 2:
            filled[:, j] = np.interp(s_grid, s_grid[hit], col[hit])
    z_ends, ends = to_face_ends(z, filled, pair.face_width)
    return PressureEnvelope(s_grid, z_ends, ends)
