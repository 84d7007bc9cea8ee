"""The full-revolution loaded contact of ``gearpipe run``: a pair with ``[contact.errors]``.

After the mesh-cycle contact (:func:`pipeline.run.chain.loaded_contact`) the same compliance
source is solved through the span of the errors (:func:`pipeline.contact.revolution.
loaded_revolution`: the hunting cycle or one revolution, each tooth pair with its own
teeth's pitch deviations, both runouts as a gap along the line of action and, each mesh
cycle, the pair at the centre distance they give, the same source's tables or tooth models
reused), at the ``[contact]`` positions per mesh cycle.
The result is cached like the mesh cycle, by a content hash of everything it depends on
(the mesh cycle's inputs and the errors) and the contact code.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from pipeline.cache.entries import cached_file
from pipeline.contact.analysis import line_of_action_load
from pipeline.contact.compliance import compliance_source
from pipeline.contact.cycle_io import CYCLE_CODE, cycle_cache_inputs
from pipeline.contact.revolution import loaded_revolution
from pipeline.contact.revolution_results import (
    LoadedRevolution,
    revolution_arrays,
    revolution_from_arrays,
)
from pipeline.contact.tooth_errors import ToothErrors

if TYPE_CHECKING:
    from pipeline.config import Gearbox
    from pipeline.progress import Steps
    from pipeline.run.chain import MeshStages, RunOptions


@dataclass(frozen=True)
class RevolutionStage:
    """The loaded contact through the span of the errors.

    Attributes
    ----------
    revolution : the loads and transmission error at every position of the span.
    errors : the errors it was solved with.
    """

    revolution: LoadedRevolution
    errors: ToothErrors

    def summary(self) -> dict[str, Any]:
        return self.revolution.summary()


def revolution_stage(box: Gearbox, stages: MeshStages, options: RunOptions,
                     log: Steps) -> RevolutionStage | None:
    """The full-revolution contact of a pair whose file gives ``[contact.errors]``, else
    None."""
    if box.errors is None:
        return None
    case, actual = stages.case, stages.stiffness.actual
    c = box.mesh_contact(case.name)
    inputs = {**cycle_cache_inputs(actual, case.operation, c, box.stiffness,
                                   box.fe_source), "errors": box.errors}

    def build() -> LoadedRevolution:
        source = compliance_source(actual, case.operation, c, box.stiffness,
                                   box.fe_source, cache=options.cache,
                                   model=stages.stiffness.model,
                                   show_progress=options.show_progress)
        return loaded_revolution(source, line_of_action_load(actual, case.operation),
                                 box.errors, c.modifications, c.local_contact, c.positions,
                                 driver=case.operation.driver,
                                 show_progress=options.show_progress)

    with log.step("loaded contact through the revolution", announce=True) as note:
        rev, _, hit = cached_file("contactrevolution", inputs, build, revolution_arrays,
                                  revolution_from_arrays, code=CYCLE_CODE,
                                  cache=options.cycle_cache)
        note["cached"] = hit
        note["text"] = (f"{rev.mesh_cycles} mesh cycles x {rev.positions_per_cycle} positions, "
                        f"TE {rev.summary()['transmission_error_peak_to_peak_m'] * 1e6:.3g} um "
                        "peak to peak")
    return RevolutionStage(rev, box.errors)
