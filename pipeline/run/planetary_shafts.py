"""The shafts of a planetary set in a run: the sun's shaft and the planets' pins deflect under
both meshes, and both loaded contacts are solved again with the misalignment they open.

What is modelled (spur sets; a helical or herringbone set with shafts is refused where the
file is read, :func:`pipeline.config.gearbox._shafts`):

* the sun on its own shaft (``[sun.shaft]``, beam or 3D superelement) loaded by all ``N``
  sun-planet meshes at once, each the first one turned by ``psi_n - psi_0`` about the sun's
  axis (:func:`pipeline.shaft.misalignment.rotated_unit_loads`). With equally spaced planets
  their forces cancel and only the moments about the axis remain, so what opens a
  misalignment is the sun's twist across its face (an ``"integral"`` seat: a sun cut on its
  shaft; a rigid seat turns as a whole and opens none); the run does not assume the
  cancellation: it loads the sun's model with every mesh and reports the net transverse
  force (zero to round-off for equal spacing). With unequal spacing the meshes see different
  gaps; the contact, which stands for every planet, takes the planet whose gap varies most
  across the face, and the others' are reported;
* each planet on its pin (``[planet.shaft]``, a Timoshenko beam in the carrier's cheeks:
  :func:`pipeline.config.shafts.pin_layout`), loaded by the sun-planet and the planet-ring
  line loads along their lines of action at their transverse operating pressure angles
  (:func:`pipeline.shaft.misalignment.planet_unit_loads`); the planet turns freely on its
  pin (no torque on the pin) and moves with the pin's seat as a rigid body; its bearing's
  radial give (``planet_bearing_radial_stiffness_N_per_m``) moves it uniformly, an approach
  only. Every planet's pin is the same and loaded alike, so one pin stands for all;
* the ring held by the housing and the carrier rigid.

The beam takes a sun's sections as plane, so its twist across the face is that of a shaft
of the seat's diameter. That holds for a sun cut on a shaft of about its root diameter:
the example's (112.5 mm, integral seat, four planets at a uniform 74 N/mm) twists by
0.32 um across the face at the base circle in the beam and 0.27 um in the 3D
superelement. On a smaller journal the sun's body is a disc whose rim twists far less than
its sections would (the torque crosses the disc towards the journal): on 80 mm journals
0.32 um (beam) against 0.10 um (3D; tests/test_run_planetary_shafts.py measures both
cases), on 50 mm journals against 0.005 um (measured once, in a run). Give such a sun
``model = "fe3d"``.

The gap of the sun-planet mesh is the sun's retreat plus the planet's along that mesh, the
planet-ring mesh's the planet's alone (:func:`pipeline.shaft.misalignment.body_retreats`);
each face's points are centred on its gear's seat (``gear_position + z - b / 2``, ``z`` the
contact's face position over the mesh's face width ``b``). The fixed point is the pair's
(:mod:`pipeline.run.shafts`) over both meshes together: start from the uniform line loads,
load the sun and the pin with both, solve both contacts with the gaps (mean taken out) as
``FlankModifications.lead_gap`` of each mesh's own contact options (its gears' flank
modifications, :meth:`~pipeline.config.gearbox.Gearbox.mesh_contact`), and repeat until
neither line load changes by more than :data:`~pipeline.run.shafts.TOLERANCE` (largest
change over the largest value, the larger of the two meshes); after
:data:`~pipeline.run.shafts.MAX_ITERATIONS` a one-line error names the iteration and the
change.

Dynamics (:func:`support_stiffness`): the sun's support is its shaft at the seat's centre
(bearings and bending in series, ``1 / C_yy``), a planet's the pin's at its seat in series
with the planet bearing, ``1 / (C_yy + 1 / k_pb)``; they replace ``[dynamics]``
``sun_bearing_stiffness_N_per_m`` and ``planet_bearing_stiffness_N_per_m``, which are then
refused.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.config import Gearbox
from pipeline.contact.analysis import analyse_contact, line_of_action_load, warn_physics
from pipeline.contact.compliance import compliance_source
from pipeline.contact.distribution import load_distribution
from pipeline.contact.results import LoadedMeshCycle
from pipeline.progress import Steps
from pipeline.run.shafts import TOLERANCE, check_settling, seat_flexibility, shaft_model
from pipeline.shaft.misalignment import (
    body_retreats,
    planet_unit_loads,
    rotated_unit_loads,
    unit_loads,
)
from pipeline.shaft.model import PointLoad, ShaftModel, ShaftSolution

MESHES = ("sun_planet", "planet_ring")


@dataclass(frozen=True)
class SunDeflection:
    """The sun's shaft under every sun-planet mesh.

    Attributes
    ----------
    solution : deflection line and bearing reactions, in the frame of the first planet's
        mesh (``y`` along its line of action away from the planet).
    displacement : (n, 6) at the face points (m, rad).
    retreats : (N, n) each planet's sun-planet flank retreat, m.
    planet : the planet whose gap the contact takes (largest variation across the face).
    net_force : the net transverse force of all meshes on the sun, N (0 for equal spacing).
    base_radius : the sun's, m.
    direction : (6,) that planet's mesh's unit load: its retreat is ``direction . (u,
        theta)`` at any section of the seat (N/N, N m/N).
    """

    solution: ShaftSolution | None
    displacement: np.ndarray
    retreats: np.ndarray
    planet: int
    net_force: float
    base_radius: float
    direction: np.ndarray


@dataclass(frozen=True)
class PinDeflection:
    """A planet's pin under both of its meshes (frame: ``x`` along the orbit's tangent,
    ``y`` radially out).

    Attributes
    ----------
    solution : the pin's deflection line and the reactions of its supports.
    displacement : (n, 6) at the planet's face points, m, rad.
    retreats : the planet's flank retreat (n,) along each mesh, by mesh name, m.
    bearing : the planet bearing's uniform retreat along each mesh, m (0: rigid).
    directions : (6,) each mesh's unit load on the pin, by mesh name.
    """

    solution: ShaftSolution | None
    displacement: np.ndarray
    retreats: Mapping[str, np.ndarray]
    bearing: Mapping[str, float]
    directions: Mapping[str, np.ndarray]


@dataclass(frozen=True)
class PlanetaryShafts:
    """Both meshes of a planetary set solved with the sun's and the pins' deflection.

    Attributes
    ----------
    z : face positions of each mesh, (n,) m, by mesh name.
    cycles : the loaded contact with the shafts, by mesh name; rigid : on rigid supports.
    gaps : (n,) the misalignment each mesh's gap opens across its face (mean out), m.
    approaches : each gap's mean, m.
    line_loads : the cycle-mean line loads (n,) N/m the last gaps were computed with.
    k_hbeta : (rigid, with the shafts) K_Hbeta of each mesh, -.
    sun, pin : the sun's and the pin's deflection (None without that shaft).
    iterations, change : fixed-point iterations and the last relative change.
    """

    z: Mapping[str, np.ndarray]
    cycles: Mapping[str, LoadedMeshCycle]
    rigid: Mapping[str, LoadedMeshCycle]
    gaps: Mapping[str, np.ndarray]
    approaches: Mapping[str, float]
    line_loads: Mapping[str, np.ndarray]
    k_hbeta: Mapping[str, tuple[float, float]]
    sun: SunDeflection | None
    pin: PinDeflection | None
    iterations: int
    change: float

    def mesh(self, name: str) -> PlanetaryMeshShafts:
        """What mesh ``name`` of the run keeps (:class:`PlanetaryMeshShafts`)."""
        return PlanetaryMeshShafts(name, self)


@dataclass(frozen=True)
class PlanetaryMeshShafts:
    """One mesh's view of :class:`PlanetaryShafts` (the run's ``MeshStages.shafts``)."""

    name: str
    system: PlanetaryShafts

    @property
    def cycle(self) -> LoadedMeshCycle:
        return self.system.cycles[self.name]

    @property
    def rigid(self) -> LoadedMeshCycle:
        return self.system.rigid[self.name]

    @property
    def z(self) -> np.ndarray:
        return self.system.z[self.name]

    @property
    def gap(self) -> np.ndarray:
        return self.system.gaps[self.name]

    @property
    def approach(self) -> float:
        return self.system.approaches[self.name]

    @property
    def iterations(self) -> int:
        return self.system.iterations

    def deflection_lines(self) -> list[tuple[str, np.ndarray, np.ndarray]]:
        """(name, z m, retreat m) along each shaft that moves this mesh's flanks: the
        retreat along this mesh's line of action of every section, ``L . (u, theta)`` (the
        sun's with its twist at the base circle), over the whole shaft."""
        out = []
        sun, pin = self.system.sun, self.system.pin
        if sun is not None and sun.solution is not None and self.name == "sun_planet":
            sol = sun.solution
            out.append(("sun", sol.z, np.c_[sol.displacement, sol.rotation] @ sun.direction))
        if pin is not None and pin.solution is not None:
            sol = pin.solution
            out.append(("planet pin", sol.z,
                        np.c_[sol.displacement, sol.rotation] @ pin.directions[self.name]))
        return out

    def deflection_columns(self) -> dict[str, np.ndarray]:
        """The deflection line of each shaft that moves this mesh's flanks, for
        ``shaft_deflection.csv``: rows by shaft and position along it, m and rad, in the
        shaft's frame (the sun's: its first planet's mesh frame, y along that line of action
        away from the planet; a pin's: x along the orbit's tangent, y radially out; z along
        the shaft from its first end), with each section's retreat along this mesh's line
        of action."""
        sun, pin = self.system.sun, self.system.pin
        parts = []
        if sun is not None and sun.solution is not None and self.name == "sun_planet":
            parts.append(("sun", sun.solution, sun.direction))
        if pin is not None and pin.solution is not None:
            parts.append(("planet pin", pin.solution, pin.directions[self.name]))
        cols: dict[str, Any] = {"shaft": np.concatenate([[n] * s.z.size for n, s, _ in parts]),
                                "z_m": np.concatenate([s.z for _, s, _ in parts])}
        for i, name in enumerate(("u_x_m", "u_y_m", "u_z_m")):
            cols[name] = np.concatenate([s.displacement[:, i] for _, s, _ in parts])
        for i, name in enumerate(("theta_x_rad", "theta_y_rad", "theta_z_rad")):
            cols[name] = np.concatenate([s.rotation[:, i] for _, s, _ in parts])
        cols["retreat_along_line_of_action_m"] = np.concatenate(
            [np.c_[s.displacement, s.rotation] @ d for _, s, d in parts])
        return cols

    def face_columns(self) -> dict[str, np.ndarray]:
        """Across this mesh's face, for ``shaft_face.csv``: the face position, the gap (mean
        taken out), the sun's retreat at the planet the contact takes and the planet's
        retreat on its pin (with its bearing's), m; the line load the last gap was computed
        with, N/m."""
        s = self.system
        cols: dict[str, np.ndarray] = {"face_position_m": self.z, "gap_m": self.gap}
        if s.sun is not None and self.name == "sun_planet":
            cols["sun_retreat_m"] = s.sun.retreats[s.sun.planet]
        if s.pin is not None:
            cols["planet_retreat_m"] = s.pin.retreats[self.name]
        cols["line_load_N_per_m"] = s.line_loads[self.name]
        return cols

    def summary(self) -> dict[str, Any]:
        """This mesh's misalignment and K_Hbeta with and without the shafts, the sun's and
        the pin's deflection (SI; keys carry units)."""
        s = self.system
        k_rigid, k_shafts = s.k_hbeta[self.name]
        out: dict[str, Any] = {
            "iterations": s.iterations, "last_change": s.change,
            "misalignment_across_face_m": float(np.ptp(self.gap)),
            "rigid_approach_m": self.approach,
            "k_hbeta_rigid": k_rigid, "k_hbeta_shafts": k_shafts,
        }
        if s.sun is not None and self.name == "sun_planet":
            sun = s.sun
            out["sun"] = {
                "net_transverse_force_N": sun.net_force,
                "seat_translation_max_m": float(np.hypot(sun.displacement[:, 0],
                                                         sun.displacement[:, 1]).max()),
                "seat_twist_at_base_circle_m": [
                    float(v * sun.base_radius) for v in (sun.displacement[:, 5].min(),
                                                         sun.displacement[:, 5].max())],
                "misalignment_by_planet_m": [float(np.ptp(r)) for r in sun.retreats],
                "planet_in_contact": sun.planet,
                "bearing_reactions_N": [[float(v) for v in row[:3]]
                                        for row in sun.solution.reactions],
                "torque_reaction_Nm": sun.solution.torque_reaction,
            }
        if s.pin is not None:
            pin = s.pin
            d = pin.displacement
            out["planet_pin"] = {
                "seat_deflection_tangential_radial_m": [float(d[:, 0].mean()),
                                                        float(d[:, 1].mean())],
                "seat_tilt_about_tangent_radius_rad": [float(d[0, 3]), float(d[0, 4])],
                "planet_retreat_across_face_m": float(np.ptp(pin.retreats[self.name])),
                "planet_bearing_retreat_m": pin.bearing[self.name],
                "support_reactions_N": [[float(v) for v in row[:3]]
                                        for row in pin.solution.reactions],
            }
        return out


def face_points(lay: Any, face_width: float, n: int) -> tuple[np.ndarray, np.ndarray]:
    """(z, points): the contact's ``n`` face-slice centres ``z`` over ``face_width`` (m) and
    where they lie on a shaft of layout ``lay``, centred on its seat (m)."""
    z = (np.arange(n) + 0.5) * face_width / n
    return z, lay.gear_position + z - 0.5 * face_width


def sun_unit_loads(base_radius: float, angles: Sequence[float], n: int) -> list[np.ndarray]:
    """Each sun-planet mesh's unit loads (n, 6) on the sun in the first mesh's frame: the
    pair's ``(0, 1, 0, 0, 0, r_b)`` turned by ``psi_k - psi_0`` (module docstring)."""
    base = unit_loads(base_radius, n)
    return [rotated_unit_loads(base, float(a - angles[0])) for a in angles]


@dataclass(frozen=True)
class LoadedShaft:
    """A shaft (the sun's, a pin) with the meshes that load it, built once per fixed point.

    Attributes
    ----------
    model : the shaft's model.
    points : (p,) the shaft positions of every face point of its meshes, m.
    flexibility : (6p, 6p) the model's flexibility there.
    cases : per load case ``(mesh name, unit loads (n, 6), index (n,) of the mesh's face
        points in ``points``)``: the sun has one case per planet (all "sun_planet"), a pin
        one per mesh.
    """

    model: ShaftModel
    points: np.ndarray
    flexibility: np.ndarray
    cases: tuple[tuple[str, np.ndarray, np.ndarray], ...]

    def loads(self, forces: Mapping[str, np.ndarray]) -> list[np.ndarray]:
        """Each case's force (p,) on the shaft's points from its mesh's slice forces, N."""
        out = []
        for mesh, _, index in self.cases:
            f = np.zeros(self.points.size)
            f[index] = forces[mesh]
            out.append(f)
        return out

    def units(self) -> list[np.ndarray]:
        """Each case's unit loads (p, 6) on the shaft's points (zero off its mesh's)."""
        out = []
        for _, unit, index in self.cases:
            u = np.zeros((self.points.size, 6))
            u[index] = unit
            out.append(u)
        return out

    def deflect(self, forces: Mapping[str, np.ndarray]) -> tuple[np.ndarray, list[np.ndarray]]:
        """(d, retreats): the displacements (p, 6) under every case and each case's retreat
        (n,) at its mesh's face points (:func:`~pipeline.shaft.misalignment.body_retreats`),
        m."""
        d, ret = body_retreats(self.flexibility, self.units(), self.loads(forces))
        return d, [r[index] for r, (_, _, index) in zip(ret, self.cases, strict=True)]

    def solve(self, forces: Mapping[str, np.ndarray]) -> ShaftSolution:
        """The shaft's deflection line and reactions under every case."""
        total = sum(u * f[:, None] for u, f in zip(self.units(), self.loads(forces),
                                                    strict=True))
        return self.model.solve([PointLoad(float(p), tuple(float(v) for v in row[:3]),
                                           tuple(float(v) for v in row[3:]))
                                 for p, row in zip(self.points, total, strict=True)])


@dataclass(frozen=True)
class ShaftSystem:
    """The sun's and the pin's loaded shafts of a planetary set and its meshes' faces.

    Attributes
    ----------
    z : each mesh's face positions (n,), m, by mesh name.
    widths : each mesh's face width, m.
    sun, pin : the loaded shafts (:class:`LoadedShaft`), None without one.
    k_bearing : the planet bearing's radial stiffness, N/m (``inf``: rigid).
    base_radius : the sun's base radius, m.
    """

    z: Mapping[str, np.ndarray]
    widths: Mapping[str, float]
    sun: LoadedShaft | None
    pin: LoadedShaft | None
    k_bearing: float
    base_radius: float

    def forces(self, w: Mapping[str, np.ndarray]) -> dict[str, np.ndarray]:
        """Each mesh's force per face slice (n,), N, from its line load (N/m)."""
        return {m: np.asarray(w[m]) * self.widths[m] / w[m].size for m in MESHES}

    def deflect(self, w: Mapping[str, np.ndarray]
                ) -> tuple[dict[str, np.ndarray], SunDeflection | None, PinDeflection | None]:
        """The gaps (n,) of both meshes (m, mean kept) under line loads ``w`` and the sun's
        and the pin's deflection (their ``solution`` not yet computed: None)."""
        f = self.forces(w)
        gaps = {m: np.zeros(self.z[m].size) for m in MESHES}
        pin = None
        if self.pin is not None:
            d, ret = self.pin.deflect(f)
            directions = {m: unit[0] for m, unit, _ in self.pin.cases}
            net = sum(directions[m][:2] * f[m].sum() for m in MESHES)
            bearing = {m: (0.0 if math.isinf(self.k_bearing)
                           else float(directions[m][:2] @ net) / self.k_bearing)
                       for m in MESHES}
            retreats = {m: r + bearing[m] for (m, _, _), r in zip(self.pin.cases, ret,
                                                                   strict=True)}
            for m in MESHES:
                gaps[m] = gaps[m] + retreats[m]
            index = self.pin.cases[0][2]
            pin = PinDeflection(None, d[index], retreats, bearing, directions)
        sun = None
        if self.sun is not None:
            d, ret = self.sun.deflect(f)
            ret = np.array(ret)
            k = int(np.argmax([np.ptp(r + gaps["sun_planet"]) for r in ret]))
            net = float(np.hypot(*sum(unit[:, :2].T @ f["sun_planet"]
                                      for _, unit, _ in self.sun.cases)))
            gaps["sun_planet"] = gaps["sun_planet"] + ret[k]
            sun = SunDeflection(None, d, ret, k, net, self.base_radius,
                                self.sun.cases[k][1][0])
        return gaps, sun, pin

    def solved(self, w: Mapping[str, np.ndarray], sun: SunDeflection | None,
               pin: PinDeflection | None) -> tuple[SunDeflection | None, PinDeflection | None]:
        """``sun`` and ``pin`` with their shafts' solutions (deflection lines, reactions)
        under ``w``."""
        f = self.forces(w)
        if sun is not None:
            sun = dataclasses.replace(sun, solution=self.sun.solve(f))
        if pin is not None:
            pin = dataclasses.replace(pin, solution=self.pin.solve(f))
        return sun, pin


def build_system(box: Gearbox, widths: Mapping[str, float], n: int, cache: Any = None
                 ) -> ShaftSystem:
    """The sun's and the pin's loaded shafts of a planetary set whose meshes have face
    widths ``widths`` (m) and ``n`` face slices each."""
    ps = box.planetary
    z = {m: (np.arange(n) + 0.5) * widths[m] / n for m in MESHES}
    sun = pin = None
    if "sun" in box.shafts:
        spec = box.shafts["sun"]
        _, points = face_points(spec[1], widths["sun_planet"], n)
        model = shaft_model(spec, points, cache)
        index = np.arange(n)
        sun = LoadedShaft(model, points, model.flexibility(points),
                          tuple(("sun_planet", u, index) for u in
                                sun_unit_loads(ps.sun.base_radius, tuple(ps.angles), n)))
    if "planet" in box.shafts:
        spec = box.shafts["planet"]
        per_mesh = {m: np.round(face_points(spec[1], widths[m], n)[1], 12) for m in MESHES}
        points = np.unique(np.concatenate(list(per_mesh.values())))
        model = shaft_model(spec, points)
        angles = (ps.sun_planet.operating_pressure_angle,
                  ps.planet_ring.operating_pressure_angle)
        pin = LoadedShaft(model, points, model.flexibility(points),
                          tuple((m, u, np.searchsorted(points, per_mesh[m])) for m, u in
                                zip(MESHES, planet_unit_loads(angles, n), strict=True)))
    return ShaftSystem(z, widths, sun, pin, box.planet_bearing_stiffness, ps.sun.base_radius)


def planetary_shaft_stage(box: Gearbox, stages: Mapping[str, Any], options: Any,
                          log: Steps) -> PlanetaryShafts | None:
    """Both meshes' contacts with the sun's and the pins' deflection (module docstring), one
    timed step; None for a set without shafts or without contact."""
    if box.kind != "planetary" or not box.shafts:
        return None
    if any(stages[m].contact is None for m in MESHES):
        return None
    pairs = {m: stages[m].stiffness.actual for m in MESHES}
    ops = {m: stages[m].case.operation for m in MESHES}
    n = box.contact.slices
    system = build_system(box, {m: pairs[m].face_width for m in MESHES}, n, options.cache)
    w = {m: np.full(n, line_of_action_load(pairs[m], ops[m]) / pairs[m].face_width)
         for m in MESHES}
    rigid_k = {m: load_distribution(stages[m].contact, pairs[m], ops[m]).k_hbeta
               for m in MESHES}
    sources: dict[str, Any] = {}
    cycles, dists = {}, {}
    change, iteration = math.inf, 0
    with log.step("sun and pin deflection and loaded contact", announce=True) as note:
        while change >= TOLERANCE:
            iteration += 1
            check_settling(iteration, change, "the sun, the pins and the meshes")
            gaps, sun, pin = system.deflect(w)
            used = w
            w_new, change = {}, 0.0
            for m in MESHES:
                cycles[m], dists[m] = _contact(box, stages[m], gaps[m], system.z[m],
                                               sources, options)
                w_new[m] = np.interp(system.z[m], dists[m].z, dists[m].cycle_mean)
                change = max(change, float(np.abs(w_new[m] - w[m]).max()
                                           / np.abs(w_new[m]).max()))
            w = w_new
        sun, pin = system.solved(used, sun, pin)
        for m in MESHES:  # once, for the cycles the fixed point keeps
            warn_physics(cycles[m])
        note["text"] = (f"{iteration} iterations; misalignment "
                        + ", ".join(f"{m} {np.ptp(gaps[m]) * 1e6:.3g} um (K_Hbeta "
                                    f"{dists[m].k_hbeta:.3f})" for m in MESHES))
    return PlanetaryShafts(
        z=system.z, cycles=cycles, rigid={m: stages[m].contact for m in MESHES},
        gaps={m: gaps[m] - gaps[m].mean() for m in MESHES},
        approaches={m: float(gaps[m].mean()) for m in MESHES}, line_loads=used,
        k_hbeta={m: (rigid_k[m], dists[m].k_hbeta) for m in MESHES}, sun=sun, pin=pin,
        iterations=iteration, change=change)


def _contact(box: Gearbox, stages: Any, gap: np.ndarray, z: np.ndarray,
             sources: dict[str, Any], options: Any) -> tuple[LoadedMeshCycle, Any]:
    """One mesh's loaded contact with ``gap`` (mean taken out) as its lead gap, and its load
    distribution; its compliance source built once into ``sources``."""
    pair, op = stages.stiffness.actual, stages.case.operation
    name = stages.case.name
    contact = box.mesh_contact(name)
    mods = dataclasses.replace(contact.modifications,
                               lead_gap=tuple(zip(z.tolist(), (gap - gap.mean()).tolist(),
                                                  strict=True)))
    opts = dataclasses.replace(contact, modifications=mods)
    if name not in sources:
        sources[name] = compliance_source(pair, op, opts, box.stiffness, box.fe_source,
                                          cache=options.cache, model=stages.stiffness.model)
    cycle = analyse_contact(sources[name], op, opts, warn=False)
    return cycle, load_distribution(cycle, pair, op)


def support_stiffness(box: Gearbox, cache: Any = None
                      ) -> tuple[float | None, float | None, float | None]:
    """The sun's and a planet's support stiffness from their shafts (N/m; None without one):
    the sun's ``1 / C_yy`` of its seat's centre (bearings and bending in series, the seat
    free to tilt), a planet's pin the same in series with the planet bearing,
    ``1 / (C_yy + 1 / k_pb)``; and the sun shaft's torsional stiffness between its seat's
    centre and its torque point, ``1 / C_theta_z theta_z`` (N m/rad; None without a sun
    shaft). The 3D superelement read from or written to ``cache``."""
    out: list[float | None] = []
    torsion = None
    for role in ("sun", "planet"):
        spec = box.shafts.get(role)
        if spec is None:
            out.append(None)
            continue
        flex = seat_flexibility(spec, cache if role == "sun" else None)
        c = float(flex[1, 1])
        if role == "planet":
            c += 1.0 / box.planet_bearing_stiffness
        else:
            torsion = float(1.0 / flex[5, 5])
        out.append(1.0 / c)
    return out[0], out[1], torsion
