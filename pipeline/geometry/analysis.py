"""The geometry stage's entry point: a pair (and its assembly errors) -> its geometry."""

from __future__ import annotations

from dataclasses import dataclass

from pipeline.geometry.assembly_errors import AssembledPair, AssemblyErrors, assemble
from pipeline.geometry.pair import GearPair
from pipeline.geometry.profile import ToothProfile, tooth_profile


@dataclass(frozen=True)
class GeometryResult:
    """Geometry of a pair.

    Attributes
    ----------
    pair : the nominal pair (contact ratios, path of contact, radii).
    assembled : the pair with its centres displaced, or ``None`` without errors.
    profiles : exact tooth profiles (pinion, gear).
    """

    pair: GearPair
    assembled: AssembledPair | None
    profiles: tuple[ToothProfile, ToothProfile]

    def summary(self) -> dict:
        """Pair and gear quantities (SI; keys carry units)."""
        out = dict(self.pair.summary())
        for g, prof in zip((self.pair.pinion, self.pair.gear), self.profiles, strict=True):
            out[f"{g.name}_base_radius_m"] = g.base_radius
            out[f"{g.name}_tip_radius_m"] = g.tip_radius_
            out[f"{g.name}_root_radius_m"] = g.root_radius
            out[f"{g.name}_tip_thickness_m"] = g.tooth_thickness_tip
            out[f"{g.name}_form_radius_m"] = prof.form_radius
            out[f"{g.name}_undercut"] = bool(prof.undercut)
            out[f"{g.name}_thin_tip"] = bool(prof.thin_tip)
        if self.assembled is not None:
            out["assembly_errors"] = self.assembled.summary()
        return out


def analyse_geometry(pair: GearPair, assembly_errors: AssemblyErrors | None = None
                     ) -> GeometryResult:
    """Contact ratios, path of contact, exact tooth profiles and assembly-error geometry."""
    assembled = assemble(pair, assembly_errors)
    return GeometryResult(pair, assembled, (tooth_profile(pair.pinion),
                                            tooth_profile(pair.gear)))
