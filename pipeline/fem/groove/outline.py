"""Transverse tooth outline for solid modelling, from the exact generated profile.

The flank comes from :func:`pipeline.geometry.profile.tooth_profile` (involute
plus the trochoidal fillet the rack cutter generates, from the middle of the
tooth space on the root circle to the tip corner). For a B-spline through it
the flank is resampled at ``points`` positions equally spaced in arc length,
keeping the form point (fillet/involute junction) and both ends. Consecutive
teeth share their root point (the middle of the tooth space), so the whole
outline is flank, tip arc, flank, flank, tip arc, ... with no root arcs.

All lengths in m, angles in rad; tooth 0 is centred on the +x axis.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.geometry.gear import GearSpec
from pipeline.geometry.profile import INVOLUTE, tooth_profile
from pipeline.validation import InputError, check_int_range


@dataclass(frozen=True, eq=False)
class ToothOutline:
    """Curves of one tooth (tooth 0, centred on +x) in the transverse plane.

    Attributes
    ----------
    left_flank : (n, 2) points (m) from the middle of the tooth space at polar
        angle -pi/z up to the tip corner, on the side of negative polar angle.
    right_flank : (n, 2) mirror image of ``left_flank`` (y -> -y), same direction.
    tip_radius : r_a in m; the tip is the arc between the flank ends.
    root_radius : r_f in m.
    """

    left_flank: np.ndarray
    right_flank: np.ndarray
    tip_radius: float
    root_radius: float


def _resample(xy: np.ndarray, keep: int, n: int) -> np.ndarray:
    """``n`` points equally spaced in arc length along polyline ``xy``, with index ``keep``."""
    s = np.concatenate([[0.0], np.cumsum(np.hypot(*np.diff(xy, axis=0).T))])
    t = np.linspace(0.0, s[-1], n)
    t[np.argmin(np.abs(t - s[keep]))] = s[keep]  # land on the form point exactly
    t = np.unique(t)
    return np.column_stack([np.interp(t, s, xy[:, 0]), np.interp(t, s, xy[:, 1])])


def tooth_outline(gear: GearSpec, points: int = 24) -> ToothOutline:
    """The exact flank of ``gear`` resampled at ``points`` points (see module doc)."""
    if gear.internal:
        raise InputError(f"{gear.name}: the relief-groove model needs an external gear")
    check_int_range("outline.points", points, 6, 500)
    prof = tooth_profile(gear)
    form = int(np.argmax(prof.kind == INVOLUTE)) if np.any(prof.kind == INVOLUTE) else 0
    # Profile frame: tooth on +y, right flank x >= 0. Turn by -90 deg: tooth on +x and
    # that flank on the side of negative polar angle.
    left = _resample(np.column_stack([prof.y, -prof.x]), form, points)
    right = left * np.array([1.0, -1.0])
    return ToothOutline(left_flank=left, right_flank=right,
                        tip_radius=float(prof.radius[-1]), root_radius=gear.root_radius)
