"""Load maps of the two helical halves of a herringbone mesh (Xu et al. 2020, Fig. 8): the unit
load on the sun and planet flanks of each half (equal at a contact point).

Each half's contact (:class:`~pipeline.contact.herringbone_results.HerringboneCycle`)
is a helical-half cycle, so :func:`pipeline.contact.loadmap.flank_load_map` grids it as
for a helical pair. The right half is the mirror image of the left: it is drawn with
the opposite hand and its face coordinate mirrored (``z -> b - z``), so that equal loads
give mirror-image maps and the two flanks meet at the same face (the apex side).
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

from pipeline.contact.herringbone_results import SIDES, HerringboneCycle
from pipeline.contact.loadmap import FlankLoadMap, flank_load_map, write_load_map_vtu
from pipeline.geometry.pair import GearPair

_OPPOSITE = {"right": "left", "left": "right"}


def half_pair(pair: GearPair, side: str) -> GearPair:
    """The helical-half pair as drawn for ``side``: the left half with the opposite hands."""
    if side == "right":
        return pair
    return GearPair(*(dataclasses.replace(g, hand=_OPPOSITE.get(g.hand, g.hand))
                      for g in (pair.pinion, pair.gear)), pair.centre_distance)


def half_load_maps(cycle: HerringboneCycle, pair: GearPair, profile_points: int = 80
                   ) -> dict[str, FlankLoadMap]:
    """Unit-load maps (N/m) of the left and right sun flanks over the mesh cycle."""
    out = {}
    for side in SIDES:
        m = flank_load_map(cycle.half(side), pair, profile_points)
        if side == "right":
            b = pair.face_width
            m = dataclasses.replace(m, z=(b - m.z)[::-1], unit_load=m.unit_load[:, ::-1])
        out[side] = m
    return out


def loaded_range(load_map: FlankLoadMap) -> tuple[float, float]:
    """(min, max) unit load over the loaded part of the flank on the path of contact, N/m
    ((0, 0) if unloaded): the "minimum / maximum load area" values of Xu et al. (2020),
    Fig. 8 (tip corners touching beyond the path are left out: their load thins out to
    nothing where their gap opens)."""
    on = (load_map.s >= load_map.s_start) & (load_map.s <= load_map.s_end)
    flank = load_map.unit_load[on]
    p = flank[flank > 0.0]
    return (float(p.min()), float(p.max())) if p.size else (0.0, 0.0)


def write_half_vtus(maps: dict[str, FlankLoadMap], pair: GearPair, folder: str | Path,
                    stem: str) -> list[Path]:
    """``<stem>_left.vtu`` and ``<stem>_right.vtu`` (coordinates in mm, unit load in N/mm)."""
    return [write_load_map_vtu(half_pair(pair, side), maps[side],
                               Path(folder) / f"{stem}_{side}.vtu") for side in SIDES]

