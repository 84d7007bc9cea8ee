"""Assembly: bodies + couplings + loads -> :class:`LinearPeriodicSystem`.

The assembly is the only place where equations are built; models (spur pair,
planetary sets, split-torque gearbox) only list bodies and couplings.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Protocol

import numpy as np
import scipy.linalg as sla

from pipeline.dynamics.bodies import Body
from pipeline.dynamics.couplings import (
    Bearing,
    GearMesh,
    Load,
    MatrixCoupling,
    Spring,
    Tie,
    TorsionalShaft,
)
from pipeline.dynamics.system import ForcingTerm, LinearPeriodicSystem, MeshOutput, ParametricTerm
from pipeline.signals import PeriodicSignal
from pipeline.validation import InputError, check_positive, check_range


@dataclass(frozen=True)
class Assembly:
    """A gearbox layout at one operating point.

    Attributes
    ----------
    bodies : the rigid bodies (unique names).
    couplings : springs, bearings, shafts, meshes, matrix couplings and ties.
    loads : constant external forces and torques.
    period : system period T in s (one mesh period for a single-stage set).
    carrier_speed : Omega in rad/s for bodies in the rotating (carrier) frame.
    name : label.
    modal_damping_ratio : zeta (-) of a constant modal damping added to every elastic
        mode of the mean stiffness, ``C += M Phi diag(2 zeta omega) Phi^T M`` (Xu et al. 2020
        sec. 2.3 "constant modal damping"); 0 adds none.
    """

    bodies: Sequence[Body]
    couplings: Sequence[object]
    loads: Sequence[Load] = ()
    period: float = 1.0
    carrier_speed: float = 0.0
    name: str = "assembly"
    modal_damping_ratio: float = 0.0
    _index: dict = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        object.__setattr__(self, "bodies", tuple(self.bodies))
        object.__setattr__(self, "couplings", tuple(self.couplings))
        object.__setattr__(self, "loads", tuple(self.loads))
        check_positive("period", self.period, "s")
        check_range("carrier_speed", self.carrier_speed, -1e5, 1e5, unit="rad/s")
        check_range("modal_damping_ratio", self.modal_damping_ratio, 0.0, 1.0)
        index: dict[tuple[str, str], int] = {}
        for b in self.bodies:
            for d in b.dofs:
                if (b.name, d) in index:
                    raise InputError(f"body name {b.name!r} is used twice")
                index[(b.name, d)] = len(index)
        object.__setattr__(self, "_index", index)

    @property
    def dof_names(self) -> tuple[str, ...]:
        return tuple(f"{b}.{d}" for (b, d) in self._index)

    def _vector(self, measure, what: str) -> np.ndarray:
        v = np.zeros(len(self._index))
        for (body, dof), c in measure:
            try:
                v[self._index[(body, dof)]] += c
            except KeyError:
                raise InputError(f"{what}: no coordinate {body}.{dof} in the assembly") from None
        return v

    def assemble(self) -> LinearPeriodicSystem:
        """Build M, C, K, G, K_Omega, the periodic terms and the forces (see module doc)."""
        n = len(self._index)
        M = np.zeros((n, n))
        G = np.zeros((n, n))
        Kw = np.zeros((n, n))
        for b in self.bodies:
            for d in b.dofs:
                i = self._index[(b.name, d)]
                M[i, i] = b.mass_of(d)
            if b.rotating_frame and "x" in b.dofs and "y" in b.dofs:
                ix, iy = self._index[(b.name, "x")], self._index[(b.name, "y")]
                # carrier frame: Coriolis 2 m Omega (-y', x'), centripetal m Omega^2 (x, y)
                G[ix, iy] -= 2 * b.mass
                G[iy, ix] += 2 * b.mass
                Kw[ix, ix] += b.mass
                Kw[iy, iy] += b.mass
        K = np.zeros((n, n))
        C = np.zeros((n, n))
        f0 = np.zeros(n)
        terms: list[ParametricTerm] = []
        forcing: list[ForcingTerm] = []
        meshes: list[MeshOutput] = []
        ties: list[Tie] = []
        springs: list[Spring] = []
        for c in self.couplings:
            if isinstance(c, (Bearing, TorsionalShaft)):
                springs.extend(c.springs())
            elif isinstance(c, Spring):
                springs.append(c)
            elif isinstance(c, MatrixCoupling):
                idx = [self._coord(cc, c.name) for cc in c.coordinates]
                K[np.ix_(idx, idx)] += c.stiffness
                if c.damping is not None:
                    C[np.ix_(idx, idx)] += c.damping
            elif isinstance(c, Tie):
                ties.append(c)
            elif isinstance(c, GearMesh):
                self._add_mesh(c, M, C, terms, forcing, meshes)
            else:
                raise InputError(f"unknown coupling type {type(c).__name__}")
        for s in springs:
            v = self._vector(s.measure, s.name)
            K += s.stiffness * np.outer(v, v)
            C += s.damping * np.outer(v, v)
        for ld in self.loads:
            f0[self._coord((ld.body, ld.dof), "load")] += float(ld.value)
        B = self._tie_basis(ties)

        def red(A: np.ndarray) -> np.ndarray:
            return B.T @ A @ B

        system = LinearPeriodicSystem(
            dof_names=self.dof_names,
            basis=B,
            coordinate_mass=M.diagonal().copy(),
            M=red(M),
            C=red(C),
            K=red(K),
            G=red(G),
            K_omega=red(Kw),
            f0=B.T @ f0,
            terms=tuple(
                ParametricTerm(t.name, t.signal, B.T @ t.u, B.T @ t.v, t.phase, t.order)
                for t in terms
            ),
            forcing=tuple(
                ForcingTerm(f.signal, B.T @ f.vector, f.phase, f.order, f.derivative)
                for f in forcing
            ),
            meshes=tuple(
                MeshOutput(m.name, B.T @ m.v, m.term, m.damping, m.transmission_error)
                for m in meshes
            ),
            period=self.period,
            carrier_speed=self.carrier_speed,
            name=self.name,
        )
        if self.modal_damping_ratio > 0.0:
            system = replace(
                system, C=system.C + modal_damping_matrix(system, self.modal_damping_ratio)
            )
        return system

    def _coord(self, coord, what: str) -> int:
        try:
            return self._index[tuple(coord)]
        except KeyError:
            raise InputError(
                f"{what}: no coordinate {coord[0]}.{coord[1]} in the assembly"
            ) from None

    def _add_mesh(self, mesh: GearMesh, M, C, terms, forcing, meshes) -> None:
        v = self._vector(mesh.measure, mesh.name)
        k_mean = mesh.stiffness.mean()
        me = mesh.equivalent_mass
        if me is None:
            rot = np.array([self._index[(b, d)] for (b, d), _ in mesh.measure if d == "theta"])
            sel = rot if rot.size else np.flatnonzero(v)
            me = 1.0 / float(np.sum(v[sel] ** 2 / np.diag(M)[sel]))
        c = 2.0 * mesh.damping_ratio * math.sqrt(k_mean * me)
        C += c * np.outer(v, v)
        e = mesh.transmission_error
        k_index = len(terms)
        terms.append(ParametricTerm(mesh.name, mesh.stiffness, v, v, mesh.phase, mesh.order))
        for fr in mesh.friction:
            u = -self._vector(fr.pattern, f"{mesh.name}.friction")
            terms.append(
                ParametricTerm(
                    f"{mesh.name}.friction", fr.coefficient, u, v, mesh.phase, mesh.order
                )
            )
        if e is not None:
            for t in terms[k_index:]:
                forcing.append(ForcingTerm(_product(t.signal, e), t.u, mesh.phase, mesh.order))
            if c > 0:
                forcing.append(ForcingTerm(e, c * v, mesh.phase, mesh.order, derivative=True))
        meshes.append(MeshOutput(mesh.name, v, k_index, c, e))

    def _tie_basis(self, ties: list[Tie]) -> np.ndarray:
        n = len(self._index)
        parent = list(range(n))

        def find(i: int) -> int:
            while parent[i] != i:
                parent[i] = parent[parent[i]]
                i = parent[i]
            return i

        for t in ties:
            for d in t.dofs:
                a = self._coord((t.body1, d), f"tie {t.body1}-{t.body2}")
                b = self._coord((t.body2, d), f"tie {t.body1}-{t.body2}")
                ra, rb = find(a), find(b)
                if ra != rb:
                    parent[max(ra, rb)] = min(ra, rb)
        roots = sorted({find(i) for i in range(n)})
        col = {r: j for j, r in enumerate(roots)}
        B = np.zeros((n, len(roots)))
        for i in range(n):
            B[i, col[find(i)]] = 1.0
        return B


def modal_damping_matrix(system: LinearPeriodicSystem, ratio: float) -> np.ndarray:
    """``M Phi diag(2 zeta omega_k) Phi^T M`` over the elastic modes of the mean stiffness, (n, n).

    Parameters
    ----------
    system : assembled system (M in kg / kg m^2; mass-normalised modes Phi).
    ratio : zeta (-), the same for every mode; rigid-body modes (omega = 0) get none.
    """
    K = system.K.copy()
    for t in system.terms:
        if np.array_equal(t.u, t.v):
            K += t.signal.mean() * np.outer(t.u, t.v)
    w2, phi = sla.eigh(0.5 * (K + K.T), system.M)
    w = np.sqrt(np.clip(w2, 0.0, None))
    w[w2 < 1e-9 * w2.max()] = 0.0
    MP = system.M @ phi
    return (MP * (2.0 * ratio * w)) @ MP.T


def _product(a: PeriodicSignal, b: PeriodicSignal) -> PeriodicSignal:
    """Pointwise product of two periodic signals, sampled on the finer of the two grids."""
    n = max(a.values.size, b.values.size)
    if a.values.size != b.values.size:
        n = 2 * n
    tau = np.arange(n) / n
    return PeriodicSignal(a(tau) * b(tau), a.period)


class DynamicModel(Protocol):
    """Any lumped-parameter model of :mod:`pipeline.dynamics.models`: what the analyses and
    the run need of it is its :class:`Assembly` (bodies, couplings, loads)."""

    def assembly(self) -> Assembly:
        """The model's bodies, couplings and loads."""
        ...
