"""Idealised mesh excitations: rectangular-wave mesh stiffness, harmonic transmission error.

These stand in for the analytical or FE mesh stiffness when a study needs an
exactly known signal (exact checks, parameter studies) and are the classical
idealisation of a spur mesh: the stiffness alternates between a double-contact
level for a fraction ``contact_ratio - 1`` of the mesh period and a single-contact
level for the rest.
"""

from __future__ import annotations

import numpy as np

from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_int_range, check_positive, check_range

MAX_MESH_STIFFNESS = 1e14
"""Largest mesh stiffness level or amplitude, N/m (as the bearing stiffnesses of
:mod:`pipeline.dynamics.options`; real meshes are 1e8-1e10 N/m)."""


def rectangular_mesh_stiffness(
    k_single: float,
    k_double: float,
    contact_ratio: float,
    samples: int = 360,
    start: float = 0.0,
    period: float = float("nan"),
) -> PeriodicSignal:
    """Rectangular-wave mesh stiffness over one mesh period.

    Parameters
    ----------
    k_single, k_double : stiffness with one and two tooth pairs in contact, N/m.
    contact_ratio : epsilon in (1, 2]; double contact lasts ``epsilon - 1`` periods.
    samples : samples per period (the jump is resolved to one sample).
    start : mesh phase at which double contact begins (0..1).
    period : mesh period in s, if known.

    Returns
    -------
    :class:`PeriodicSignal` of the stiffness in N/m.
    """
    check_range("k_single", k_single, 0.0, MAX_MESH_STIFFNESS, lo_open=True, unit="N/m")
    check_range("k_double", k_double, 0.0, MAX_MESH_STIFFNESS, lo_open=True, unit="N/m")
    check_range("contact_ratio", contact_ratio, 1.0, 2.0, lo_open=True)
    check_range("start", start, 0.0, 1.0, hi_open=True)
    n = check_int_range("samples", samples, 8, 10_000_000)
    tau = (np.arange(n) / n - start) % 1.0
    return PeriodicSignal(np.where(tau < contact_ratio - 1.0 - 1e-12, k_double, k_single), period)


def harmonic_signal(
    mean: float, amplitudes, phases=None, samples: int = 360, period: float = float("nan")
) -> PeriodicSignal:
    """``mean + sum_l a_l cos(2 pi l tau + phi_l)`` sampled over one period.

    Parameters
    ----------
    mean : signal mean (its unit).
    amplitudes : shape (L,), amplitude of orders 1..L.
    phases : shape (L,), rad (default zeros).
    samples : samples per period.
    """
    a = np.atleast_1d(np.asarray(amplitudes, dtype=float))
    p = np.zeros_like(a) if phases is None else np.atleast_1d(np.asarray(phases, dtype=float))
    check_range("mean", mean, -MAX_MESH_STIFFNESS, MAX_MESH_STIFFNESS)
    for i, (ai, pi) in enumerate(zip(a, p, strict=True)):
        check_range(f"amplitudes[{i}]", ai, -MAX_MESH_STIFFNESS, MAX_MESH_STIFFNESS)
        check_range(f"phases[{i}]", pi, -2 * np.pi, 2 * np.pi, unit="rad")
    n = check_int_range("samples", samples, 8, 10_000_000)
    tau = np.arange(n) / n
    l = np.arange(1, a.size + 1)
    return PeriodicSignal(
        mean + (a * np.cos(2 * np.pi * l * tau[:, None] + p)).sum(axis=1), period
    )


def contact_line_stiffness(
    k_mean: float,
    transverse_ratio: float,
    overlap_ratio: float,
    samples: int = 360,
    period: float = float("nan"),
) -> PeriodicSignal:
    """Helical mesh stiffness ``k(t) = k_0 L(t)`` from the contact-line length (Xu et al. 2020, eq.
    13).

    On the plane of action (transverse length ``eps_alpha`` and axial length
    ``eps_beta``, both in base pitches) each tooth pair touches along a line
    ``s + z = c``; its length inside the rectangle is summed over all pairs in
    contact and scaled so that the mean stiffness is ``k_mean``.

    Parameters
    ----------
    k_mean : mean mesh stiffness, N/m.
    transverse_ratio : eps_alpha > 1 (or > 0 when ``overlap_ratio`` > 0).
    overlap_ratio : eps_beta >= 0 (0 gives the rectangular spur wave).
    samples : samples per mesh period.

    Returns
    -------
    :class:`PeriodicSignal` in N/m.
    """
    check_range("k_mean", k_mean, 0.0, MAX_MESH_STIFFNESS, lo_open=True, unit="N/m")
    check_range("transverse_ratio", transverse_ratio, 0.0, 10.0, lo_open=True)
    check_range("overlap_ratio", overlap_ratio, 0.0, 20.0)
    n = check_int_range("samples", samples, 8, 10_000_000)
    ea, eb = transverse_ratio, overlap_ratio
    tau = np.arange(n) / n
    j = np.arange(-int(np.ceil(ea + eb)) - 1, 2)
    c = tau[:, None] + j[None, :] + ea + eb  # line positions covering the rectangle
    if eb == 0.0:
        L = ((c >= 0) & (c < ea)).sum(axis=1).astype(float)
    else:
        L = np.clip(np.minimum(eb, c) - np.maximum(0.0, c - ea), 0.0, None).sum(axis=1)
    return PeriodicSignal(k_mean * L / L.mean(), period)


def constant_pair_excitation(
    s_start: float,
    s_end: float,
    s_pitch: float,
    base_pitch: float,
    t1t2: float,
    k_pair: float,
    friction: float = 0.0,
    samples: int = 360,
    period: float = float("nan"),
):
    """Mesh stiffness and friction coefficients (Jin et al. 2018) of a spur mesh, constant pair
    stiffness.

    Each tooth pair in contact adds ``k_pair``; pairs enter at roll coordinate
    ``s_start`` and leave at ``s_end`` one base pitch apart (pinion driving). The
    friction of a pair is ``mu lambda k_pair delta`` along the profile normal ``n``
    (``lambda = +1`` before the pitch point, ``-1`` after: it opposes the sliding of
    the pinion flank), with arms ``rho1 = s`` on the pinion and ``rho2 = T1T2 - s``
    on the gear (Jin et al. 2018, eqs. 15-16). Signs follow
    :mod:`pipeline.dynamics.mesh_geometry` (+n on the pinion; torques positive in
    each gear's own sense of rotation).

    Parameters
    ----------
    s_start, s_end, s_pitch : roll coordinates of contact start, end and pitch point, m.
    base_pitch : transverse base pitch, m.
    t1t2 : distance between the base-circle tangent points, m.
    k_pair : stiffness of one tooth pair, N/m.
    friction : constant friction coefficient mu (-).
    samples : samples per mesh period.

    Returns
    -------
    (k, K_f, K_Tf_pinion, K_Tf_gear) as :class:`PeriodicSignal` in N/m, N/m, N m/m, N m/m.
    """
    check_positive("k_pair", k_pair, "N/m")
    check_range("friction", friction, 0.0, 0.5)
    n = check_int_range("samples", samples, 8, 10_000_000)
    if not s_start < s_pitch < s_end:
        raise InputError(
            f"s_pitch = {s_pitch:.6g} m must lie between s_start = {s_start:.6g} "
            f"and s_end = {s_end:.6g} m"
        )
    tau = np.arange(n) / n
    j = np.arange(int(np.ceil((s_end - s_start) / base_pitch)) + 1)
    s = s_start + (tau[:, None] + j[None, :]) * base_pitch
    on = s <= s_end
    lam = np.where(s < s_pitch, 1.0, -1.0) * on
    k = k_pair * on.sum(axis=1)
    kf = friction * k_pair * lam.sum(axis=1)
    kt1 = friction * k_pair * (lam * s).sum(axis=1)
    kt2 = -friction * k_pair * (lam * (t1t2 - s)).sum(axis=1)
    return tuple(PeriodicSignal(v, period) for v in (k, kf, kt1, kt2))
