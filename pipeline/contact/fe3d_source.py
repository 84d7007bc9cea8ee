"""3D FE influence coefficients of a helical pair as a compliance source for the contact solver.

:class:`FE3DCompliance` implements :class:`pipeline.contact.source.ComplianceSource`
from the 3D influence matrices of :func:`pipeline.fem.influence.influence_matrix`,
one per gear (an adapter of the FE stage to the contact solver's protocol), so the
loaded-contact solver (Yang et al. 2026, eqs. 27-29, local approach eq. 24) sees the face-width
coupling of the teeth that the slice method neglects. By default each gear is its whole
body (``FE3DSettings.body = "whole"``: all teeth, the body down to the clamped bore, the
full face; :mod:`pipeline.fem.whole3d`), as the 2D source's whole gears are; ``"sector"``
keeps the few-tooth sector clamped at its cut faces (an upper bound on stiffness).

Method
------
* Tables: one structural table per gear (:mod:`pipeline.contact.fe3d_table`); a whole
  gear's is solved for one loaded tooth and read on its neighbours (the gear is alike
  from every tooth), and a left-hand gear's is its right-hand mirror image's, so the two
  gears of a pair of equal gears share one solve.
* Candidate points are the slices of :func:`pipeline.contact.source.slice_points`
  (``settings.slices`` across the face; ``compliance_source`` gives a spur pair without lead
  modifications one), so results compare
  directly with :class:`~pipeline.contact.source.SliceCompliance` and
  :class:`~pipeline.contact.fe2d_source.FE2DCompliance`.
* Each candidate point stands for a uniform load on its piece of contact line
  (face width ``w``, roll coordinate ``s + (z' - z) tan(beta_b)``). That piece is
  sampled at ``m = max(1, ceil(2 w / dz))`` midpoints (``dz`` the table's face
  spacing; a spur pair's single slice gets ~2 samples per face interval), each
  sample mapped to the flank grid of each gear (below) and interpolated
  bilinearly in (arc coordinate, face position) with linear extrapolation beyond
  the grid (the tip and root ends of the path of contact, and the outer half-slices
  at the end faces). Averaging the ``m`` rows gives an interpolation matrix ``W``
  (n, N) per gear, and ``G_normal = W1 S1 W1^T + W2 S2 W2^T``: approach averaged over
  piece ``i`` per unit load spread over piece ``j`` (a Galerkin slice average,
  symmetric by construction). Points in *different* transverse sections are coupled.
* Normal to transverse: the solver's loads and approaches are along the transverse
  line of action (:mod:`pipeline.contact.source`); the flank normal leans out of the
  transverse plane by the base helix angle, so ``G = G_normal / cos^2(beta_b)``.
* The local Hertz approach is not included (the contact solver adds Yang et al. 2026, eq. 24).

Mapping (sign conventions)
--------------------------
* Teeth: as in :mod:`pipeline.contact.fe2d_source`, tooth pair ``k`` is pinion model tooth
  ``mid - k`` and gear model tooth ``mid + k`` (``mid = teeth // 2`` of each gear's model:
  its ``z`` for a whole gear), loads on the
  right flanks (the flank that faces clockwise seen from +z): the pinion turns
  clockwise and drives, the gear turns counter-clockwise.
* Profile: arc coordinate ``t = rho^2 / (2 r_b)`` with ``rho_1 = s`` on the pinion and
  ``rho_2 = T1T2 - s`` on the gear (:meth:`GearPair.contact_radii`).
* Face: turning a right flank clockwise moves its contact along the line of action
  towards the tip, and the 3D sector turns the section at ``z'`` by
  ``theta(z') = h tan(beta) / r (z' - b/2)`` (``h`` = +1 right hand, -1 left hand,
  :mod:`pipeline.fem.sector3d`). So on the right flank a contact line (fixed plane of
  action) has ``d rho / d z' = -h tan(beta_b)``. The pair's convention is
  ``s = s0 + k p_bt + z tan(beta_b)`` (``d rho_1 / dz = +tan(beta_b)``, and
  ``d rho_2 / dz = -tan(beta_b)``), hence ``z' = z`` for a left-hand pinion (right-hand
  gear) and ``z' = b - z`` for a right-hand pinion (left-hand gear): the same flip for
  both gears, i.e. both sectors share one axis direction, as two parallel gears in
  mesh do. Spur gears use ``z' = z``. (The tests check the sign with the flank grid:
  points on such a line project onto one transverse line and share one transverse
  normal.) Gears of different width are centred on each other (``z'`` shifted by
  half the difference).

Verification and what remains
-----------------------------
tests/test_fem_whole3d.py climbs the ladder against the 2D whole gear of
:mod:`pipeline.fem.sector2d` (same bore clamp): a spur gear with sliding end faces is
plane strain (3D / 2D 0.99 for the rim coupling and 0.96 for the loaded tooth at
refinement 0.6, converging with refinement), a thin one with free faces plane stress
(0.996-0.997 at b = m_n / 3). On the pair of Yang et al. (2026)
(workflows/fe3d_helical_stiffness.py, refinement 0.6, 87k / 188k DOF) the whole-gear 3D
LTCA mesh stiffness is 10.5 % below the slice method's, +0.4 % above the 2D plane-strain
whole gears and 5.7 % above the 2D plane-stress ones (-10.9 % and -15.3 % vs slice). The
130 mm face is 17.7 m_n wide, so most of it is in plane strain; what is left between 3D
and 2D plane strain is a balance of (i) the coarse 3D mesh, a few % stiffer (the spur
ladder above), (ii) the free end faces, softer where a contact line reaches them, and
(iii) the face coupling of the helical contact lines, which the 2D slices lack; none of
them exceeds a few %. The 10 % to the slice method is the body: the whole-gear FE (2D
and 3D) couples the two or three tooth pairs in contact through the rim and web
(:mod:`pipeline.contact.fe2d_source`), which the slice method's Sainsot foundation term,
per pair, does not. The 3-tooth sectors of ``body = "sector"`` came out 38 % stiffer than the slice
method on the same pair, because of their clamped cuts.

Cost: ``workflows/benchmarks/bench_fe3d.py`` prints the breakdown, side by side with a
baseline revision. Convergence: ``workflows/fe3d_convergence.py`` (the refinement study
of the mesh stiffness and TE p-p, the graded mesh against every tooth fine).

Limits
------
* External pairs only (no internal 3D gears), no herringbone (analyse one helical half,
  as the other sources); the loaded flanks are all right flanks, which by the 180 deg
  turn about a radial axis covers the opposite rotation as well.
* A gear is clamped at its bore (or at ``r_f - hub_depth m_n`` if ``hub_depth`` is
  given); a sector also at its radial cuts (``cuts``): stiffer than a whole gear body.
  workflows/validate_stiffness.py found a clamped 5-tooth 2D sector +55 % stiffer than
  the slice model on the assembly-error study; here (tests, z 30 helical pair) the
  3-tooth sector gave a 22 % higher LTCA mesh stiffness than the slice method, the
  whole gears 3 % lower.
* Friction is not in the FE loads; wrap the source in
  :class:`~pipeline.contact.source.FrictionCorrected` to add the slice model's
  friction effect.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, field

import numpy as np

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.contact.fe3d_table import FlankTable3D, flank_table
from pipeline.contact.source import ContactPoints, candidate_range, slice_points
from pipeline.fem.loft3d import helix_sign
from pipeline.fem.settings import FE3DSettings
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at
from pipeline.validation import InputError


def touching_pairs(pair: GearPair, tip_contact: bool = True) -> np.ndarray:
    """Tooth-pair indices ``k`` that can touch somewhere on the face at some mesh position.

    Pair ``k`` touches at ``s_start + u + k p_bt + z tan(beta_b)`` for ``u`` in
    ``[0, p_bt)``, ``z`` in ``[0, b]``; it can touch when that reaches the candidate range
    (:func:`pipeline.contact.source.candidate_range`: the path of contact, with
    ``tip_contact`` widened by the tip zones).
    """
    k = pair.pair_indices(tip_contact)
    lo, hi = candidate_range(pair, tip_contact)
    reach = pair.face_width * math.tan(pair.pinion.base_helix_angle)
    p = pair.base_pitch
    keep = (pair.s_start + k * p <= hi) & (pair.s_start + (k + 1) * p + reach > lo)
    return k[keep]


@dataclass(frozen=True)
class FE3DCompliance:
    """3D FE-enriched compliance source (module docstring); build with :meth:`build`.

    Attributes
    ----------
    pair : the gear pair (external, not herringbone).
    settings : FE settings.
    pinion_table, gear_table : structural tables of both gears (m/N).
    tip_contact : candidate points (and tabulated teeth) beyond the path of contact too
        (:func:`pipeline.contact.source.candidate_range`).
    """

    pair: GearPair
    settings: FE3DSettings = field(default_factory=FE3DSettings)
    pinion_table: FlankTable3D | None = None
    gear_table: FlankTable3D | None = None
    tip_contact: bool = True

    @classmethod
    def build(cls, pair: GearPair, settings: FE3DSettings | None = None, *,
              cache: Cache = DEFAULT_CACHE, show_progress: bool = False,
              tip_contact: bool = True) -> FE3DCompliance:
        """Mesh and solve (or read from ``cache``) both gears' tables, once.

        ``show_progress`` reports every step longer than a second (mesh, assembly,
        factorisation, solves) on stderr; the tables' ``info["timings_s"]`` keep the
        breakdown (:meth:`summary`).
        """
        settings = settings or FE3DSettings()
        if pair.pinion.herringbone or pair.gear.herringbone:
            raise InputError("fe3d source: analyse one helical half of a herringbone pair")
        cls.check_pair(pair, settings, tip_contact=tip_contact)
        k = touching_pairs(pair, tip_contact)
        teeth = cls._model_teeth(pair, settings, tip_contact)
        tables = [flank_table(g, n, np.sort(n // 2 + sign * k), settings, cache,
                              show_progress)
                  for g, n, sign in ((pair.pinion, teeth[0], -1), (pair.gear, teeth[1], 1))]
        return cls(pair, settings, *tables, tip_contact)

    @classmethod
    def check_pair(cls, pair: GearPair, settings: FE3DSettings, mesh: str = "",
                   tip_contact: bool = True) -> None:
        """Refuse a pair the 3D models cannot hold (an internal gear; a sector with fewer
        teeth than the tooth pairs in contact need), before any meshing; ``mesh`` names the
        mesh in the message."""
        of = f" of the {mesh} mesh" if mesh else ""
        if pair.gear.internal:
            raise InputError(f'contact.compliance = "fe3d": the 3D models are of external gears '
                             f"only; the {pair.gear.name}{of} is internal: use \"fe2d\"")
        k = touching_pairs(pair, tip_contact)
        teeth = cls._model_teeth(pair, settings, tip_contact)
        if settings.body == "sector" and (np.abs(k).max() > teeth[0] // 2
                                          or teeth[0] - 1 - teeth[0] // 2 < np.abs(k).max()):
            need = 2 * int(np.abs(k).max()) + 1
            raise InputError(
                f"fe.teeth = {settings.teeth} is outside the allowed range [{need}, 99]: the "
                f"sector must hold the tooth pairs {k.min()}..{k.max()} in contact{of}",
                field="fe.teeth", value=settings.teeth, bounds=(need, 99, False, False),
                note=f"the tooth pairs in contact{of}")

    @staticmethod
    def _model_teeth(pair: GearPair, settings: FE3DSettings, tip_contact: bool = True
                     ) -> tuple[int, int]:
        """Teeth of the pinion's and the gear's 3D models."""
        if settings.body == "whole":
            return pair.pinion.teeth, pair.gear.teeth
        n = (settings.teeth if settings.teeth is not None
             else 2 * int(np.abs(touching_pairs(pair, tip_contact)).max()) + 1)
        return n, n

    @property
    def model_teeth(self) -> tuple[int, int]:
        """Teeth of the pinion's and the gear's 3D models (z1, z2 for whole gears)."""
        return self._model_teeth(self.pair, self.settings, self.tip_contact)

    def points(self, position: float) -> ContactPoints:
        """Slice contact points of all tooth pairs in contact, ordered by pair, then by z."""
        return slice_points(self.pair, self.settings.slices, position, self.tip_contact)

    def weights(self, position: float) -> tuple[np.ndarray, np.ndarray]:
        """Interpolation matrices ``(W1, W2)``, (n, N1) and (n, N2), of the candidate points
        on the pinion and gear tables (slice averages, module docstring)."""
        return self._weights(self.points(position))

    def _samples(self, pts: ContactPoints) -> int:
        """Samples per slice: ~2 per face interval of the finer table (module docstring)."""
        dz = min(np.diff(t.z).min() if t.z.size > 1 else self.pair.face_width
                 for t in (self.pinion_table, self.gear_table))
        return int(max(1, math.ceil(2 * pts.width.max() / dz))) if len(pts) else 1

    def flank_coordinates(self, pts: ContactPoints, samples: int = 1
                          ) -> tuple[tuple[np.ndarray, np.ndarray, np.ndarray], ...]:
        """Where contact points lie on each gear's sector: ``((tooth, arc, z'), (tooth, arc, z'))``
        for the pinion and the gear, each array (n, samples): sector tooth index, arc
        coordinate (m) and sector face position (m) of ``samples`` midpoints across each
        point's slice (``samples = 1``: the points themselves). Mapping: module docstring."""
        pair = self.pair
        tb = math.tan(pair.pinion.base_helix_angle)
        u = (np.arange(samples) + 0.5) / samples - 0.5  # offsets, fractions of the width
        z = pts.z[:, None] + pts.width[:, None] * u[None, :]
        r1, r2 = contact_radii_at(pair, pts.s[:, None] + (z - pts.z[:, None]) * tb)
        mid1, mid2 = (n // 2 for n in self.model_teeth)
        b = pair.face_width
        out = []
        # z' = b - z for a right-hand pinion / left-hand gear (module docstring)
        flips = (helix_sign(pair.pinion) > 0, helix_sign(pair.gear) < 0)
        for table, gear, r, tooth, flip in (
                (self.pinion_table, pair.pinion, r1, mid1 - pts.pair, flips[0]),
                (self.gear_table, pair.gear, r2, mid2 + pts.pair, flips[1])):
            zs = (b - z if flip else z) + 0.5 * (table.width - b)
            arc = (r**2 - gear.base_radius**2) / (2 * gear.base_radius)
            out.append((np.repeat(tooth[:, None], samples, axis=1), arc, zs))
        return out[0], out[1]

    def _weights(self, pts: ContactPoints) -> tuple[np.ndarray, np.ndarray]:
        m = self._samples(pts)
        out = []
        for table, (tooth, arc, zs) in zip((self.pinion_table, self.gear_table),
                                           self.flank_coordinates(pts, m), strict=True):
            W = table.weights(tooth.ravel(), arc.ravel(), zs.ravel())
            out.append(W.reshape(len(pts), m, -1).mean(axis=1))
        return out[0], out[1]

    def matrix(self, position: float) -> np.ndarray:
        """``G`` (m/N), (n, n): pinion + gear structural compliance along the transverse
        line of action, all points coupled (module docstring)."""
        pts = self.points(position)
        if len(pts) == 0:
            return np.zeros((0, 0))
        W1, W2 = self._weights(pts)
        G = W1 @ self.pinion_table.structural @ W1.T + W2 @ self.gear_table.structural @ W2.T
        G = 0.5 * (G + G.T)
        return G / math.cos(self.pair.pinion.base_helix_angle) ** 2

    def summary(self) -> dict:
        """Model teeth, settings and the FE figures of both tables (DOFs, solver, timing
        breakdown in s, cache use)."""
        return {"body": self.settings.body, "model_teeth": self.model_teeth,
                "tooth_pairs": touching_pairs(self.pair, self.tip_contact),
                "settings": asdict(self.settings),
                "pinion": {"teeth": self.pinion_table.teeth, **self.pinion_table.info},
                "gear": {"teeth": self.gear_table.teeth, **self.gear_table.info}}
