"""Superposition of stage responses for gear trains with incommensurate mesh frequencies.

Jin et al. (2018)'s Fourier series method splits every time-varying coefficient into its
mean and its fluctuation, keeps the fluctuations to first order, and adds up the
responses to each excitation. Stages that mesh at incommensurate frequencies then
superpose: stage s is solved alone (its coefficients vary with its own mesh period
T_s, all others are held at their means) and

    q(t) = Q_0 + sum_s (q_s(t) - Q_0),

where Q_0, the static response under mean coefficients, is common to all stage
systems. Within a stage the harmonic balance keeps its full (Hill) coupling; only
the cross-stage products of fluctuations are dropped.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from pipeline.dynamics.harmonic_balance import harmonic_balance
from pipeline.dynamics.results import HarmonicResponse
from pipeline.dynamics.system import LinearPeriodicSystem
from pipeline.validation import InputError, check_positive


@dataclass(frozen=True)
class MultiRateResponse:
    """DTE of every mesh from superposed stage responses.

    Attributes
    ----------
    time : shape (N,), s.
    dte : shape (n_mesh, N), dynamic transmission error along each line of action, m.
    mesh_names : row labels of ``dte``.
    stages : the harmonic-balance solution of each stage system (per-order amplitudes
        and contribution proportions of that stage's harmonic orders).
    """

    time: np.ndarray
    dte: np.ndarray
    mesh_names: tuple[str, ...]
    stages: Mapping[str, HarmonicResponse]

    def mesh(self, name: str) -> int:
        """Row of a mesh in ``dte``."""
        return self.mesh_names.index(name)


def _dte_series(hr: HarmonicResponse, t: np.ndarray) -> np.ndarray:
    """DTE of every mesh of one stage solution at times ``t`` (s), shape (n_mesh, N)."""
    D = hr.dte_coefficients  # (2H+1, n_mesh)
    H = (D.shape[0] - 1) // 2
    h = np.arange(-H, H + 1)
    E = np.exp(2j * np.pi * np.outer(t / hr.response.period, h))
    return (E @ D).real.T


def superpose_stages(
    systems: Mapping[str, LinearPeriodicSystem],
    n_harmonics: int,
    duration: float,
    samples: int = 2000,
    coupling: str = "full",
) -> MultiRateResponse:
    """Harmonic balance of each stage system and the superposed DTE over ``duration``.

    Parameters
    ----------
    systems : stage name -> system in which only that stage varies (same bodies,
        couplings and mean coefficients; periods differ).
    n_harmonics : H of every stage solution.
    duration : s, length of the returned time history (from t = 0).
    samples : time samples.
    coupling : "full" (Hill within each stage) or "first_order" (Jin et al. 2018 throughout).
    """
    check_positive("duration", duration, "s")
    if not systems:
        raise InputError("superpose_stages needs at least one stage system")
    stages = {
        name: harmonic_balance(s, n_harmonics, coupling=coupling) for name, s in systems.items()
    }
    names = {tuple(hr.response.mesh_names) for hr in stages.values()}
    if len(names) != 1:
        raise InputError("the stage systems do not have the same meshes")
    # static DTE under the mean coefficients (order 0 of the first-order solution)
    q0 = [
        harmonic_balance(s, 1, coupling="first_order").dte_coefficients[1].real
        for s in systems.values()
    ]
    if not np.allclose(q0, q0[0], rtol=1e-8, atol=1e-15):
        raise InputError(
            "the stage systems have different static responses (mean coefficients differ)"
        )
    t = np.linspace(0.0, duration, int(samples))
    dte = sum(_dte_series(hr, t) for hr in stages.values()) - (len(stages) - 1) * q0[0][:, None]
    return MultiRateResponse(time=t, dte=dte, mesh_names=names.pop(), stages=stages)
