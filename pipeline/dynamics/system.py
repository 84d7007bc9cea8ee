"""The assembled linear time-periodic system that every solver works on.

    M q'' + (C + Omega G) q' + (K - Omega^2 K_Omega + sum_j s_j(tau_j) u_j v_j^T) q
        = f0 + sum_i g_i(tau_i)

with the system phase ``tau = t / T`` (T the system period, normally one mesh
period), ``tau_j = order_j tau - phase_j`` the phase of term j, Omega the carrier
speed (rad/s) for bodies in a rotating frame. Each time-varying term is rank one,
``s_j(tau) u_j v_j^T`` (a mesh stiffness has ``u = v``; a friction term has the
friction pattern as ``u``), which is what makes the Woodbury harmonic balance cheap.

Coordinates: ``q`` are the *independent* coordinates; ``q_full = basis @ q``
restores every named DOF (ties remove coordinates).
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from pipeline.signals import PeriodicSignal
from pipeline.validation import check_positive


@dataclass(frozen=True)
class ParametricTerm:
    """Rank-one periodic stiffness ``s(order tau - phase) u v^T``.

    Attributes
    ----------
    name : label (mesh name, or mesh name + ".friction").
    signal : s over one of its own periods (N/m, or N m/m for friction torques).
    u : shape (n,), generalized-force pattern.
    v : shape (n,), measure.
    phase : delay in periods of the signal.
    order : signal periods per system period.
    """

    name: str
    signal: PeriodicSignal
    u: np.ndarray
    v: np.ndarray
    phase: float = 0.0
    order: int = 1


@dataclass(frozen=True)
class ForcingTerm:
    """Periodic force ``g(tau) = vector * s(order tau - phase)`` (or its time derivative).

    Attributes
    ----------
    signal : s, dimensionless carrier of the time dependence (unit folded in ``vector``).
    vector : shape (n,), N or N m per unit of s.
    phase, order : as in :class:`ParametricTerm`.
    derivative : the force is ``vector * d s / dt`` (1/s) instead of ``vector * s``.
    """

    signal: PeriodicSignal
    vector: np.ndarray
    phase: float = 0.0
    order: int = 1
    derivative: bool = False


@dataclass(frozen=True)
class MeshOutput:
    """What is needed to rebuild a mesh force from the response.

    Attributes
    ----------
    name : mesh name.
    v : shape (n,), measure (delta = v . q), m per coordinate unit.
    term : index of the mesh-stiffness term in ``system.terms``.
    damping : mesh damping c in N s/m.
    transmission_error : e(tau) in m or ``None``.
    """

    name: str
    v: np.ndarray
    term: int
    damping: float
    transmission_error: PeriodicSignal | None = None


@dataclass(frozen=True)
class SystemMatrices:
    """The equation-of-motion matrices at one phase, dense or sparse.

    ``M q'' + (C + Omega G) q' + K q = F`` at phase ``tau``.

    Attributes
    ----------
    tau : system phase t / T (-).
    M : (n, n) mass, kg and kg m^2.
    C : (n, n) damping, N s/m (without the gyroscopic part).
    G : (n, n) gyroscopic matrix per unit carrier speed (multiply by Omega, rad/s).
    K_omega : (n, n) centripetal matrix per unit Omega^2.
    K : (n, n) full stiffness K(tau) = K - Omega^2 K_Omega + sum_j s_j u_j v_j^T, N/m.
    F : shape (n,), generalized force F(tau), N and N m.
    carrier_speed : Omega, rad/s.
    """

    tau: float
    M: object
    C: object
    G: object
    K_omega: object
    K: object
    F: np.ndarray
    carrier_speed: float


@dataclass(frozen=True)
class LinearPeriodicSystem:
    """Matrices and periodic terms of one operating point.

    Attributes
    ----------
    dof_names : names of the full coordinates, ``"body.dof"``, length n_full.
    basis : (n_full, n), ``q_full = basis @ q``.
    coordinate_mass : (n_full,), mass (kg) or polar moment of inertia (kg m^2) of each
        named coordinate's own body, so that ``M = basis.T @ diag(coordinate_mass) @ basis``
        and ``coordinate_mass * q_full**2`` splits the kinetic energy over the named
        coordinates (tied coordinates each keep their own body's share).
    M, C, K, G, K_omega : (n, n) mass (kg, kg m^2), damping, constant stiffness,
        gyroscopic (per unit carrier speed) and centripetal (per unit Omega^2) matrices.
    f0 : (n,) constant generalized force (N, N m).
    terms : rank-one periodic stiffness terms.
    forcing : periodic forces.
    meshes : mesh outputs (one per gear mesh).
    period : system period T in s.
    carrier_speed : Omega in rad/s (0 for fixed-axis gearboxes).
    name : label.
    """

    dof_names: tuple[str, ...]
    basis: np.ndarray
    coordinate_mass: np.ndarray
    M: np.ndarray
    C: np.ndarray
    K: np.ndarray
    G: np.ndarray
    K_omega: np.ndarray
    f0: np.ndarray
    terms: tuple[ParametricTerm, ...]
    forcing: tuple[ForcingTerm, ...]
    meshes: tuple[MeshOutput, ...]
    period: float
    carrier_speed: float = 0.0
    name: str = "system"

    @property
    def n(self) -> int:
        """Number of independent coordinates."""
        return self.M.shape[0]

    @property
    def frequency(self) -> float:
        """Fundamental frequency 1/T in Hz."""
        return 1.0 / self.period

    def damping_matrix(self) -> np.ndarray:
        """C + Omega G, (n, n)."""
        return self.C + self.carrier_speed * self.G

    def constant_stiffness(self) -> np.ndarray:
        """K - Omega^2 K_Omega, (n, n), without the periodic terms."""
        return self.K - self.carrier_speed**2 * self.K_omega

    def term_values(self, tau: np.ndarray) -> np.ndarray:
        """Periodic coefficients at system phases ``tau``: shape (n_terms, len(tau))."""
        tau = np.atleast_1d(np.asarray(tau, dtype=float))
        return np.array([t.signal(t.order * tau - t.phase) for t in self.terms]).reshape(
            len(self.terms), tau.size
        )

    def stiffness(self, tau: float) -> np.ndarray:
        """Full stiffness K(tau), (n, n)."""
        s = self.term_values(np.array([tau]))[:, 0]
        return self.constant_stiffness() + self._rank_sum(s)

    def mean_stiffness(self) -> np.ndarray:
        """Stiffness with every periodic coefficient replaced by its mean, (n, n)."""
        s = np.array([t.signal.mean() for t in self.terms])
        return self.constant_stiffness() + self._rank_sum(s)

    def _rank_sum(self, s: np.ndarray) -> np.ndarray:
        if not self.terms:
            return np.zeros((self.n, self.n))
        U = np.array([t.u for t in self.terms]).T
        V = np.array([t.v for t in self.terms]).T
        return (U * s) @ V.T

    def force(self, tau: float) -> np.ndarray:
        """Generalized force F(tau) = f0 + sum_i g_i(tau_i), shape (n,), N and N m.

        A ``derivative`` forcing term uses the central difference of its sampled
        signal over one sample (exact for the piecewise-linear interpolant away from
        its nodes).
        """
        f = np.array(self.f0, dtype=float, copy=True)
        for g in self.forcing:
            x = g.order * tau - g.phase
            if g.derivative:
                h = 0.5 / g.signal.values.size
                ds = (g.signal(x + h) - g.signal(x - h)) / (2 * h)  # per signal period
                f = f + g.vector * float(np.squeeze(ds)) * g.order / self.period
            else:
                f = f + g.vector * float(np.squeeze(g.signal(x)))
        return f

    def matrices(self, tau: float = 0.0, sparse: bool = False) -> SystemMatrices:
        """M, C, G, K_Omega, K(tau) and F(tau) as dense arrays or scipy CSR arrays.

        Parameters
        ----------
        tau : system phase t / T (-).
        sparse : return ``scipy.sparse.csr_array`` matrices (F stays dense).
        """
        mats = (self.M, self.C, self.G, self.K_omega, self.stiffness(tau))
        if sparse:
            from scipy.sparse import csr_array

            mats = tuple(csr_array(m) for m in mats)
        M, C, G, Kw, K = mats
        return SystemMatrices(float(tau), M, C, G, Kw, K, self.force(tau), self.carrier_speed)

    def with_period(self, period: float) -> LinearPeriodicSystem:
        """The same machine at another speed: period T' and carrier speed scaled by T/T'.

        Parameters
        ----------
        period : new system period in s.
        """
        check_positive("period", period, "s")
        return replace(
            self, period=period, carrier_speed=self.carrier_speed * self.period / period
        )

    def with_mesh_frequency(self, frequency: float) -> LinearPeriodicSystem:
        """Shorthand for :meth:`with_period` with ``T = 1 / frequency`` (Hz)."""
        check_positive("mesh_frequency", frequency, "Hz")
        return self.with_period(1.0 / frequency)

    def expand(self, q: np.ndarray) -> np.ndarray:
        """Independent coordinates (..., n) -> full named coordinates (..., n_full)."""
        return np.asarray(q) @ self.basis.T

    def index(self, name: str) -> int:
        """Position of a full coordinate name (``"body.dof"``) in ``dof_names``."""
        return self.dof_names.index(name)
