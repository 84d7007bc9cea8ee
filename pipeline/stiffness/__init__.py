"""Analytical mesh stiffness: potential energy on the exact profile, Sainsot body term,
friction (constant or EHL), slicing for helical gears, ISO 6336 and the contact-line method,
friction stiffness/torque coefficients and Fourier series. Stiffness in N/m, compliance in m/N.
"""

from pipeline.signals import FourierSeries, PeriodicSignal
from pipeline.stiffness.analysis import PairStiffness, analyse_pair
from pipeline.stiffness.iso6336 import contact_line_stiffness, iso_stiffness
from pipeline.stiffness.mesh import (
    FrictionModel,
    MeshStiffness,
    OperatingPoint,
    PairModel,
    mesh_stiffness,
)

__all__ = [
    "FourierSeries",
    "FrictionModel",
    "MeshStiffness",
    "OperatingPoint",
    "PairModel",
    "PairStiffness",
    "PeriodicSignal",
    "analyse_pair",
    "contact_line_stiffness",
    "iso_stiffness",
    "mesh_stiffness",
]
