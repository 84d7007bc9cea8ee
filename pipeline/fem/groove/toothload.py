"""Tooth-mesh forces of the planets on one helical half of the sun gear (nodal loads).

Each of the N_p equally spaced planets (polar angles ``phase + 2 pi p / N_p``)
presses on the sun with the normal tooth force of a helical mesh. Per unit
tangential force its direction at a surface point is

    d = e_theta - tan(alpha_t) e_r - s tan(beta) e_z,

tangential (the torque), radial towards the axis (the transverse pressure
angle alpha_t) and axial (perpendicular to the helix: the helix direction
``s tan(beta) e_theta + e_z`` for a half whose teeth turn by ``s tan(beta) / r``
per unit z, ``s`` = :attr:`HelicalTeeth.sign`). The force is spread as a
uniform traction over a band of the half's outer surface one angular pitch
2 pi / z wide that follows the helix over the face width - the zone the
contact lines of one mesh sweep - and, when real teeth are modelled, only
over the flank heights between the reference radius less one module and the
tip. Loads are consistent (the surface mass matrix times the nodal
direction field) and scaled so that every planet carries torque T / N_p about
the axis. Lengths in m, forces in N.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.fem.linear_static import ElasticModel
from pipeline.fem.tetmesh import surface_mass
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError, check_int_range, check_range


def planet_mesh_loads(
    model: ElasticModel, triangles: np.ndarray, gear: GearSpec, sign: int,
    z_reference: float, planets: int, torque: float = 1.0, phase: float = 0.0,
    toothed: bool = False,
) -> np.ndarray:
    """Nodal forces (n_dof,) in N of ``planets`` tooth meshes on one sun half.

    Parameters
    ----------
    model : assembled 3D P2 body; DOF ``3 * node + component``.
    triangles : (6, n) outer-surface triangles of the half (basis numbering).
    gear : the sun gear (z, alpha_t, beta, radii).
    sign : +1 / -1, the turning sense of the half's helix (module doc).
    z_reference : axial position (m) where the band is centred on the planet angle.
    planets : N_p >= 1, equally spaced.
    torque : total torque about +z the forces exert, N m (non-zero).
    phase : polar angle of planet 0, rad.
    toothed : restrict the bands to the flank heights (real teeth modelled).
    """
    check_int_range("groove.planets", planets, 1, 64)
    check_range("groove.torque", abs(torque), 1e-12, 1e12, unit="N m")
    nodes = model.basis.doflocs[:, ::3]
    n = nodes.shape[1]
    lead = sign * math.tan(gear.helix_angle) / gear.reference_radius  # rad/m
    c = nodes[:, triangles[:3]].mean(axis=1)  # (3, n_tri) centroids
    r_c = np.hypot(c[0], c[1])
    # Polar angle measured in the frame that follows the helix.
    psi = np.arctan2(c[1], c[0]) - lead * (c[2] - z_reference)
    on_flank = np.ones(r_c.size, dtype=bool)
    if toothed:
        on_flank = r_c >= gear.reference_radius - gear.module
    x, y = nodes[0], nodes[1]
    r = np.hypot(x, y)
    r = np.where(r > 0, r, 1.0)
    e_t = np.stack([-y / r, x / r, 0 * r])
    e_r = np.stack([x / r, y / r, 0 * r])
    e_z = np.stack([0 * r, 0 * r, np.ones_like(r)])
    d = e_t - math.tan(gear.transverse_pressure_angle) * e_r - sign * math.tan(
        gear.helix_angle) * e_z
    f = np.zeros((n, 3))
    for p in range(planets):
        phi_p = phase + 2 * math.pi * p / planets
        dpsi = (psi - phi_p + math.pi) % (2 * math.pi) - math.pi
        band = on_flank & (np.abs(dpsi) <= math.pi / gear.teeth)
        if not band.any():
            raise InputError(f"groove: no surface triangles under planet {p} "
                             "(mesh too coarse for the tooth-force band)")
        fp = np.asarray(surface_mass(nodes, triangles[:, band], n) @ d.T)  # (n, 3)
        mz = float(np.sum(x * fp[:, 1] - y * fp[:, 0]))
        f += fp * (torque / planets / mz)
    return f.ravel()
