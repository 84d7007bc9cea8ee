"""Input of the relief-groove stiffness study (frozen, SI) and the body it describes.

Layout along the gear axis z, origin at the middle of the groove (Xu et al. 2020,
Fig. 2): left helical half [-g/2 - b/2, -g/2], groove [-g/2, g/2], right half
[g/2, g/2 + b/2], where b is ``GearSpec.face_width`` (both toothed halves) and g
the groove width; optional shaft extensions beyond the outer gear faces. The
reference nodes O_L, O_R sit at the centres of the halves, l_LR = b/2 + g apart.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from pipeline.fem.groove.body import CoaxialBody, HelicalTeeth, Segment
from pipeline.fem.groove.mesh import MeshSettings
from pipeline.geometry.gear import GearSpec
from pipeline.validation import InputError, check_choice, check_int_range, check_range

# how the reference nodes O_L, O_R are tied to the body (:mod:`pipeline.fem.groove.coupling`)
COUPLINGS = ("distributed", "rigid", "tooth_forces")

TEETH_MODELS = ("root_cylinder", "helical_teeth")


@dataclass(frozen=True)
class GrooveSpec:
    """A herringbone sun gear body and how to model it.

    Attributes
    ----------
    gear : the herringbone gear (``herringbone=True``, ``groove_width`` >= 0,
        ``bore_radius`` the bore).
    groove_bottom_diameter : diameter of the groove bottom in m (<= root diameter).
    shaft_length_left, shaft_length_right : shaft extensions beyond the outer gear
        faces in m (0: none). They carry no load in the coupling cases and are
        there to include the end restraint of a real sun shaft.
    shaft_diameter_left, shaft_diameter_right : their diameters in m (None: the
        root diameter).
    teeth_model : "root_cylinder" (halves replaced by the root cylinder) or
        "helical_teeth" (the real helical teeth, opposite hands).
    coupling : "distributed" (mesh forces smeared over each half's outer surface,
        RBE3-like), "rigid" (outer surfaces rigid, RBE2-like) or "tooth_forces"
        (k_t from the planets' tooth-mesh forces on the left half; the 12 x 12
        matrix from the distributed cases of the same solve).
    planets : number of equally spaced planets for "tooth_forces".
    mesh_size : largest element edge in m.
    sun_torque : sun torque T_s in N m used for the phase shift in reports.
    """

    gear: GearSpec
    groove_bottom_diameter: float
    shaft_length_left: float = 0.0
    shaft_length_right: float = 0.0
    shaft_diameter_left: float | None = None
    shaft_diameter_right: float | None = None
    teeth_model: str = "root_cylinder"
    coupling: str = "distributed"
    planets: int = 4
    mesh_size: float = 0.03
    sun_torque: float = 0.0

    def __post_init__(self) -> None:
        g = self.gear
        if not g.herringbone or g.internal:
            raise InputError(f"{g.name}: the relief-groove model needs an external "
                             "herringbone gear (herringbone = true)")
        check_range("groove.bottom_diameter", self.groove_bottom_diameter,
                    2 * g.bore_radius, 2 * g.root_radius, lo_open=True, unit="m")
        for side in ("left", "right"):
            check_range(f"groove.shaft_length_{side}", getattr(self, f"shaft_length_{side}"),
                        0.0, 100.0, unit="m")
            d = getattr(self, f"shaft_diameter_{side}")
            if d is not None:
                check_range(f"groove.shaft_diameter_{side}", d, 2 * g.bore_radius,
                            2 * g.tip_radius_, lo_open=True, unit="m")
        check_choice("groove.teeth_model", self.teeth_model, TEETH_MODELS)
        check_choice("groove.coupling", self.coupling, COUPLINGS)
        check_int_range("groove.planets", self.planets, 1, 64)
        check_range("groove.mesh_size", self.mesh_size, 1e-4 * g.root_radius,
                    2 * g.root_radius, unit="m")
        check_range("groove.sun_torque", self.sun_torque, -1e9, 1e9, unit="N m")

    @property
    def l_LR(self) -> float:
        """Distance between the half centres O_L and O_R, m."""
        return self.gear.half_width + self.gear.groove_width

    @property
    def node_z(self) -> tuple[float, float]:
        """Axial positions of O_L and O_R, m."""
        return -self.l_LR / 2.0, self.l_LR / 2.0

    def mesh_settings(self) -> MeshSettings:
        return MeshSettings(size=self.mesh_size)

    def body(self) -> CoaxialBody:
        """The coaxial body to mesh (segment names: shaft_left, left_gear, groove, ...)."""
        g = self.gear
        a, w = g.half_width, g.groove_width
        rf = g.root_radius
        toothed = self.teeth_model == "helical_teeth"
        segs = []
        if self.shaft_length_left > 0:
            d = self.shaft_diameter_left or 2 * rf
            segs.append(Segment("shaft_left", -w / 2 - a - self.shaft_length_left, -w / 2 - a,
                                d / 2))
        # Opposite hands, tooth 0 aligned at the groove: a herringbone with its apex there.
        segs.append(Segment("left_gear", -w / 2 - a, -w / 2, rf,
                            HelicalTeeth(g, -1, -w / 2) if toothed else None))
        if w > 0:
            segs.append(Segment("groove", -w / 2, w / 2, self.groove_bottom_diameter / 2))
        segs.append(Segment("right_gear", w / 2, w / 2 + a, rf,
                            HelicalTeeth(g, 1, w / 2) if toothed else None))
        if self.shaft_length_right > 0:
            d = self.shaft_diameter_right or 2 * rf
            segs.append(Segment("shaft_right", w / 2 + a, w / 2 + a + self.shaft_length_right,
                                d / 2))
        return CoaxialBody(tuple(segs), g.bore_radius)

    def section_torsional_rigidity(self, diameter: float) -> float:
        """G J (N m^2) of a round section of ``diameter`` (m) with the bore."""
        j = math.pi / 32.0 * (diameter**4 - (2 * self.gear.bore_radius) ** 4)
        return self.gear.material.shear_modulus * j
