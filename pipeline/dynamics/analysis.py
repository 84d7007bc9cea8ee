"""The dynamics stage's entry points: modes, steady response and frequency sweep of a model.

Each takes a model (anything with ``assembly()``: the pair, planetary, herringbone
planetary and split-torque models) and the stage's own options, and returns a
result that knows its ``summary()`` and ``columns()``.
"""

from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import Executor
from dataclasses import dataclass

import numpy as np

from pipeline.dynamics.modal import classify_by_energy, modal_analysis
from pipeline.dynamics.options import ResponseOptions, SweepOptions
from pipeline.dynamics.results import HarmonicResponse, ModalResult, Response
from pipeline.dynamics.sweep import SweepResult, mesh_force_sweep


def analyse_modes(model) -> ModalResult:
    """Natural frequencies, mode shapes and mode kinds: the model's own classification
    (``model.classify``, Lin and Parker's types of a planetary set), else the energy-share
    rule of :func:`~pipeline.dynamics.modal.classify_by_energy` (a pair, other models)."""
    system = model.assembly().assemble()
    res = modal_analysis(system, gyroscopic=system.carrier_speed != 0.0)
    classify: Callable | None = getattr(model, "classify", None)
    return classify(res) if classify is not None else classify_by_energy(res)


@dataclass(frozen=True)
class ResponseResult:
    """Steady response of a model at its operating speed.

    Attributes
    ----------
    response : time history of one steady period (or the integrated transient).
    harmonic : the harmonic-balance coefficients (method "harmonic_balance"), else ``None``.
    """

    response: Response
    harmonic: HarmonicResponse | None = None

    def summary(self) -> dict:
        return self.response.summary()

    def columns(self) -> dict[str, np.ndarray]:
        return self.response.columns()


def analyse_response(model, options: ResponseOptions | None = None, *,
                     refine: int = 1) -> ResponseResult:
    """Steady dynamic response by the method of ``options``.

    ``refine`` multiplies the harmonics (harmonic balance) and the segments (propagator)
    for a finer run (``--full`` on the command line uses 2); at most 500 harmonics.
    """
    from pipeline.dynamics.harmonic_balance import harmonic_balance
    from pipeline.dynamics.integrate import integrate, steady_state

    options = options or ResponseOptions()
    system = model.assembly().assemble()
    segments = None if options.segments is None else options.segments * refine
    if options.method == "harmonic_balance":
        hr = harmonic_balance(system, min(options.n_harmonics * refine, 500))
        return ResponseResult(hr.response, hr)
    if options.method == "floquet":
        return ResponseResult(steady_state(system, segments))
    return ResponseResult(integrate(system, options.periods, segments=segments))


def analyse_sweep(model, options: SweepOptions | None = None, *, full: bool = False,
                  executor: Executor | str | None = "auto",
                  show_progress: bool = False,
                  natural_frequencies: np.ndarray | None = None) -> SweepResult:
    """RMS, mean and maximum dynamic mesh force against mesh frequency.

    The range is the one of ``options`` (:meth:`SweepOptions.bounds`): the given ends,
    the others derived from the model's operating mesh frequency (1 / its period) and
    its natural frequencies (``natural_frequencies`` in Hz, computed when ``None`` and
    needed). ``executor``: "auto" runs sweeps of 50 points or more in a local process
    pool, ``None`` serially, or any ``concurrent.futures.Executor``.
    """
    options = options or SweepOptions()
    system = model.assembly().assemble()
    if natural_frequencies is None and (options.f_min is None or options.f_max is None):
        natural_frequencies = analyse_modes(model).frequencies
    freqs = options.frequencies(full, system.frequency,
                                () if natural_frequencies is None else natural_frequencies)
    if executor == "auto":
        executor = "local" if freqs.size >= 50 else None
    return mesh_force_sweep(system, freqs, options.method, options.n_harmonics,
                            executor=executor, show_progress=show_progress)
