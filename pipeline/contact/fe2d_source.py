"""2D FE influence coefficients as a compliance source for the loaded-contact solver.

:class:`FE2DCompliance` adapts the FE stage to the contact solver's protocol
(:class:`pipeline.contact.source.ComplianceSource`) from 2D influence matrices
(:func:`pipeline.fem.influence.influence_matrix`) of both gears:

* For each gear one structural influence matrix is computed once, on ``radii``
  points of the right flank of every tooth that a tooth pair in contact reaches (one
  factorisation per gear, all right-hand sides together; :mod:`.fe2d_table`, cached on
  disk by content hash). At any mesh position the compliance between candidate
  points is interpolated (linearly in the arc coordinate, per pair of teeth) from
  those tables and summed over the two gears; contact radii outside the tabulated
  range (the last ``1.1 c`` of arc below the tips, ``c = settings.patch`` m_n, 0.33 mm
  for the demo pair) are extrapolated linearly, among them a tip corner touching beyond
  the path of contact, which loads its tooth at the tip radius (against CalculiX the
  loaded TE there agrees within 0.2 %, ``workflows/reference/calculix_spur_contact.py``).
  A grid reaching 2 and 4 times closer to the tip (``patch`` 0.05 and 0.025 m_n at
  refinement 2 and 4) raises the extrapolated structural compliance at the corner by 1.0
  and 2.4 % (its couplings to other points by 0.1 %) and moves the loaded TE by at most
  0.2 and 0.42 % (``tests/test_reference_calculix.py``). The tip itself is no grid point:
  a patch centred there would cross the corner, where the half-plane near field that the
  structural part is defined against does not hold.
* Candidate points are the slices of :class:`pipeline.contact.source.SliceCompliance`
  (``settings.slices`` across the face; one per tooth pair for a spur pair without lead
  modifications when built by ``compliance_source``). Two points are coupled when they lie in the
  same transverse section (same ``z``): the 2D model couples the tooth pairs in
  contact through the rims; different sections are independent, as in Yang et al. (2026)'s
  slice method. Per slice of width ``w`` the 2D per-unit-width compliance is
  divided by ``w`` (m/N).
* Tooth mapping (sign convention): tooth pair ``k`` (:meth:`GearPair.pair_indices`)
  is pinion sector tooth ``mid - k`` and gear sector tooth ``mid + k``, with
  ``mid = teeth // 2`` (per gear); loads on the right flanks. This is the mirror image of a
  counter-clockwise driving pinion; the mirror leaves every compliance unchanged. An
  internal gear (ring) turns with the pinion, so physically its pair ``k`` is tooth
  ``mid - k`` loaded on the left flank; mirrored, that is the same rule (right flanks,
  ``mid + k``). The ring body is the rim between the root circle and
  ``rim_outer_radius`` (``gear.bore_radius``), clamped on the rim circle.
* The local Hertz approach is not included (the contact solver adds Yang et al. 2026, eq. 24).

Graded meshes (the default, ``mesh = "graded"``). Whole gears (``teeth = None``) are
meshed fine only on the outline of the teeth whose flanks are tabulated (flank and
fillet elements ``m_n / (12 refinement)``), ``0.6 m_n`` on the outline of the other
teeth, and the element size grows by half the distance from the outline up to
``4 m_n`` in the body (:meth:`pipeline.fem.mesh_settings.SectorSettings.graded`). The
unloaded teeth stay in the model (they stiffen the rim), coarsely meshed.

Convergence (the assembly-error paper's pair, z 50/50, m 3 mm, 21 mm bores, plane strain,
30 radii, 60 positions, Weber local contact; ``workflows/benchmarks/bench_fe_enriched.py
--convergence``). The uniform whole-gear model (``mesh = "uniform"``, every tooth at the
flank size) at refinement 0.5 / 0.7 / 1 / 1.4 / 2 (97k / 144k / 221k / 334k / 526k
unknowns per gear) gives mean mesh stiffness 282.39 / 281.39 / 280.91 / 280.72 / 280.63
N/um, min 230.79 / 229.73 / 229.27 / 229.06 / 228.97, max 300.28 / 299.34 / 298.93 /
298.78 / 298.70; ``k_inf + C h^p`` through the three finest levels extrapolates to mean
280.56 (p = 2.25), min 228.87 (p = 1.98), max 298.63 N/um (p = 2.18); refinement 1 is
+0.13 / +0.18 / +0.10 % from these. The graded default (refinement 1, 20k unknowns per
gear) is +0.28 / +0.34 / +0.24 % (mean / min / max), within the 1 % it promises; refining
the graded family (refinement 2, tooth 0.2 m_n, body 2 m_n, growth 0.2: 85k unknowns)
gives +0.04 %, so both families converge to the same limit. Coarse far fields cost
little: 1 m_n on the unloaded teeth, 6 m_n body, growth 0.6 (12.6k unknowns) is still
+0.56 %. FE models are stiffer than the limit at every level (displacement elements).
Tests:
``tests/test_fem_fe2d_source.py`` (graded vs uniform on a coarse case; slow: the default
against the uniform refinement 2 on a z 24/36 pair, 1 %).

Cost (same pair, 60 positions, ``bench_fe_enriched.py`` on the shared 2-core machine, best
of 3, 2026-11-27; the pair's gears are equal, so one table is solved and the other read
back, :mod:`.fe2d_table`): cold 2.25 s in the process (imports 0.64, meshing 0.52,
assembly 0.10, factorisation 0.17, solves 0.20, near field 0.06, contact cycle 0.47 s;
2.7 s with the interpreter's start), peak RSS 0.17 GiB, against 11.2 s and 0.53 GiB for
the uniform model at refinement 1; warm: tables read in 0.03 s, contact cycle 0.54 s.
(Before the equal gears shared their table: cold 4.0 s, 43.8 s for the uniform model, on
a more loaded day.)

Against the analytical mesh stiffness (``workflows/validate_stiffness.py``, whose docstring
gives the numbers for the assembly-error paper's spur pair: single contact within 2 %,
double contact 30 % softer in FE because the two pairs in contact share the body's
deformation). Helical pair of Yang et al. (2026): FE-enriched mean 20 % below analytical
(max -21 %, min -19.5 %), nearly constant over the cycle. Its transverse contact ratio is
2.05, so every transverse section always has two or three pairs in contact, and their
coupling through the gear body (30 % of the single-pair compliance; 40 % of that is torsion
of the ring between bore and root) acts at every position; without it FE and analytical
agree within 1 %. Planet-ring pairs (``workflows/configs/planet_ring_pair.toml``):
FE-enriched mean 23 % below analytical (max -24 %, min -7 %) and 11 % below the optimised
slice curve; single contact is 7 % stiffer in FE, double contact softer because the two
pairs share the planet body's torsion (coupling 36 % of the planet's single-tooth
compliance, 10 % for the ring rim); the rest of the gap to the analytical curve is its
local contact term (constant Hertz vs Yang et al. 2026, eq. 24: -13.5 %), as for external
pairs (``tests/test_fem_fe2d_ring.py``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.contact._interpolation import linear_weights
from pipeline.contact.fe2d_table import gear_table, sector_teeth, table_jobs
from pipeline.contact.source import ContactPoints, slice_points
from pipeline.fem.influence import InfluenceMatrix
from pipeline.fem.settings import FE2DSettings
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at
from pipeline.progress import progress


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
    info : how the tables were obtained: per gear (``"pinion"``, ``"gear"``) ``cached``,
        ``seconds`` (wall time), ``dof``, ``free_dof``, ``solver`` and ``timings`` (s:
        mesh, assembly, loads, factor, solve, nearfield, total, of the build that made the
        table); ``seconds`` of the whole build.
    tip_contact : candidate points (and tabulated teeth) beyond the path of contact too
        (:func:`pipeline.contact.source.candidate_range`).
    """

    pair: GearPair
    settings: FE2DSettings = field(default_factory=FE2DSettings)
    pinion_table: InfluenceMatrix | None = None
    gear_table: InfluenceMatrix | None = None
    info: dict = field(default_factory=dict, compare=False)
    tip_contact: bool = True

    @classmethod
    def build(cls, pair: GearPair, settings: FE2DSettings | None = None, *,
              cache: Cache = DEFAULT_CACHE, show_progress: bool = False,
              tip_contact: bool = True) -> FE2DCompliance:
        """Tables of both gears from the cache, or meshed and solved (one factorisation
        each), read from and written to ``cache``; the teeth of every tooth pair that can
        touch (:meth:`GearPair.pair_indices` with ``beyond = tip_contact``)."""
        t0 = time.perf_counter()
        settings = settings or FE2DSettings()
        tables, info = {}, {}
        for name, gear, teeth in progress(table_jobs(pair, settings, tip_contact),
                                          "2D FE tables", enabled=show_progress):
            tables[name], info[name] = gear_table(gear, settings, teeth, cache=cache)
            info[name]["timings"] = dict(tables[name].timings)
        info["seconds"] = time.perf_counter() - t0
        return cls(pair, settings, tables["pinion"], tables["gear"], info, tip_contact)

    def points(self, position: float) -> ContactPoints:
        """Slice contact points of all tooth pairs in contact, ordered by pair, then by z."""
        return slice_points(self.pair, self.settings.slices, position, self.tip_contact)

    def matrix(self, position: float) -> np.ndarray:
        """``G`` (m/N), (n, n): pinion + gear structural compliance, same-section coupling."""
        pts = self.points(position)
        r1, r2 = contact_radii_at(self.pair, pts.s)
        n_r = self.settings.points
        out = np.zeros((len(pts), len(pts)))
        same = np.isclose(pts.z[:, None], pts.z[None, :], rtol=0, atol=1e-12)
        i, j = np.nonzero(same)
        m1 = sector_teeth(self.pair.pinion, self.settings) // 2
        m2 = sector_teeth(self.pair.gear, self.settings) // 2
        for table, r, tooth, rb in ((self.pinion_table, r1, m1 - pts.pair,
                                     self.pair.pinion.base_radius),
                                    (self.gear_table, r2, m2 + pts.pair,
                                     self.pair.gear.base_radius)):
            arc = (np.asarray(r) ** 2 - rb**2) / (2 * rb)
            tooth = tooth - table.points.tooth[0]  # block index in the table
            out[i, j] += _interp_block(table, n_r, tooth[i], arc[i], tooth[j], arc[j])
        return out / pts.width[:, None]
