"""Herringbone sun-planet loaded contact: both helical halves solved together through the groove.

Model (one sun-planet mesh standing for each of the N planets, which carry equal loads)
---------------------------------------------------------------------------------------
* The **planet** is one rigid body on its bearing common to both halves: its rotation
  (the approach x along the transverse line of action, unknown) is the same for both;
  its bearing deflections move both halves alike and do not change the split.
* The **sun** is two helical halves of opposite hand (the candidate points, compliance
  ``G`` and initial separations of the helical-half pair, the right half the mirror image
  of the left: no stagger), joined by the relief groove's FE stiffness condensed to
  the twist and axial stretch (:class:`~pipeline.contact.groove_flank.GrooveFlankCoupling`,
  compliance ``C`` of O_L relative to O_R).
* **Torque entry** (``torque_entry``): where the sun's torque leaves the sun.
  ``"right"`` (default): at the right half, the side of Xu et al. (2020)'s torsion point
  O_T (l_LT = 657.5 mm > l_RT = 432.5 mm, Fig. 2): the left half's torque and axial
  force cross the groove, the right half's do not. ``"left"``: mirrored.
  ``"both"``: half the torque on each half, as eqs. 20d / 21d of Xu et al. (2020)
  apply T_D / 2 to each; the groove then carries half the difference of the halves.
  With f the fraction entering at O_L (0, 1, 0.5), the groove carries the generalised
  force (per planet) ``g = [r_b ((1 - f) P_L - f P_R), tan(beta_b) ((1 - f) P_L + f P_R)]``
  (torque, axial force), and O_L moves relative to O_R by ``d = N C g``.
* **Flank kinematics.** A twist d_t of the left half against the torque moves its flank
  back by ``r_b d_t``; an axial shift d_z of a helicoid by ``tan(beta_b) d_z`` along the
  transverse line of action, with opposite sign on the two hands; + (towards the right
  half) unloads the left half, as the slide of Xu et al. (2020), sec. 3.1.
* **Sun axial position** (``sun_axial``): ``"held"``: the sun sits at the slide z_a
  (``axial_slide``) on an axial support of stiffness k_a (``axial_support_stiffness``,
  default rigid) relative to the planets, so it moves by ``N tan(beta_b) (P_L - P_R) / k_a``
  more; ``"free"``: no axial support, the axial forces of the halves balance, which with
  equal planets means ``P_L = P_R`` (the groove then changes the sun's axial position,
  not the split).

All of this is linear in the loads, so the held case is one contact problem on the
candidate points of both halves: ``G2 = diag(G, G) + N B^T C B + (N t^2 / k_a) v v^T``
with ``B`` the rows ``[r_b w_t; t w_a]`` (``w`` the groove weights above on the points of
each half, ``t = tan(beta_b)``), ``v = [1_L; -1_R]``, separations shifted by ``+-t z_a``,
and the total load P; :func:`~pipeline.contact.complementarity.solve_contact` solves it
exactly as a helical pair (its approach is the planet's). The free case is two helical
contacts at P / 2.

Outputs per position: each half's load, its own flank approach (static TE) and own
tangent mesh stiffness (teeth and local contact of that half only: the dynamic models
have the groove and supports as their own springs), unit loads over both flanks, the
planet's approach and the whole mesh stiffness, the groove twist and torque and the sun's
axial position (:class:`~pipeline.contact.herringbone_results.HerringboneCycle`).

Checks (``tests/test_contact_herringbone.py``,
``tests/test_dyn_herringbone_excitation.py``): a rigid groove gives two helical contacts at
P/2 (loads to 1e-9, approaches to 1e-12 m); with the linear local contact the split is
springs in series, ``P_L (c_L + (1-f) c_g) = P_R (c_R + f c_g)``, to 1e-9 for the torque at
the right, the left and both; every position balances the sun torque to 1e-12, the groove
twist is the groove torque over k_t to 1e-12, a free sun has P_L = P_R and slides to make
up the twist; the herringbone planetary model excited left/right from it
(:mod:`pipeline.dynamics.herringbone_excitation`, ``e_h = x_h - P_h / k_h`` per position)
carries the contact's half loads at zero speed to 1e-6 (axially rigid groove; with the FE's
axial stretch 8e-4, because the model puts half the sun's axial bearing on each half). The
twist's mesh phase (Xu et al. 2020, eq. 11; 2e-3 of a mesh period for the wind-turbine set)
is not applied on top: the contact has both halves at the planet's position and the twist
in their approach. Measured on the wind-turbine set, beside Xu et al. (2020):
``workflows/herringbone_groove_study.py``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from pipeline.contact.complementarity import mesh_stiffnesses, solve_contact
from pipeline.contact.groove_flank import GrooveFlankCoupling
from pipeline.contact.herringbone_results import LEFT_FRACTION, HerringboneCycle
from pipeline.contact.hertz import HertzLineContact, LeverScaled
from pipeline.contact.ltca import (
    LOCAL_MODELS,
    along_line_of_action,
    check_tip_zone,
    mesh_positions,
    weber_model,
)
from pipeline.contact.recording import CycleRecorder
from pipeline.contact.separations import FlankModifications, initial_separations
from pipeline.contact.source import ComplianceSource, candidate_range
from pipeline.contact.tangency import TangencyContact
from pipeline.progress import progress
from pipeline.stiffness.tooth import hertz_compliance
from pipeline.validation import InputError, check_choice, check_int_range, check_range

TORQUE_ENTRIES = LEFT_FRACTION
"""Fraction of the sun torque entering at O_L for each ``torque_entry``."""
SUN_LOAD_SIDE = {"right": "R", "left": "L", "both": "both"}
"""``torque_entry`` -> the herringbone planetary model's ``sun_load_side`` (the same entry)."""
SUN_AXIAL = ("held", "free")


@dataclass(frozen=True)
class HerringboneOptions:
    """How the halves of a herringbone sun are loaded and held (SI; module docstring).

    Attributes
    ----------
    torque_entry : "right" (default: Xu et al. 2020's torsion point O_T), "left" or "both".
    sun_axial : "held" (at ``axial_slide`` on ``axial_support_stiffness``) or "free".
    axial_slide : z_a, axial slide of the sun relative to the planets, m (+ towards the
        right half), in [-0.05, 0.05] m; "held" only.
    axial_support_stiffness : k_a, axial stiffness holding the sun relative to the
        planets, N/m, > 0 (inf: rigid); "held" only.
    """

    torque_entry: str = "right"
    sun_axial: str = "held"
    axial_slide: float = 0.0
    axial_support_stiffness: float = math.inf

    def __post_init__(self) -> None:
        check_choice("herringbone.torque_entry", self.torque_entry, tuple(TORQUE_ENTRIES))
        check_choice("herringbone.sun_axial", self.sun_axial, SUN_AXIAL)
        check_range("herringbone.axial_slide", self.axial_slide, -0.05, 0.05, unit="m")
        k = float(self.axial_support_stiffness)
        if not (k > 0.0):  # inf allowed: a rigid support
            raise InputError(f"herringbone.axial_support_stiffness = {k:g} N/m is outside the "
                             "allowed range (0, inf] N/m", field="axial_support_stiffness",
                             value=k, bounds=(0.0, math.inf, True, False))
        if self.sun_axial == "free" and self.axial_slide != 0.0:
            raise InputError("herringbone: a free sun (sun_axial = \"free\") finds its own "
                             "axial position; an axial slide applies to a held sun")
        if self.sun_axial == "free" and k != math.inf:
            raise InputError(f"herringbone.axial_support_stiffness = {k:g} N/m applies to a "
                             "held sun (sun_axial = \"held\"); a free sun has no axial support")


def _stack_hertz(h: HertzLineContact | LeverScaled | TangencyContact
                 ) -> HertzLineContact | LeverScaled | TangencyContact:
    """The same local contact model on the points of both halves (2n,)."""
    if isinstance(h, LeverScaled):
        return LeverScaled(_stack_hertz(h.model), np.concatenate([h.lever, h.lever]))
    if isinstance(h, TangencyContact):
        return TangencyContact(_stack_hertz(h.base), np.concatenate([h.ratio, h.ratio]),
                               np.concatenate([h.offset, h.offset]))
    return HertzLineContact(*(np.concatenate([a, a]) for a in (
        h.slice_width, h.radius_1, h.radius_2, h.depth_1, h.depth_2)),
        h.material_1, h.material_2)


def herringbone_mesh_cycle(
    source: ComplianceSource,
    load: float,
    groove: GrooveFlankCoupling,
    n_planets: int,
    *,
    options: HerringboneOptions | None = None,
    modifications: FlankModifications | None = None,
    local: str = "weber",
    positions: int | ArrayLike = 60,
    tol: float = 1e-10,
    max_iter: int = 100,
    show_progress: bool = False,
) -> HerringboneCycle:
    """Loaded contact of a herringbone sun-planet mesh over a mesh cycle (module docstring).

    Parameters
    ----------
    source : compliance of ONE helical half of the sun-planet pair (sun = pinion), e.g.
        :func:`~pipeline.contact.analytical_compliance` of
        :func:`~pipeline.dynamics.models.planetary_gears.helical_half`.
    load : P, load of the whole mesh (both halves) along the transverse line of action, N
        (sun torque / (N r_b,sun)), > 0.
    groove : the sun halves' relative compliance (rigid, a torsion spring, or the FE).
    n_planets : N, planets loading the sun (1-64).
    options : torque entry and axial holding (default :class:`HerringboneOptions`).
    modifications, local, positions, tol, max_iter, show_progress : as for
        :func:`~pipeline.contact.loaded_mesh_cycle` (flank modifications apply to both
        halves alike; the sun turns).

    Returns
    -------
    HerringboneCycle

    Raises
    ------
    InputError for invalid inputs; ContactConvergenceError naming the position.
    """
    opts = options or HerringboneOptions()
    check_range("contact.load", load, 0.0, math.inf, lo_open=True, unit="N")
    check_choice("contact.local_contact", local, LOCAL_MODELS)
    N = check_int_range("planetary.planets", n_planets, 1, 64)
    mods = modifications or FlankModifications()
    pair = source.pair
    s0 = mesh_positions(pair, positions)
    rb = pair.pinion.base_radius
    t = math.tan(pair.pinion.base_helix_angle)
    f = TORQUE_ENTRIES[opts.torque_entry]
    C = groove.compliance
    za = opts.axial_slide
    ka = float(opts.axial_support_stiffness)
    c_hertz = hertz_compliance(pair.pinion, pair.gear)
    m = s0.size
    halves = {side: CycleRecorder(pair, m, source.tip_contact) for side in ("left", "right")}
    per = {n: np.zeros(m) for n in ("PL", "PR", "x", "k", "twist", "torque", "axial", "z")}
    for i in progress(range(m), "herringbone contact", total=m, enabled=show_progress):
        label = f"mesh position {i} (s0 = {s0[i] * 1e3:.6g} mm)"
        pts = source.points(float(s0[i]))
        n = len(pts)
        if n == 0:
            raise InputError(f"{label}: the compliance source gives no candidate points")
        G = np.asarray(source.matrix(float(s0[i])), dtype=float)
        eps = initial_separations(pair, pts, mods, candidate_range(pair, source.tip_contact))
        hertz = weber_model(pair, pts) if local == "weber" else None
        if local == "linear":
            G = G + np.diag(c_hertz / pts.width)
        G, eps, hertz, lever = along_line_of_action(pair, pts, G, eps, hertz)  # the sun turns
        if opts.sun_axial == "free":
            sol = solve_contact(G, eps, 0.5 * load, hertz, tol=tol, max_iter=max_iter,
                                label=label)
            check_tip_zone(eps, sol.loads, sol.approach, label)
            pL = pR = sol.loads
            x_half = (sol.approach, sol.approach)
            res, tol_i, newton = sol.residual, sol.tolerance, sol.newton_iterations
        else:
            # groove weights per point of each half: torque (w_t) and axial force (w_a)
            B = np.zeros((2, 2 * n))
            B[0, :n], B[0, n:] = rb * (1.0 - f), -rb * f
            B[1, :n], B[1, n:] = t * (1.0 - f), t * f
            v = np.concatenate([np.ones(n), -np.ones(n)])
            G2 = np.zeros((2 * n, 2 * n))
            G2[:n, :n] = G2[n:, n:] = G
            G2 += N * B.T @ C @ B
            if math.isfinite(ka):
                G2 += (N * t * t / ka) * np.outer(v, v)
            eps2 = np.concatenate([eps + t * za, eps - t * za])
            sol = solve_contact(G2, eps2, load, None if hertz is None else _stack_hertz(hertz),
                                tol=tol, max_iter=max_iter, label=label)
            check_tip_zone(eps2, sol.loads, sol.approach, label)
            pL, pR = sol.loads[:n], sol.loads[n:]
            res, tol_i, newton = sol.residual, sol.tolerance, sol.newton_iterations
            x_half = None
        PL, PR = float(pL.sum()), float(pR.sum())
        g = np.array([rb * ((1.0 - f) * PL - f * PR), t * ((1.0 - f) * PL + f * PR)])
        d = N * C @ g  # O_L relative to O_R: twist (rad), axial (m)
        shift_L = (1.0 - f) * (rb * d[0] + t * d[1])
        shift_R = f * (-rb * d[0] + t * d[1])
        if x_half is None:
            z = za + (N * t * (PL - PR) / ka if math.isfinite(ka) else 0.0)
            x = sol.approach
            x_half = (x - shift_L - t * z, x - shift_R + t * z)
            k_tot = sol.mesh_stiffness_tangent
        else:
            # free sun: x = a_L + shift_L + t z = a_R + shift_R - t z
            z = (x_half[1] + shift_R - x_half[0] - shift_L) / (2.0 * t) if t else 0.0
            x = x_half[0] + shift_L + t * z
            # P_L = P_R = P / 2 and the shifts are linear in P: dx/dP = (1/k_h + s/P) / 2
            k_tot = 2.0 / (1.0 / sol.mesh_stiffness_tangent + (shift_L + shift_R) / load)
        per["PL"][i], per["PR"][i], per["x"][i], per["k"][i] = PL, PR, x, k_tot
        per["twist"][i], per["torque"][i], per["axial"][i], per["z"][i] = (
            d[0], N * g[0], d[1], z)
        for side, p, xh in (("left", pL, x_half[0]), ("right", pR, x_half[1])):
            k = mesh_stiffnesses(G, p, xh, eps, None if local == "linear" else hertz)
            # gaps and local approaches along each point's own normal (ltca)
            u = (c_hertz / pts.width * p / lever if local == "linear"
                 else hertz.approach(p) * lever if hertz is not None else np.zeros_like(p))
            halves[side].add(i, pts, p, eps * lever, u, xh, k, (res, tol_i, newton), lever)
    return HerringboneCycle(
        left=halves["left"].cycle(s0, float(per["PL"].mean()), local),
        right=halves["right"].cycle(s0, float(per["PR"].mean()), local),
        load_left=per["PL"], load_right=per["PR"], approach=per["x"],
        mesh_stiffness=per["k"], groove_twist=per["twist"], groove_torque=per["torque"],
        groove_axial=per["axial"], sun_axial_position=per["z"], load=float(load),
        n_planets=N, base_radius=rb, base_helix_angle=pair.pinion.base_helix_angle,
        torque_entry=opts.torque_entry, sun_axial=opts.sun_axial, axial_slide=za,
        axial_support_stiffness=ka, groove_compliance=np.array(C),
    )
