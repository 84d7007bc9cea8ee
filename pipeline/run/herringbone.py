"""The herringbone sun-planet stage of a run: groove FE -> contact of both halves -> excitation.

For a planetary set whose herringbone sun has a ``[groove]`` table, the run adds to the
sun-planet mesh (:mod:`pipeline.run.chain`):

1. the groove's 12 x 12 stiffness by 3D FE (:func:`pipeline.fem.groove.groove_stiffness`),
   cached by a content hash of the groove spec (gear, groove, shafts, mesh size, models);
2. the loaded contact of both helical halves through it
   (:func:`pipeline.contact.herringbone.herringbone_mesh_cycle`, ``[herringbone]``
   options) with the sun-planet mesh's contact options
   (:meth:`~pipeline.config.gearbox.Gearbox.mesh_contact`: the sun's and the planet's flank
   modifications, each half's face in its own frame, the right half the left's mirror
   image), cached by a hash of everything the helical-half cycle depends on plus the
   condensed groove compliance, the planets and those options;
3. with ``[dynamics] excitation = "contact"``, the left/right sun-planet excitation of the
   herringbone planetary model (:mod:`pipeline.dynamics.herringbone_excitation`), whose sun
   halves are then joined by the same FE matrix.

The functions take the stages' own inputs, so workflows use them as the run does.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.cache.entries import cached_file
from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.contact.analysis import line_of_action_load
from pipeline.contact.compliance import compliance_source
from pipeline.contact.cycle_io import CYCLE_CODE, cycle_cache_inputs
from pipeline.contact.groove_flank import GrooveFlankCoupling
from pipeline.contact.herringbone import (
    SUN_LOAD_SIDE,
    HerringboneOptions,
    herringbone_mesh_cycle,
)
from pipeline.contact.herringbone_results import (
    HerringboneCycle,
    herringbone_arrays,
    herringbone_from_arrays,
)
from pipeline.contact.options import ContactOptions
from pipeline.fem.groove.result import GrooveStiffness
from pipeline.fem.groove.spec import GrooveSpec
from pipeline.fem.mesh_cache import MESH_CODE
from pipeline.geometry.pair import GearPair
from pipeline.io import to_jsonable
from pipeline.operation import OperatingPoint
from pipeline.stiffness.options import StiffnessOptions

TORQUE_SIDE = SUN_LOAD_SIDE
"""``[herringbone] torque_entry`` -> the herringbone model's ``sun_load_side``."""


@dataclass(frozen=True)
class HerringboneStage:
    """The sun-planet mesh of a herringbone set through its groove.

    Attributes
    ----------
    groove : the groove FE result (12 x 12 between O_L and O_R, K_j).
    cycle : the contact of both halves over a mesh cycle.
    pair : the helical-half sun-planet pair (sun = pinion).
    operation : the sun's torque on this planet's mesh (both halves) and its speed
        relative to the carrier.
    groove_cached, cycle_cached : True when read from the cache.
    """

    groove: GrooveStiffness
    cycle: HerringboneCycle
    pair: GearPair
    operation: OperatingPoint
    groove_cached: bool = False
    cycle_cached: bool = False

    def summary(self) -> dict[str, Any]:
        """Groove K_j and k_t, and the contact summary (SI; units in keys)."""
        return {"groove_Kj_Nm2": self.groove.equivalent_Kj,
                "groove_torsional_stiffness_Nm_per_rad": self.groove.torsional_stiffness,
                **self.cycle.summary()}


def _groove_arrays(g: GrooveStiffness) -> dict[str, np.ndarray]:
    return {"json": np.array(json.dumps(to_jsonable(g.to_dict())))}


def _groove_from_arrays(z: dict[str, np.ndarray]) -> GrooveStiffness:
    return GrooveStiffness.from_dict(json.loads(str(z["json"])))


def cached_groove(spec: GrooveSpec, *, cache: Cache = DEFAULT_CACHE,
                  progress: bool = False) -> tuple[GrooveStiffness, bool]:
    """The groove FE result of ``spec`` from the cache, or computed and stored (its phases
    on stderr with ``progress``).

    Returns (result, True if read from the cache); ``result.timings`` are those of the
    run that computed it.
    """
    from pipeline.fem.groove.study import groove_stiffness

    res, _, hit = cached_file("groovestiffness", {"spec": spec},
                              lambda: groove_stiffness(spec, cache=cache, progress=progress),
                              _groove_arrays, _groove_from_arrays, code=MESH_CODE,
                              cache=cache)
    return res, hit


def cached_herringbone_cycle(
    pair: GearPair, operation: OperatingPoint, groove: GrooveFlankCoupling, n_planets: int,
    contact: ContactOptions, stiffness: StiffnessOptions, herringbone: HerringboneOptions,
    *, fe: Any = None, model: Any = None, cache: Cache = DEFAULT_CACHE,
    cycle_cache: Cache | None = None, show_progress: bool = False,
) -> tuple[HerringboneCycle, bool]:
    """Herringbone contact of a sun-planet mesh, from the cache when its inputs are unchanged.

    Parameters
    ----------
    pair : helical-half sun-planet pair (sun = pinion).
    operation : sun torque on this mesh (both halves, N m) and its speed (rad/s).
    groove : condensed groove compliance. n_planets : N.
    contact, stiffness, fe : the ``[contact]``, ``[stiffness]`` options and FE source settings.
    herringbone : torque entry and axial holding.
    model : prebuilt analytical tooth models of ``pair`` (optional).
    cache : the cache of the FE tables, and of the cycle unless ``cycle_cache`` is given.

    Returns (cycle, True if read from the cache).
    """
    inputs = {**cycle_cache_inputs(pair, operation, contact, stiffness, fe),
              "groove": groove.compliance.tolist(),
              "n_planets": n_planets, "herringbone": herringbone}

    def build() -> HerringboneCycle:
        # the source sees one half's load (friction direction, EHL pressure)
        half = OperatingPoint(0.5 * operation.torque, operation.speed, operation.driver)
        source = compliance_source(pair, half, contact, stiffness, fe, cache=cache, model=model,
                                   show_progress=show_progress)
        return herringbone_mesh_cycle(source, line_of_action_load(pair, operation), groove,
                                      n_planets, options=herringbone,
                                      modifications=contact.modifications,
                                      local=contact.local_contact, positions=contact.positions,
                                      show_progress=show_progress)

    cycle, _, hit = cached_file("herringbone", inputs, build, herringbone_arrays,
                                herringbone_from_arrays, code=CYCLE_CODE,
                                cache=cache if cycle_cache is None else cycle_cache)
    return cycle, hit


def herringbone_stage(box, stages, options, log) -> HerringboneStage | None:
    """The herringbone stage of a run's sun-planet mesh, or ``None`` when the set has no
    herringbone sun with a ``[groove]`` table (module docstring)."""
    from pipeline.dynamics.models.planetary_gears import mesh_operations

    ps = box.planetary
    if box.kind != "planetary" or not ps.sun.herringbone or box.groove is None:
        return None
    with log.step("groove FE", announce=True) as note:
        groove, g_hit = cached_groove(box.groove, cache=options.cache,
                                      progress=options.show_progress)
        note["cached"] = g_hit
        note["text"] = f"K_j = {groove.equivalent_Kj:.4g} N m^2"
    op = mesh_operations(ps, box.operation, 1)[0]
    pair = stages.case.pair
    with log.step(f"herringbone contact ({box.contact.compliance}) [sun_planet]",
                  announce=True) as note:
        cycle, c_hit = cached_herringbone_cycle(
            pair, op, GrooveFlankCoupling.from_matrix(groove.coupling_matrix), ps.n_planets,
            box.mesh_contact("sun_planet"), box.stiffness, box.herringbone, fe=box.fe_source,
            model=stages.stiffness.model, cache=options.cache, cycle_cache=options.cycle_cache,
            show_progress=options.show_progress)
        note["cached"] = c_hit
        s = cycle.summary()
        note["text"] = (f"load left/right {s['left']['load_share_mean']:.3f} / "
                        f"{s['right']['load_share_mean']:.3f}")
    return HerringboneStage(groove, cycle, pair, op, g_hit, c_hit)
