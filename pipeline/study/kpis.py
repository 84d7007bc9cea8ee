"""Key performance indicators of a design point: one table, name -> unit and function.

Each KPI is one row of :data:`KPIS`: its column name (unit suffix as in the gearbox
file's keys), what it needs (``"contact"``: the loaded contact cycle of the main mesh;
``"root_stress"``: the FE fillet stress tables of its gears; ``"dynamics"``: a speed
sweep of the dynamic model; ``"rating"``: the ISO 6336 rating of every mesh, which needs a
``[rating]`` table in the base file) and a function of the
:class:`PointResult`. Adding a KPI is adding one row. The load distribution KPIs
(K_Hbeta, Hertz pressure, TE orders) are those of the report
(:func:`pipeline.contact.distribution.load_distribution`), the root stress is the
report's FE 2D root stress (:func:`pipeline.contact.root_stress.analyse_root_stress`:
fillet stress tables once per gear geometry, in the FE cache of the machine that
evaluates the point).

The main mesh is the first mesh of the gearbox (a pair: its mesh; a planetary set: the
sun-planet mesh).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

import numpy as np

from pipeline.cache.folder import Cache
from pipeline.contact.distribution import LoadDistribution, load_distribution
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError


@dataclass(frozen=True)
class PointResult:
    """What the pipeline gave at one design point.

    Attributes
    ----------
    run : the static stages of every mesh (:class:`pipeline.run.runner.RunResult`, without
        its dynamics stages).
    sweep : the dynamic mesh forces over the study's speed range
        (:class:`pipeline.dynamics.sweep.SweepResult`), or ``None``.
    speeds_rpm : shape (F,), driver speeds of the sweep points, rpm (or ``None``).
    cache : the cache of the root stress tables (as the run's).
    """

    run: Any
    sweep: Any = None
    speeds_rpm: np.ndarray | None = None
    cache: Cache = field(default_factory=Cache)

    @property
    def main(self) -> Any:
        """The static stages of the main mesh (:class:`pipeline.run.chain.MeshStages`)."""
        return next(iter(self.run.meshes.values()))

    @property
    def contact(self) -> LoadedMeshCycle:
        """Loaded contact cycle of the main mesh."""
        return self.main.contact

    @property
    def pair(self) -> GearPair:
        """The main mesh's pair as installed (assembly errors applied)."""
        return self.main.stiffness.actual

    @property
    def operation(self) -> OperatingPoint:
        """Torque (N m) and speed (rad/s) of the main mesh's driving gear."""
        return self.main.case.operation

    @cached_property
    def distribution(self) -> LoadDistribution:
        """Load distribution of the main mesh's loaded contact (as in its report)."""
        return load_distribution(self.contact, self.pair, self.operation)

    @cached_property
    def root_stress(self) -> Any:
        """FE 2D root stress of both gears of the main mesh under its contact loads."""
        from pipeline.contact.root_stress import analyse_root_stress

        return analyse_root_stress(self.contact, self.pair, self.operation,
                                   self.run.gearbox.fe_source, cache=self.cache)

    @cached_property
    def rating(self) -> Any:
        """The ISO 6336 rating of every mesh (:func:`pipeline.run.rating.rating_stage`: its
        K_Hbeta from each mesh's loaded contact, without dynamics and FE root stress)."""
        from pipeline.progress import Steps
        from pipeline.run.rating import rating_stage

        meshes = self.run.meshes
        dists = {name: load_distribution(st.contact, st.stiffness.actual, st.case.operation)
                 for name, st in meshes.items()}
        return rating_stage(self.run.gearbox, meshes, dists, {}, None,
                            Steps("", enabled=False))


@dataclass(frozen=True)
class KPI:
    """One KPI: column ``name`` (unit suffix), ``unit`` text, what it ``needs``, ``func``,
    ``help`` (one sentence) and ``label`` (axis text of the figures, without the unit)."""

    name: str
    unit: str
    needs: str
    func: Callable[[PointResult], float]
    help: str = ""
    label: str = ""


def _ripple(r: PointResult) -> float:
    k = r.contact.mesh_stiffness
    return float((k.max() - k.min()) / k.mean() * 100.0)


def _tip_share(r: PointResult) -> float:
    tip = r.contact.tip_contact_peak()
    return 0.0 if tip is None else tip["share"] * 100.0


def _peak_factor(r: PointResult) -> tuple[float, float]:
    df = r.sweep.dynamic_factor.max(axis=0)
    i = int(np.argmax(df))
    return float(df[i]), float(r.speeds_rpm[i])


KPIS: tuple[KPI, ...] = (
    KPI("te_peak_to_peak_um", "um", "contact",
        lambda r: float(np.ptp(r.contact.transmission_error)) * 1e6,
        "peak-to-peak loaded static transmission error along the line of action",
        "TE peak to peak"),
    KPI("te_order1_um", "um", "contact", lambda r: r.distribution.te_orders[0] * 1e6,
        "amplitude of the 1st mesh order of the loaded TE",
        "TE mesh order 1"),
    KPI("te_order2_um", "um", "contact", lambda r: r.distribution.te_orders[1] * 1e6,
        "amplitude of the 2nd mesh order of the loaded TE",
        "TE mesh order 2"),
    KPI("te_order3_um", "um", "contact", lambda r: r.distribution.te_orders[2] * 1e6,
        "amplitude of the 3rd mesh order of the loaded TE",
        "TE mesh order 3"),
    KPI("k_hbeta", "-", "contact", lambda r: r.distribution.k_hbeta,
        "face load factor K_Hbeta: largest over mean line load across the face (ISO 6336-1)",
        "face load factor K_Hβ"),
    KPI("contact_pressure_max_MPa", "MPa", "contact",
        lambda r: r.distribution.hertz_max.value * 1e-6,
        "largest Hertz contact pressure p_H over both flanks and the cycle",
        "max. contact pressure p_H"),
    KPI("root_stress_max_MPa", "MPa", "root_stress",
        lambda r: max(r.root_stress.pinion.max_stress, r.root_stress.gear.max_stress) * 1e-6,
        "largest FE 2D fillet principal stress of either gear over the cycle",
        "max. root stress, FE"),
    KPI("mesh_stiffness_mean_N_per_um", "N/um", "contact",
        lambda r: float(r.contact.mesh_stiffness.mean()) * 1e-6,
        "mean loaded (tangent) mesh stiffness over the cycle",
        "mean mesh stiffness"),
    KPI("mesh_stiffness_ripple_percent", "%", "contact", _ripple,
        "(max - min) / mean of the loaded mesh stiffness",
        "mesh stiffness ripple"),
    KPI("max_unit_load_N_per_mm", "N/mm", "contact",
        lambda r: float(r.contact.max_unit_load.max()) * 1e-3,
        "largest load per unit length of contact line over the cycle",
        "max. unit load"),
    KPI("loaded_contact_ratio", "-", "contact", lambda r: r.contact.loaded_contact_ratio,
        "mean number of tooth pairs carrying load over the cycle (1: the load jumps between "
        "pairs, as with a relief too long or deep for the load)",
        "loaded contact ratio"),
    KPI("tip_contact_share_percent", "%", "contact", _tip_share,
        "largest share of a position's load carried by a tip corner beyond the path of "
        "contact (edge contact at the tip; 0 when none)",
        "tip-corner load share"),
    KPI("safety_pitting_min", "-", "rating", lambda r: r.rating.smallest("pitting")[0],
        "smallest ISO 6336-2 pitting safety factor S_H of any gear of any mesh",
        "min. pitting safety S_H"),
    KPI("safety_bending_min", "-", "rating", lambda r: r.rating.smallest("bending")[0],
        "smallest ISO 6336-3 bending safety factor S_F of any gear rated in bending",
        "min. bending safety S_F"),
    KPI("dynamic_factor_peak", "-", "dynamics", lambda r: _peak_factor(r)[0],
        "largest max/mean dynamic mesh force over the study's speed range",
        "peak dynamic factor"),
    KPI("dynamic_factor_peak_speed_rpm", "rpm", "dynamics", lambda r: _peak_factor(r)[1],
        "driver speed of that largest dynamic factor",
        "speed of peak dynamic factor"),
)
"""Every KPI a study can ask for, in table order."""

KPI_BY_NAME = {k.name: k for k in KPIS}


def kpi_label(name: str) -> str:
    """Axis label of a KPI column: its reader's name and unit, ``"TE peak to peak (um)"``;
    a column that is not a KPI keeps its name."""
    kpi = KPI_BY_NAME.get(name)
    if kpi is None:
        return name
    return kpi.label if kpi.unit == "-" else f"{kpi.label} ({kpi.unit})"


def select_kpis(names: tuple[str, ...], dynamics: bool, rating: bool = False
                ) -> tuple[KPI, ...]:
    """The KPIs a study asks for (all by default; the dynamic ones only with a speed range,
    the safety factors only when the base file has a ``[rating]`` table).

    Raises :class:`InputError` for an unknown name, a dynamic KPI without a speed range or a
    rating KPI without a ``[rating]`` table.
    """
    if not names:
        return tuple(k for k in KPIS if (dynamics or k.needs != "dynamics")
                     and (rating or k.needs != "rating"))
    out = []
    for n in names:
        if n not in KPI_BY_NAME:
            from pipeline.config.schema import unknown

            raise unknown(n, list(KPI_BY_NAME), "kpis.names: KPI")
        if KPI_BY_NAME[n].needs == "dynamics" and not dynamics:
            raise InputError(f"kpis.names: {n!r} needs kpis.speed_range_rpm = [low, high] and "
                             "a [dynamics] table in the base file")
        if KPI_BY_NAME[n].needs == "rating" and not rating:
            raise InputError(f"kpis.names: {n!r} needs a [rating] table in the base file")
        out.append(KPI_BY_NAME[n])
    return tuple(out)


def kpi_row(result: PointResult, kpis: tuple[KPI, ...]) -> dict[str, float]:
    """``{KPI name: value}`` of one point (units in the names)."""
    return {k.name: float(k.func(result)) for k in kpis}
