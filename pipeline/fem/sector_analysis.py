"""The FE stage's entry point for one gear: a 2D sector, its flank influence matrix and the
single-tooth FE compliance beside the analytical one.

``analyse_sector(gear, options) -> SectorResult``; the command ``gearpipe fe`` writes
its columns, matrix and figures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.fem.flank import active_radii, flank_points
from pipeline.fem.influence import InfluenceMatrix, constrained_dofs, influence_matrix
from pipeline.fem.linear_static import build_model, solve_static
from pipeline.fem.mesh_settings import SectorSettings
from pipeline.fem.patch_loads import patch_loads
from pipeline.fem.sector2d import SectorMesh2D, sector_mesh_2d
from pipeline.fem.settings import FE2DSettings, check_table_points
from pipeline.geometry.gear import GearSpec


@dataclass(frozen=True, eq=False)
class SectorResult:
    """2D sector FE of one gear.

    Attributes
    ----------
    gear : the gear.
    options : the 2D FE model (teeth of the sector: ``options.sector_teeth``, points,
        refinement, plane model).
    sector : the sector mesh.
    radii : shape (p,), radii of the flank points on each tooth, m.
    influence : the influence matrix of all ``teeth x p`` points (``structural``: m^2/N,
        per unit face width).
    analytical_tooth, analytical_foundation : shape (p,), analytical compliance of the
        middle tooth (bending + shear + axial; Sainsot foundation), m^2/N.
    """

    gear: GearSpec
    options: FE2DSettings
    sector: SectorMesh2D
    radii: np.ndarray
    influence: InfluenceMatrix
    analytical_tooth: np.ndarray
    analytical_foundation: np.ndarray

    @property
    def _mid(self) -> slice:
        mid, p = self.options.sector_teeth // 2, self.radii.size
        return slice(mid * p, (mid + 1) * p)

    @property
    def middle_tooth_compliance(self) -> np.ndarray:
        """Structural FE compliance on the middle tooth's diagonal, shape (p,), m^2/N."""
        return np.diag(self.influence.structural)[self._mid]

    def columns(self) -> dict[str, np.ndarray]:
        """Single-tooth compliance along the profile, FE and analytical, with units."""
        return {
            "radius [m]": self.radii,
            "fe_structural [m^2/N]": self.middle_tooth_compliance,
            "fe_raw_patch [m^2/N]": np.diag(self.influence.fe)[self._mid],
            "analytical_total [m^2/N]": self.analytical_tooth + self.analytical_foundation,
            "analytical_tooth [m^2/N]": self.analytical_tooth,
            "analytical_foundation [m^2/N]": self.analytical_foundation,
        }

    def summary(self) -> dict:
        """Sizes, solver, timings (s), symmetry, rim coupling and FE/analytical ratios."""
        G, S, diag = self.influence, self.influence.structural, self.middle_tooth_compliance
        ratio = diag / (self.analytical_tooth + self.analytical_foundation)
        p = self.radii.size
        return {
            "sector_teeth": self.options.sector_teeth, "nodes": self.sector.n_nodes,
            "dof": G.n_dof,
            "points": S.shape[0], "solver": G.method, "timings_s": G.timings,
            "symmetry_error": G.symmetry_error(),
            "rim_coupling_max_ratio": float(np.max(S[self._mid, :p] / diag[:, None])),
            "fe_over_analytical_min": float(ratio.min()),
            "fe_over_analytical_max": float(ratio.max()),
            "fe_compliance_pitch_m2_per_N": float(np.interp(self.gear.reference_radius,
                                                            self.radii, diag)),
        }

    def pitch_load_displacement(self, line_load: float = 1e3) -> np.ndarray:
        """Nodal displacements (m) under ``line_load`` (N/m) at the middle tooth's pitch point."""
        g, n = self.gear, self.options.sector_teeth
        model = build_model(self.sector.mesh, g.material, kind=self.options.kind)
        one = flank_points(g, n, [n // 2], [g.reference_radius])
        loads = line_load * patch_loads(self.sector, one, self.influence.patch_half_width)
        return solve_static(model, loads.toarray(),
                            constrained_dofs(self.sector, model)).displacements[:, 0]


def sector_settings(gear: GearSpec, options: FE2DSettings) -> SectorSettings:
    """Mesh settings of ``gear``'s sector for ``options`` (every tooth at the flank size);
    an influence matrix of more flank points than the machine holds is refused first."""
    n = options.sector_teeth
    check_table_points(options.points * n, f"fe.points x fe.teeth = {options.points} x {n}",
                       "lower fe.points or fe.teeth")
    return SectorSettings.for_gear(gear, n, options.refinement)


def analyse_sector(gear: GearSpec, options: FE2DSettings | None = None, *,
                   cache: Cache = DEFAULT_CACHE) -> SectorResult:
    """Mesh a 2D sector of ``gear`` (read from and written to ``cache``), compute its
    flank influence matrix and compare the middle tooth's compliance with the analytical
    tooth model."""
    from pipeline.stiffness.tooth import tooth_compliance, tooth_model

    options = options or FE2DSettings()
    n = options.sector_teeth
    sec = sector_mesh_2d(gear, sector_settings(gear, options), cache=cache)
    r = active_radii(gear, options.points)
    pts = flank_points(gear, n, np.repeat(np.arange(n), r.size), np.tile(r, n))
    G = influence_matrix(sec, pts, kind=options.kind)
    an = tooth_compliance(tooth_model(gear), r)
    return SectorResult(gear, options, sec, r, G, an.tooth, an.foundation)
