"""3D FE influence coefficients of a helical pair as a compliance source for the contact solver.

:class:`FE3DCompliance` implements :class:`pipeline.contact.source.ComplianceSource`
from the 3D sector influence matrices of :mod:`pipeline.fem.influence3d`, one per
gear, so the loaded-contact solver (Yang et al. 2026, eqs. 27-29, local approach eq. 24)
sees the face-width coupling of the teeth that the slice method neglects.

Method
------
* Tables. For each gear one structural influence matrix ``S`` (m/N: normal approach
  per unit normal load, FE minus the Boussinesq near field) is computed once, on a
  grid of ``radii x face`` points on the right flank of every sector tooth that a
  tooth pair in contact can reach over a mesh cycle (one solver set-up per gear).
  Profile points are equally spaced in the arc coordinate of the involute between the
  form (or base) circle and the tip, ``c`` of arc inside both ends (``c`` the load
  patch half-width: the patch reaches the tip corner but does not cross it); face
  points from ``face_margin c`` to ``b - face_margin c``, about ``c`` apart.
  ``S`` is symmetrised (it is symmetric to solver accuracy) and projected onto the
  positive semidefinite matrices (negative eigenvalues, discretisation error of
  ~0.2-2 % of the largest, set to zero: the contact solver needs a semidefinite
  ``G``; the change is recorded in the table's ``info``). Tables are cached on
  disk by a content hash of the gear, mesh settings, grid and boundary conditions
  (``meshes/fe3dtable-<hash>.npz``, written atomically), like the meshes themselves.
* Candidate points are the slices of :func:`pipeline.contact.source.slice_points`
  (``slices`` across a helical face, one slice for spur gears), so results compare
  directly with :class:`~pipeline.contact.source.SliceCompliance` and
  :class:`~pipeline.fem.fe_source.FESectorCompliance`.
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
* Teeth: as in :mod:`pipeline.fem.fe_source`, tooth pair ``k`` is pinion sector tooth
  ``mid - k`` and gear sector tooth ``mid + k`` (``mid = teeth // 2``), loads on the
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

Limits
------
* External pairs only (the 3D sector has no internal gears), no herringbone (analyse
  one helical half, as the other sources); the loaded flanks are all right flanks,
  which by the 180 deg turn about a radial axis covers the opposite rotation as well.
* The sector is clamped at its bore (or at ``r_f - hub_depth m_n`` if ``hub_depth``
  is given) and, by default, at its radial cuts: stiffer than a whole gear body, so
  the body/foundation part of the compliance is low; the tooth part is what the 3D
  model adds. workflows/validate_stiffness.py found a clamped 5-tooth 2D sector +55 %
  stiffer than the slice model on the assembly-error paper's pair; here (tests, z 30 helical pair)
  the default 3-tooth sector gave a 16 % higher LTCA mesh stiffness than a 5-tooth one.
  Use ``teeth`` = 2 max|k| + 3 or more where the budget allows.
* Discretisation: the default 3D meshes are coarse (flank elements ``m_n / (3
  refinement)``); a displacement FE model is stiffer than the real tooth (a few %
  for line loads, ~10 % for a concentrated patch at refinement 1, see
  :mod:`pipeline.fem.influence3d`), and ``S`` is positive definite only up to that
  error, hence the projection above.
* Friction is not in the FE loads; wrap the source in
  :class:`~pipeline.contact.source.FrictionCorrected` to add the slice model's
  friction effect.
"""

from __future__ import annotations

import math
import time
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path

import numpy as np

from pipeline.contact.source import ContactPoints, slice_points
from pipeline.fem.cache import cached_file, load_arrays, save_arrays
from pipeline.fem.fe_source import linear_weights
from pipeline.fem.flank import active_radii
from pipeline.fem.flank3d import face_positions, flank_grid
from pipeline.fem.influence3d import CUTS, ENDS, SOLVERS, influence_matrix_3d
from pipeline.fem.sector2d import SectorMeshSettings, inner_radius
from pipeline.fem.sector3d import (
    GEOMETRY_VERSION,
    Sector3DSettings,
    helix_sign,
    sector3d_mesh,
)
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.validation import InputError, check_choice, check_int_range, check_range

# Bump when the same inputs would give a different table.
TABLE_FORMAT = 2  # 2: tables on sector3d_mesh's own meshes (no cleaned-outline copy)
_STORED = ("structural", "dof", "free_dof", "solver", "seconds")  # arrays in the cache file


@dataclass(frozen=True)
class FE3DSettings:
    """Settings of the 3D FE compliance tables.

    Attributes
    ----------
    teeth : teeth per sector (3..99, odd values centre the loaded teeth), or None for
        the fewest that hold the tooth pairs in contact (``2 max|k| + 1``).
    radii : flank grid points along the profile (2..200).
    face : flank grid points across the face width (1..200), or None for a spacing of
        about one patch half-width (the structural kernel then varies little between
        nodes; coarser face grids blur its peak at the diagonal).
    refinement : mesh refinement (:meth:`Sector3DSettings.for_gear`), 0.2..4.
    patch : load patch half-width c in normal modules (0.1..2). Default 0.5, wider than
        :mod:`pipeline.fem.influence3d`'s 0.3: the near-field subtraction needs the patch
        resolved by the mesh (0.3 m_n needs refinement 2), and the structural part does
        not depend on c once it is. At refinement 0.6 and c = 0.3 m_n (less than one
        flank element) the structural diagonal fell below its neighbours (table
        eigenvalues down to -16 % of the largest); at c = 0.5-0.6 m_n: -0.2 to -0.4 %.
    face_margin : distance of the outer face grid points from the end faces, in
        patch half-widths (0..10; 1 keeps every patch whole on the flank).
    cuts : "clamped" or "free" sector cut faces.
    ends : "free" or "sliding" (u_z = 0) end faces.
    slices : slices across the face width of a helical pair (spur: 1).
    hub_depth : if given, the sector is clamped at ``max(bore, r_f - hub_depth m_n)``
        instead of the bore (1..100 modules): a shallower body for deep gears.
    method : solver of :func:`pipeline.fem.influence3d.influence_matrix_3d`.
    """

    teeth: int | None = None
    radii: int = 8
    face: int | None = None
    refinement: float = 1.0
    patch: float = 0.5
    face_margin: float = 1.0
    cuts: str = "clamped"
    ends: str = "free"
    slices: int = 30
    hub_depth: float | None = None
    method: str = "auto"

    def __post_init__(self) -> None:
        if self.teeth is not None:
            check_int_range("fe3d.teeth", self.teeth, 3, 99)
        check_int_range("fe3d.radii", self.radii, 2, 200)
        if self.face is not None:
            check_int_range("fe3d.face", self.face, 1, 200)
        check_range("fe3d.refinement", self.refinement, 0.2, 4.0)
        check_range("fe3d.patch", self.patch, 0.1, 2.0, unit="m_n")
        check_range("fe3d.face_margin", self.face_margin, 0.0, 10.0)
        check_choice("fe3d.cuts", self.cuts, CUTS)
        check_choice("fe3d.ends", self.ends, ENDS)
        check_int_range("fe3d.slices", self.slices, 1, 10_000)
        if self.hub_depth is not None:
            check_range("fe3d.hub_depth", self.hub_depth, 1.0, 100.0, unit="m_n")
        check_choice("fe3d.method", self.method, SOLVERS)


@dataclass(frozen=True, eq=False)
class FlankTable3D:
    """Structural compliance on the right-flank grid of some teeth of one gear's 3D sector.

    Attributes
    ----------
    teeth : (n_t,) sector tooth indices of the grid, ascending.
    arc : (n_p,) arc coordinates of the profile points, m (ascending).
    z : (n_f,) face positions in the sector frame, m (ascending).
    structural : (N, N) structural compliance, m/N (symmetric, semidefinite: module
        docstring), N = n_t n_f n_p, points
        ordered by tooth (outer), face position, then profile (inner).
    width : meshed face width of the sector, m.
    info : DOFs, solver, timings (s) of the FE solve and whether the table was read
        from the cache.
    """

    teeth: np.ndarray
    arc: np.ndarray
    z: np.ndarray
    structural: np.ndarray
    width: float
    info: dict = field(default_factory=dict)

    @property
    def shape(self) -> tuple[int, int, int]:
        return (self.teeth.size, self.z.size, self.arc.size)

    def weights(self, tooth: np.ndarray, arc: np.ndarray, z: np.ndarray) -> np.ndarray:
        """(n, N) bilinear interpolation weights (linear extrapolation) of ``n`` points.

        ``tooth`` sector tooth indices (must be in :attr:`teeth`), ``arc`` and ``z`` in m;
        ``W @ S @ W.T`` is the compliance between the points.
        """
        tooth = np.asarray(tooth, dtype=int).reshape(-1)
        arc = np.asarray(arc, dtype=float).reshape(-1)
        z = np.asarray(z, dtype=float).reshape(-1)
        block = np.searchsorted(self.teeth, tooth)
        if np.any(block >= self.teeth.size) or np.any(self.teeth[np.minimum(
                block, self.teeth.size - 1)] != tooth):
            raise InputError(f"fe3d table: teeth {np.setdiff1d(tooth, self.teeth)} are not "
                             f"tabulated (tabulated: {self.teeth})")
        n_t, n_f, n_p = self.shape
        ka, wa = linear_weights(self.arc, arc)
        kz, wz = linear_weights(self.z, z)
        W = np.zeros((tooth.size, n_t * n_f * n_p))
        rows = np.arange(tooth.size)
        for da, fa in ((0, 1 - wa), (1, wa)):
            for dz, fz in ((0, 1 - wz), (1, wz)):
                cols = (block * n_f + np.minimum(kz + dz, n_f - 1)) * n_p + np.minimum(
                    ka + da, n_p - 1)
                np.add.at(W, (rows, cols), fa * fz)
        return W


def touching_pairs(pair: GearPair) -> np.ndarray:
    """Tooth-pair indices ``k`` that are in contact somewhere on the face at some mesh position.

    Pair ``k`` touches at ``s_start + u + k p_bt + z tan(beta_b)`` for ``u`` in
    ``[0, p_bt)``, ``z`` in ``[0, b]``; it is in mesh when that reaches ``[s_start, s_end]``.
    """
    k = pair.pair_indices()
    reach = pair.face_width * math.tan(pair.pinion.base_helix_angle)
    p = pair.base_pitch
    keep = (k * p <= pair.path_length) & ((k + 1) * p + reach > 0)
    return k[keep]


def _sector_settings(gear: GearSpec, teeth: int, settings: FE3DSettings) -> Sector3DSettings:
    s3 = Sector3DSettings.for_gear(gear, teeth, settings.refinement)
    if settings.hub_depth is not None:
        r = max(gear.bore_radius, gear.root_radius - settings.hub_depth * gear.module)
        s3 = replace(s3, inner_radius=r)
    return s3


def _grid(gear: GearSpec, sector_width: float, settings: FE3DSettings
          ) -> tuple[np.ndarray, np.ndarray, float]:
    """Profile radii (m), face positions (m) and patch half-width c (m) of the table grid."""
    from pipeline.geometry.profile import tooth_profile

    c = settings.patch * gear.module
    form = tooth_profile(gear).form_radius
    r = active_radii(gear, settings.radii, lo=max(form, gear.base_radius), margin=c)
    margin = min(settings.face_margin * c, 0.5 * sector_width * (1 - 1e-9))
    n = settings.face
    if n is None:
        n = max(2, int(round((sector_width - 2 * margin) / c)) + 1)
    z = face_positions(sector_width, n, margin)
    return r, z, c


def flank_table(gear: GearSpec, sector_teeth: int, loaded: np.ndarray, settings: FE3DSettings,
                cache: bool = True, cache_dir: str | Path | None = None) -> FlankTable3D:
    """The (cached) structural table of ``gear``'s right flanks on sector teeth ``loaded``.

    Parameters
    ----------
    gear : an external, non-herringbone gear.
    sector_teeth : teeth of the 3D sector.
    loaded : sector tooth indices whose right flanks carry grid points (ascending).
    settings : grid, mesh and boundary-condition settings.
    cache, cache_dir : on-disk cache of tables and meshes (default ``meshes/``).
    """
    loaded = np.unique(np.asarray(loaded, dtype=int))
    s3 = _sector_settings(gear, sector_teeth, settings)
    width = gear.face_width
    r, z, c = _grid(gear, width, settings)
    rb = gear.base_radius
    arc = (r * r - rb * rb) / (2 * rb)
    key = {"format": TABLE_FORMAT, "geometry": GEOMETRY_VERSION, "gear": asdict(gear),
           "sector": asdict(s3), "inner_radius": inner_radius(gear, SectorMeshSettings(
               teeth=sector_teeth, inner_radius=s3.inner_radius)),
           "teeth": loaded, "radii": r, "z": z, "c": c, "cuts": settings.cuts,
           "ends": settings.ends}

    def build() -> dict:
        t0 = time.perf_counter()
        sector = sector3d_mesh(gear, s3, cache=cache, cache_dir=cache_dir)
        pts = flank_grid(sector, loaded, r, z)
        res = influence_matrix_3d(sector, pts, patch_half_width=c, method=settings.method,
                                  cuts=settings.cuts, ends=settings.ends)
        return {"structural": res.structural, "dof": res.n_dof, "free_dof": res.n_free,
                "solver": res.method, "seconds": time.perf_counter() - t0,
                "timings_s": res.timings, "symmetry_error": res.symmetry_error()}

    def save(path: Path, v: dict) -> Path:
        return save_arrays(path, {k: v[k] for k in _STORED})

    v, _, hit = cached_file("fe3dtable", key, build, load_arrays, save, cache_dir, cache)
    info = {"dof": int(v["dof"]), "free_dof": int(v["free_dof"]), "solver": str(v["solver"]),
            "seconds": float(v["seconds"]), "cached": hit,
            **{k: v[k] for k in ("timings_s", "symmetry_error") if k in v}}
    S = v["structural"]
    return _table(loaded, arc, z, S, width, info)


def _table(teeth, arc, z, S, width, info) -> FlankTable3D:
    """Symmetrise ``S`` and project it onto the positive semidefinite matrices.

    The FE structural matrix is positive definite only up to discretisation error
    (:mod:`pipeline.fem.influence3d`); the contact solver rejects an indefinite ``G``.
    Negative eigenvalues are set to zero (the nearest semidefinite matrix in the
    Frobenius norm); ``info`` records the smallest eigenvalue relative to the largest
    and the relative size of the change.
    """
    S = 0.5 * (S + S.T)
    ev, V = np.linalg.eigh(S)
    Sp = (V * np.maximum(ev, 0.0)) @ V.T
    Sp = 0.5 * (Sp + Sp.T)
    info = {**info, "min_eigenvalue_ratio": float(ev[0] / ev[-1]),
            "psd_projection_change": float(np.linalg.norm(Sp - S) / np.linalg.norm(S))}
    return FlankTable3D(teeth, arc, z, Sp, width, info)


@dataclass(frozen=True)
class FE3DCompliance:
    """3D FE-enriched compliance source (module docstring); build with :meth:`build`.

    Attributes
    ----------
    pair : the gear pair (external, not herringbone).
    settings : FE settings.
    pinion_table, gear_table : structural tables of both gears (m/N).
    """

    pair: GearPair
    settings: FE3DSettings = field(default_factory=FE3DSettings)
    pinion_table: FlankTable3D | None = None
    gear_table: FlankTable3D | None = None

    @classmethod
    def build(cls, pair: GearPair, settings: FE3DSettings | None = None, cache: bool = True,
              cache_dir: str | Path | None = None) -> FE3DCompliance:
        """Mesh and solve (or read from the cache) both gears' tables, once."""
        settings = settings or FE3DSettings()
        if pair.pinion.herringbone or pair.gear.herringbone:
            raise InputError("fe3d source: analyse one helical half of a herringbone pair")
        if pair.gear.internal:
            raise InputError("fe3d source: internal gears are not supported (3D sectors "
                             "are external only)")
        k = touching_pairs(pair)
        teeth = cls._teeth(pair, settings)
        mid = teeth // 2
        if np.abs(k).max() > mid or teeth - 1 - mid < np.abs(k).max():
            raise InputError(f"fe3d.teeth = {settings.teeth} does not cover tooth pairs "
                             f"{k.min()}..{k.max()}: use at least {2 * np.abs(k).max() + 1}")
        tables = [flank_table(g, teeth, np.sort(mid + sign * k), settings, cache, cache_dir)
                  for g, sign in ((pair.pinion, -1), (pair.gear, 1))]
        return cls(pair, settings, *tables)

    @staticmethod
    def _teeth(pair: GearPair, settings: FE3DSettings) -> int:
        if settings.teeth is not None:
            return settings.teeth
        return 2 * int(np.abs(touching_pairs(pair)).max()) + 1

    @property
    def sector_teeth(self) -> int:
        """Teeth of both 3D sectors."""
        return self._teeth(self.pair, self.settings)

    def points(self, position: float) -> ContactPoints:
        """Slice contact points of all tooth pairs in contact, ordered by pair, then by z."""
        return slice_points(self.pair, self.settings.slices, position)

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
        s = np.clip(pts.s[:, None] + (z - pts.z[:, None]) * tb, pair.s_start, pair.s_end)
        rho1, rho2 = pair.curvature_radii(s)
        mid = self.sector_teeth // 2
        b = pair.face_width
        out = []
        # z' = b - z for a right-hand pinion / left-hand gear (module docstring)
        flips = (helix_sign(pair.pinion) > 0, helix_sign(pair.gear) < 0)
        for table, gear, rho, tooth, flip in (
                (self.pinion_table, pair.pinion, rho1, mid - pts.pair, flips[0]),
                (self.gear_table, pair.gear, rho2, mid + pts.pair, flips[1])):
            zs = (b - z if flip else z) + 0.5 * (table.width - b)
            arc = np.asarray(rho) ** 2 / (2 * gear.base_radius)
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
        """Sector teeth, grid sizes and the FE figures of both tables."""
        return {"sector_teeth": self.sector_teeth, "tooth_pairs": touching_pairs(self.pair),
                "settings": asdict(self.settings),
                "pinion": {"teeth": self.pinion_table.teeth, **self.pinion_table.info},
                "gear": {"teeth": self.gear_table.teeth, **self.gear_table.info}}
