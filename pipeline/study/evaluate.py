"""One design point: gearbox document in, KPI row out (pure; writes nothing).

:func:`evaluate_point` composes the static stages of :mod:`pipeline.run.chain` for every
mesh (geometry, analytical stiffness, the ``[contact] compliance`` source, loaded
contact) and, with a speed range, the dynamic model of :mod:`pipeline.run.dynamics`
swept over it; the KPIs of :mod:`pipeline.study.kpis` are read from the result.

The stages are those of ``gearpipe run`` (:func:`pipeline.run.chain.mesh_stages`), so a
herringbone sun with a ``[groove]`` table also gets its groove stage (the groove FE read from
the FE cache of the machine the point runs on, the two-half contact solved per point);
contact cycles are not kept in the cache (one file per point).

FE tables depend only on the gears and the FE settings, not on flank modifications,
load or assembly errors, so a study builds them once per distinct geometry
(:func:`fe_geometry_key`, :func:`build_fe_tables`) and hands the built sources to every
point of that geometry (``fe``); a point then neither meshes nor reads the disk.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from typing import Any

import numpy as np

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.config import Gearbox, gearbox_from_dict
from pipeline.io import content_hash
from pipeline.study.kpis import KPI, PointResult, kpi_row


def point_gearbox(doc: Mapping[str, Any], name: str = "point") -> Gearbox:
    """The gearbox of a point document (validated like a gearbox file)."""
    return gearbox_from_dict(doc, name=name)


def _actual(case) -> Any:
    from pipeline.geometry.assembly_errors import assemble

    assembled = assemble(case.pair, case.assembly_errors)
    return case.pair if assembled is None else assembled.actual


def fe_geometry_key(box: Gearbox) -> str | None:
    """Content hash of what the FE tables of every mesh depend on (gears, FE settings,
    tooth pairs in contact), or ``None`` for the analytical compliance."""
    from pipeline.cache.entries import unlabelled
    from pipeline.run.chain import mesh_cases

    if box.fe_source is None:
        return None
    parts = []
    for case in mesh_cases(box):
        pair = _actual(case)
        parts.append({"mesh": case.name, "pinion": unlabelled(pair.pinion),
                      "gear": unlabelled(pair.gear),
                      "pairs": np.asarray(pair.pair_indices()).tolist()})
    return content_hash({"compliance": box.contact.compliance,
                         "settings": dataclasses.asdict(box.fe_source), "meshes": parts})


def build_fe_tables(doc: Mapping[str, Any], *, cache: Cache = DEFAULT_CACHE) -> dict[str, Any]:
    """The FE compliance source (both gears' tables) of every mesh of a point's gearbox,
    ``{mesh name: FE2DCompliance | FE3DCompliance}`` (read from the FE cache when there)."""
    from pipeline.run.chain import mesh_cases

    box = point_gearbox(doc)
    out = {}
    for case in mesh_cases(box):
        pair = _actual(case)
        if box.contact.compliance == "fe2d":
            from pipeline.contact.fe2d_source import FE2DCompliance

            out[case.name] = FE2DCompliance.build(pair, box.fe_source, cache=cache)
        else:
            from pipeline.contact.fe3d_source import FE3DCompliance

            out[case.name] = FE3DCompliance.build(pair, box.fe_source, cache=cache)
    return out


def point_result(box: Gearbox, fe: Mapping[str, Any] | None = None, *,
                 speed_range_rpm: tuple[float, float] | None = None, speed_points: int = 40,
                 cache: Cache = DEFAULT_CACHE) -> PointResult:
    """Static stages of every mesh (:func:`pipeline.run.chain.mesh_stages`, contact cycles
    not kept in the cache) and, with ``speed_range_rpm``, a sweep of the dynamic model over
    that driver speed range (rpm, ``speed_points`` equally spaced speeds)."""
    from pipeline.progress import Steps
    from pipeline.run.chain import RunOptions, mesh_stages
    from pipeline.run.runner import RunResult

    options = RunOptions(cache=cache, show_progress=False, cache_cycles=False)
    meshes = mesh_stages(box, options, Steps("", enabled=False), prebuilt=fe)
    run = RunResult(box, meshes, None, Steps("", enabled=False))
    if speed_range_rpm is None:
        return PointResult(run, cache=cache)
    from pipeline.dynamics.sweep import mesh_force_sweep
    from pipeline.run.dynamics import dynamic_model, dynamics_options

    model, _ = dynamic_model(box, meshes, cache)
    opts = dynamics_options(box).sweep
    speeds = np.linspace(*speed_range_rpm, speed_points)
    period = next(iter(meshes.values())).stiffness.mesh.mesh_period  # at the operating speed
    op_rpm = box.operation.speed * 30.0 / np.pi
    freqs = speeds / op_rpm / period
    sweep = mesh_force_sweep(model.assembly().assemble(), freqs, opts.method, opts.n_harmonics,
                             executor=None)
    return PointResult(run, sweep, speeds, cache=cache)


def evaluate_point(doc: Mapping[str, Any], fe: Mapping[str, Any] | None = None, *,
                   kpis: tuple[KPI, ...], speed_range_rpm: tuple[float, float] | None = None,
                   speed_points: int = 40, cache: Cache = DEFAULT_CACHE
                   ) -> dict[str, float]:
    """KPI row ``{name: value}`` of one point document (units in the KPI names).

    Parameters
    ----------
    doc : the point's gearbox document (base file with the point's values, file units).
    fe : prebuilt FE sources ``{mesh name: source}`` of this geometry
        (:func:`build_fe_tables`), or ``None`` to build or read them here.
    kpis : the KPIs to compute.
    speed_range_rpm, speed_points : driver speed range (rpm) of the dynamic KPIs.
    cache : the FE cache used when ``fe`` is ``None``.
    """
    box = point_gearbox(doc)
    res = point_result(box, fe, speed_range_rpm=speed_range_rpm, speed_points=speed_points,
                       cache=cache)
    return kpi_row(res, kpis)
