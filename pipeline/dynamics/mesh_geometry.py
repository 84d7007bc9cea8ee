"""Line-of-action projections of cylindrical gear meshes (the mesh measure).

For a mesh between gear 1 and gear 2 with unit line-of-action direction
``d = (cos a, sin a)`` in the assembly frame, the compression is

    delta = [ (p1 - p2) . d + s1 rb1 theta1 + s2 rb2 theta2 ] cos(beta_b)
            + h (z1 - z2) sin(beta_b)

* ``p1, p2`` transverse centre displacements (m), ``z1, z2`` axial (m);
* ``s1 = +1`` when a positive rotation of gear 1 moves its contact point along
  ``+d`` (it pushes into the mesh), ``s2 = +1`` when a positive rotation of
  gear 2 moves its contact point along ``-d``;
* ``beta_b`` the base helix angle (rad), ``h = +1/-1`` the hand of the helix
  seen from gear 1 (left and right halves of a herringbone gear have opposite h).

This is eq. 17 of Xu et al. (2020) and the Lin-Parker planar projection when
``beta_b = 0``.
"""

from __future__ import annotations

import math

from pipeline.dynamics.bodies import Body, Coordinate, add_measures


def cylindrical_mesh_measure(
    gear1: Body,
    gear2: Body,
    line_angle: float,
    base_radius1: float,
    base_radius2: float,
    spin1: int = 1,
    spin2: int = 1,
    base_helix_angle: float = 0.0,
    hand: int = 1,
) -> dict[Coordinate, float]:
    """Mesh measure ``{(body, dof): c}`` for a spur or helical mesh.

    Parameters
    ----------
    gear1, gear2 : the two bodies (missing DOFs are simply left out).
    line_angle : rad, direction ``d`` of the line of action in the assembly frame.
    base_radius1, base_radius2 : m.
    spin1, spin2 : +1 or -1, see the module docstring.
    base_helix_angle : beta_b in rad (0 for spur).
    hand : +1 or -1, sign of the axial coupling.

    Returns
    -------
    dict mapping coordinates to coefficients (m/m for translations, m/rad for rotations).
    """
    cb, sb = math.cos(base_helix_angle), math.sin(base_helix_angle)
    parts = [gear1.in_plane(line_angle, cb), gear2.in_plane(line_angle, -cb)]
    rot: dict[Coordinate, float] = {}
    if "theta" in gear1.dofs:
        rot[(gear1.name, "theta")] = spin1 * base_radius1 * cb
    if "theta" in gear2.dofs:
        rot[(gear2.name, "theta")] = spin2 * base_radius2 * cb
    ax: dict[Coordinate, float] = {}
    if sb != 0.0:
        if "z" in gear1.dofs:
            ax[(gear1.name, "z")] = hand * sb
        if "z" in gear2.dofs:
            ax[(gear2.name, "z")] = -hand * sb
    return add_measures(*parts, rot, ax)


def friction_direction_measure(
    gear1: Body, gear2: Body, line_angle: float
) -> dict[Coordinate, float]:
    """Unit friction-force pattern: +n on gear 1 and -n on gear 2.

    ``n`` is the in-plane normal to the line of action, ``n = d`` turned by +90 deg
    (the sliding direction along the profile). A friction stiffness K_f > 0 with
    this pattern pushes gear 1 along +n.
    """
    return add_measures(
        gear1.in_plane(line_angle + math.pi / 2), gear2.in_plane(line_angle + math.pi / 2, -1.0)
    )
