"""Loaded tooth contact through a whole revolution, every tooth pair with its own errors.

The mesh-cycle contact (:func:`pipeline.contact.ltca.loaded_mesh_cycle`) assumes every
tooth pair alike. With per-tooth errors (:mod:`pipeline.contact.tooth_errors`: single
pitch deviations and runout of either gear) no two mesh cycles are alike, so the contact
is solved at ``m`` positions in each of the ``N`` mesh cycles of the span: the hunting
cycle (``N = LCM(z1, z2)``, after which the same teeth meet again) or one revolution of a
gear (``N = z``). Position ``j`` of cycle ``c`` lies at the roll coordinate
``s0_j + c p_bt`` (unrolled); there tooth pair ``k`` is at ``s0_j + k p_bt`` on the path,
as in every mesh cycle, and carries the gap of the flank modifications plus
:func:`~pipeline.contact.tooth_errors.pitch_gaps` of its two teeth and the
:func:`~pipeline.contact.tooth_errors.runout_gaps` of the instant.

What repeats and what does not. The candidate points, their compliance ``G``, the local
contact model and the gaps of the flank modifications depend only on the position in the
mesh cycle (``j``) and on the pair's geometry, so without runout they are built once per
``j`` (``m`` calls to the compliance source, as for one mesh cycle) and the errors change
only the gaps: the ``N m`` solves (:func:`~pipeline.contact.complementarity.solve_contact`)
are what repeats. Each solve is warm-started from the previous position's loads on the same
tooth pair (pairs keep their identity across cycles: pair ``k`` of cycle ``c`` is pair
``k + 1`` of cycle ``c + 1``). Without errors every cycle is the same problem, so the
revolution repeats the mesh cycle to round-off.

Runout. An eccentric gear's teeth are translated by ``e`` once per revolution
(:mod:`pipeline.contact.tooth_errors`): along the line of action that is a gap common to
every pair in mesh (:func:`~pipeline.contact.tooth_errors.runout_gaps`), which adds itself
to the transmission error and leaves the loads unchanged (the conditions of
:mod:`pipeline.contact.complementarity` hold with ``eps + d`` and ``x_s + d``); along the
line of centres it changes the centre distance by ``delta_a``
(:func:`~pipeline.contact.tooth_errors.centre_distance_change`), and with it the pressure
angle, the path of contact and the contact ratio; across it, it turns the line of centres
(:func:`~pipeline.contact.tooth_errors.centre_line_turn`), which moves the contact along
the path at a given pinion angle. Both modulate the mesh harmonics: sidebands at the mesh
orders +- 1. Each mesh cycle ``c`` is solved quasi-statically on the
pair at the centre distance ``a + delta_a_c`` of the cycle's middle, per cycle rather than
per position because each new pair costs its tip-contact zone (about 7 ms on the demo
pair), ``N`` times instead of ``N m``. The once-per-revolution modulation is then a
staircase of ``N`` steps. For a pinion runout its sidebands at ``z1 +- 1`` are ``e |sum_j
(D_j +- i r_b1 S_j / a) exp(-2 pi i j (1 +- 1/N) / m)| / m`` (``D_j`` and ``S_j`` the TE's
derivatives by ``a`` and by ``s0`` at position ``j``; derived in
``tests/test_contact_revolution.py``), within a few per cent of the smooth modulation's
``|dC_1/da -+ z1 C_1 / a| e / 2`` (``C_1`` the complex first mesh-order harmonic; +0.9 %
and -0.2 % on the demo pair with tip reliefs at 20 % load, sidebands of 6.2 and 2.7 nm).
The positions ``s0_j`` are moved by :func:`~pipeline.contact.tooth_errors.roll_shift`
(the contact at the same pinion angle on that pair with its line of centres turned), and
the common gap is kept. The compliance source is the same gears' at the new centre
distance (:func:`at_centre_distance`): the analytical
slices' tooth models and the FE sources' influence tables belong to each gear alone (as
when a design study reuses FE tables, :func:`pipeline.contact.compliance.
compliance_source`), so they are reused and only the pair, hence where each contact point
lies on the flanks, changes. The points, ``G`` and the local model are then built at all
``N m`` positions instead of ``m``; without eccentricity the rigid-offset-only problem
above is what remains. Position ``j = 0`` lies exactly at the start of the path of
contact, where the contact model's TE steps when no relief keeps the entering pair
unloaded (corner contact before ``s_start``, path contact from it: 0.54 um on the demo
pair at full load without relief); a runout moves the path's start past that sample
whatever its size, so that sample shows the whole step once per revolution. With tip
relief the entering pair carries nothing there and the TE is continuous.

Pitch deviations differ from pair to pair and redistribute the load.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from pipeline.contact.complementarity import solve_contact
from pipeline.contact.hertz import LocalCompliance
from pipeline.contact.ltca import (
    LOCAL_MODELS,
    along_line_of_action,
    check_tip_zone,
    mesh_positions,
    weber_model,
)
from pipeline.contact.recording import CycleRecorder
from pipeline.contact.revolution_results import LoadedRevolution
from pipeline.contact.separations import FlankModifications, initial_separations
from pipeline.contact.source import (
    ComplianceSource,
    ContactPoints,
    FrictionCorrected,
    SliceCompliance,
    candidate_range,
)
from pipeline.contact.tooth_errors import (
    ToothErrors,
    centre_distance_change,
    centre_line_turn,
    pitch_gaps,
    roll_shift,
    runout_gaps,
    tooth_offsets,
)
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import tip_contact
from pipeline.progress import progress
from pipeline.stiffness.tooth import hertz_compliance
from pipeline.validation import InputError, check_choice, check_int_range, check_range

MAX_POSITIONS = 100_000
"""Most positions of a full-revolution contact (mesh cycles x positions per cycle): about
3 min for the demo pair with a runout at the 1.6-1.7 ms per position of
``workflows/benchmarks/bench_revolution.py`` (2 shared cores; 0.9 ms without a runout,
whose positions share their setup)."""
MAX_POINT_RECORDS = 10_000_000
"""Most candidate points over all positions: the result keeps 12 numbers per point (about
1 GB at this many)."""


@dataclass(frozen=True)
class _Phase:
    """What one position in the mesh cycle gives every cycle: points, the problem along
    the line of action (``G``, local model, lever factors ``a``), the modifications' gaps
    ``eps`` (m) and, for the linear local model, its compliance ``c_lin`` (m/N)."""

    points: ContactPoints
    G: np.ndarray
    hertz: LocalCompliance | None
    lever: np.ndarray
    eps: np.ndarray
    c_lin: np.ndarray | None
    levers: tuple[np.ndarray, np.ndarray]

    def error_gaps(self, pair: GearPair, errors: ToothErrors, cycle: int,
                   runout: tuple[float, float],
                   offsets: tuple[np.ndarray, np.ndarray]) -> np.ndarray:
        """Gaps of the points from both gears' errors in mesh cycle ``cycle`` (m, along
        each point's contact normal), with the runout gaps ``runout`` of the instant and the
        teeth's pitch ``offsets`` (:func:`~pipeline.contact.tooth_errors.tooth_offsets`)."""
        g1, g2 = pitch_gaps(pair, errors, cycle, self.points.pair, offsets)
        return (g1 + runout[0]) * self.levers[0] + (g2 + runout[1]) * self.levers[1]


def _phase(source: ComplianceSource, s0: float, mods: FlankModifications, local: str,
           driver: str, c_hertz: float) -> _Phase:
    pair = source.pair
    pts = source.points(s0)
    if len(pts) == 0:
        raise InputError(f"mesh position s0 = {s0 * 1e3:.6g} mm: the compliance source gives "
                         "no candidate points")
    G = np.asarray(source.matrix(s0), dtype=float)
    eps = initial_separations(pair, pts, mods, candidate_range(pair, source.tip_contact))
    hertz = c_lin = None
    if local == "weber":
        hertz = weber_model(pair, pts)
    elif local == "linear":
        c_lin = c_hertz / pts.width
        G = G + np.diag(c_lin)
    # eps is scaled by the lever per position (errors added first): pass zeros here
    Gt, _, hertz, lever = along_line_of_action(pair, pts, G, np.zeros(len(pts)), hertz, driver)
    tc = tip_contact(pair, pts.s)
    return _Phase(pts, Gt, hertz, lever, eps, c_lin, (tc.lever_pinion, tc.lever_gear))


def at_centre_distance(source: ComplianceSource, pair: GearPair) -> ComplianceSource:
    """``source`` for the same gears at the centre distance of ``pair`` (module docstring):
    analytical slices with their tooth models, an FE source with its influence tables, a
    friction-corrected source with both parts."""
    if isinstance(source, SliceCompliance):
        return dataclasses.replace(source, model=dataclasses.replace(source.model, pair=pair))
    if isinstance(source, FrictionCorrected):
        return dataclasses.replace(source, base=at_centre_distance(source.base, pair),
                                   slices=at_centre_distance(source.slices, pair))
    if dataclasses.is_dataclass(source) and "pair" in {f.name for f in
                                                        dataclasses.fields(source)}:
        return dataclasses.replace(source, pair=pair)
    raise InputError(f"contact.errors: a runout changes the centre distance, which the "
                     f"{type(source).__name__} compliance source cannot take; give "
                     "eccentricity_pinion_um = eccentricity_gear_um = 0")


def _runout_source(source: ComplianceSource, nominal: GearPair, delta_a: float,
                   turn: float) -> tuple[ComplianceSource, float]:
    """``source`` on the pair at centre distance ``a + delta_a`` (m) and how much further
    along the path that pair touches at the same pinion angle (m), its line of centres
    turned by ``turn`` (rad)."""
    pair = GearPair(nominal.pinion, nominal.gear,
                    centre_distance=nominal.operating_centre_distance + delta_a)
    if not np.array_equal(pair.pair_indices(source.tip_contact),
                          nominal.pair_indices(source.tip_contact)):
        raise InputError(f"contact.errors: the runout changes the centre distance by "
                         f"{delta_a * 1e6:.4g} um, which changes how many tooth pairs can "
                         "touch at once (the contact ratio crosses a whole number); the "
                         "full-revolution contact keeps the tooth pairs of the nominal pair")
    return at_centre_distance(source, pair), roll_shift(nominal, pair, turn)


def revolution_size(errors: ToothErrors, pair: GearPair, positions: int) -> tuple[int, int]:
    """(mesh cycles, positions in all) of the span, refused above :data:`MAX_POSITIONS`
    (the message names the shorter spans when there are any)."""
    cycles = errors.mesh_cycles(pair)
    total = cycles * positions
    if total > MAX_POSITIONS:
        z = {"pinion": pair.pinion.teeth, "gear": pair.gear.teeth}
        shorter = [f'"{k}" ({n} mesh cycles)' for k, n in z.items() if n < cycles]
        raise InputError(
            f"contact.errors.span = \"{errors.span}\" is {cycles} mesh cycles x "
            f"contact.positions = {positions} = {total} contact solves, more than "
            f"{MAX_POSITIONS} (minutes of solves): give fewer positions per mesh cycle"
            + (f" or span = {' or '.join(shorter)}, one revolution" if shorter else ""))
    return cycles, total


def _keys(cycle: int, points: ContactPoints) -> np.ndarray:
    """Identity of each point across cycles: the tooth pair's meshing number ``c - k``
    and the face position (to 1 nm)."""
    n = cycle - points.pair.astype(np.int64)
    return n * (1 << 32) + np.round(points.z * 1e9).astype(np.int64)


def _warm_start(prev: tuple[np.ndarray, np.ndarray] | None,
                keys: np.ndarray) -> np.ndarray | None:
    if prev is None or not prev[1].any():
        return None
    _, i_new, i_old = np.intersect1d(keys, prev[0], return_indices=True)
    start = np.zeros(keys.size)
    start[i_new] = prev[1][i_old]
    return start if start.any() else None


def loaded_revolution(
    source: ComplianceSource,
    load: float,
    errors: ToothErrors,
    modifications: FlankModifications | None = None,
    local: str = "weber",
    positions: int = 60,
    *,
    driver: str = "pinion",
    tol: float = 1e-10,
    max_iter: int = 100,
    show_progress: bool = False,
) -> LoadedRevolution:
    """Loads and transmission error at ``positions`` positions of every mesh cycle of the
    span of ``errors`` (module docstring).

    Parameters
    ----------
    source : compliance source of the pair (built once; only its ``m`` positions of one
        mesh cycle are asked for).
    load : P along the transverse line of action, N, > 0.
    errors : per-tooth errors of both gears and the span.
    modifications : flank modifications of every tooth (their ``pitch_errors`` per pair of
        one mesh cycle must be empty: the per-tooth errors replace them).
    local : local contact model (:data:`~pipeline.contact.ltca.LOCAL_MODELS`).
    positions : positions per mesh cycle, >= 1.
    driver, tol, max_iter : as for :func:`~pipeline.contact.ltca.loaded_mesh_cycle`.
    show_progress : progress bar on stderr.
    """
    check_range("contact.load", load, 0.0, math.inf, lo_open=True, unit="N")
    check_choice("contact.local_contact", local, LOCAL_MODELS)
    mods = modifications or FlankModifications()
    if mods.pitch_errors:
        raise InputError("contact.pitch_errors_um offsets the tooth pairs of one mesh cycle; "
                         "with [contact.errors] give the teeth's own deviations "
                         "(single_pitch_pinion_um, single_pitch_gear_um) instead")
    pair = source.pair
    errors.check_pair(pair)
    check_int_range("contact.positions", positions, 1, 1_000_000)
    s0 = mesh_positions(pair, int(positions))
    m = s0.size
    cycles, total = revolution_size(errors, pair, m)
    c_hertz = hertz_compliance(pair.pinion, pair.gear)
    first = _phase(source, float(s0[0]), mods, local, driver, c_hertz)
    records = total * len(first.points)  # refused before the other phases are built
    if records > MAX_POINT_RECORDS:
        raise InputError(
            f"contact.errors.span = \"{errors.span}\": {cycles} mesh cycles of {m} positions "
            f"with {len(first.points)} candidate points each keep about {records} point "
            f"records, more than {MAX_POINT_RECORDS} (about 1 GB): give fewer "
            "contact.positions or contact.slices, or a shorter span")
    cycle_of = np.repeat(np.arange(cycles), m)
    roll = cycle_of * pair.base_pitch + np.tile(s0 - s0[0], cycles)
    runout = runout_gaps(pair, errors, roll)
    eccentric = bool(errors.pinion.eccentricity or errors.gear.eccentricity)
    middle = np.arange(cycles) * pair.base_pitch + float(np.mean(s0 - s0[0]))
    delta_a = centre_distance_change(pair, errors, middle) if eccentric else np.zeros(cycles)
    turn = centre_line_turn(pair, errors, middle)
    phases = [] if eccentric else [first] + [
        _phase(source, float(s), mods, local, driver, c_hertz) for s in s0[1:]]
    offsets = tooth_offsets(pair, errors)
    record = CycleRecorder(pair, total, source.tip_contact)
    prev = None
    for i in progress(range(total), "revolution contact", total=total, enabled=show_progress):
        c = int(cycle_of[i])
        if eccentric:
            if i % m == 0:
                src, shift = _runout_source(source, pair, float(delta_a[c]), float(turn[c]))
                record.pair = src.pair  # it places the points' corners and curvatures
            ph = _phase(src, float(s0[i % m]) + shift, mods, local, driver, c_hertz)
        else:
            ph = phases[i % m]
        label = f"mesh cycle {c}, position {i % m} (s0 = {s0[i % m] * 1e3:.6g} mm)"
        eps = ph.eps + ph.error_gaps(pair, errors, c, (runout[0][i], runout[1][i]), offsets)
        eps_t = eps / ph.lever
        keys = _keys(c, ph.points)
        sol = solve_contact(ph.G, eps_t, load, ph.hertz, tol=tol, max_iter=max_iter,
                            start=_warm_start(prev, keys), label=label)
        check_tip_zone(eps_t, sol.loads, sol.approach, label)
        prev = (keys, sol.loads)
        u = (sol.contact_deformation * ph.lever if ph.c_lin is None
             else ph.c_lin * sol.loads / ph.lever)
        record.add(i, ph.points, sol.loads, eps, u, sol.approach,
                   (sol.mesh_stiffness_tangent, sol.mesh_stiffness_secant,
                    sol.mesh_stiffness_pointwise),
                   (sol.residual, sol.tolerance, sol.newton_iterations), ph.lever)
    contact = record.cycle(s0[0] + roll, load, local)
    return LoadedRevolution(contact=contact, mesh_cycles=cycles, positions_per_cycle=m,
                            teeth=np.array([pair.pinion.teeth, pair.gear.teeth]),
                            span=errors.span, runout_gap=runout[0] + runout[1],
                            centre_distance_change=np.repeat(delta_a, m))
