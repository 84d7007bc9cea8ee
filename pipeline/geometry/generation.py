"""Generating a gear's tooth space with its rack cutter (envelope of the rack profile).

Frames (transverse section, SI): the gear centre is the origin and the tooth
being described is centred on the +y axis; its right flank lies at x > 0. The
rack's rolling line is tangent to the reference circle (radius r) at I = (0, r);
its own reference line is shifted out by the profile shift, to y = r + x m_n. The
cutter tooth that cuts the right flank is centred on the tooth space at
u = p_t / 2 (half a transverse pitch to the right of the tooth).

The normal-section rack (ISO 53) has straight flanks at alpha_n, a tip line
h_f* m_n below its reference line, and a tip round of radius rho_a0* m_n; its
transverse section is the same profile stretched by 1/cos(beta) along the
pitch line (the tip round becomes an ellipse), which is how helical gears are
handled here.

A rack point (u, y) with unit normal n, translated by d along the pitch line,
touches the gear when the normal passes through I (law of gearing):

    (u + d) n_y - (y - r) n_u = 0   ->   d = (y - r) n_u / n_y - u,

and the gear has then turned clockwise by d / r, so the generated point in the
gear frame is the fixed-frame point (u + d, y) turned back anticlockwise by d / r.
The tip line generates the root circle, the tip round the trochoidal fillet and
the straight flank the involute.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from pipeline.geometry.gear import GearSpec


@dataclass(frozen=True)
class RackPoints:
    """Points of the transverse rack profile with outward unit normals (all arrays shape (n,)).

    ``u``, ``y`` in m in the gear's fixed frame at zero rack displacement; ``nu``,
    ``ny`` the unit normal pointing out of the cutter tooth into the tooth space
    of the rack (towards the gear material being generated).
    """

    u: np.ndarray
    y: np.ndarray
    nu: np.ndarray
    ny: np.ndarray


def rack_tip(gear: GearSpec, n_line: int, n_round: int) -> tuple[RackPoints, RackPoints]:
    """The left half of the cutter tip: tip line (centre to round) and tip round.

    Returns ``(tip_line, tip_round)``; the tip line runs from the middle of the
    cutter tooth towards its left corner, the round from the tip line to the flank.
    """
    m, a = gear.module, gear.pressure_angle
    rho = gear.cutter_tip_radius_coef * m
    hf = gear.dedendum_coef * m
    cb = math.cos(gear.helix_angle)
    # normal section, cutter tooth centred at 0: left flank u = -(pi m/4 + y' tan a),
    # y' measured from the rack reference line (positive away from the gear centre)
    uc = -(math.pi * m / 4.0 + (rho - hf) * math.tan(a)) + rho / math.cos(a)
    yc = -hf + rho
    t = np.linspace(0.0, math.pi / 2.0 - a, n_round)
    un, yn = uc - rho * np.sin(t), yc - rho * np.cos(t)
    nun, nyn = -np.sin(t), -np.cos(t)
    u_line = np.linspace(0.0, uc, n_line)
    return (_to_transverse(gear, u_line, np.full(n_line, -hf), np.zeros(n_line),
                           -np.ones(n_line), cb),
            _to_transverse(gear, un, yn, nun, nyn, cb))


def rack_flank(gear: GearSpec, y_normal: np.ndarray) -> RackPoints:
    """Points of the cutter's left straight flank at heights ``y_normal``.

    ``y_normal`` in m, measured from the cutter's reference line.
    """
    m, a = gear.module, gear.pressure_angle
    y_normal = np.asarray(y_normal, dtype=float)
    un = -(math.pi * m / 4.0 + y_normal * math.tan(a))
    ones = np.ones_like(y_normal)
    return _to_transverse(gear, un, y_normal, -math.cos(a) * ones, -math.sin(a) * ones,
                          math.cos(gear.helix_angle))


def _to_transverse(gear: GearSpec, un: np.ndarray, yn: np.ndarray, nun: np.ndarray,
                   nyn: np.ndarray, cb: float) -> RackPoints:
    """Stretch normal-section rack points by 1/cos(beta) and place them on the gear."""
    r = gear.reference_radius
    pt = math.pi * gear.transverse_module
    u = pt / 2.0 + un / cb
    y = r + gear.profile_shift * gear.module + yn
    nu, ny = nun * cb, nyn
    norm = np.hypot(nu, ny)
    return RackPoints(u, y, nu / norm, ny / norm)


def generate(gear: GearSpec, rack: RackPoints) -> tuple[np.ndarray, np.ndarray]:
    """Gear-frame points (x, y) in m that the rack points generate (envelope, law of gearing)."""
    r = gear.reference_radius
    with np.errstate(divide="ignore", invalid="ignore"):
        d = np.where(rack.ny != 0.0, (rack.y - r) * rack.nu / rack.ny, 0.0) - rack.u
    phi = d / r
    qx, qy = rack.u + d, rack.y
    c, s = np.cos(phi), np.sin(phi)
    return c * qx - s * qy, s * qx + c * qy
