"""Exact involute gear geometry: gears, tooth profiles, pairs, contact paths, planetary sets.

All lengths in m, angles in rad.
"""

from pipeline.geometry.gear import GearSpec, Material
from pipeline.geometry.pair import GearPair
from pipeline.geometry.transverse import TransverseLayout

__all__ = ["GearSpec", "Material", "GearPair", "TransverseLayout"]
