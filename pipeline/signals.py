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

    def complex_coefficients(self) -> np.ndarray:
        """c_l for l = -N..N with signal = sum c_l exp(i 2 pi l tau), shape (2N+1,)."""
        pos = 0.5 * self.amplitude * np.exp(1j * self.phase)
        return np.concatenate([np.conj(pos[::-1]), [self.mean], pos])


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
