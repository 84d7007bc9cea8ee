"""2D FE influence coefficients as a compliance source for the loaded-contact solver.

:class:`FE2DCompliance` adapts the FE stage to the contact solver's protocol
(:class:`pipeline.contact.source.ComplianceSource`) from 2D sector influence matrices
(:func:`pipeline.fem.influence.influence_matrix`) of both gears:

* For each gear one structural influence matrix is computed once, on ``radii``
  points of the right flank of every tooth of a ``teeth``-tooth sector (one
  factorisation per gear). At any mesh position the compliance between candidate
  points is interpolated (linearly in the arc coordinate, per pair of teeth) from
  those tables and summed over the two gears; contact radii outside the tabulated
  range (the last ``0.15 m_n`` of arc below the tips) are extrapolated linearly.
* Candidate points are the slices of :class:`pipeline.contact.source.SliceCompliance`
  (one per tooth pair for spur gears). Two points are coupled when they lie in the
  same transverse section (same ``z``): the 2D model couples the tooth pairs in
  contact through the rims; different sections are independent, as in Yang et al. (2026)'s
  slice method. Per slice of width ``w`` the 2D per-unit-width compliance is
  divided by ``w`` (m/N).
* Tooth mapping (sign convention): tooth pair ``k`` (:meth:`GearPair.pair_indices`)
  is pinion sector tooth ``mid - k`` and gear sector tooth ``mid + k``, with
  ``mid = teeth // 2`` (per gear); loads on the right flanks. This is the mirror image of a
  counter-clockwise driving pinion; the mirror leaves every compliance unchanged.
* The local Hertz approach is not included (the contact solver adds Yang et al. 2026, eq. 24).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from pipeline.contact._interpolation import linear_weights
from pipeline.contact.source import ContactPoints, slice_points
from pipeline.fem.flank import active_radii, flank_points
from pipeline.fem.influence import InfluenceMatrix, influence_matrix
from pipeline.fem.sector2d import SectorSettings2D, sector_mesh_2d
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError, check_int_range, check_range


@dataclass(frozen=True)
class FE2DSettings:
    """Settings of the FE compliance tables.

    Attributes
    ----------
    teeth : teeth per sector (>= 3, covering the tooth pairs in contact), or None for the
        whole gear (default: a sector with clamped cut faces is too stiff for deep gear
        bodies - the assembly-error paper's gear: -42 % with 7 teeth, -4 % as a whole gear, vs the
        analytical compliance; see :mod:`pipeline.fem.influence`).
    radii : tabulated points per flank.
    refinement : mesh refinement (:meth:`SectorSettings2D.for_gear`).
    kind : "plane_strain" or "plane_stress".
    slices : slices across the face width for helical pairs (spur: 1).
    cuts : "clamped" or "free" sector cut faces.
    """

    teeth: int | None = None
    radii: int = 30
    refinement: float = 1.0
    kind: str = "plane_strain"
    slices: int = 30
    cuts: str = "clamped"

    def __post_init__(self) -> None:
        if self.teeth is not None:
            check_int_range("fe.teeth", self.teeth, 3, 99)
        check_int_range("fe.radii", self.radii, 4, 1000)
        check_range("fe.refinement", self.refinement, 0.1, 20.0)
        check_int_range("fe.slices", self.slices, 1, 10_000)


def _teeth(gear: GearSpec, settings: FE2DSettings) -> int:
    return gear.teeth if settings.teeth is None else settings.teeth


def gear_table(gear: GearSpec, settings: FE2DSettings, teeth: np.ndarray) -> InfluenceMatrix:
    """Influence matrix of ``settings.radii`` right-flank points on the sector teeth ``teeth``
    (consecutive indices, ascending)."""
    n = _teeth(gear, settings)
    sec = sector_mesh_2d(gear, SectorSettings2D.for_gear(gear, n, settings.refinement))
    from pipeline.geometry.profile import tooth_profile

    # tabulate as close to both ends of the involute as the load patch (0.1 m_n) allows
    form = tooth_profile(gear).form_radius
    if gear.internal:
        r = active_radii(gear, settings.radii, hi=min(form, gear.root_radius),
                         margin=0.11 * gear.module)
    else:
        r = active_radii(gear, settings.radii, lo=max(form, gear.base_radius),
                         margin=0.11 * gear.module)
    pts = flank_points(gear, n, np.repeat(teeth, r.size), np.tile(r, teeth.size))
    return influence_matrix(sec, pts, kind=settings.kind, cuts=settings.cuts)


def _interp_block(table: InfluenceMatrix, n_r: int, ti: np.ndarray, ai: np.ndarray,
                  tj: np.ndarray, aj: np.ndarray) -> np.ndarray:
    """Bilinear interpolation (linear extrapolation) of the structural table, m^2/N."""
    S = table.structural
    arc = table.points.arc[:n_r]
    ki, wi = linear_weights(arc, ai)
    kj, wj = linear_weights(arc, aj)
    oi, oj = ti * n_r + ki, tj * n_r + kj
    return ((1 - wi) * (1 - wj) * S[oi, oj] + wi * (1 - wj) * S[oi + 1, oj]
            + (1 - wi) * wj * S[oi, oj + 1] + wi * wj * S[oi + 1, oj + 1])


@dataclass(frozen=True)
class FE2DCompliance:
    """FE-enriched compliance source (module docstring); build with :meth:`build`.

    Attributes
    ----------
    pair : the gear pair.
    settings : FE settings.
    pinion_table, gear_table : influence matrices of both gears (per unit width).
    """

    pair: GearPair
    settings: FE2DSettings = field(default_factory=FE2DSettings)
    pinion_table: InfluenceMatrix | None = None
    gear_table: InfluenceMatrix | None = None

    @classmethod
    def build(cls, pair: GearPair, settings: FE2DSettings | None = None) -> FE2DCompliance:
        """Mesh and solve both sectors (one factorisation each)."""
        settings = settings or FE2DSettings()
        if pair.pinion.herringbone:
            raise InputError("fe source: analyse one helical half of a herringbone pair")
        k = pair.pair_indices()
        mid = min(_teeth(pair.pinion, settings), _teeth(pair.gear, settings)) // 2
        if np.abs(k).max() > mid:
            raise InputError(f"fe.teeth = {settings.teeth} does not cover tooth pairs "
                             f"{k.min()}..{k.max()}: use at least {2 * np.abs(k).max() + 1}")
        m1 = _teeth(pair.pinion, settings) // 2
        m2 = _teeth(pair.gear, settings) // 2
        return cls(pair, settings, gear_table(pair.pinion, settings, np.sort(m1 - k)),
                   gear_table(pair.gear, settings, np.sort(m2 + k)))

    def points(self, position: float) -> ContactPoints:
        """Slice contact points of all tooth pairs in contact, ordered by pair, then by z."""
        return slice_points(self.pair, self.settings.slices, position)

    def matrix(self, position: float) -> np.ndarray:
        """``G`` (m/N), (n, n): pinion + gear structural compliance, same-section coupling."""
        pts = self.points(position)
        r1, r2 = self.pair.contact_radii(pts.s)
        n_r = self.settings.radii
        out = np.zeros((len(pts), len(pts)))
        same = np.isclose(pts.z[:, None], pts.z[None, :], rtol=0, atol=1e-12)
        i, j = np.nonzero(same)
        m1 = _teeth(self.pair.pinion, self.settings) // 2
        m2 = _teeth(self.pair.gear, self.settings) // 2
        for table, r, tooth, rb in ((self.pinion_table, r1, m1 - pts.pair,
                                     self.pair.pinion.base_radius),
                                    (self.gear_table, r2, m2 + pts.pair,
                                     self.pair.gear.base_radius)):
            arc = (np.asarray(r) ** 2 - rb**2) / (2 * rb)
            tooth = tooth - table.points.tooth[0]  # block index in the table
            out[i, j] += _interp_block(table, n_r, tooth[i], arc[i], tooth[j], arc[j])
        return out / pts.width[:, None]
