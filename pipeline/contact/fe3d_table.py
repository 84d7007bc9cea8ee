"""Structural flank tables of one gear's 3D FE model (for the 3D FE compliance source).

The tables of :class:`~pipeline.contact.fe3d_source.FE3DCompliance`.
For each gear one structural influence matrix ``S`` (m/N: normal approach
per unit normal load, FE minus the Boussinesq near field) is computed once, on a
grid of ``radii x face`` points on the right flank of every tooth that a tooth pair
in contact can reach over a mesh cycle (one solver set-up per gear). The FE model is
the whole gear body (``body = "whole"``, default: all teeth, body down to the bore,
full face width, mesh graded from the loaded teeth, :mod:`pipeline.fem.whole3d`) or a
sector of a few teeth clamped at its cut faces (``body = "sector"``).

One loaded tooth (whole gears). A whole gear looks the same from each of its teeth (a
clamped bore, all teeth alike), so the approach at tooth ``a`` per unit load at tooth
``b`` depends on ``a - b`` only. The table is therefore solved for one loaded tooth
``t0 = z // 2`` and read on the teeth ``t0 - s .. t0 + s`` (``s`` the span of the
tabulated teeth): one solve per grid point of one flank instead of one per point of
every tabulated flank, and a mesh fine on ``t0`` and nearly as fine (1.5 flank sizes) on
:data:`FINE_NEIGHBOURS` teeth on each side only (the other teeth and the body coarse;
the teeth beyond two rim depths along the root circle left out, the read teeth always
kept: :mod:`pipeline.fem.whole3d`, where the unknowns of each region are counted). The
tabulated block ``(a, b)`` is the columns read at offset ``a - b``; the two halves of the
table read Maxwell-Betti's pairs on differently meshed teeth
(``info["reciprocity_error"]``, 0.1-0.2 % at the defaults) and are averaged. Against the
former model (every tabulated tooth loaded and fine) on the z 30/30 helical pair of
``bench_fe3d``: mesh stiffness mean, min and max 0.08-0.12 % stiffer, TE p-p 0.12 %
smaller, from one 26k-unknown model for both gears (mirror images, below) and 56 instead
of 2 x 168 load cases; against every tooth kept and fine (268k unknowns) +0.15-0.16 %,
TE p-p -0.06 % (``workflows/fe3d_convergence.py``); on the traction pair of Yang et al.
(2026) (``gearpipe contact``, with fine neighbours and every tooth kept) within 0.07 %,
TE p-p 0.01 %. Responses read on a coarse neighbour made the z 30/30 pair 0.5 % stiffer
than with every tooth fine (hence the near neighbours: +0.10 % at 1.5 flank sizes,
+0.25 % at 2), coarser far teeth changed it by 0.05 %.
A sector (``body = "sector"``) is clamped at its cuts, not alike from every tooth: its
tabulated teeth are all loaded.

Mirror images share a table. A left-hand gear is the right-hand one mirrored at
mid-face (its section at ``z`` is the right-hand section at ``b - z``, right flanks stay
right flanks and the elasticity is isotropic), so its table is the right-hand gear's with
the face positions reversed (the grid is symmetric about mid-face); the cache key is the
right-hand gear without its name. The two gears of a pair of equal gears, or any gears of
one geometry, are solved once.

Profile points are equally spaced in the arc coordinate of the involute between the
form (or base) circle and the tip, ``c`` of arc inside both ends (``c`` the load
patch half-width: the patch reaches the tip corner but does not cross it); face
points from ``face_margin c`` to ``b - face_margin c``, about ``c`` apart.
``S`` is symmetrised (it is symmetric to solver accuracy) and projected onto the
positive semidefinite matrices (negative eigenvalues, discretisation error of
~0.2-2 % of the largest, set to zero: the contact solver needs a semidefinite
``G``; the change is recorded in the table's ``info``: 1.2-1.4 % in the Frobenius norm
on the pair of Yang et al. 2026). Tables are cached on
disk by a content hash of the gear, mesh settings, grid and boundary conditions
(``meshes/fe3dtable-<hash>.npz``, written atomically), like the meshes themselves.

Progress of the mesh, assembly, factorisation and solves goes to stderr
(:class:`pipeline.progress.Steps`); each table's ``info["timings_s"]`` keeps the wall
times of the build that computed it (also when it is read back from the cache).

Discretisation: the default 3D meshes are coarse (flank elements ``m_n / (3
refinement)``); a displacement FE model is stiffer than the real tooth (a few %
for line loads, ~10 % for a concentrated patch at refinement 1, see
:mod:`pipeline.fem.influence`), and ``S`` is positive definite only up to that
error, hence the projection above.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass, field, replace

import numpy as np

from pipeline.cache.entries import cached_file, same_arrays, unlabelled
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.contact._interpolation import linear_weights
from pipeline.fem.flank import active_radii
from pipeline.fem.flank_grid import face_positions, flank_grid
from pipeline.fem.influence import influence_matrix
from pipeline.fem.mesh_cache import MESH_CODE
from pipeline.fem.mesh_settings import SectorSettings3D
from pipeline.fem.sector2d import inner_radius
from pipeline.fem.sector3d import sector_mesh_3d
from pipeline.fem.settings import FE3DSettings, check_table_points
from pipeline.fem.solvers import solver_named
from pipeline.geometry.gear import GearSpec
from pipeline.progress import Steps
from pipeline.validation import InputError

# Bump when the same inputs would give a different table.
TABLE_CODE = (*MESH_CODE, "pipeline.contact.fe3d_table")
"""The code the 3D tables depend on (part of their cache key)."""
FINE_NEIGHBOURS = 1
"""Teeth on each side of a whole gear's loaded tooth meshed nearly as finely as it is
(``near``, 1.5 flank sizes: :mod:`pipeline.fem.whole3d`; module docstring: the
responses read on a coarse neighbour made the mesh stiffness 0.5 % stiffer than with
every tooth fine, one fine neighbour 0.13 %, all read teeth fine 0.004 %)."""
_STORED = ("structural", "dof", "free_dof", "condensed_dof", "solver", "seconds",
           "timing_names", "timing_values", "symmetry_error")  # arrays in the cache file
@dataclass(frozen=True, eq=False)
class FlankTable3D:
    """Structural compliance on the right-flank grid of some teeth of one gear's 3D model.

    Attributes
    ----------
    teeth : (n_t,) tooth indices of the grid in the model (sector or whole gear), ascending.
    arc : (n_p,) arc coordinates of the profile points, m (ascending).
    z : (n_f,) face positions in the sector frame, m (ascending).
    structural : (N, N) structural compliance, m/N (symmetric, semidefinite: module
        docstring), N = n_t n_f n_p, points
        ordered by tooth (outer), face position, then profile (inner).
    width : meshed face width of the model, m.
    info : "body", "model_teeth" (teeth of the mesh), "dof", "free_dof",
        "condensed_dof" (of the free DOFs, those eliminated before the factorisation:
        :func:`pipeline.fem.influence.far_part`), "solver",
        "seconds" (wall time of the build that computed the table), "timings_s" (its
        breakdown: mesh, assembly, loads, factorise, solve, near field, s), "cached"
        (read from the cache), "wall_s" (this call), "symmetry_error", and the
        positive-semidefinite projection figures (:func:`_table`).
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


def _sector_settings(gear: GearSpec, teeth: int, settings: FE3DSettings,
                     loaded: np.ndarray | None = None, near=()) -> SectorSettings3D:
    """Mesh settings: a sector of ``teeth`` teeth, or the whole gear (``teeth = z``)
    graded from the ``loaded`` and ``near`` teeth (every tooth kept and fine for
    ``settings.mesh = "uniform"``)."""
    if teeth == gear.teeth:
        s3 = SectorSettings3D.whole_gear(gear, loaded, settings.refinement, near=near)
        if settings.mesh == "uniform":
            s3 = replace(s3, loaded=None, near=(), size_near=None, size_tooth=None,
                         reach=None)
    else:
        s3 = SectorSettings3D.for_gear(gear, teeth, settings.refinement)
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
    r = active_radii(gear, settings.points, lo=max(form, gear.base_radius), margin=c)
    margin = min(settings.face_margin * c, 0.5 * sector_width * (1 - 1e-9))
    n = settings.face_points
    if n is None:
        n = max(2, int(round((sector_width - 2 * margin) / c)) + 1)
    z = face_positions(sector_width, n, margin)
    return r, z, c


def flank_table(gear: GearSpec, model_teeth: int, loaded: np.ndarray, settings: FE3DSettings,
                cache: Cache = DEFAULT_CACHE, progress: bool = True, one_tooth: bool = True
                ) -> FlankTable3D:
    """The (cached) structural table of ``gear``'s right flanks on teeth ``loaded``.

    Parameters
    ----------
    gear : an external, non-herringbone gear.
    model_teeth : teeth of the 3D model: ``gear.teeth`` for the whole gear, else a sector.
    loaded : tooth indices of the model whose right flanks carry grid points.
    settings : grid, mesh and boundary-condition settings.
    cache : the on-disk cache of tables and meshes.
    progress : report the steps on stderr (:class:`pipeline.progress.Steps`).
    one_tooth : a whole gear's table from the columns of one loaded tooth
        (:func:`_tooth_columns`, module docstring); False solves every tabulated tooth on
        a mesh fine on all of them (the former model, the tests' reference). A sector's
        teeth are always solved one by one.
    """
    t_call = time.perf_counter()
    loaded = np.unique(np.asarray(loaded, dtype=int))
    span = int(loaded.max() - loaded.min())
    if one_tooth and model_teeth == gear.teeth and 2 * span + 1 <= gear.teeth:
        return _whole_gear_table(gear, loaded, settings, cache, progress, t_call)
    s3 = _sector_settings(gear, model_teeth, settings, loaded)
    r, z, c = _grid(gear, gear.face_width, settings)
    _check_points(r.size * z.size * loaded.size, r, z, loaded.size)
    key = {"gear": unlabelled(gear),
           "sector": asdict(s3), "inner_radius": inner_radius(gear, s3),
           "teeth": loaded, "radii": r, "z": z, "c": c, "cuts": settings.cuts,
           "ends": settings.ends}
    body = "whole" if model_teeth == gear.teeth else "sector"
    steps = Steps(f"fe3d {gear.name} ({body}, {model_teeth} teeth)", enabled=progress)
    v, hit = _solved("fe3dtable", key, gear, s3, loaded, r, z, c, None, settings, cache, steps)
    info = {"body": body, "model_teeth": int(model_teeth), **_info(v, hit, t_call)}
    return _table(loaded, _arc(gear, r), z, v["structural"], gear.face_width, info)


def _whole_gear_table(gear: GearSpec, loaded: np.ndarray, settings: FE3DSettings, cache: Cache,
                      progress: bool, t_call: float) -> FlankTable3D:
    """A whole gear's table from one loaded tooth's columns (module docstring)."""
    span = int(loaded.max() - loaded.min())
    mirrored = gear.hand == "left"
    model = replace(gear, hand="right") if mirrored else gear
    r, z, _ = _grid(gear, gear.face_width, settings)
    n_f, n_p = z.size, r.size
    _check_points(n_p * n_f * loaded.size, r, z, loaded.size)
    cols = _tooth_columns(model, span, settings, cache, progress)
    K = cols["structural"].reshape(2 * span + 1, n_f * n_p, n_f * n_p)
    if mirrored:  # the left-hand gear is the right-hand one mirrored at mid-face: z -> b - z
        flip = np.arange(n_f * n_p).reshape(n_f, n_p)[::-1].ravel()
        K = K[:, flip][:, :, flip]
    # approach at tooth a per unit load at tooth b: the loaded tooth's columns read at the
    # offset a - b (the whole gear is the same seen from every tooth)
    offset = loaded[:, None] - loaded[None, :] + span
    S = K[offset].transpose(0, 2, 1, 3).reshape(loaded.size * n_f * n_p, -1)
    info = {"body": "whole", "model_teeth": int(gear.teeth), "mirrored": mirrored,
            "load_tooth": int(cols["load_tooth"]), "read_offsets": span,
            "reciprocity_error": float(np.abs(S - S.T).max() / np.abs(S).max()),
            **_info(cols, cols["cached"], t_call)}
    return _table(loaded, _arc(gear, r), z, S, gear.face_width, info)


def _tooth_columns(gear: GearSpec, span: int, settings: FE3DSettings, cache: Cache,
                   progress: bool) -> dict:
    """The (cached) structural columns of one loaded tooth of the whole ``gear``: the
    approach on the right flanks of the teeth ``t0 - span .. t0 + span`` per unit load
    on the grid of tooth ``t0 = z // 2`` (the mesh is fine on ``t0`` and its
    :data:`FINE_NEIGHBOURS` neighbours on each side).

    Returns the stored arrays (``structural``: (2 span + 1) n x n, n the grid points of a
    flank, the teeth in ascending order) with ``load_tooth`` and ``cached``.
    """
    t0 = gear.teeth // 2
    reads = t0 + np.arange(-span, span + 1)
    near = min(span, FINE_NEIGHBOURS)
    s3 = _sector_settings(gear, gear.teeth, settings, [t0],
                          near=[t0 + k for k in range(-near, near + 1) if k])
    if s3.reach is not None and s3.reach < span - near + 1:
        # the read teeth kept, each with a kept neighbour beyond it
        s3 = replace(s3, reach=span - near + 1)
    r, z, c = _grid(gear, gear.face_width, settings)
    key = {"gear": unlabelled(gear), "sector": asdict(s3),
           "inner_radius": inner_radius(gear, s3), "load_tooth": t0, "read_teeth": reads,
           "radii": r, "z": z, "c": c, "ends": settings.ends}
    steps = Steps(f"fe3d {gear.name} (whole, {gear.teeth} teeth, one loaded tooth)",
                  enabled=progress)
    n = r.size * z.size
    v, hit = _solved("fe3dteeth", key, gear, s3, reads, r, z, c,
                     np.arange(span * n, (span + 1) * n), settings, cache, steps)
    return {**v, "load_tooth": t0, "cached": hit}


def _solved(kind: str, key: dict, gear: GearSpec, s3: SectorSettings3D, teeth: np.ndarray,
            r: np.ndarray, z: np.ndarray, c: float, loaded: np.ndarray | None,
            settings: FE3DSettings, cache: Cache, steps: Steps) -> tuple[dict, bool]:
    """Mesh, solve and cache (or read) the structural compliance of the grid on ``teeth``
    per unit load at the grid points ``loaded`` (all if None)."""
    def build() -> dict:
        t0 = time.perf_counter()
        with steps.step("mesh"):
            sector = sector_mesh_3d(gear, s3, cache=cache)
        pts = flank_grid(sector, teeth, r, z)
        res = influence_matrix(sector, pts, patch_half_width=c,
                               solver=solver_named(settings.solver, dim=3),
                               cuts=settings.cuts, ends=settings.ends, steps=steps,
                               loaded=loaded)
        seconds = time.perf_counter() - t0
        timings = {**steps.timings, "total": seconds}
        return {"structural": res.structural, "dof": res.n_dof, "free_dof": res.n_free,
                "condensed_dof": res.n_condensed, "solver": res.method, "seconds": seconds,
                "timing_names": np.array(list(timings)),
                "timing_values": np.array(list(timings.values())),
                "symmetry_error": res.symmetry_error()}

    def stored(v: dict) -> dict:
        return {k: v[k] for k in _STORED}

    v, _, hit = cached_file(kind, key, build, stored, same_arrays, code=TABLE_CODE,
                            cache=cache)
    return v, hit


def _info(v: dict, hit: bool, t_call: float) -> dict:
    """The build figures of a table (:class:`FlankTable3D` ``info``)."""
    timings = {str(n): float(t) for n, t in zip(v["timing_names"], v["timing_values"],
                                               strict=True)}
    return {"dof": int(v["dof"]), "free_dof": int(v["free_dof"]),
            "condensed_dof": int(v["condensed_dof"]), "solver": str(v["solver"]),
            "seconds": float(v["seconds"]), "timings_s": timings, "cached": hit,
            "wall_s": time.perf_counter() - t_call,
            "symmetry_error": float(v["symmetry_error"])}


def _check_points(n: int, r: np.ndarray, z: np.ndarray, teeth: int) -> None:
    check_table_points(n, f"fe.points x fe.face_points x loaded teeth = {r.size} x {z.size} x "
                          f"{teeth}", "lower fe.points or fe.face_points")


def _arc(gear: GearSpec, r: np.ndarray) -> np.ndarray:
    """Arc coordinates (m) of the involute radii ``r`` (m)."""
    rb = gear.base_radius
    return (r * r - rb * rb) / (2 * rb)


def _table(teeth, arc, z, S, width, info) -> FlankTable3D:
    """Symmetrise ``S`` and project it onto the positive semidefinite matrices.

    The FE structural matrix is positive definite only up to discretisation error
    (:mod:`pipeline.fem.influence`); the contact solver rejects an indefinite ``G``.
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
