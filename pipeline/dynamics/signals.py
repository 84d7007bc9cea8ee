"""Exact averages and Fourier coefficients of the periodic coefficients of a system.

A :class:`~pipeline.signals.PeriodicSignal` is the piecewise-linear
periodic interpolant of its samples. Both solvers use that same function:

* the time integrator holds each coefficient at its exact mean over a segment
  (second-order accurate, exact for piecewise-constant stiffness on aligned segments);
* the harmonic balance uses its exact Fourier coefficients: for n samples the
  linear interpolant has ``c_l = DFT_l / n * sinc^2(l / n)`` (hat-function kernel).
"""

from __future__ import annotations

import numpy as np

from pipeline.signals import PeriodicSignal


def _antiderivative(signal: PeriodicSignal, sigma: np.ndarray) -> np.ndarray:
    """Integral of the linear interpolant from 0 to ``sigma`` (signal periods), same shape."""
    v = signal.values
    n = v.size
    v1 = np.roll(v, -1)
    cum = np.concatenate([[0.0], np.cumsum(0.5 * (v + v1))]) / n  # at k / n, k = 0..n
    p = np.floor(sigma)
    x = (sigma - p) * n
    k = np.minimum(np.floor(x).astype(int), n - 1)
    w = x - k
    return p * cum[-1] + cum[k] + (v[k] * w + 0.5 * (v1[k] - v[k]) * w * w) / n


def segment_means(
    signal: PeriodicSignal, order: int, phase: float, edges: np.ndarray
) -> np.ndarray:
    """Mean of ``s(order tau - phase)`` over each segment ``[edges[i], edges[i+1]]``.

    Parameters
    ----------
    edges : shape (m+1,), increasing system phases.

    Returns
    -------
    shape (m,), in the unit of the signal.
    """
    sig = order * np.asarray(edges, dtype=float) - phase
    F = _antiderivative(signal, sig)
    return np.diff(F) / np.diff(sig)


def segment_slopes(
    signal: PeriodicSignal, order: int, phase: float, edges: np.ndarray
) -> np.ndarray:
    """Mean of ``d/dtau s(order tau - phase)`` over each segment, shape (m,)."""
    e = np.asarray(edges, dtype=float)
    return np.diff(signal(order * e - phase)) / np.diff(e)


def fourier_coefficients(
    signal: PeriodicSignal, order: int, phase: float, n_harmonics: int
) -> np.ndarray:
    """Complex coefficients of ``s(order tau - phase)`` for harmonics h = -H..H.

    Returns
    -------
    shape (2H+1,), ``s = sum_h c_h exp(i 2 pi h tau)`` exactly for the linear
    interpolant (truncated at |h| <= H).
    """
    H = int(n_harmonics)
    v = signal.values
    n = v.size
    dft = np.fft.fft(v) / n
    h = np.arange(-H, H + 1)
    out = np.zeros(2 * H + 1, dtype=complex)
    mask = h % order == 0
    l = h[mask] // order
    out[mask] = dft[l % n] * np.sinc(l / n) ** 2 * np.exp(-2j * np.pi * l * phase)
    return out
