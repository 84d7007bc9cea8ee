"""The dynamics steps of a run: model from the static stages, modes, response, sweep.

The mesh excitation of each mesh comes from the static stages of the same run
(:mod:`pipeline.run.chain`): ``[dynamics] excitation = "analytical"`` takes the
potential-energy k(t) and friction terms, ``"contact"`` the loaded contact cycle
(loaded k(t), static transmission error and friction of the chosen compliance
source). The dynamic factor at the operating speed is the largest dynamic mesh force
over the static mesh load of the contact stage.
"""

from __future__ import annotations

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
from pipeline.dynamics.modal import ModalResult
from pipeline.dynamics.options import PairDynamicsOptions
from pipeline.dynamics.sweep import SweepResult
from pipeline.run.steps import StepLog


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
    """

    model: Any
    excitation: str
    modes: ModalResult
    response: ResponseResult
    sweep: SweepResult

    def summary(self, modes: int = 8) -> dict[str, Any]:
        """First natural frequencies (Hz), response per mesh (N, m), dynamic factors (-)."""
        resp = self.response.response
        per_mesh = self.response.summary()["meshes"]
        force = resp.mesh_force[:, resp.steady_slice()]
        for i, name in enumerate(resp.mesh_names):
            mean = float(force[i].mean())
            per_mesh[name]["max_force_N"] = float(force[i].max())
            per_mesh[name]["dynamic_factor"] = float(force[i].max() / mean) if mean else np.nan
        sw = self.sweep
        k = np.argmax(sw.dynamic_factor, axis=1)
        return {
            "excitation": self.excitation,
            "dofs": len(self.modes.dof_names),
            "natural_frequencies_Hz": [float(f) for f in self.modes.frequencies[:modes]],
            "response_at_operating_speed": {"method": resp.method, "mesh_period_s": resp.period,
                                            "meshes": per_mesh},
            "sweep": {**sw.summary(),
                      "max_dynamic_factor": {m: float(sw.dynamic_factor[i, k[i]])
                                             for i, m in enumerate(sw.mesh_names)},
                      "max_dynamic_factor_at_Hz": {m: float(sw.frequencies[k[i]])
                                                   for i, m in enumerate(sw.mesh_names)}},
        }


def dynamic_model(box: Gearbox, meshes: dict) -> tuple[Any, str]:
    """The dynamic model of a gearbox excited by the run's static stages.

    Returns (model, excitation name).
    """
    from pipeline.dynamics.mesh_input import excitation_from_stiffness
    from pipeline.dynamics.models.spur_pair import spur_pair_model

    if box.kind == "lumped":
        return box.lumped, "lumped"
    opts = box.dynamics or PairDynamicsOptions()
    stages = meshes["mesh"]
    excitation = excitation_from_stiffness(stages.stiffness.mesh)
    model = spur_pair_model(stages.stiffness.actual, (box.bodies["pinion"], box.bodies["gear"]),
                            box.operation, opts, excitation)
    return model, opts.excitation


def dynamics_stages(box: Gearbox, meshes: dict, options, log: StepLog) -> DynamicsStages:
    """Model, modes, response at the operating speed and speed sweep."""
    opts = box.dynamics or PairDynamicsOptions()
    with log.step("dynamic model"):
        model, excitation = dynamic_model(box, meshes)
    with log.step("modes") as note:
        modes = analyse_modes(model)
        note["text"] = f"{len(modes.dof_names)} DOF"
    with log.step("response at the operating speed"):
        response = analyse_response(model, opts.response, refine=2 if options.full else 1)
    with log.step("speed sweep", long=True) as note:
        sweep = analyse_sweep(model, opts.sweep, full=options.full,
                              show_progress=options.show_progress)
        note["text"] = f"{sweep.frequencies.size} speeds"
    return DynamicsStages(model, excitation, modes, response, sweep)
