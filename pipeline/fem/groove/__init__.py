"""Stiffness joining the two halves of a herringbone sun gear through its relief groove.

``spec`` (input) -> ``mesh`` (Gmsh, cached) -> P2 elasticity -> ``coupling``
(12 x 12 between O_L and O_R) -> ``result`` (:class:`GrooveStiffness`), driven by
``study``; ``config`` reads TOML, ``stress`` gives the torsional shear stress
(:mod:`pipeline.viz.groove` draws the twisted body).

The sun body (left half, groove, right half, optional shafts) is meshed in Gmsh with curved
P2 tetrahedra, either with the real helical teeth (exact profile lofted along the helix,
opposite hands) or with each half replaced by its root cylinder. Each half is tied to a
node at its centre (O_L, O_R) by a distributed (RBE3-like) coupling: a generalised force at
the node is spread as a traction that varies like a rigid motion over the half's outer
surface - the planets' mesh torque smeared over the face width - and the node moves with
the least-squares rigid fit of that surface (:mod:`.coupling`). Six self-equilibrated load
cases on one solver set-up give the 6 x 6 relative flexibility and the 12 x 12 stiffness
between O_L and O_R (rigid-body null space exactly six). ``coupling = "rigid"`` (RBE2) is
the stiff bound; ``"tooth_forces"`` loads the left half with the helical mesh forces of
each planet (tangential, radial, axial) over a band one pitch wide following the helix
(:mod:`.toothload`). K_j = k_t l_LR is what Xu et al. (2020), eq. 1 calls G I_j.

Checks: a plain and a hollow cylinder give G J / L within 1e-4; a stepped shaft gives the
series sum plus a shoulder compliance equal to 0.097 d of extra small shaft per shoulder
(independent of the segment lengths, i.e. a local Saint-Venant effect, bounded by the step
height); k_t changes by < 0.1 % between h = 30 and 22 mm. Xu et al. (2020)'s sun compared:
``workflows/groove_sweep.py``.
"""

from pipeline._lazy import lazy_exports

# imported on first use: ``study`` pulls in scikit-fem and Gmsh, which a gearbox file
# naming a groove needs only when the groove is analysed
_EXPORTS = {"GrooveStiffness": "pipeline.fem.groove.result",
            "PhaseShift": "pipeline.fem.groove.result",
            "GrooveSpec": "pipeline.fem.groove.spec",
            "analyse_groove": "pipeline.fem.groove.study",
            "groove_stiffness": "pipeline.fem.groove.study"}
__getattr__ = lazy_exports(__name__, _EXPORTS)
__all__ = sorted(_EXPORTS)
