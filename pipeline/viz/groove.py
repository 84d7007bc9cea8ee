"""Picture of the twisted sun body coloured by the torsional shear stress (pyvista).

pyvista costs seconds to import, so it is imported inside the function only; the plotter
comes from :func:`~pipeline.viz._offscreen.offscreen_plotter` (renders without a display).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from pipeline.fem.groove.stress import torsional_shear_stress
from pipeline.viz._offscreen import offscreen_plotter

if TYPE_CHECKING:
    from pipeline.fem.groove.spec import GrooveSpec
    from pipeline.fem.groove.study import GrooveAnalysis

_SEGMENT_LABELS = {
    "shaft_left": "left shaft (no load)",
    "left_gear": "left half, O_L: +T",
    "groove": "groove",
    "right_gear": "right half, O_R: -T",
    "shaft_right": "right shaft (no load)",
}
"""What the twist picture calls each segment of the body (:meth:`GrooveSpec.body`)."""


def segment_labels(spec: GrooveSpec) -> list[tuple[np.ndarray, str]]:
    """Label point (m, above the body on +x, at the segment's middle in z) and text of
    every segment of the body: the halves with the torques at their centres O_L, O_R,
    the groove and the shaft extensions."""
    body = spec.body()
    top = 1.3 * max(seg.outer_radius for seg in body.segments)
    return [(np.array([top, 0.0, 0.5 * (seg.z0 + seg.z1)]), _SEGMENT_LABELS[seg.name])
            for seg in body.segments]


def render_twisted_body(
    analysis: GrooveAnalysis, torque: float, magnification: float | None = None,
    window: tuple[int, int] = (1400, 800),
):
    """Off-screen pyvista Plotter of the body deformed by relative torque ``torque`` (N m).

    Save it with :func:`pipeline.viz.save` (which also closes it).

    Parameters
    ----------
    analysis : from :func:`pipeline.fem.groove.study.analyse_groove`.
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
    plotter = offscreen_plotter(window_size=list(window))
    lim = float(np.percentile(np.abs(tau), 99.5))
    # Mesh edges make the twist visible: axial element edges turn into helices.
    plotter.add_mesh(surf, scalars="shear stress tau_theta_z [MPa]", cmap="coolwarm",
                     clim=(-lim, lim), show_edges=True, edge_color="#555555", line_width=0.5,
                     scalar_bar_args={"title": "shear stress tau_theta_z [MPa]",
                                      "vertical": False, "position_x": 0.3,
                                      "position_y": 0.04, "width": 0.4})
    points, texts = zip(*segment_labels(analysis.spec), strict=True)
    plotter.add_point_labels(np.array(points), list(texts), font_size=14, point_size=1,
                             shape_opacity=0.7, always_visible=True)
    plotter.add_text(f"{analysis.spec.gear.name}: relative torque T = {torque / 1e3:.4g} kN m "
                     f"between the half centres O_L and O_R, displacement x{magnification:.3g}\n"
                     f"k_t = {analysis.result.torsional_stiffness:.4g} N m/rad, "
                     f"K_j = {analysis.result.equivalent_Kj:.4g} N m^2 "
                     f"({analysis.spec.teeth_model}, {analysis.spec.coupling})", font_size=10)
    # Gear axis horizontal, +z (the right half) to the right, seen slightly from above.
    zc = 0.5 * (mesh.p[2].min() + mesh.p[2].max())
    plotter.camera_position = [(1.0, 1.6, zc + 0.5), (0.0, 0.0, zc), (1.0, 0.0, 0.0)]
    plotter.reset_camera()
    plotter.camera.zoom(1.3)
    return plotter
