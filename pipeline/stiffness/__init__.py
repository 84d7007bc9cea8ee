"""Analytical mesh stiffness: potential energy on the exact profile, Sainsot body term,
friction (constant or EHL), slicing for helical gears, ISO 6336 and the contact-line method,
friction stiffness/torque coefficients and Fourier series. Stiffness in N/m, compliance in m/N.
"""

from pipeline.operation import OperatingPoint
from pipeline.signals import FourierSeries, PeriodicSignal
from pipeline.stiffness.analysis import StiffnessResult, analyse_stiffness
from pipeline.stiffness.iso6336 import contact_line_stiffness, iso_stiffness
from pipeline.stiffness.mesh import (
    FrictionModel,
    MeshStiffness,
    PairModel,
    mesh_stiffness,
)
from pipeline.stiffness.options import StiffnessOptions

__all__ = [
    "FourierSeries",
    "FrictionModel",
    "MeshStiffness",
    "OperatingPoint",
    "PairModel",
    "StiffnessOptions",
    "StiffnessResult",
    "PeriodicSignal",
    "analyse_stiffness",
    "contact_line_stiffness",
    "iso_stiffness",
    "mesh_stiffness",
]
