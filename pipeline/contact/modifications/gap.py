"""The gap both gears' modifications open at the contact points of a mesh, and its maps.

At a contact point the two flanks' deviations (material removed, m) add up along the
transverse line of action: ``w(s, z) = w_1(rho_1(s), z_1) + w_2(rho_2(s), z_2)``, each gear's
at its own roll length and face position (:mod:`.frame`). The contributions are summed in
the fixed order of :data:`~.gear.TERMS`, the pinion's before the gear's for each.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.contact.modifications.frame import FlankFrame, flank_frames
from pipeline.contact.modifications.gear import TERMS, GearModification
from pipeline.geometry.pair import GearPair


def modification_gap(pair: GearPair, s: np.ndarray, z: np.ndarray,
                     flanks: tuple[GearModification, GearModification]) -> np.ndarray:
    """Gap (m) the pinion's and the gear's modifications ``flanks`` open at roll coordinates
    ``s`` (m, on the path of contact) and face positions ``z`` (m, in ``[0, b]``)."""
    s, z = np.broadcast_arrays(np.asarray(s, dtype=float), np.asarray(z, dtype=float))
    frames = flank_frames(pair)
    terms = [m.terms(f, s, z) for m, f in zip(flanks, frames, strict=True)]
    gap = np.zeros(s.shape)
    first = True
    for name in TERMS:
        for by_gear in terms:
            if name in by_gear:
                gap = by_gear[name] if first else gap + by_gear[name]
                first = False
    return gap


@dataclass(frozen=True)
class ModificationMap:
    """One gear's modification over its active flank in one mesh.

    Attributes
    ----------
    role : "pinion" or "gear".
    base_radius : its base radius r_b, m (diameter ``2 sqrt(roll^2 + r_b^2)``).
    face : (nf,) face positions z_i (its own face coordinate), m.
    roll : (nr,) roll lengths of its active flank, ascending, m.
    diameter : (nr,) the diameters there, m.
    deviation : (nf, nr) material removed, m.
    """

    role: str
    base_radius: float
    face: np.ndarray
    roll: np.ndarray
    diameter: np.ndarray
    deviation: np.ndarray


def modification_maps(pair: GearPair, flanks: tuple[GearModification, GearModification],
                      n_face: int = 61, n_roll: int = 81) -> tuple[ModificationMap, ...]:
    """Each gear's modification map over the part of its flank the mesh ``pair`` touches
    (its active flank and the common face width), on an ``n_face`` x ``n_roll`` grid."""
    out = []
    for mod, frame in zip(flanks, flank_frames(pair), strict=True):
        out.append(_map(frame, mod, pair.face_width, n_face, n_roll))
    return tuple(out)


def _map(frame: FlankFrame, mod: GearModification, b: float, n_face: int,
         n_roll: int) -> ModificationMap:
    s = np.linspace(min(frame.root_s, frame.tip_s), max(frame.root_s, frame.tip_s), n_roll)
    roll = frame.roll(s)
    order = np.argsort(roll)
    s, roll = s[order], roll[order]
    z = np.linspace(0.0, b, n_face)
    ss, zz = np.meshgrid(s, z)
    return ModificationMap(frame.role, frame.base_radius, z + frame.face_shift, roll,
                           frame.diameter(s), mod.deviation(frame, ss, zz))
