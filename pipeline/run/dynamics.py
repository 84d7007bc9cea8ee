"""The dynamics steps of a run: model from the static stages, modes, response, sweep.

The mesh excitation of each mesh comes from the static stages of the same run
(:mod:`pipeline.run.chain`): ``[dynamics] excitation = "analytical"`` takes the
potential-energy k(t) and friction terms, ``"contact"`` the loaded contact cycle
(loaded k(t), static transmission error and friction of the chosen compliance
source). The dynamic factor (at the operating speed and over the sweep) is the largest
elastic mesh force k (delta - e) over the mean mesh force
(:meth:`pipeline.dynamics.results.Response.dynamic_factor`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.config import Gearbox
from pipeline.dynamics.analysis import (
    ResponseResult,
    analyse_modes,
    analyse_response,
    analyse_sweep,
)
from pipeline.dynamics.assembly import DynamicModel
from pipeline.dynamics.contact_excitation import excitation_from_contact
from pipeline.dynamics.mesh_input import (
    MeshExcitation,
    excitation_from_signal,
    excitation_from_stiffness,
)
from pipeline.dynamics.modal import ModalResult
from pipeline.dynamics.operating import (
    OperatingFrequency,
    elastic_modes,
    modes_that_matter,
    pair_operating_frequency,
    planetary_operating_frequency,
    system_operating_frequency,
)
from pipeline.dynamics.options import PairDynamicsOptions, PlanetaryDynamicsOptions
from pipeline.dynamics.sweep import SweepResult, mesh_force_sweep
from pipeline.progress import Steps


@dataclass(frozen=True)
class WithoutShafts:
    """The dynamics of a gearbox on shafts solved again without them, for comparison: the
    supports ``[dynamics]`` gives without shafts (its typed bearing stiffnesses or their
    defaults), no motor or driven machine, the contact on rigid supports as the excitation,
    the same sweep frequencies.

    Attributes
    ----------
    modes : natural frequencies (Hz) and mode shapes.
    sweep : mesh force and dynamic factor against the same mesh frequencies.
    """

    modes: ModalResult
    sweep: SweepResult

    def summary(self, cut: float) -> dict[str, Any]:
        """Elastic natural frequencies up to ``cut`` (Hz) and the sweep's largest dynamic
        factor and where (Hz)."""
        fn = self.modes.frequencies
        listed = [float(f) for f in fn[elastic_modes(fn)] if f <= cut]
        df = self.sweep.dynamic_factor
        k = np.argmax(df, axis=1)
        return {"natural_frequencies_Hz": listed,
                "max_dynamic_factor": {m: float(df[i, k[i]])
                                       for i, m in enumerate(self.sweep.mesh_names)},
                "max_dynamic_factor_at_Hz": {m: float(self.sweep.frequencies[k[i]])
                                             for i, m in enumerate(self.sweep.mesh_names)}}


@dataclass(frozen=True)
class DynamicsStages:
    """The dynamics of a run.

    Attributes
    ----------
    model : the lumped-parameter model (its ``assembly()`` gives the matrices).
    excitation : "analytical", "contact" or "lumped" (given in the file).
    modes : natural frequencies (Hz) and mode shapes.
    response : steady response at the operating speed.
    sweep : mesh force and dynamic factor against mesh frequency.
    operating : the operating mesh frequency (Hz) and the members' mesh orders.
    sweep_given : True when the file gives an end of the sweep range, False when the
        range is the default around the operating point
        (:func:`pipeline.dynamics.options.default_sweep_range`).
    without_shafts : a pair on shafts: the same dynamics without them (:class:`WithoutShafts`),
        else None.
    """

    model: DynamicModel
    excitation: str
    modes: ModalResult
    response: ResponseResult
    sweep: SweepResult
    operating: OperatingFrequency
    sweep_given: bool = False
    without_shafts: WithoutShafts | None = None

    def summary(self) -> dict[str, Any]:
        """Operating mesh frequency (Hz) and speeds (rpm); the elastic natural frequencies
        (Hz) up to ``max(10 f_m, top of the sweep)``
        (:func:`~pipeline.dynamics.operating.modes_that_matter`), the counts of named
        coordinates, independent DOF (one mode each), rigid-body modes and elastic modes
        above the cut (``modes.csv`` lists every mode); response per mesh (N, m)
        and dynamic factors (-) at the operating speed and over the sweep."""
        resp = self.response.response
        per_mesh = self.response.summary()["meshes"]
        force = resp.mesh_force[:, resp.steady_slice()]
        elastic = resp.elastic_mesh_force()[:, resp.steady_slice()]
        for i, name in enumerate(resp.mesh_names):
            mean = float(force[i].mean())
            per_mesh[name]["max_force_N"] = float(force[i].max())
            per_mesh[name]["max_elastic_force_N"] = float(elastic[i].max())
            per_mesh[name]["dynamic_factor"] = (float(elastic[i].max() / mean) if mean
                                                else np.nan)
        sw = self.sweep
        k = np.argmax(sw.dynamic_factor, axis=1)
        fn = self.modes.frequencies
        listed, cut = modes_that_matter(fn, self.operating.mesh_frequency,
                                        float(sw.frequencies[-1]))
        elastic = elastic_modes(fn)
        out = {
            "excitation": self.excitation,
            "coordinates": len(self.modes.dof_names),
            "independent_dofs": int(fn.size),
            "operating_point": self.operating.summary(),
            "natural_frequencies_Hz": [float(fn[i]) for i in listed],
            "modes_listed": [{"mode": int(i), "frequency_Hz": float(fn[i]),
                              "kind": self.modes.kinds[i]} for i in listed],
            "natural_frequency_cut_Hz": cut,
            "rigid_body_modes": int(fn.size - elastic.size),
            "elastic_modes_above_cut": int(elastic.size - listed.size),
            "response_at_operating_speed": {"method": resp.method, "mesh_period_s": resp.period,
                                            "meshes": per_mesh},
            "sweep": {**sw.summary(),
                      "range": "given" if self.sweep_given else "default",
                      "max_dynamic_factor": {m: float(sw.dynamic_factor[i, k[i]])
                                             for i, m in enumerate(sw.mesh_names)},
                      "max_dynamic_factor_at_Hz": {m: float(sw.frequencies[k[i]])
                                                   for i, m in enumerate(sw.mesh_names)}},
        }
        if self.without_shafts is not None:
            out["without_shafts"] = self.without_shafts.summary(cut)
        return out


def dynamics_options(box: Gearbox) -> PairDynamicsOptions | PlanetaryDynamicsOptions:
    """The ``[dynamics]`` options of a gearbox (defaults of its kind when the table is absent)."""
    if box.dynamics is not None:
        return box.dynamics
    return PlanetaryDynamicsOptions() if box.kind == "planetary" else PairDynamicsOptions()


def needs_contact(box: Gearbox) -> bool:
    """True when the dynamic model takes its mesh excitation from the loaded contact."""
    return box.kind != "lumped" and dynamics_options(box).excitation == "contact"


def mesh_excitation(stages, friction, excitation: str) -> MeshExcitation:
    """The excitation of one mesh from its static stages: its loaded contact cycle
    (``excitation = "contact"``: loaded k(t), static TE, friction of the loaded points) or
    its analytical stiffness (``"analytical"``)."""
    if excitation == "contact":
        return excitation_from_contact(stages.contact, stages.stiffness.actual,
                                       stages.case.operation, friction)
    return excitation_from_stiffness(stages.stiffness.mesh)


def dynamic_model(box: Gearbox, meshes: Mapping[str, Any], cache: Any = None
                  ) -> tuple[Any, str]:
    """The dynamic model of a gearbox excited by the static stages of its meshes.

    A pair: :func:`~pipeline.dynamics.models.spur_pair.spur_pair_model`; a planetary set:
    :func:`~pipeline.dynamics.models.planetary_gears.planetary_model_from_gears` (or its
    herringbone variant) with one sun-planet and one planet-ring excitation (an explicit
    ``[dynamics.sun_mesh_stiffness]`` / ``ring_mesh_stiffness`` replaces it); a
    ``[lumped_model]``: that model. Returns (model, excitation name). A pair's gears on
    shafts are supported by them and, with ``[dynamics] drive_inertia_kgm2`` /
    ``load_inertia_kgm2``, tied by their torsion to the motor and the driven machine
    (:func:`pipeline.run.shafts.support_stiffness`; the 3D superelement read from or written
    to ``cache``); a planetary set's sun on its shaft and planets on pins are supported by
    them (:func:`pipeline.run.planetary_shafts.support_stiffness`).
    """
    from pipeline.dynamics.models import planetary_gears as pg
    from pipeline.dynamics.models.spur_pair import spur_pair_model

    if box.kind == "lumped":
        return box.lumped, "lumped"
    opts = dynamics_options(box)
    friction = box.stiffness.friction_model
    if box.kind == "planetary":
        drive_torsion = None
        if box.shafts:  # the sun's shaft and the planets' pins support them
            from pipeline.run.planetary_shafts import support_stiffness as planetary_supports

            k_sun, k_planet, drive_torsion = planetary_supports(box, cache)
            opts = dataclasses.replace(
                opts, **{k: v for k, v in (("sun_bearing_stiffness", k_sun),
                                           ("planet_bearing_stiffness", k_planet))
                         if v is not None})
        excitations = [excitation_from_signal(given) if given is not None
                       else mesh_excitation(meshes[name], friction, opts.excitation)
                       for name, given in (("sun_planet", opts.sun_mesh_stiffness),
                                           ("planet_ring", opts.ring_mesh_stiffness))]
        if not box.planetary.sun.herringbone:
            return (pg.planetary_model_from_gears(box.planetary, box.bodies, box.carrier,
                                                  box.operation, opts, *excitations,
                                                  drive_torsion),
                    opts.excitation)
        hb = meshes["sun_planet"].herringbone if "sun_planet" in meshes else None
        extra = {}
        if hb is not None and box.fe_groove_in_dynamics:
            # both halves through the groove: left/right excitation, the same FE groove and
            # torque entry (the file cannot also give [dynamics] groove keys or another
            # sun_load_side: the loader refuses them, see pipeline.config.gearbox)
            from pipeline.dynamics.herringbone_excitation import excitation_from_herringbone
            from pipeline.run.herringbone import TORQUE_SIDE

            excitations[0] = excitation_from_herringbone(hb.cycle, hb.pair, hb.operation)
            extra = {"groove": hb.groove,
                     "sun_load_side": TORQUE_SIDE[box.herringbone.torque_entry]}
        return (pg.herringbone_planetary_model_from_gears(
            box.planetary, box.bodies, box.carrier, box.operation, opts, *excitations,
            **extra), opts.excitation)
    stages = meshes["mesh"]
    excitation = None
    if opts.mesh_stiffness is None or opts.friction:
        excitation = mesh_excitation(stages, friction, opts.excitation)
    supports = torsion = (None, None)
    if box.shafts:
        from pipeline.run.shafts import support_stiffness

        supports, torsion = support_stiffness(box, cache)
    model = spur_pair_model(stages.stiffness.actual, (box.bodies["pinion"], box.bodies["gear"]),
                            box.operation, opts, excitation, supports, torsion)
    return model, opts.excitation


def operating_frequency(box: Gearbox, model: Any) -> OperatingFrequency:
    """The operating mesh frequency of a gearbox (Hz) and its members' mesh orders, from
    its tooth counts and the driver's speed (:mod:`pipeline.dynamics.operating`); a
    ``[lumped_model]`` from its system's period."""
    if box.kind == "planetary":
        ps = box.planetary
        return planetary_operating_frequency(ps.sun.teeth, ps.ring.teeth, box.operation.speed)
    if box.kind == "lumped":
        return system_operating_frequency(model.assembly().assemble())
    pair = box.pair
    return pair_operating_frequency(pair.pinion.teeth, pair.gear.teeth, box.operation.speed)


def dynamics_stages(box: Gearbox, meshes: dict, options, log: Steps) -> DynamicsStages:
    """Model, modes, response at the operating speed and speed sweep."""
    opts = dynamics_options(box)
    with log.step("dynamic model"):
        model, excitation = dynamic_model(box, meshes, options.cache)
        operating = operating_frequency(box, model)
    with log.step("modes") as note:
        modes = analyse_modes(model)
        note["text"] = modes.counts()
    with log.step("response at the operating speed"):
        response = analyse_response(model, opts.response, refine=2 if options.full else 1)
    with log.step("speed sweep", announce=True) as note:
        sweep = analyse_sweep(model, opts.sweep, full=options.full,
                              show_progress=options.show_progress,
                              natural_frequencies=modes.frequencies)
        note["text"] = (f"{sweep.frequencies.size} speeds, {sweep.frequencies[0]:.4g}-"
                        f"{sweep.frequencies[-1]:.4g} Hz (operating mesh frequency "
                        f"{operating.mesh_frequency:.4g} Hz)")
    without = None
    if box.shafts and meshes:
        with log.step("modes and sweep without the shafts"):
            without = without_shafts(box, meshes, sweep)
    return DynamicsStages(model, excitation, modes, response, sweep, operating,
                          opts.sweep.given, without)


def without_shafts(box: Gearbox, meshes: Mapping[str, Any], sweep: SweepResult
                   ) -> WithoutShafts:
    """The dynamics without the shafts (:class:`WithoutShafts`) over the frequencies of
    ``sweep``; ``meshes`` the static stages by mesh, with their shaft stages."""
    opts = dynamics_options(box)
    drives = ({"drive_inertia": None, "load_inertia": None} if box.kind == "pair"
              else {"drive_inertia": None})
    plain = dataclasses.replace(box, shafts={},
                                dynamics=dataclasses.replace(opts, **drives))
    rigid = {name: st if st.shafts is None else dataclasses.replace(
        st, contact=st.shafts.rigid, shafts=None) for name, st in meshes.items()}
    model, _ = dynamic_model(plain, rigid)
    system = model.assembly().assemble()
    return WithoutShafts(analyse_modes(model),
                         mesh_force_sweep(system, sweep.frequencies, sweep.method,
                                          opts.sweep.n_harmonics))
