"""Options of the loaded tooth contact stage (SI). In a gearbox file they are the
``[contact]`` table (read by :mod:`pipeline.config`); its keys, units in the names::

    [contact]
    compliance = "analytical"      # "analytical" (slices), "fe2d", "fe3d" (settings: [fe])
    positions = 60                 # mesh positions over one cycle
    slices = 30                    # slices across the face (helical, or lead-modified spur)
    local_contact = "weber"        # "weber" (Yang et al. 2026, eq. 24), "linear", "none"
    slice_coupling = 0.0           # kappa in [0, 0.25): 0 = independent slices (Yang et al. 2026)
    tip_relief_pinion_um = 0.0     # C_a at the pinion tip, along the line of action
    tip_relief_length_pinion_mm = 0.0   # roll length L_a of the pinion relief along the path
    tip_relief_gear_um = 0.0
    tip_relief_length_gear_mm = 0.0
    relief_shape = "linear"        # or "parabolic"
    crowning_um = 0.0              # lead crowning C_b (both gears together)
    slope_deviation_um = 0.0       # helix slope deviation / misalignment f_Hb over the face
    pitch_errors_um = []           # offsets of tooth pairs k = 0, 1, 2, ...
    load_map_profile_points = 80   # grid points along the path in the load map
    render = true                  # pyvista PNG of the load map

The tip relief, crowning and slope keys are the short form of each gear's modifications
(``[pinion.modifications]``, ``[gear.modifications]``, :mod:`pipeline.config.modifications`),
read into the same model. Friction, the foundation correction and the load come from the
``[stiffness]`` and ``[operation]`` tables, as for ``gearpipe stiffness``.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, field

from pipeline.contact.ltca import LOCAL_MODELS
from pipeline.contact.separations import FlankModifications
from pipeline.validation import PhysicsWarning, check_choice, check_int_range, check_range

COMPLIANCES = ("analytical", "fe2d", "fe3d")
"""Compliance sources of the loaded contact (:mod:`pipeline.contact.compliance`)."""
MAX_SLICES = 1000
"""Most slices across the face: the contact solve grows as slices^2.3 (a helical pair, one
position: 0.03 s at 100 slices, 2.5 s at 1000, 13 s at 2000; 10000 would take minutes)."""


@dataclass(frozen=True)
class ContactOptions:
    """Options of ``gearpipe contact`` (SI).

    Attributes
    ----------
    compliance : compliance source, "analytical", "fe2d" or "fe3d"
        (:mod:`pipeline.contact.compliance`).
    positions : mesh positions per cycle, 2 .. 10000.
    slices : slices across the face (1 .. :data:`MAX_SLICES`) of a helical pair, or of a spur
        pair with lead crowning or a helix slope deviation (:meth:`face_slices`).
    local_contact : "weber", "linear" or "none".
    slice_coupling : kappa in [0, 0.25).
    modifications : flank modifications and errors (m).
    load_map_profile_points : grid points along the path for the load map, 2 .. 2000.
    render : write the pyvista PNG of the load map.
    tip_contact : teeth may also touch beyond the path of contact, at a tip corner
        (:mod:`pipeline.geometry.tip_contact`); False confines contact to the nominal
        path (the slice method's assumption, and a control).
    """

    compliance: str = "analytical"
    positions: int = 60
    slices: int = 30
    local_contact: str = "weber"
    slice_coupling: float = 0.0
    modifications: FlankModifications = field(default_factory=FlankModifications)
    load_map_profile_points: int = 80
    render: bool = True
    tip_contact: bool = True

    def __post_init__(self) -> None:
        check_choice("contact.compliance", self.compliance, COMPLIANCES)
        check_int_range("contact.positions", self.positions, 2, 10_000)
        check_int_range("contact.slices", self.slices, 1, MAX_SLICES)
        check_choice("contact.local_contact", self.local_contact, LOCAL_MODELS)
        check_range("contact.slice_coupling", self.slice_coupling, 0.0, 0.25, hi_open=True)
        check_int_range("contact.load_map_profile_points", self.load_map_profile_points, 2,
                        2_000)
        if self.slices == 1 and self.modifications.varies_across_face:
            warnings.warn("contact.slices = 1 cannot resolve lead crowning or a helix slope "
                          "deviation across the face (the line load stays even, K_Hbeta = 1); "
                          "use 20 or more", PhysicsWarning, stacklevel=2)

    def face_slices(self, pair) -> int:
        """Slices across the face the contact solve of ``pair`` (a GearPair) uses.

        ``slices`` for a helical pair, and for a spur pair whose gap varies along the face
        (lead crowning, helix slope deviation); one slice for any other spur pair, whose line
        load is uniform over the face by construction (the same loads at 1/30 of the cost).
        """
        if pair.pinion.is_helical or self.modifications.varies_across_face:
            return self.slices
        return 1
