"""gearpipe: a finite-element-enriched gear stiffness pipeline.

Stages, one sub-package each, in the order data flows through them:

* ``geometry`` - gear spec, involute, exact tooth profile (rack- or shaper-generated),
  pair, assembly errors, planetary sets, gear bodies (mass, polar moment);
  :func:`~pipeline.geometry.analysis.analyse_geometry`.
* ``stiffness`` - analytical mesh stiffness: potential energy on the exact profile,
  Sainsot body term (ring rims: their own fit), friction (+EHL), helical slices,
  ISO 6336-1 and the contact-line method, Fourier series;
  :func:`~pipeline.stiffness.analyse_stiffness`.
* ``fem`` - Gmsh meshing (one session manager), scikit-fem elasticity, solvers, one
  influence routine for 2D and 3D sectors and whole gears, fillet stress, the relief
  groove of a herringbone sun (``fem.groove``), size estimates before meshing.
* ``contact`` - loaded tooth contact (complementarity solver, Hertz/Weber local contact),
  compliance sources (analytical slices, FE 2D, FE 3D), load distribution (K_Hbeta,
  tooth-pair unit load ratio, Hertz pressure, TE orders), root stress (FE 2D beside ISO
  6336-3), both halves of a herringbone sun through its groove;
  :func:`~pipeline.contact.analyse_contact`.
* ``dynamics`` - lumped-parameter models and their solvers (package map in its
  docstring): modes, periodic response, speed sweeps.
* ``viz`` - every figure (``plot_x(..., ax=None) -> Axes``, pyvista renders, ``save``).
* ``report`` - the tooth load distribution report (HTML, JSON, CSV per mesh).
* ``config`` - the gearbox file -> frozen stage inputs (units defined once, strict tables).
* ``run`` - the whole chain on one gearbox (:func:`~pipeline.run.run_pipeline`).
* ``study`` - design studies over a base gearbox file (Dask or serial, resumable).
* ``verification`` - the catalogue of checks against exact solutions, published values and
  an independent FE model that ``gearpipe validate`` runs and reports.

The command line (``gearpipe``, one module per command, with the file writers beside
them) lives in ``pipeline/cli/``; the stages do not import it. Shared by all:
``io`` (atomic files), ``cache`` (the on-disk cache: one :class:`~pipeline.cache.Cache`
passed to every step that caches, entries keyed by inputs and producing code),
``output_folder`` (a result folder written as a unit),
``provenance`` (``run.json``), ``signals`` (periodic signals, Fourier series),
``operation`` (the operating point), ``validation`` (input checks), ``progress``,
``parallel`` (the process pool).

Everything inside the package is in SI units (m, N, Pa, rad, s); conversion to mm, deg,
N m and rpm happens only at the edges (``config``, reports, command output). Frozen
dataclasses hold inputs and results, their docstrings give every array's shape and
unit; the friction sign convention lives in :mod:`pipeline.stiffness.friction`, the roll
coordinate ``s`` along the line of action (from the pinion's base tangent point T1) in
:mod:`pipeline.geometry.pair`.

References
----------
Code, tests and docs cite these by author and year ("Xu et al. (2020), eq. 14"). The
four papers the pipeline reproduces come first.

* Jin et al. (2018) — G. H. Jin, H. Y. Yang, R. P. Zhu. Tooth surface friction and its
  influence on dynamic transmission error of double power input transmission system.
  *Journal of Vibroengineering* 20(5), 2018 (paper 2901). Split-torque helicopter
  transmission (``dynamics/models/split_torque*.py``), friction stiffness and friction torque
  coefficients, EHL friction (eq. 9), Fourier series method.
* The assembly-error paper — *Theoretical modelling of mesh stiffness for spur gears with
  assembly errors and friction* (potential-energy stiffness with friction and centre
  displacements, 6-DOF spur pair; base case z 50/50, m 3 mm, 340 N m, 2340 rpm). Our copy is
  the article text as published at https://www.zhygear.com/?p=31927; it names no authors,
  journal or year, and we did not find the original publication, so the code calls it "the
  assembly-error paper".
* Xu et al. (2020) — X. Xu, H. Ge, J. Deng, J. Wang, R. Chen. An investigation on dynamic
  characteristics of herringbone planetary gear system with torsional flexibility between
  the left and right teeth of the sun gear. *Mechanics & Industry* 21, 602 (2020). 1.5 MW
  wind-turbine herringbone planetary stage with sun relief-groove flexibility
  (``dynamics/models/wind_turbine_planetary.py``, ``groove_mesh.py``, ``fem/groove/``).
* Yang et al. (2026) — Z. Yang, K. Yu, J. Zhang. A helical gear meshing stiffness model
  incorporating friction effects and contact deformation. *Applied Sciences* 16(2), 804
  (2026), doi:10.3390/app16020804. Helical slice potential-energy method with friction and
  local contact deformation (eq. 24), two-level LTCA, contact-line method.

Methods and data the code relies on:

* Chen and Shao (2013) — Z. Chen, Y. Shao. Mesh stiffness of an internal spur gear pair
  with ring gear rim deformation. *Mechanism and Machine Theory* 69, 1-12 (2013). Ring
  tooth as a cantilever from the root circle; rim deformation between supports
  (``stiffness/sections.py``, ``stiffness/ring_body.py``).
* Liang et al. (2014) — X. Liang, M. J. Zuo, T. H. Patel. Evaluating the time-varying mesh
  stiffness of a planetary gear set using the potential energy method. *Proceedings of the
  IMechE, Part C* 228(3), 535-547 (2014). Potential energy of ring teeth
  (``stiffness/sections.py``).
* Sainsot et al. (2004) — P. Sainsot, P. Velex, O. Duverger. Contribution of gear body to
  tooth deflections: a new bidimensional analytical formula. *Journal of Mechanical Design*
  126(4), 748-752 (2004). Fillet-foundation term (``stiffness/foundation.py``).
* Lin and Parker (1999) — J. Lin, R. G. Parker. Analytical characterization of the unique
  properties of planetary gear free vibration. *Journal of Vibration and Acoustics* 121(3),
  316-321 (1999). Planar planetary model, mode types (``dynamics/models/planetary.py``).
* Harris (1958) — S. L. Harris. Dynamic loads on the teeth of spur gears. *Proceedings of
  the IMechE* 172, 87-112 (1958). Transmission error of a relieved pair against load: at light
  load it follows the tip reliefs (``tests/test_contact_modifications.py``).
* ISO 21771:2007 — Gears, cylindrical involute gears and gear pairs, concepts and geometry.
  Roll length, profile and helix modifications, profile twist
  (``contact/modifications/``).
* ISO 6336-1:2019 — Calculation of load capacity of spur and helical gears, Part 1:
  Basic principles, introduction and general influence factors. Single stiffness c' and
  mesh stiffness c_gamma_alpha (``stiffness/iso6336.py``).
* ISO 6336-2:2019 and ISO 6336-3:2019 — Calculation of load capacity of spur and
  helical gears, Part 2: surface durability (pitting), zone and elasticity factors Z_H, Z_E
  (the Hertz check in ``tests/test_contact_distribution.py``); Part 3: tooth bending strength,
  method B form factor Y_F, stress correction factor Y_S, helix factor Y_beta
  (``contact/iso_root_stress.py``).
* Xu et al. (2007) — H. Xu, A. Kahraman, N. E. Anderson, D. G. Maddock. A friction
  coefficient model for the prediction of instantaneous coefficient of friction for spur
  and helical gears. *Journal of Tribology* 129(1), 58-69 (2007). EHL friction regression
  (``stiffness/friction.py``, via Jin et al. 2018, eq. 9).
* Weber and Banaschek (1953) — C. Weber, K. Banaschek. *Formänderung und Profilrücknahme
  bei gerad- und schrägverzahnten Rädern*. Vieweg, Braunschweig, 1953. Local contact
  approach (``contact/hertz.py``, ``fem/nearfield_halfplane.py``).
* Cornell (1981) — R. W. Cornell. Compliance and stress sensitivity of spur gear teeth.
  *Journal of Mechanical Design* 103(2), 447-459 (1981).
* Andersson and Vedmar (2003) — A. Andersson, L. Vedmar, *Journal of Mechanical Design*
  125, 524-534 (2003), as cited in ``fem/nearfield_halfplane.py`` for FE/half-plane hybrids (the
  reference was not re-checked here).
* Johnson (1985) — K. L. Johnson. *Contact Mechanics*. Cambridge University Press, 1985.
  Hertz line contact, half-plane and half-space kernels.
* Lawson and Hanson (1974) — C. L. Lawson, R. J. Hanson. *Solving Least Squares
  Problems*. Prentice-Hall, 1974. NNLS active-set method (``contact/active_set.py``).
* Bertsekas (1999) — D. P. Bertsekas. *Nonlinear Programming*, 2nd ed. Athena
  Scientific, 1999. Gradient projection (``contact/complementarity.py``).
* Nayfeh and Mook (1979) — A. H. Nayfeh, D. T. Mook. *Nonlinear Oscillations*. Wiley,
  1979. Parametric resonance check in ``tests/test_dyn_exact.py``.
"""

__version__ = "0.1.0"
