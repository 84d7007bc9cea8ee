"""Picture of the twisted sun body coloured by the torsional shear stress (pyvista).

pyvista costs seconds to import, so it is imported inside the function only.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipeline.fem.groove.study import GrooveAnalysis


def torsional_shear_stress(analysis: GrooveAnalysis, u: np.ndarray) -> np.ndarray:
    """Element-mean shear stress tau_theta_z (Pa), shape (n_elements,), for displacement u (m)."""
    basis = analysis.model.basis
    lam, mu = analysis.model.lam, analysis.model.mu
    grad = basis.interpolate(u).grad  # (3, 3, n_el, n_q)
    w = basis.dx / basis.dx.sum(axis=1, keepdims=True)
    g = np.einsum("ijeq,eq->eij", grad, w)  # element means
    eps = 0.5 * (g + g.transpose(0, 2, 1))
    sigma = 2 * mu * eps + lam * np.trace(eps, axis1=1, axis2=2)[:, None, None] * np.eye(3)
    mesh = analysis.mesh.mesh
    c = mesh.p[:, mesh.t].mean(axis=1)  # (3, n_el) centroids
    r = np.hypot(c[0], c[1])
    e_theta = np.stack([-c[1], c[0], 0 * r]) / np.where(r > 0, r, 1.0)
    return np.einsum("ie,eij,j->e", e_theta, sigma, np.array([0.0, 0.0, 1.0]))


def render_twisted_body(
    analysis: GrooveAnalysis, path: str | Path, torque: float, magnification: float | None = None,
    window: tuple[int, int] = (1400, 800),
) -> Path:
    """Write a PNG of the body deformed by relative torque ``torque`` (N m) between the halves.

    Parameters
    ----------
    analysis : from :func:`pipeline.fem.groove.study.analyse_groove`.
    path : PNG file to write.
    torque : relative torque in N m (O_L against O_R).
    magnification : displacement scale (default: largest displacement shown as 8 %
        of the root radius).
    window : image size in pixels.
    """
    import pyvista as pv

    mesh = analysis.mesh.mesh
    u = analysis.torque_displacement(torque)
    tau = torsional_shear_stress(analysis, u) / 1e6
    nv = mesh.p.shape[1]
    disp = u.reshape(-1, 3)[:nv]  # vertex DOFs come first in the P2 numbering
    if magnification is None:
        magnification = 0.08 * analysis.spec.gear.root_radius / max(np.abs(disp).max(), 1e-300)
    cells = np.hstack([np.full((mesh.t.shape[1], 1), 4), mesh.t.T]).ravel()
    grid = pv.UnstructuredGrid(cells, np.full(mesh.t.shape[1], pv.CellType.TETRA),
                               (mesh.p + magnification * disp.T).T)
    grid.cell_data["shear stress tau_theta_z [MPa]"] = tau
    surf = grid.extract_surface(algorithm="dataset_surface")
    plotter = pv.Plotter(off_screen=True, window_size=list(window))
    lim = float(np.percentile(np.abs(tau), 99.5))
    # Mesh edges make the twist visible: axial element edges turn into helices.
    plotter.add_mesh(surf, scalars="shear stress tau_theta_z [MPa]", cmap="coolwarm",
                     clim=(-lim, lim), show_edges=True, edge_color="#555555", line_width=0.5,
                     scalar_bar_args={"title": "shear stress tau_theta_z [MPa]",
                                      "vertical": False, "position_x": 0.3,
                                      "position_y": 0.04, "width": 0.4})
    plotter.add_text(f"{analysis.spec.gear.name}: relative torque {torque / 1e3:.4g} kN m, "
                     f"displacement x{magnification:.3g}\n"
                     f"k_t = {analysis.result.torsional_stiffness:.4g} N m/rad, "
                     f"K_j = {analysis.result.equivalent_Kj:.4g} N m^2 "
                     f"({analysis.spec.teeth_model}, {analysis.spec.coupling})", font_size=10)
    # Gear axis horizontal, seen slightly from above the side.
    zc = 0.5 * (mesh.p[2].min() + mesh.p[2].max())
    plotter.camera_position = [(1.0, -1.6, zc + 0.5), (0.0, 0.0, zc), (1.0, 0.0, 0.0)]
    plotter.reset_camera()
    plotter.camera.zoom(1.3)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    plotter.screenshot(str(path))
    plotter.close()
    return path
