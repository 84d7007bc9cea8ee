"""The shafts' deflection in a run: the loaded contact solved again with the misalignment
the shafts' deflection opens, until the line load stops changing.

For a pair whose gears sit on shafts (``[pinion.shaft]``, ``[gear.shaft]``;
:mod:`pipeline.config.shafts`), a fixed point over the line load ``w(z)`` across the face
(``[contact] slices`` face points):

1. start from the uniform line load ``P / b``;
2. load both shafts with it and take the gap they open across the face
   (:func:`pipeline.shaft.misalignment.shaft_gap`; its mean, a rigid approach of the gears
   that moves the transmission error only, taken out); a helical pair's axial force acts
   at each face slice's cycle-mean contact position along the line of action
   (:class:`~pipeline.shaft.misalignment.HelicalMesh`), the pitch point to start with;
3. solve the loaded contact with that gap added to the flank modifications
   (``FlankModifications.lead_gap``) and take its cycle-mean line load and, per face slice,
   the load-weighted mean roll coordinate of its contact points;
4. repeat from 2 until the line load changes by less than :data:`TOLERANCE` (largest change
   over the largest line load); after :data:`MAX_ITERATIONS` a one-line error names the
   iteration and the change.

The contact on rigid supports (the run's own cycle) is kept beside the coupled one. The
face positions ``z`` are the contact's; for a right-hand helical pinion they run against the
shafts' axial coordinate (:func:`pipeline.shaft.misalignment.seat_points`). ``[operation]
pinion_rotation`` and the driver pick the loaded flanks: the pinion driving clockwise seen
from the end the shafts' positions grow towards is the misalignment module's frame, the
other way its reflection (a helical mesh's hands reversed in the coupling).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from pipeline.config import Gearbox
from pipeline.contact.analysis import analyse_contact, line_of_action_load, warn_physics
from pipeline.contact.compliance import compliance_source
from pipeline.contact.distribution import load_distribution
from pipeline.contact.results import LoadedMeshCycle
from pipeline.progress import Steps
from pipeline.shaft.beam import BeamShaft
from pipeline.shaft.misalignment import FlankRetreat, HelicalMesh, seat_points, shaft_gap
from pipeline.validation import InputError

TOLERANCE = 1e-3
"""The fixed point's tolerance on the line load: largest change over its largest value."""
MAX_ITERATIONS = 40


@dataclass(frozen=True)
class ShaftStage:
    """The contact with the shafts' deflection.

    Attributes
    ----------
    cycle : the loaded contact with the shafts' misalignment.
    rigid : the loaded contact on rigid supports.
    z : (n,) face positions, m.
    gap : (n,) the misalignment the shafts open across the face (mean taken out), m.
    approach : the mean gap (the rigid approach of the gears), m.
    retreats : each gear's flank retreat (pinion, gear; None without a shaft).
    iterations : fixed-point iterations taken; change : the last relative change.
    mesh : a helical pair's mesh with the cycle-mean roll coordinates the last gap was
        computed with (None: spur).
    line_load : (n,) the line load the last gap was computed with, N/m (the cycle-mean one
        of the iteration before the last).
    reflected : the other flanks load the shafts (the pinion turning counterclockwise, or
        the gear driving; :mod:`pipeline.shaft.misalignment`): ``mesh`` is the reflected
        one (its pinion's hand reversed), the retreats' solutions the real shafts' motion.
    """

    cycle: LoadedMeshCycle
    rigid: LoadedMeshCycle
    z: np.ndarray
    gap: np.ndarray
    approach: float
    retreats: tuple[FlankRetreat | None, FlankRetreat | None]
    iterations: int
    change: float
    mesh: HelicalMesh | None = None
    line_load: np.ndarray | None = None
    reflected: bool = False

    def summary(self) -> dict[str, Any]:
        """The misalignment, the K_Hbeta with and without the shafts, each shaft's seat
        deflection and bearing reactions (SI; keys carry units)."""
        out: dict[str, Any] = {
            "iterations": self.iterations, "last_change": self.change,
            "misalignment_across_face_m": float(np.ptp(self.gap)),
            "rigid_approach_m": self.approach,
        }
        for i, (role, r) in enumerate(zip(("pinion", "gear"), self.retreats, strict=True)):
            if r is None or r.solution is None:
                continue
            sol = r.solution
            out[role] = {
                "seat_translation_m": [float(r.translation.min()), float(r.translation.max())],
                "seat_twist_at_base_circle_m": [float(r.twist.min()), float(r.twist.max())],
                "bearing_reactions_N": [[float(v) for v in row[:3]] for row in sol.reactions],
                "bearing_moments_Nm": [[float(v) for v in row[3:]] for row in sol.reactions],
                "torque_reaction_Nm": sol.torque_reaction,
            }
            if self.mesh is not None:
                out[role]["mesh_axial_force_N"] = self.mesh.axial_ratio(i) * self.cycle.load
        return out


    def deflection_columns(self) -> dict[str, np.ndarray]:
        """The deflection line of each shaft, for ``shaft_deflection.csv``: rows by shaft
        and position along it, in the shaft's mesh frame (y along the line of action, away
        from the mate; z along the shaft from its first end; :mod:`pipeline.shaft.misalignment`),
        m and rad."""
        parts = [(role, r.solution) for role, r in zip(("pinion", "gear"), self.retreats,
                                                       strict=True)
                 if r is not None and r.solution is not None]
        cols: dict[str, Any] = {"shaft": np.concatenate([[role] * s.z.size
                                                         for role, s in parts]),
                                "z_m": np.concatenate([s.z for _, s in parts])}
        for i, name in enumerate(("u_x_m", "u_y_line_of_action_m", "u_z_m")):
            cols[name] = np.concatenate([s.displacement[:, i] for _, s in parts])
        for i, name in enumerate(("theta_x_rad", "theta_y_rad", "theta_z_rad")):
            cols[name] = np.concatenate([s.rotation[:, i] for _, s in parts])
        return cols

    def face_columns(self) -> dict[str, np.ndarray]:
        """Across the face, for ``shaft_face.csv``: the contact's face position, the gap the
        shafts open (mean taken out), each gear's flank retreat and its parts (translation
        u_y, twist r_b theta_z, a helical mesh's axial terms), m; the line load the last gap
        was computed with, N/m."""
        cols: dict[str, np.ndarray] = {"face_position_m": self.z, "gap_m": self.gap}
        for role, r in zip(("pinion", "gear"), self.retreats, strict=True):
            if r is None:
                continue
            cols[f"{role}_retreat_m"] = r.total
            cols[f"{role}_translation_m"] = r.translation
            cols[f"{role}_twist_at_base_circle_m"] = r.twist
            if r.axial is not None:
                cols[f"{role}_axial_terms_m"] = r.axial
        if self.line_load is not None:
            cols["line_load_N_per_m"] = self.line_load
        return cols


def check_settling(iteration: int, change: float, what: str) -> None:
    """The fixed point's one-line error once ``iteration`` passes :data:`MAX_ITERATIONS`,
    naming the last relative ``change`` of the line load and ``what`` does not settle."""
    if iteration > MAX_ITERATIONS:
        raise InputError(f"shafts: the line load still changes by {change:.3g} (relative) "
                         f"after iteration {MAX_ITERATIONS}; {what} do not settle")


def shaft_model(spec: tuple[str, Any], nodes: Any = (), cache: Any = None) -> Any:
    """The shaft model a ``[<gear>.shaft]`` names, ``spec`` = (model, layout): the beam with
    extra nodes at ``nodes`` (m along the shaft), or the 3D superelement (read from or
    written to ``cache``)."""
    model, layout = spec
    if model == "fe3d":
        from pipeline.shaft.fe3d import Fe3dShaft

        return Fe3dShaft(layout) if cache is None else Fe3dShaft(layout, cache=cache)
    return BeamShaft(layout, extra_nodes=tuple(float(p) for p in nodes))


def seat_flexibility(spec: tuple[str, Any], cache: Any = None) -> np.ndarray:
    """(6, 6) the flexibility at the seat's centre of the shaft ``spec`` (bearings and the
    torque point as supports; m/N, rad/N m)."""
    layout = spec[1]
    return shaft_model(spec, (), cache).flexibility(np.array([layout.gear_position]))


def _face_model(spec: tuple[str, Any] | None, z: np.ndarray, cache: Any) -> Any:
    """A pair's shaft model with beam nodes at the contact's face points ``z`` (m from the
    face's first end); None without a shaft."""
    if spec is None:
        return None
    layout = spec[1]
    start = layout.gear_position - 0.5 * layout.seat_width
    return shaft_model(spec, start + z, cache)


def support_stiffness(box: Gearbox, cache: Any = None
                      ) -> tuple[tuple[float | None, float | None],
                                 tuple[float | None, float | None]]:
    """Each gear's support at its seat's centre from its shaft, None without a shaft:
    ((lateral pinion, gear), (torsional pinion, gear)).

    Lateral: N/m, bearings and shaft bending in series, the seat free to tilt: ``1 / C_yy``
    of the seat flexibility, the same in x and y for round shafts on round bearings.
    Torsional: N m/rad, the shaft's torsion between the seat's centre and the torque point,
    ``1 / C_theta_z theta_z``. The 3D superelement is read from or written to ``cache``.
    """
    lateral, torsional = [], []
    for role in ("pinion", "gear"):
        spec = box.shafts.get(role)
        if spec is None:
            lateral.append(None)
            torsional.append(None)
            continue
        c = seat_flexibility(spec, cache)
        lateral.append(float(1.0 / c[1, 1]))
        torsional.append(float(1.0 / c[5, 5]))
    return (lateral[0], lateral[1]), (torsional[0], torsional[1])


@dataclass(frozen=True)
class PositionMemo:
    """A compliance source that computes the candidate points and the compliance matrix of
    each mesh position once: every iteration of the fixed point solves the same positions
    on the same source (only the lead gap, outside the source, changes), and on the demo's
    pair with FE 2D contact rebuilding them (interpolated FE tables, the slices' friction
    change) took a third of an iteration. Returns copies, so a caller may change them.

    Attributes
    ----------
    base : the source (:class:`~pipeline.contact.source.ComplianceSource`).
    """

    base: Any
    _points: dict = field(default_factory=dict, repr=False, compare=False)
    _matrices: dict = field(default_factory=dict, repr=False, compare=False)

    @property
    def pair(self) -> Any:
        return self.base.pair

    @property
    def tip_contact(self) -> bool:
        return self.base.tip_contact

    def points(self, position: float) -> Any:
        if position not in self._points:
            self._points[position] = self.base.points(position)
        return self._points[position]

    def matrix(self, position: float) -> np.ndarray:
        if position not in self._matrices:
            self._matrices[position] = np.array(self.base.matrix(position), dtype=float)
        return self._matrices[position].copy()


def shaft_stage(box: Gearbox, stages: Any, options: Any, log: Steps) -> ShaftStage | None:
    """The :class:`ShaftStage` of a pair with shafts (module docstring), one timed step; None
    without shafts."""
    if box.kind != "pair" or not box.shafts:
        return None
    pair, op = stages.stiffness.actual, stages.case.operation
    n = box.contact.slices
    b = pair.face_width
    z = (np.arange(n) + 0.5) * b / n
    models = [_face_model(box.shafts.get(role), z, options.cache) for role in ("pinion", "gear")]
    reflected = (box.pinion_rotation == "counterclockwise") != (op.driver == "gear")
    mesh = (HelicalMesh.of(pair, np.full(n, pair.s_pitch), reflected)
            if pair.pinion.is_helical or pair.pinion.herringbone else None)
    flex = [None if m is None else m.flexibility(seat_points(m, z, mesh)) for m in models]
    radii = [pair.pinion.base_radius, pair.gear.base_radius]
    w = np.full(n, line_of_action_load(pair, op) / b)
    source, change, iteration = None, np.inf, 0
    with log.step("shaft deflection and loaded contact", announce=True) as note:
        while change >= TOLERANCE:
            iteration += 1
            check_settling(iteration, change, "the shafts and the mesh")
            gap, retreats = shaft_gap(models, radii, z, w, pair.pinion.helix_angle, flex,
                                      mesh)
            used, loaded = mesh, w
            approach = float(gap.mean())
            contact = box.mesh_contact(stages.case.name)
            mods = dataclasses.replace(contact.modifications,
                                       lead_gap=tuple(zip(z.tolist(),
                                                          (gap - approach).tolist(),
                                                          strict=True)))
            opts = dataclasses.replace(contact, modifications=mods)
            if source is None:
                source = PositionMemo(compliance_source(pair, op, opts, box.stiffness,
                                                        box.fe_source, cache=options.cache,
                                                        model=stages.stiffness.model))
            cycle = analyse_contact(source, op, opts, warn=False)
            dist = load_distribution(cycle, pair, op)
            w_new = np.interp(z, dist.z, dist.cycle_mean)
            change = float(np.abs(w_new - w).max() / np.abs(w_new).max())
            w = w_new
            if mesh is not None:
                mesh = dataclasses.replace(mesh, roll=mean_roll(cycle, b, n, pair.s_pitch))
        warn_physics(cycle)  # once, for the cycle the fixed point keeps
        note["text"] = (f"{iteration} iterations, misalignment {np.ptp(gap) * 1e6:.3g} um "
                        f"across the face, K_Hbeta {dist.k_hbeta:.3f}")
    if reflected:  # the shafts' motion in the real gearbox (misalignment module docstring)
        retreats = [r if r is None or r.solution is None
                    else dataclasses.replace(r, solution=r.solution.reflected())
                    for r in retreats]
    return ShaftStage(cycle, stages.contact, z, gap - approach, approach,
                      (retreats[0], retreats[1]), iteration, change, used, loaded, reflected)


def mean_roll(cycle: LoadedMeshCycle, face_width: float, n: int, empty: float
              ) -> np.ndarray:
    """(n,) the load-weighted mean roll coordinate ``s`` (m) of the contact points of each
    of ``n`` equal face slices over the cycle (the points binned by their face position);
    ``empty`` (m) for a slice that carries nothing."""
    iz = np.clip((cycle.point_z / (face_width / n)).astype(int), 0, n - 1)
    load = np.bincount(iz, weights=cycle.point_load, minlength=n)
    moment = np.bincount(iz, weights=cycle.point_load * cycle.point_s, minlength=n)
    out = np.full(n, float(empty))
    np.divide(moment, load, out=out, where=load > 0.0)
    return out
