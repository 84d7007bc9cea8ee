"""Flank modifications of each gear of a mesh and the gap they open.

- :mod:`.shapes` - the closed-form shapes (relief linear / parabolic / arc, crowning, slope);
- :mod:`.frame` - a gear's roll length, diameter and face position at a contact point;
- :mod:`.profile` - tip and root relief, profile crowning, profile slope;
- :mod:`.lead` - lead crowning, end relief at each face, helix slope;
- :mod:`.topography` - a deviation grid over face x profile (bilinear);
- :mod:`.gear` - one gear's modifications and the twist;
- :mod:`.gap` - both gears' sum at the contact points, and each flank's map.
"""

from pipeline.contact.modifications.frame import FlankFrame, flank_frames
from pipeline.contact.modifications.gap import (
    ModificationMap,
    modification_gap,
    modification_maps,
)
from pipeline.contact.modifications.gear import GearModification
from pipeline.contact.modifications.lead import LeadModification
from pipeline.contact.modifications.profile import ProfileModification
from pipeline.contact.modifications.topography import Topography

__all__ = ["FlankFrame", "GearModification", "LeadModification", "ModificationMap",
           "ProfileModification", "Topography", "flank_frames", "modification_gap",
           "modification_maps"]
