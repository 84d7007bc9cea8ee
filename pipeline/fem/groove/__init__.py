"""Stiffness joining the two halves of a herringbone sun gear through its relief groove.

``spec`` (input) -> ``mesh`` (Gmsh, cached) -> P2 elasticity -> ``coupling``
(12 x 12 between O_L and O_R) -> ``result`` (:class:`GrooveStiffness`), driven by
``study``; ``config`` reads TOML, ``stress`` gives the torsional shear stress
(:mod:`pipeline.viz.groove` draws the twisted body).
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
