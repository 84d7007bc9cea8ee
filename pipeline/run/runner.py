"""A whole run on one gearbox: :func:`run_pipeline` (the static stages of every mesh, the
dynamics, the meshes' load distributions, the rating) and its :class:`RunResult`, or the
same stage by stage (:func:`run_stages`); and the dynamic model a gearbox file describes
(:func:`gearbox_dynamic_model`) for the dynamics commands."""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.config import Gearbox
from pipeline.dynamics.assembly import DynamicModel
from pipeline.progress import Steps
from pipeline.run.chain import (
    MeshStages,
    RunOptions,
    contact_stages,
    coupled_stages,
    mesh_stages,
)
from pipeline.run.distribution import DistributionStage, distribution_stages
from pipeline.run.dynamics import DynamicsStages, dynamic_model, dynamics_stages, needs_contact
from pipeline.run.rating import RatingStage, rating_stage
from pipeline.validation import InputError


@dataclass(frozen=True)
class RunResult:
    """Everything one run computed.

    Attributes
    ----------
    gearbox : the gearbox it ran on.
    meshes : name -> the static stages of each mesh.
    dynamics : the dynamics results (:class:`pipeline.run.dynamics.DynamicsStages`) or
        ``None`` when the file asks for no dynamics.
    log : step durations (s) and which steps came from the cache.
    distributions : name -> the load distribution and root stress of each mesh with a
        contact cycle (:class:`pipeline.run.distribution.DistributionStage`).
    rating : the ISO 6336 rating of every mesh (:class:`pipeline.run.rating.RatingStage`),
        or ``None`` without a ``[rating]`` table.
    """

    gearbox: Gearbox
    meshes: dict[str, MeshStages]
    dynamics: DynamicsStages | None
    log: Steps = field(compare=False)
    distributions: dict[str, DistributionStage] = field(default_factory=dict, compare=False)
    rating: RatingStage | None = field(default=None, compare=False)

    def summary(self) -> dict[str, Any]:
        """One summary of the run (SI; keys carry units)."""
        out: dict[str, Any] = {"gearbox": self.gearbox.name, "kind": self.gearbox.kind,
                               "meshes": {k: v.summary() for k, v in self.meshes.items()}}
        if self.dynamics is not None:
            out["dynamics"] = self.dynamics.summary()
        if self.rating is not None:
            out["rating"] = self.rating.summary()
        out["timing"] = self.log.summary()
        return out


RUN_STAGES = ("analytical", "contact", "dynamics", "complete")
"""What :func:`run_stages` yields, in this order."""


def run_stages(box: Gearbox, options: RunOptions | None = None
               ) -> Iterator[tuple[str, RunResult]]:
    """:func:`run_pipeline` stage by stage: the result as it grows, so that a caller can
    write what is ready while the rest computes; writes only the cache.

    Yields (stage, result) for each stage of :data:`RUN_STAGES`: ``"analytical"``, the
    meshes with their geometry and analytical stiffness (``contact`` None); ``"contact"``,
    the meshes' static stages whole (loaded contact, shafts, revolution, herringbone);
    ``"dynamics"``, with the dynamics (``None`` without a ``[dynamics]`` table);
    ``"complete"``, with the load distributions and the rating: what :func:`run_pipeline`
    returns. A ``[lumped_model]`` has no meshes: the first two stages are empty.
    The dynamics come before the load distributions, which they do not need (nor the
    distributions them), so that their figures can be drawn while the root stress computes.
    """
    options = options or RunOptions()
    log = Steps(options.label, enabled=options.show_progress, every_step=True)
    meshes = mesh_stages(box, options, log, contact=False)  # none for a [lumped_model]
    yield "analytical", RunResult(box, meshes, None, log)
    meshes = coupled_stages(box, {name: contact_stages(box, st, options, log)
                                  for name, st in meshes.items()}, options, log)
    yield "contact", RunResult(box, meshes, None, log)
    dynamics = None
    if box.kind == "lumped" or box.dynamics is not None:
        dynamics = dynamics_stages(box, meshes, options, log)
    yield "dynamics", RunResult(box, meshes, dynamics, log)
    distributions = distribution_stages(box, meshes, options, log)
    rating = rating_stage(box, meshes, {k: d.distribution for k, d in distributions.items()},
                          {k: d.root_stress for k, d in distributions.items()}, dynamics, log)
    yield "complete", RunResult(box, meshes, dynamics, log, distributions, rating)


def run_pipeline(box: Gearbox, options: RunOptions | None = None) -> RunResult:
    """Run every stage the gearbox file asks for (module docstring); writes only the cache."""
    *_, (_, result) = run_stages(box, options)
    return result


def gearbox_dynamic_model(box: Gearbox, cache: Cache = DEFAULT_CACHE) -> DynamicModel:
    """The dynamic model a gearbox file describes, excited by its static stages.

    The same composition as ``gearpipe run`` (:func:`mesh_stages`, then
    :func:`pipeline.run.dynamics.dynamic_model`):
    the analytical stiffness of each mesh, or with ``[dynamics] excitation = "contact"``
    its loaded contact cycle on the ``[contact] compliance`` source (read from the cache
    when ``gearpipe run`` or an earlier command computed it, in ``cache``).
    """
    if box.kind == "gear":
        raise InputError(f"{box.name}: the file describes a single gear; a dynamic model needs "
                         "a gear pair ([pinion] and [gear]), a planetary set or a "
                         "[lumped_model]")
    options = RunOptions(show_progress=False, cache=cache)
    meshes = mesh_stages(box, options, Steps("", enabled=False),
                         contact=needs_contact(box))
    return dynamic_model(box, meshes, cache)[0]
