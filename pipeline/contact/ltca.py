"""Loaded tooth contact analysis over a mesh cycle from any :class:`ComplianceSource`.

For each mesh position: the source gives the candidate points and their
structural compliance ``G``; :mod:`pipeline.contact.separations` gives the
initial gaps; a local contact model gives ``u_c(F)``; and
:func:`pipeline.contact.complementarity.solve_contact` solves Yang et al. (2026) eqs.
(27)-(29) for the loads and the approach, checking its residual. Positions are
solved in order, each warm-started from the loads of the previous position on
the points they share (same tooth pair, same face position).

Local contact models (``local``):

* ``"weber"`` - the nonlinear local approach of Yang et al. (2026), eq. (24)
  (:class:`~pipeline.contact.hertz.HertzLineContact`), with the profile radii of
  curvature and the distances ``h_1, h_2`` from the contact point along the load
  line to each tooth's centreline. This is Yang et al. (2026)'s optimised slice method.
* ``"linear"`` - the constant Hertz compliance ``4 (1 - nu^2) / (pi E w)`` per
  slice (the assembly-error paper / Yang et al. 2026, eq. 7), exactly what
  :mod:`pipeline.stiffness.mesh` adds. With independent slices, no friction difference and ``eps =
  0`` the
  LTCA mesh stiffness then equals the analytical slice stiffness exactly (every
  slice is loaded and ``k = 1^T G^-1 1 = sum_i 1 / G_ii``).
* ``"none"`` - structural compliance only.

Beyond the path of contact (``tip_contact`` of the source, ``[contact] tip_contact``,
default on) tooth pairs can still touch at a tip corner: the leaving pair's pinion corner
past the end of the path, the approaching pair's gear corner before its start
(:mod:`pipeline.geometry.tip_contact`: the rigid gap in closed form, the contact point on
the mate's flank, off the line of action). Candidate points reach into those tip zones
(:func:`pipeline.contact.source.candidate_zone`, out to a rigid gap of 200 um), their
gap is the corner's plus the corner gear's full tip relief, and their compliance comes
from every source at the actual contact radii (the corner's tip radius, the mate's
flank radius). A corner's force ``F_n`` acts along the mate's flank normal, whose
distance from the turning gear's centre is ``a r_b`` (lever factor ``a <= 1``), so it
carries ``Ft = a F_n`` of the line-of-action load and a rigid turn closes its gap ``a``
times as fast: :func:`along_line_of_action` poses the problem in ``Ft`` (``G / (a
a^T)``, ``eps / a``, the local model through ``a``), which leaves the solver and its
convexity unchanged. The local contact of a corner is Hertz of its tip rounding
(``tip_rounding_mm``), or for a sharp corner of a local radius 0.05 m_n, against the mate's
involute at the contact point, with Weber's depths at the actual radii (a sharp corner's
approach is unbounded: :mod:`pipeline.geometry.tip_contact` states the model and its
effect). Friction is left out there.

Checked against the independent CalculiX contact model of the demo pair
(``workflows/reference/calculix_spur_contact.py``, ``tests/test_reference_calculix.py``).
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from pipeline.contact.complementarity import solve_contact
from pipeline.contact.hertz import HertzLineContact, LeverScaled, effective_radius
from pipeline.contact.recording import CycleRecorder
from pipeline.contact.results import LoadedMeshCycle
from pipeline.contact.separations import FlankModifications, initial_separations
from pipeline.contact.source import TIP_GAP, ComplianceSource, ContactPoints, candidate_range
from pipeline.contact.tangency import Q_MIN, TangencyContact
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at, curvature_radii_at, tangency_offset
from pipeline.geometry.tip_contact import tip_contact as tip_contact_geometry
from pipeline.progress import progress
from pipeline.stiffness.tooth import hertz_compliance, load_geometry
from pipeline.validation import InputError, check_choice, check_int_range, check_range

LOCAL_MODELS = ("weber", "linear", "none")


def weber_model(pair: GearPair, points: ContactPoints) -> HertzLineContact | TangencyContact:
    """Yang et al. (2026), eq. (24) local approach of the candidate points (n,).

    ``h_k`` is the distance from the contact point along the load line (the
    line of action) to the centreline of tooth ``k``: ``h_c / cos(load angle)``
    with the half thickness ``h_c`` at the load point (the ``k_1, k_2`` of Yang et al. 2026).
    Beyond the path of contact the point is a tip corner: Hertz of its edge rounding
    against the mate's flank (:func:`~pipeline.geometry.tip_contact.curvature_radii_at`),
    with the depths at the actual contact radii. With a tip rounded by design, the points
    of that gear's tip half take Weber's model with the involute's radius (at the
    tangency, for points on the rounding) and the correction of
    :mod:`pipeline.contact.tangency` for a patch that spans the tangency: zero where the
    involute's patch ends before it, the rounding's own Hertz where the rounding's patch
    lies past it.
    """
    rho1, rho2 = curvature_radii_at(pair, points.s)
    r1, r2 = contact_radii_at(pair, points.s)
    depths = []
    for gear, r in ((pair.pinion, r1), (pair.gear, r2)):
        angle, h_c, _ = load_geometry(gear, r)
        depths.append(np.abs(h_c / np.cos(angle)))

    def model(rho_a, rho_b) -> HertzLineContact:
        # The Hertz half-width and pressure depend on the radii only through
        # R = rho1 rho2 / (rho1 + rho2) (a concave ring flank: rho2 < 0, R > rho1), and
        # HertzLineContact takes two convex radii; two equal radii 2R have that R.
        radius = 2.0 * effective_radius(rho_a, rho_b)
        return HertzLineContact(points.width, radius, radius, depths[0], depths[1],
                                pair.pinion.material, pair.gear.material)

    if not (pair.pinion.tip_rounding or pair.gear.tip_rounding):
        return model(rho1, rho2)
    # A rounded tip near its tangency with the involute: Weber with the involute's radius
    # there and the correction of :mod:`pipeline.contact.tangency` (the rounding's own
    # Hertz far past the tangency, the involute's well before it: unchanged there)
    ratio, offset = np.ones(rho1.shape), np.zeros(rho1.shape)
    rho1_i, rho2_i = rho1.copy(), rho2.copy()
    for k, (gear, r, tip_side) in enumerate(((pair.pinion, r1, points.s >= pair.s_pitch),
                                             (pair.gear, r2, points.s < pair.s_pitch))):
        if not gear.tip_rounding:
            continue
        e = tangency_offset(gear, r)
        rounding = tip_side & (e > 0.0)
        rb = gear.base_radius
        involute = np.sqrt(np.maximum(gear.active_tip_radius**2 - rb * rb, 0.0))
        own, mate = (rho1, rho2) if k == 0 else (rho2, rho1)
        on_involute = np.where(rounding, involute, own)  # own: rho_r on the rounding
        r_i = effective_radius(on_involute, mate)
        r_r = effective_radius(gear.tip_rounding, mate)
        near = tip_side & (e > -2.0 * gear.module)
        q = np.minimum(r_r / r_i, 1.0)
        if (near & (q < Q_MIN)).any():
            name = "pinion" if k == 0 else "gear"
            r_max = float(np.max(r_i[near]))
            raise InputError(f"{name}.tip_rounding = {gear.tip_rounding * 1e3:.6g} mm is below "
                             f"the {Q_MIN * r_max * 1e3:.4g} mm the tangency contact model "
                             f"resolves ({Q_MIN:g} of the flanks' effective radius "
                             f"{r_max * 1e3:.4g} mm): give a larger rounding, or 0 for a "
                             "sharp corner")
        ratio = np.where(near, q, ratio)
        offset = np.where(near, e, offset)
        (rho1_i if k == 0 else rho2_i)[rounding] = involute
    return TangencyContact(model(rho1_i, rho2_i), ratio, offset)


def along_line_of_action(pair: GearPair, points: ContactPoints, G: np.ndarray, eps: np.ndarray,
                         hertz, driver: str = "pinion"):
    """The contact problem in loads and approaches along the line of action: a tip corner's
    force ``F`` acts off it, with lever factor ``a`` (:mod:`pipeline.geometry.tip_contact`;
    1 on the path), so its line-of-action load is ``Ft = a F``, its gap closes by ``a``
    per unit of approach, and ``G / (a a^T)``, ``eps / a`` and the local model seen
    through ``a`` (:class:`~pipeline.contact.hertz.LeverScaled`) pose the old problem in
    ``Ft``. Returns ``(G, eps, hertz, a)``."""
    a = tip_contact_geometry(pair, points.s).lever(driver)
    if np.all(a == 1.0):
        return G, eps, hertz, a
    if hertz is not None:
        hertz = LeverScaled(hertz, a)
    return G / np.outer(a, a), eps / a, hertz, a


def check_tip_zone(eps: np.ndarray, loads: np.ndarray, approach: float, label: str) -> None:
    """Refuse a solution whose elastic approach (``approach`` beyond the smallest
    separation ``eps`` of a point carrying ``loads > 0``, m) would close a tip corner beyond
    the candidate zone (:data:`~pipeline.contact.source.TIP_GAP`): its loads would be
    wrong."""
    loaded = loads > 0.0
    if not loaded.any():
        return
    elastic = approach - float(np.min(eps[loaded]))
    if elastic >= TIP_GAP:
        raise InputError(f"{label}: elastic approach {elastic * 1e6:.4g} um reaches the "
                         f"{TIP_GAP * 1e6:.4g} um tip zone of the candidate points: the load "
                         "is beyond what the loaded contact models")


def _keys(points: ContactPoints) -> np.ndarray:
    """Integer identity of each point: tooth pair and face position (to 1 nm)."""
    return points.pair.astype(np.int64) * (1 << 32) + np.round(points.z * 1e9).astype(np.int64)


def _warm_start(prev_keys: np.ndarray | None, prev_loads: np.ndarray | None,
                keys: np.ndarray) -> np.ndarray | None:
    if prev_keys is None or prev_loads is None or not prev_loads.any():
        return None
    _, i_new, i_old = np.intersect1d(keys, prev_keys, return_indices=True)
    start = np.zeros(keys.size)
    start[i_new] = prev_loads[i_old]
    return start if start.any() else None


def mesh_positions(pair: GearPair, positions: int | ArrayLike) -> np.ndarray:
    """Roll coordinates s0 (m) of the mesh positions: ``positions`` equally spaced over one
    mesh cycle (an int >= 1), or the given roll coordinates (a non-empty finite array)."""
    if np.ndim(positions) == 0:
        check_int_range("contact.positions", int(positions), 1, 1_000_000)
        return pair.mesh_cycle(int(positions))
    s0 = np.asarray(positions, dtype=float).reshape(-1)
    if s0.size == 0 or not np.all(np.isfinite(s0)):
        raise InputError("contact positions must be a non-empty array of finite roll "
                         "coordinates (m)")
    return s0


def loaded_mesh_cycle(
    source: ComplianceSource,
    load: float,
    modifications: FlankModifications | None = None,
    local: str = "weber",
    positions: int | ArrayLike = 60,
    *,
    driver: str = "pinion",
    tol: float = 1e-10,
    max_iter: int = 100,
    show_progress: bool = False,
) -> LoadedMeshCycle:
    """Loads, transmission error and mesh stiffness at every position of a mesh cycle.

    Parameters
    ----------
    source : compliance source (:class:`~pipeline.contact.source.SliceCompliance` or FE).
    load : P, total load along the transverse line of action, N (driving torque over
        the driver's base radius), > 0.
    modifications : flank modifications and errors (default none).
    local : local contact model, one of "weber", "linear", "none" (module docstring).
    positions : number of equally spaced positions over one mesh cycle (>= 1), or the
        roll coordinates s0 (m) themselves.
    driver : "pinion" or "gear", the gear that turns under ``load`` (sets the lever
        factors of tip-corner contact, module docstring). Whether teeth may touch beyond
        the path of contact is the source's ``tip_contact``.
    tol, max_iter : passed to :func:`~pipeline.contact.complementarity.solve_contact`.
    show_progress : progress bar on stderr.

    Returns
    -------
    LoadedMeshCycle

    Raises
    ------
    InputError for invalid inputs; ContactConvergenceError naming the position.
    """
    check_range("contact.load", load, 0.0, math.inf, lo_open=True, unit="N")
    check_choice("contact.local_contact", local, LOCAL_MODELS)
    mods = modifications or FlankModifications()
    pair = source.pair
    s0 = mesh_positions(pair, positions)
    k_all = pair.pair_indices(source.tip_contact)
    c_hertz = hertz_compliance(pair.pinion, pair.gear)  # m^2/N, per unit width
    m = s0.size
    record = CycleRecorder(pair, m, source.tip_contact)
    prev_keys = prev_loads = None
    for i in progress(range(m), "contact", total=m, enabled=show_progress):
        label = f"mesh position {i} (s0 = {s0[i] * 1e3:.6g} mm)"
        pts = source.points(float(s0[i]))
        if len(pts) == 0:
            raise InputError(f"{label}: the compliance source gives no candidate points")
        if not np.isin(pts.pair, k_all).all():
            raise InputError(f"{label}: tooth-pair indices {np.setdiff1d(pts.pair, k_all)} of "
                             f"the candidate points are not among pair.pair_indices() {k_all}")
        G = np.asarray(source.matrix(float(s0[i])), dtype=float)
        eps = initial_separations(pair, pts, mods, candidate_range(pair, source.tip_contact))
        hertz = None
        c_lin = None
        if local == "weber":
            hertz = weber_model(pair, pts)
        elif local == "linear":
            c_lin = c_hertz / pts.width
            G = G + np.diag(c_lin)
        Gt, eps_t, hertz, lever = along_line_of_action(pair, pts, G, eps, hertz, driver)
        keys = _keys(pts)
        sol = solve_contact(Gt, eps_t, load, hertz, tol=tol, max_iter=max_iter,
                            start=_warm_start(prev_keys, prev_loads, keys), label=label)
        check_tip_zone(eps_t, sol.loads, sol.approach, label)
        prev_keys, prev_loads = keys, sol.loads
        # the local approach along each point's own normal: a tip corner's is a times
        # the one along the line of action
        u = sol.contact_deformation * lever if c_lin is None else c_lin * sol.loads / lever
        record.add(i, pts, sol.loads, eps, u, sol.approach,
                   (sol.mesh_stiffness_tangent, sol.mesh_stiffness_secant,
                    sol.mesh_stiffness_pointwise),
                   (sol.residual, sol.tolerance, sol.newton_iterations), lever)
    return record.cycle(s0, load, local)
