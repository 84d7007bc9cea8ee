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
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from pipeline.contact.complementarity import solve_contact
from pipeline.contact.hertz import HertzLineContact, LeverScaled
from pipeline.contact.recording import CycleRecorder
from pipeline.contact.results import LoadedMeshCycle
from pipeline.contact.separations import FlankModifications, initial_separations
from pipeline.contact.source import TIP_GAP, ComplianceSource, ContactPoints, candidate_zone
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import tip_contact as tip_contact_geometry
from pipeline.progress import progress
from pipeline.stiffness.tooth import hertz_compliance, load_geometry
from pipeline.validation import InputError, check_choice, check_int_range, check_range

LOCAL_MODELS = ("weber", "linear", "none")


def weber_model(pair: GearPair, points: ContactPoints) -> HertzLineContact:
    """Yang et al. (2026), eq. (24) local approach of the candidate points (n,).

    ``h_k`` is the distance from the contact point along the load line (the
    line of action) to the centreline of tooth ``k``: ``h_c / cos(load angle)``
    with the half thickness ``h_c`` at the load point (the ``k_1, k_2`` of Yang et al. 2026).
    """
    s = np.clip(points.s, pair.s_start, pair.s_end)
    rho1, rho2 = pair.curvature_radii(s)
    r1, r2 = pair.contact_radii(s)
    depths = []
    for gear, r in ((pair.pinion, r1), (pair.gear, r2)):
        angle, h_c, _ = load_geometry(gear, r)
        depths.append(np.abs(h_c / np.cos(angle)))
    radius_1, radius_2 = rho1, rho2
    if pair.gear.internal:
        # Convex pinion flank in the concave ring flank: the Hertz half-width and pressure
        # depend on the radii only through R = rho1 |rho2| / (|rho2| - rho1) (> rho1), and
        # HertzLineContact takes two convex radii; two equal radii 2R have that R.
        radius_1 = radius_2 = 2.0 * rho1 * np.abs(rho2) / (np.abs(rho2) - rho1)
    return HertzLineContact(points.width, radius_1, radius_2, depths[0], depths[1],
                            pair.pinion.material, pair.gear.material)


def _check_tip_zone(eps: np.ndarray, sol, label: str) -> None:
    """Refuse a solution whose elastic approach (beyond the smallest separation ``eps`` of
    a loaded point, m) would close a tip corner beyond the candidate zone
    (:data:`~pipeline.contact.source.TIP_GAP`): its loads would be wrong."""
    loaded = sol.loads > 0.0
    if not loaded.any():
        return
    elastic = sol.approach - float(np.min(eps[loaded]))
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
    tip_contact: bool = True,
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
        factors of tip-corner contact, module docstring).
    tip_contact : let tooth pairs touch at a tip corner beyond the path of contact; False
        keeps every point off the path out of mesh.
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
    k_all = pair.pair_indices()
    c_hertz = hertz_compliance(pair.pinion, pair.gear)  # m^2/N, per unit width
    m = s0.size
    record = CycleRecorder(pair, m)
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
        eps = initial_separations(pair, pts, mods,
                                  candidate_zone(pair) if tip_contact else None)
        hertz = None
        c_lin = None
        if local == "weber":
            hertz = weber_model(pair, pts)
        elif local == "linear":
            c_lin = c_hertz / pts.width
            G = G + np.diag(c_lin)
        a = tip_contact_geometry(pair, pts.s).lever(driver)
        if hertz is not None and np.any(a != 1.0):
            hertz = LeverScaled(hertz, a)
        keys = _keys(pts)
        sol = solve_contact(G / np.outer(a, a), eps / a, load, hertz, tol=tol,
                            max_iter=max_iter, start=_warm_start(prev_keys, prev_loads, keys),
                            label=label)
        _check_tip_zone(eps / a, sol, label)
        prev_keys, prev_loads = keys, sol.loads
        u = sol.contact_deformation if c_lin is None else c_lin * sol.loads
        record.add(i, pts, sol.loads, eps, u, sol.approach,
                   (sol.mesh_stiffness_tangent, sol.mesh_stiffness_secant,
                    sol.mesh_stiffness_pointwise),
                   (sol.residual, sol.tolerance, sol.newton_iterations))
    return record.cycle(s0, load, local)
