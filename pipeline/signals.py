"""Periodic signals over one mesh cycle and their Fourier series (shared by every stage).

A time-varying mesh stiffness, friction stiffness or transmission error is
periodic in the mesh phase ``tau = t / T_m`` (one mesh period is ``tau`` in
[0, 1)). :class:`PeriodicSignal` stores one period sampled at equally spaced
phases and evaluates it (with periodic wrap-around) anywhere; its Fourier series

    K(t) = k_0 + sum_{l=1}^{N} A_l cos(l omega_m t + phi_l)

is what the harmonic-balance dynamics use.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from pipeline.validation import InputError

MIN_SAMPLES = 4
"""Fewest samples of one period a :class:`PeriodicSignal` takes."""


@dataclass(frozen=True)
class FourierSeries:
    """Cosine series ``mean + sum_l amplitude[l-1] cos(2 pi l tau + phase[l-1])``.

    Attributes
    ----------
    mean : k_0, in the unit of the signal.
    amplitude : shape (N,), A_l >= 0, same unit.
    phase : shape (N,), phi_l in rad.
    """

    mean: float
    amplitude: np.ndarray
    phase: np.ndarray

    @property
    def orders(self) -> np.ndarray:
        """Harmonic orders 1..N, shape (N,)."""
        return np.arange(1, len(self.amplitude) + 1)

    def __call__(self, tau: ArrayLike) -> np.ndarray:
        """Evaluate at mesh phase ``tau`` (any shape, 1 = one mesh period)."""
        t = np.asarray(tau, dtype=float)[..., None]
        terms = self.amplitude * np.cos(2 * np.pi * self.orders * t + self.phase)
        return self.mean + terms.sum(axis=-1)


@dataclass(frozen=True)
class PeriodicSignal:
    """One period of a signal sampled at ``tau_k = k / n``, k = 0..n-1.

    Attributes
    ----------
    values : shape (n,) samples over one period (unit as documented by the producer).
    period : the period in s when known (``nan`` if the signal is used in phase only).
    """

    values: np.ndarray
    period: float = float("nan")

    def __post_init__(self) -> None:
        v = np.asarray(self.values, dtype=float)
        if v.ndim != 1 or v.size < MIN_SAMPLES:
            raise InputError(
                f"a periodic signal has samples of shape {v.shape}; it needs one period as a "
                f"1-D array of at least {MIN_SAMPLES} samples"
            )
        if not np.all(np.isfinite(v)):
            raise InputError("a periodic signal has samples that are not finite (nan or inf)")
        object.__setattr__(self, "values", v)

    @property
    def tau(self) -> np.ndarray:
        """Sample phases, shape (n,), in [0, 1)."""
        return np.arange(self.values.size) / self.values.size

    def __call__(self, tau: ArrayLike) -> np.ndarray:
        """Piecewise-linear periodic interpolation at phase ``tau`` (any shape)."""
        n = self.values.size
        x = np.mod(np.asarray(tau, dtype=float), 1.0) * n
        i0 = np.floor(x).astype(int) % n
        w = x - np.floor(x)
        return (1.0 - w) * self.values[i0] + w * self.values[(i0 + 1) % n]

    def mean(self) -> float:
        return float(self.values.mean())

    def fourier(self, n_harmonics: int) -> FourierSeries:
        """Fourier series of the sampled period (exact DFT of the samples).

        ``n_harmonics`` must be below n/2 so that every order is resolved.
        """
        n = self.values.size
        if not 1 <= n_harmonics < n // 2:
            raise InputError(
                f"n_harmonics = {n_harmonics} is outside the allowed range [1, {n // 2 - 1}] "
                f"for {n} samples per period"
            )
        c = np.fft.rfft(self.values) / n
        amp = 2.0 * np.abs(c[1 : n_harmonics + 1])
        phase = np.angle(c[1 : n_harmonics + 1])
        return FourierSeries(mean=float(c[0].real), amplitude=amp, phase=phase)

    def shifted(self, dtau: float) -> PeriodicSignal:
        """The signal delayed by ``dtau`` periods: ``new(tau) = old(tau - dtau)``."""
        return PeriodicSignal(self(self.tau - dtau), self.period)


@dataclass(frozen=True)
class Jump:
    """A phase where a periodic signal may jump (a tooth pair enters or leaves contact).

    Attributes
    ----------
    phase : in [0, 1), signal periods.
    sample_side : which side's value a sample lying exactly at ``phase`` holds: "after"
        (the signal is right-continuous there) or "before" (left-continuous).
    """

    phase: float
    sample_side: str

    def __post_init__(self) -> None:
        if not 0.0 <= self.phase < 1.0 or self.sample_side not in ("after", "before"):
            raise InputError(f"a jump needs a phase in [0, 1) and sample_side 'after' or "
                             f"'before'; got {self.phase!r}, {self.sample_side!r}")


JUMP_TOLERANCE = 1e-9
"""Phases closer than this (signal periods) to a jump count as lying on it."""


def _line_through(x: np.ndarray, v: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Piecewise-linear interpolant of (x, v) at t, extended by its end segments' lines."""
    if x.size == 1:
        return np.full(t.shape, v[0])
    out = np.interp(t, x, v)
    lo, hi = t < x[0], t > x[-1]
    out[lo] = v[0] + (t[lo] - x[0]) * (v[1] - v[0]) / (x[1] - x[0])
    out[hi] = v[-1] + (t[hi] - x[-1]) * (v[-1] - v[-2]) / (x[-1] - x[-2])
    return out


def _piece_coordinates(tau: np.ndarray, start: Jump, end: Jump,
                       width: float) -> tuple[np.ndarray, np.ndarray]:
    """Which phases ``tau`` lie on the piece from ``start`` to ``start + width`` and where.

    Returns (mask, x): x = start.phase + d with d in [0, width]; a phase on a jump goes to
    the side the jump names (on a single jump, "before" puts it at the end of the piece).
    """
    d = (tau - start.phase) % 1.0
    d[np.minimum(d, 1.0 - d) < JUMP_TOLERANCE] = 0.0
    on_start = d == 0.0
    if width < 1.0:
        d[np.abs(d - width) < JUMP_TOLERANCE] = width
        mask = (d > 0.0) & (d < width)
        mask |= on_start & (start.sample_side == "after")
        mask |= (d == width) & (end.sample_side == "before")
    else:
        mask = np.ones(d.shape, dtype=bool)
        if start.sample_side == "before":
            d[on_start] = 1.0
    return mask, start.phase + d


def resample_with_jumps(signal: PeriodicSignal, jumps: tuple[Jump, ...],
                        n: int) -> PeriodicSignal:
    """The signal at ``n`` phases with its jumps where they are, not smeared over a sample.

    The piecewise-linear interpolant of :class:`PeriodicSignal` turns a jump between two
    samples into a ramp one sample interval wide, placed by the sampling and not by the
    gears. Here the signal is smooth between the given jumps: each piece is the
    piecewise-linear interpolant of *its own* samples, extended by its end segments' lines
    up to the jumps, then sampled at ``k / n``; a jump then spans one interval of the
    finer grid at the right phase. The derivative of the signal (the damping force of a
    mesh, ``c (delta' - e')``) and the response to it converge with the sampling.

    Parameters
    ----------
    signal : samples at ``k / m``.
    jumps : distinct phases where the signal may jump (at most one per sample interval
        is resolved; a piece holding no sample leaves the signal as it is).
    n : samples of the result (>= the signal's).

    Returns
    -------
    :class:`PeriodicSignal` of ``n`` samples, same period; the signal resampled by linear
    interpolation when there are no jumps or a piece between two jumps holds no sample.
    """
    fine = np.arange(n) / n
    order = sorted(jumps, key=lambda j: j.phase)
    if not order:
        return PeriodicSignal(signal(fine), signal.period)
    tau = signal.tau
    out = np.empty(n)
    for i, start in enumerate(order):
        end = order[(i + 1) % len(order)]
        width = (end.phase - start.phase) % 1.0 or 1.0
        mine, x = _piece_coordinates(tau, start, end, width)
        mine_f, xf = _piece_coordinates(fine, start, end, width)
        if not mine.any():
            return PeriodicSignal(signal(fine), signal.period)
        by_x = np.argsort(x[mine])
        out[mine_f] = _line_through(x[mine][by_x], signal.values[mine][by_x], xf[mine_f])
    return PeriodicSignal(out, signal.period)
