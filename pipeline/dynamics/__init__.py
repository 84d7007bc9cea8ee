"""Lumped-parameter gearbox dynamics: bodies and couplings assembled into a linear
time-periodic system, excited by the loaded mesh stiffness and static transmission
error of every mesh, solved for modes, periodic responses and frequency sweeps.

Package map (data flows top to bottom):

- :mod:`.bodies` - rigid bodies with named degrees of freedom (``"sun.x"``, ...).
- :mod:`.couplings` - springs, bearings, torsional shafts, gear meshes (with friction
  loads), matrix couplings (e.g. a groove stiffness), ties and external loads.
- :mod:`.mesh_geometry` - line-of-action projections of cylindrical gear meshes.
- :mod:`.excitation`, :mod:`.mesh_input`, :mod:`.contact_excitation` - mesh stiffness,
  transmission error and friction terms as periodic signals: idealised (rectangular,
  contact-line), from the pipeline's analytical stiffness (:func:`analytical_excitation`)
  or from the loaded tooth contact (:func:`excitation_from_contact`: tangent k(t), static
  transmission error; the compliance it contains and what the models must not count
  again are in that module); :mod:`.herringbone_excitation` - left/right sun-mesh
  excitation from the contact of both herringbone halves through the groove.
- :mod:`.assembly` - :class:`Assembly`: bodies + couplings + loads ->
  :class:`~.system.LinearPeriodicSystem` (:mod:`.system`: M, C, K(t), G, F(t)).
- :mod:`.models` - ready-made gearboxes: spur pair (6 DOF), planar planetary set
  (Lin and Parker 1999), herringbone planetary (Xu et al. 2020), split-torque
  transmission (Jin et al. 2018), planetary models from a set's gears
  (``planetary_gears``), and the published cases as inputs
  (``wind_turbine_planetary``, ``split_torque_helicopter``).
- :mod:`.modal` - natural frequencies, mode shapes and planetary mode types.
- :mod:`.harmonic_balance` - periodic response by the Fourier series method (Hill's
  coupling or first order); :mod:`.multirate` superposes stages with incommensurate
  mesh frequencies.
- :mod:`.integrate` - exact piecewise propagators, Floquet steady state;
  :mod:`.quasi_static` - the zero-speed limit (:func:`quasi_static_response`).
- :mod:`.sweep` - mesh-force sweeps over speed (local or Dask executors), load sharing;
  :mod:`.peaks` refines peak frequencies; :mod:`.operating` - the operating mesh
  frequency, the members' speeds at any mesh frequency, the modes that matter there.
- :mod:`.results` - :class:`Response`, :class:`HarmonicResponse`, :class:`ModalResult`.
- :mod:`.reduction`, :mod:`.signals` - rigid-body-mode removal and exact segment means
  / Fourier coefficients shared by the solvers.
- :mod:`.options`, :mod:`.analysis` - the stage's inputs and its entry points
  (:func:`~.analysis.analyse_modes`, :func:`~.analysis.analyse_response`, ...);
  :mod:`.hb_sweep` - harmonic balance over many frequencies, planned once;
  :mod:`.layout` - where the bodies sit, for the mode-shape figures.
- The commands ``gearpipe modes|response|sweep`` are in :mod:`pipeline.cli`; figures
  are in :mod:`pipeline.viz.dynamics`.

Bodies and couplings assemble into M, C, K(t), G, K_Omega and F(t), dense or sparse
(``system.matrices(tau, sparse=True)``). The herringbone planetary model has 8(N+3) DOF
and takes a ``GrooveStiffness``. The harmonic balance is within 1 % of time integration,
130-500x faster at equal accuracy. The Lin-Parker Table 2 frequencies in the tests are
also checked against hand-written reduced models (one planet with fixed central members
for the planet modes, the rotational reduction for 3, 4 and 5 planets) within 0.1 Hz.
The studies ``workflows/dynamics_spur_dte.py``, ``dynamics_split_torque.py`` and
``dynamics_herringbone_sweep.py`` state in their docstrings what they reproduce from
their papers and what they do not. Not in the planetary models: the friction terms, a
stagger of the herringbone halves.
"""

from pipeline.dynamics.assembly import Assembly
from pipeline.dynamics.bodies import Body
from pipeline.dynamics.contact_excitation import excitation_from_contact
from pipeline.dynamics.couplings import (
    Bearing,
    FrictionLoad,
    GearMesh,
    Load,
    MatrixCoupling,
    Spring,
    Tie,
    TorsionalShaft,
)
from pipeline.dynamics.harmonic_balance import harmonic_balance
from pipeline.dynamics.integrate import integrate, steady_state
from pipeline.dynamics.mesh_input import MeshExcitation, analytical_excitation
from pipeline.dynamics.modal import modal_analysis
from pipeline.dynamics.models.herringbone_planetary import HerringbonePlanetaryModel
from pipeline.dynamics.models.planetary import PlanetaryModel
from pipeline.dynamics.models.split_torque import SplitTorqueModel
from pipeline.dynamics.models.spur_pair import SpurPairModel
from pipeline.dynamics.multirate import superpose_stages
from pipeline.dynamics.quasi_static import quasi_static_response
from pipeline.dynamics.results import HarmonicResponse, ModalResult, Response
from pipeline.dynamics.sweep import SweepResult, load_sharing_factor, mesh_force_sweep
from pipeline.dynamics.system import LinearPeriodicSystem

__all__ = [
    "Assembly",
    "Bearing",
    "Body",
    "FrictionLoad",
    "GearMesh",
    "HarmonicResponse",
    "HerringbonePlanetaryModel",
    "LinearPeriodicSystem",
    "Load",
    "MatrixCoupling",
    "MeshExcitation",
    "ModalResult",
    "PlanetaryModel",
    "Response",
    "SplitTorqueModel",
    "Spring",
    "SpurPairModel",
    "SweepResult",
    "Tie",
    "TorsionalShaft",
    "analytical_excitation",
    "excitation_from_contact",
    "harmonic_balance",
    "integrate",
    "load_sharing_factor",
    "mesh_force_sweep",
    "modal_analysis",
    "quasi_static_response",
    "steady_state",
    "superpose_stages",
]
