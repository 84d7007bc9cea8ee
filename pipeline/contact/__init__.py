"""Loaded tooth contact analysis (LTCA): load sharing, transmission error, mesh stiffness.

Arrays in, arrays out: for each mesh position the caller supplies the
compliance matrix ``G`` (m/N) of the candidate contact points (analytical slice
compliance or FE influence coefficients), their initial separations ``eps``
(m) and, optionally, a local Hertz contact model; the solver returns the loads,
the loaded approach and the mesh stiffness.

- :func:`analytical_compliance` -> :func:`analyse_contact` - the stage's entry points:
  a pair's compliance source and its loaded mesh cycle at the operating torque
  (:mod:`.analysis`; options :class:`ContactOptions`).
- :func:`solve_contact` - one mesh position (:mod:`.complementarity`; its exact
  inner QP solver is :mod:`.active_set`). The only solver: everything below calls it.
- :func:`solve_positions` - a stack of given (G, eps) with a fixed point count (:mod:`.sweep`).
- :class:`ComplianceSource`, :class:`ContactPoints`, :class:`SliceCompliance` -
  candidate points and compliance G of a pair at a mesh position (:mod:`.source`).
- :class:`FlankModifications`, :func:`initial_separations` - eps from each gear's flank
  modifications, pitch errors and the shafts' lead gap (:mod:`.separations`); the per-gear
  model (tip / root relief, crownings, slopes, end reliefs, twist, topography grid) and the
  flanks' modification maps in :mod:`.modifications`.
- :func:`loaded_mesh_cycle` - a mesh cycle from a compliance source, warm-started:
  loads, load sharing, transmission error, mesh stiffness, unit loads (:mod:`.ltca`).
- A herringbone sun-planet mesh, both helical halves through the sun's relief groove
  (:mod:`.herringbone`, result :mod:`.herringbone_results`, the groove condensed to the
  flank DOFs :mod:`.groove_flank`, left/right load maps :mod:`.herringbone_maps`).
- Load maps over the flank (pyvista PNG, VTU) in :mod:`.loadmap`; the
  ``gearpipe contact`` command in :mod:`pipeline.cli.contact` (options: :mod:`.options`).
- :class:`HertzLineContact` - Weber-Banaschek local approach, Yang et al. (2026), eq. (24),
  and Hertz half-width / maximum pressure (:mod:`.hertz`).
- :class:`ContactSolution`, :class:`ContactSweep` - results (:mod:`.results`).
- :func:`load_distribution` - line load, K_Hbeta, tooth-pair unit load ratio, Hertz
  pressure, TE orders of a loaded mesh cycle (:mod:`.distribution`); root stress (FE 2D, ISO
  6336-3) in :mod:`.root_stress` and :mod:`.iso_root_stress`; the largest Hertz pressure
  over the cycle at every point of the flanks in :mod:`.pressure_envelope`.
- :class:`FE2DCompliance`, :class:`FE3DCompliance` - the FE stage's influence matrices
  adapted to :class:`ComplianceSource` (:mod:`.fe2d_source`; :mod:`.fe3d_source` on the
  tables of :mod:`.fe3d_table`).
"""

from pipeline._lazy import lazy_exports
from pipeline.contact.analysis import analyse_contact, analytical_compliance, line_of_action_load
from pipeline.contact.complementarity import (
    ContactConvergenceError,
    complementarity_residual,
    solve_contact,
)
from pipeline.contact.distribution import LoadDistribution, load_distribution
from pipeline.contact.hertz import (
    HertzLineContact,
    LinearLocalCompliance,
    LocalCompliance,
    contact_modulus,
    effective_radius,
    hertz_half_width,
    hertz_max_pressure,
)
from pipeline.contact.ltca import loaded_mesh_cycle
from pipeline.contact.options import ContactOptions
from pipeline.contact.results import ContactSolution, ContactSweep, LoadedMeshCycle
from pipeline.contact.separations import FlankModifications, initial_separations
from pipeline.contact.source import ComplianceSource, ContactPoints, SliceCompliance
from pipeline.contact.sweep import solve_positions

# FE sources are imported on first use: they pull in scikit-fem and Gmsh (seconds)
_FE_EXPORTS = {"FE2DCompliance": "pipeline.contact.fe2d_source",
               "FE2DSettings": "pipeline.fem.settings",
               "FE3DCompliance": "pipeline.contact.fe3d_source",
               "FE3DSettings": "pipeline.fem.settings"}


__getattr__ = lazy_exports(__name__, _FE_EXPORTS)

__all__ = [
    "ContactOptions", "analyse_contact", "analytical_compliance", "line_of_action_load",
    "ComplianceSource", "ContactConvergenceError", "ContactPoints", "ContactSolution",
    "ContactSweep", "FE2DCompliance", "FE2DSettings", "FE3DCompliance", "FE3DSettings",
    "FlankModifications", "HertzLineContact", "LinearLocalCompliance",
    "LoadedMeshCycle", "LocalCompliance", "SliceCompliance", "complementarity_residual",
    "contact_modulus", "effective_radius", "hertz_half_width", "hertz_max_pressure",
    "initial_separations", "loaded_mesh_cycle", "solve_contact", "solve_positions",
    "LoadDistribution", "load_distribution",
]
