"""Stiffness joining the two halves of a herringbone sun gear through its relief groove.

``spec`` (input) -> ``mesh`` (Gmsh, cached) -> P2 elasticity -> ``coupling``
(12 x 12 between O_L and O_R) -> ``result`` (:class:`GrooveStiffness`), driven by
``study``; ``config`` reads TOML, ``stress`` gives the torsional shear stress
(:mod:`pipeline.viz.groove` draws the twisted body).
"""

from pipeline.fem.groove.result import GrooveStiffness, PhaseShift
from pipeline.fem.groove.spec import GrooveSpec
from pipeline.fem.groove.study import analyse_groove, groove_stiffness

__all__ = ["GrooveSpec", "GrooveStiffness", "PhaseShift", "analyse_groove", "groove_stiffness"]
