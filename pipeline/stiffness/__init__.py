"""Analytical mesh stiffness: potential energy on the exact profile, Sainsot body term,
friction (constant or EHL), slicing for helical gears, ISO 6336 and the contact-line method,
friction stiffness/torque coefficients and Fourier series. Stiffness in N/m, compliance in m/N.

Internal (ring) gears go through geometry, stiffness and contact like external ones
(``workflows/configs/planet_ring_pair.toml``, ``tests/test_internal_gears.py``): the ring
tooth hangs from its rim (:mod:`.tooth`, :mod:`.sections`), its body term is Sainsot's form
refitted to whole-ring FE (:mod:`.ring_body`) and friction keeps its sign convention
(:mod:`.friction`). ISO 6336-1 takes z_n2 = inf for the ring (:mod:`.iso6336`); planet-ring
pairs (m 3 mm, 20 deg, rim 4 m_n, 20-37 / 60-120 teeth) come out 1.11-1.16 x its
c_gamma_alpha b where external pairs are 0.85-0.92 x, and 1.45-1.56 x the external pair
with the same planet (ISO: 1.10-1.23). Without the big gear's body term the
internal/external ratio is within 3 % of ISO's: the difference is the body (at the pitch
point 6.6e-12 m^2/N for the ring against 28e-12 for an 80-tooth external gear, whose
Sainsot term includes the torsion down to its bore); the ring tooth itself is 8-16 %
stiffer at the pitch point and the contact ratio 8-16 % larger. As z_ring grows the
internal and the external pair close in on the pinion-rack pair from either side like 1/z
(contact ratio, tooth compliance, mesh stiffness without the body terms: 0.55 % apart at
2000 teeth). Herringbone pairs are analysed per helical half as for external gears;
assembly errors are modelled for external pairs only (an internal pair with them is refused
in one line).
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
