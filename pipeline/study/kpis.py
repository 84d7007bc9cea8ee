"""Key performance indicators of a design point: one table, name -> unit and function.

Each KPI is one row of :data:`KPIS`: its column name (unit suffix as in the gearbox
file's keys), what it needs (``"contact"``: the loaded contact cycle of the main mesh;
``"dynamics"``: a speed sweep of the dynamic model) and a function of the
:class:`PointResult`. Adding a KPI is adding one row; a KPI of the load distribution
reads ``r.contact``, ``r.pair`` and ``r.operation`` like the rows below.

The main mesh is the first mesh of the gearbox (a pair: its mesh; a planetary set: the
sun-planet mesh).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.pair import GearPair
from pipeline.operation import OperatingPoint
from pipeline.validation import InputError


@dataclass(frozen=True)
class PointResult:
    """What the pipeline gave at one design point.

    Attributes
    ----------
    run : the static stages of every mesh (:class:`pipeline.run.chain.RunResult`, without
        its dynamics stages).
    sweep : the dynamic mesh forces over the study's speed range
        (:class:`pipeline.dynamics.sweep.SweepResult`), or ``None``.
    speeds_rpm : shape (F,), driver speeds of the sweep points, rpm (or ``None``).
    """

    run: Any
    sweep: Any = None
    speeds_rpm: np.ndarray | None = None

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


@dataclass(frozen=True)
class KPI:
    """One KPI: column ``name`` (unit suffix), ``unit`` text, what it ``needs``, ``func``."""

    name: str
    unit: str
    needs: str
    func: Callable[[PointResult], float]
    help: str = ""


def te_order_amplitude(cycle: LoadedMeshCycle, order: int) -> float:
    """Single-sided amplitude of mesh order ``order`` of the loaded static TE, m.

    The cycle's positions are equally spaced over one mesh period, so the discrete
    Fourier transform of the TE samples gives the mesh orders directly.
    """
    te = np.asarray(cycle.transmission_error, dtype=float)
    if order >= te.size / 2:
        return float("nan")
    return float(2.0 * np.abs(np.fft.rfft(te)[order]) / te.size)


def _ripple(r: PointResult) -> float:
    k = r.contact.mesh_stiffness
    return float((k.max() - k.min()) / k.mean() * 100.0)


def _peak_factor(r: PointResult) -> tuple[float, float]:
    df = r.sweep.dynamic_factor.max(axis=0)
    i = int(np.argmax(df))
    return float(df[i]), float(r.speeds_rpm[i])


KPIS: tuple[KPI, ...] = (
    KPI("te_peak_to_peak_um", "um", "contact",
        lambda r: float(np.ptp(r.contact.transmission_error)) * 1e6,
        "peak-to-peak loaded static transmission error along the line of action"),
    KPI("te_order1_um", "um", "contact", lambda r: te_order_amplitude(r.contact, 1) * 1e6,
        "amplitude of the 1st mesh order of the loaded TE"),
    KPI("te_order2_um", "um", "contact", lambda r: te_order_amplitude(r.contact, 2) * 1e6,
        "amplitude of the 2nd mesh order of the loaded TE"),
    KPI("te_order3_um", "um", "contact", lambda r: te_order_amplitude(r.contact, 3) * 1e6,
        "amplitude of the 3rd mesh order of the loaded TE"),
    KPI("mesh_stiffness_mean_N_per_um", "N/um", "contact",
        lambda r: float(r.contact.mesh_stiffness.mean()) * 1e-6,
        "mean loaded (tangent) mesh stiffness over the cycle"),
    KPI("mesh_stiffness_ripple_percent", "%", "contact", _ripple,
        "(max - min) / mean of the loaded mesh stiffness"),
    KPI("max_unit_load_N_per_mm", "N/mm", "contact",
        lambda r: float(r.contact.max_unit_load.max()) * 1e-3,
        "largest load per unit length of contact line over the cycle"),
    KPI("dynamic_factor_peak", "-", "dynamics", lambda r: _peak_factor(r)[0],
        "largest max/mean dynamic mesh force over the study's speed range"),
    KPI("dynamic_factor_peak_speed_rpm", "rpm", "dynamics", lambda r: _peak_factor(r)[1],
        "driver speed of that largest dynamic factor"),
)
"""Every KPI a study can ask for, in table order."""

KPI_BY_NAME = {k.name: k for k in KPIS}


def select_kpis(names: tuple[str, ...], dynamics: bool) -> tuple[KPI, ...]:
    """The KPIs a study asks for (all by default; the dynamic ones only with a speed range).

    Raises :class:`InputError` for an unknown name or a dynamic KPI without a speed range.
    """
    if not names:
        return tuple(k for k in KPIS if dynamics or k.needs != "dynamics")
    out = []
    for n in names:
        if n not in KPI_BY_NAME:
            from pipeline.config.schema import unknown

            raise unknown(n, list(KPI_BY_NAME), "kpis.names: KPI")
        if KPI_BY_NAME[n].needs == "dynamics" and not dynamics:
            raise InputError(f"kpis.names: {n!r} needs kpis.speed_range_rpm = [low, high] and "
                             "a [dynamics] table in the base file")
        out.append(KPI_BY_NAME[n])
    return tuple(out)


def kpi_row(result: PointResult, kpis: tuple[KPI, ...]) -> dict[str, float]:
    """``{KPI name: value}`` of one point (units in the names)."""
    return {k.name: float(k.func(result)) for k in kpis}
