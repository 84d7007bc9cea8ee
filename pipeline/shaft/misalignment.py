"""The gap the shafts' deflection opens across the face, in the plane of action.

Each gear's shaft is solved in its own *mesh frame*: ``y`` is the direction in which the
mesh force pushes this gear's axis (along the line of action, away from the mate), ``z``
the shaft's axis (the face coordinate runs with it, from the face's first end at
``gear_position - b / 2``), and a positive rotation about ``z`` turns the loaded flank back
from the mate. In that frame a face slice ``j`` of width ``dz_j`` carrying the line load
``w_j`` (N/m, along the line of action) loads the shaft with

* the force ``F_j = w_j dz_j`` along ``+y`` at ``z_j``;
* the moment ``F_j r_b`` about ``+z`` (the line of action is tangent to the base circle,
  so its lever arm is the base radius ``r_b``),

and the flank there retreats from the mate by ``delta_j = u_y(z_j) + r_b theta_z(z_j)``
(first order in the deflection: the displacement across the line of action, ``u_x``,
changes the centre distance, a second-order effect on the gap, left out). The gap the two
shafts open at face point ``j`` is the sum of the two gears' retreats, ``g_j = delta_p,j +
delta_g,j``: its variation across the face is the misalignment in the plane of action
(ISO 6336-1's ``f_sh``), its mean a rigid approach that adds to the transmission error
only.

Spur gears: a helical mesh's axial force tilts the shafts as well (its moment about ``x``,
``F_a`` times the contact point's distance along the line of action), which is not built
yet: a helical pair is refused.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from pipeline.shaft.model import PointLoad, ShaftModel, ShaftSolution
from pipeline.validation import InputError


@dataclass(frozen=True)
class FlankRetreat:
    """One gear's retreat across the face.

    Attributes
    ----------
    z : (n,) face positions from the face's first end, m.
    translation : (n,) ``u_y`` of the shaft there, m.
    twist : (n,) ``r_b theta_z`` there, m.
    solution : the shaft's whole solution (deflection line, bearing reactions) in the mesh
        frame, or None.
    """

    z: np.ndarray
    translation: np.ndarray
    twist: np.ndarray
    solution: ShaftSolution | None = None

    @property
    def total(self) -> np.ndarray:
        """``delta`` (n,), m."""
        return self.translation + self.twist


def seat_loads(z: np.ndarray, line_load: np.ndarray, face_width: float, gear_position: float,
               base_radius: float) -> list[PointLoad]:
    """The mesh's load on one gear's shaft in its mesh frame (module docstring): ``z`` (n,)
    slice centres from the face's first end (m), ``line_load`` (n,) N/m; slices of equal
    width ``face_width / n``."""
    z = np.asarray(z, dtype=float)
    w = np.asarray(line_load, dtype=float)
    if z.shape != w.shape or z.ndim != 1 or z.size == 0:
        raise InputError("shaft loads: one line load per face position")
    dz = face_width / z.size
    start = gear_position - 0.5 * face_width
    return [PointLoad(float(start + zj), (0.0, float(wj * dz), 0.0),
                      (0.0, 0.0, float(wj * dz * base_radius)))
            for zj, wj in zip(z, w, strict=True)]


def seat_points(model: ShaftModel, z: np.ndarray) -> np.ndarray:
    """The shaft positions (m) of the face points ``z`` (m from the face's first end)."""
    lay = model.layout
    return lay.gear_position - 0.5 * lay.seat_width + np.asarray(z, dtype=float)


def flank_retreat(model: ShaftModel, z: np.ndarray, line_load: np.ndarray,
                  base_radius: float, flexibility: np.ndarray | None = None) -> FlankRetreat:
    """The retreat of one gear's flank across the face under the mesh's line load
    (module docstring), ``model`` the gear's shaft in its mesh frame; ``flexibility`` its
    :meth:`~pipeline.shaft.model.ShaftModel.flexibility` at the face points when computed
    already (a fixed point reuses it)."""
    lay = model.layout
    loads = seat_loads(z, line_load, lay.seat_width, lay.gear_position, base_radius)
    c = model.flexibility(seat_points(model, z)) if flexibility is None else flexibility
    f = np.zeros(6 * len(loads))
    f[1::6] = [ld.force[1] for ld in loads]
    f[5::6] = [ld.moment[2] for ld in loads]
    d = c @ f
    return FlankRetreat(np.asarray(z, dtype=float), d[1::6], base_radius * d[5::6],
                        model.solve(loads))


def shaft_gap(models: Sequence[ShaftModel | None], base_radii: Sequence[float],
              z: np.ndarray, line_load: np.ndarray, helix_angle: float = 0.0,
              flexibilities: Sequence[np.ndarray | None] | None = None
              ) -> tuple[np.ndarray, tuple[FlankRetreat | None, ...]]:
    """The gap (n,) the shafts of both gears open across the face (m; a gear without a
    shaft: rigid) and each gear's retreat (module docstring); ``flexibilities`` of the
    models at the face points, when computed already."""
    if helix_angle != 0.0:
        raise InputError("shafts: the tilt a helical mesh's axial force gives is not built "
                         "yet; shafts take spur pairs")
    flex = flexibilities or [None] * len(models)
    retreats = tuple(None if m is None else flank_retreat(m, z, line_load, rb, c)
                     for m, rb, c in zip(models, base_radii, flex, strict=True))
    gap = np.zeros(np.shape(z))
    for r in retreats:
        if r is not None:
            gap = gap + r.total
    return gap, retreats
