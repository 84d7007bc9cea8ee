"""The ``"beam"`` shaft model: Timoshenko beam finite elements of one shaft and its bearings.

The shaft is a line of two-node Timoshenko elements (:mod:`.timoshenko`: bending in both
planes with shear, torsion ``G J``, axial ``E A``; 6 DOFs per node) whose nodes include
every segment end, the seat's ends and centre, each bearing, the torque point and any
point a load or a flexibility asks for (:mod:`.nodes`). The element is exact at its
nodes for loads at nodes, so the statics do not depend on the mesh; the element length
matters only for the mass matrix (the dynamics).

Supports (:class:`~pipeline.shaft.layout.Bearing`):

* a bearing's radial stiffness acts on u_x and u_y, its tilting stiffness on theta_x and
  theta_y, as springs at its node; ``inf`` is a rigid support, eliminated exactly
  (:mod:`.constraints`), never a penalty;
* the axial bearing fixes u_z; the torque point fixes theta_z (the torque is held there).

The seat (:attr:`~pipeline.shaft.layout.ShaftLayout.hub`): ``"rigid"`` makes the seat's
nodes move as one rigid body with the seat's centre node (a master-slave transformation,
exact); ``"integral"`` leaves the seat as ordinary elements of its segment's diameter.

Off-node points: :meth:`BeamShaft.solve` and :meth:`BeamShaft.flexibility` build (and
return results of) a copy of the model with nodes added at the loads' and the asked
points (:meth:`BeamShaft.with_nodes`), so they are exact, never interpolated. A caller
that asks often at the same points builds the model once with ``extra_nodes`` holding
them; then nothing is rebuilt.

Equations: ``K u = f + r`` with ``K`` the beam elements and the bearing springs, ``r``
the rigid supports' loads; ``u = B p`` with ``B = T Z`` (:mod:`.constraints`) and
``B^T K B p = B^T f`` solved with one sparse LU factorisation, reused for every right-hand
side.
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field, replace

import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as spla

from pipeline.shaft import constraints, nodes, timoshenko
from pipeline.shaft.layout import ShaftLayout
from pipeline.shaft.model import PointLoad, ShaftSolution
from pipeline.validation import InputError, check_range

DOF_NAMES = ("u_x", "u_y", "u_z", "theta_x", "theta_y", "theta_z")


@dataclass(frozen=True)
class Disc:
    """A rigid body on the shaft (a gear body, a coupling half) for the mass matrix.

    Attributes
    ----------
    z : its axial position, m (a node of the model).
    mass : kg (on u_x, u_y, u_z).
    polar_inertia : moment of inertia about the shaft's axis, kg m^2 (on theta_z).
    diametral_inertia : about a diameter, kg m^2 (on theta_x and theta_y).
    """

    z: float
    mass: float = 0.0
    polar_inertia: float = 0.0
    diametral_inertia: float = 0.0

    def __post_init__(self) -> None:
        check_range("disc.mass", self.mass, 0.0, unit="kg")
        check_range("disc.polar_inertia", self.polar_inertia, 0.0, unit="kg m^2")
        check_range("disc.diametral_inertia", self.diametral_inertia, 0.0, unit="kg m^2")


@dataclass(frozen=True)
class _Supports:
    """The rigid supports as rows of ``C u = 0`` and their reduction (module docstring)."""

    rows: np.ndarray          # (r,) constrained DOFs
    owner: tuple[int, ...]    # bearing index per row; -1 for the torque point
    transform: sp.csr_matrix  # T (the rigid seat)
    a: sp.csr_matrix          # C T
    basis: sp.csr_matrix      # B = T Z, (6n, n_reduced)


def _dofs(index: np.ndarray) -> np.ndarray:
    return (6 * np.asarray(index)[:, None] + np.arange(6)).ravel()


def _assemble(element: np.ndarray, n_nodes: int) -> sp.csr_matrix:
    """(6n, 6n) sparse matrix from (ne, 12, 12) element matrices of consecutive nodes."""
    ne = element.shape[0]
    dof = (6 * np.arange(ne)[:, None] + np.arange(12))            # (ne, 12)
    rows = np.broadcast_to(dof[:, :, None], element.shape).ravel()
    cols = np.broadcast_to(dof[:, None, :], element.shape).ravel()
    return sp.csr_matrix((element.ravel(), (rows, cols)), shape=(6 * n_nodes, 6 * n_nodes))


@dataclass(frozen=True)
class BeamShaft:
    """Timoshenko beam model of one shaft (module docstring); a
    :class:`~pipeline.shaft.model.ShaftModel`.

    Parameters
    ----------
    layout : the shaft.
    element_length : element-length target, m, in (0, the shaft's length]; default the
        shaft's length / 24; at least two elements between neighbouring key points.
    extra_nodes : points that must be nodes (loads, seat points), m, on the shaft.

    Attributes
    ----------
    z : (n,) node positions, m.
    """

    layout: ShaftLayout
    element_length: float | None = None
    extra_nodes: tuple[float, ...] = ()
    z: np.ndarray = field(init=False, repr=False, compare=False)
    _stiffness: sp.csr_matrix = field(init=False, repr=False, compare=False)
    _supports: _Supports = field(init=False, repr=False, compare=False)
    _factor: spla.SuperLU = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        lay = self.layout
        length_mm = lay.length * 1e3
        if self.element_length is not None:
            check_range(f"{lay.name}.element_length_mm", self.element_length * 1e3, 0.0,
                        length_mm, lo_open=True, unit="mm", note="the shaft's length")
        for p in self.extra_nodes:
            check_range(f"{lay.name} point z_mm", p * 1e3, 0.0, length_mm, unit="mm",
                        note="on the shaft")
        z = nodes.beam_nodes(lay, self.element_length, self.extra_nodes)
        z.flags.writeable = False
        set_ = object.__setattr__  # derived, immutable after construction
        set_(self, "z", z)
        k = _assemble(timoshenko.element_stiffness(self._sections()), z.size)
        set_(self, "_stiffness", (k + self._springs()).tocsr())
        sup = self._reduce(hold_torque=True)
        set_(self, "_supports", sup)
        kr = (sup.basis.T @ self._stiffness @ sup.basis).tocsc()
        set_(self, "_factor", spla.splu(kr))

    # -- the model's pieces ---------------------------------------------------------------

    def _sections(self) -> timoshenko.Sections:
        lay, z = self.layout, self.z
        ends = np.array([s.end for s in lay.segments])
        seg = np.minimum(np.searchsorted(ends, 0.5 * (z[:-1] + z[1:])), ends.size - 1)
        outer = np.array([s.outer_diameter for s in lay.segments])[seg]
        inner = np.array([s.inner_diameter for s in lay.segments])[seg]
        mat = lay.material
        return timoshenko.Sections(
            length=np.diff(z),
            area=np.pi / 4.0 * (outer**2 - inner**2),
            second_moment=np.pi / 64.0 * (outer**4 - inner**4),
            shear_coefficient=timoshenko.shear_coefficient(mat.poisson_ratio, outer, inner),
            youngs_modulus=mat.youngs_modulus, shear_modulus=mat.shear_modulus,
            density=mat.density)

    def node(self, points: Iterable[float] | np.ndarray) -> np.ndarray:
        """Indices of the nodes at ``points`` (m); ``ValueError`` if one is not a node."""
        return nodes.node_index(self.z, points, nodes.merge_tolerance(self.layout))

    def _bearing_nodes(self) -> np.ndarray:
        return self.node([b.position for b in self.layout.bearings])

    def _springs(self) -> sp.csr_matrix:
        """The elastic bearings' springs, (6n, 6n) diagonal."""
        diag = np.zeros(6 * self.z.size)
        for b, i in zip(self.layout.bearings, self._bearing_nodes(), strict=True):
            if math.isfinite(b.radial_stiffness):
                diag[6 * i + np.array([0, 1])] += b.radial_stiffness
            if math.isfinite(b.tilting_stiffness):
                diag[6 * i + np.array([3, 4])] += b.tilting_stiffness
        return sp.diags(diag).tocsr()

    def _transform(self) -> sp.csr_matrix:
        """``T``: identity, or the rigid seat's master-slave transformation."""
        if self.layout.hub != "rigid":
            return sp.identity(6 * self.z.size, format="csr")
        lo, hi = self.layout.seat
        tol = nodes.merge_tolerance(self.layout)
        master = int(self.node([self.layout.gear_position])[0])
        on_seat = np.flatnonzero((self.z >= lo - tol) & (self.z <= hi + tol))
        return constraints.rigid_body_transform(self.z, master, on_seat[on_seat != master])

    def _reduce(self, *, hold_torque: bool) -> _Supports:
        rows, owner = [], []
        for j, (b, i) in enumerate(zip(self.layout.bearings, self._bearing_nodes(),
                                       strict=True)):
            fixed = ([0, 1] if math.isinf(b.radial_stiffness) else []) + \
                    ([3, 4] if math.isinf(b.tilting_stiffness) else []) + \
                    ([2] if b.axial else [])
            rows += [6 * i + c for c in fixed]
            owner += [j] * len(fixed)
        if hold_torque:
            rows.append(6 * int(self.node([self.layout.torque_position])[0]) + 5)
            owner.append(-1)
        rows = np.array(rows, int)
        n = 6 * self.z.size
        c = sp.csr_matrix((np.ones(rows.size), (np.arange(rows.size), rows)),
                          shape=(rows.size, n))
        t = self._transform()
        a = (c @ t).tocsr()
        try:
            z = constraints.eliminate(a)
        except ValueError:
            raise InputError(f"{self.layout.name}.bearings: rigid supports hold the same "
                             "motion twice (clamping bearings on the rigid seat); make one "
                             "of them elastic") from None
        return _Supports(rows, tuple(owner), t, a, (t @ z).tocsr())

    # -- matrices for the dynamics ----------------------------------------------------------

    def stiffness_matrix(self) -> sp.csr_matrix:
        """(6n, 6n) stiffness of the beam elements and the elastic bearings on all nodal
        DOFs (node-major, order of :data:`DOF_NAMES`), N/m, N, N m/rad."""
        return self._stiffness

    def mass_matrix(self, discs: Sequence[Disc] = ()) -> sp.csr_matrix:
        """(6n, 6n) consistent mass of the shaft plus the ``discs`` at their nodes, kg,
        kg m, kg m^2 (order of :meth:`stiffness_matrix`)."""
        m = _assemble(timoshenko.element_mass(self._sections()), self.z.size)
        diag = np.zeros(6 * self.z.size)
        for d in discs:
            i = 6 * int(self.node([d.z])[0])
            diag[i:i + 6] += [d.mass, d.mass, d.mass, d.diametral_inertia,
                              d.diametral_inertia, d.polar_inertia]
        return (m + sp.diags(diag)).tocsr()

    def basis(self, *, hold_torque: bool = True) -> sp.csr_matrix:
        """(6n, n_reduced) ``B``: nodal DOFs ``u = B p`` that satisfy the rigid seat and the
        rigid supports exactly; ``hold_torque=False`` frees theta_z at the torque point
        (the dynamics put an inertia there). Reduce with ``B^T K B``, ``B^T M B``."""
        return self._supports.basis if hold_torque else self._reduce(hold_torque=False).basis

    # -- the ShaftModel interface -----------------------------------------------------------

    def with_nodes(self, points: Iterable[float]) -> BeamShaft:
        """This model, or a copy with nodes added at ``points`` (m) that are not nodes."""
        tol = nodes.merge_tolerance(self.layout)
        new = tuple(float(p) for p in points
                    if np.min(np.abs(self.z - p)) > tol)
        return self if not new else replace(self, extra_nodes=self.extra_nodes + new)

    def solve(self, loads: Sequence[PointLoad]) -> ShaftSolution:
        """The deflection line at every node and the supports' loads under ``loads``
        (anywhere on the shaft; off-node loads add nodes: module docstring)."""
        model = self.with_nodes(ld.z for ld in loads)
        if model is not self:
            return model.solve(loads)
        f = np.zeros(6 * self.z.size)
        for ld, i in zip(loads, self.node([ld.z for ld in loads]), strict=True):
            f[6 * i:6 * i + 6] += [*ld.force, *ld.moment]
        return self._solution(f)

    def _solution(self, f: np.ndarray) -> ShaftSolution:
        sup = self._supports
        u = sup.basis @ self._factor.solve(sup.basis.T @ f)
        lam = constraints.multipliers(sup.a, sup.transform.T @ (self._stiffness @ u - f))
        uu = u.reshape(-1, 6)
        reactions = np.zeros((len(self.layout.bearings), 6))
        for j, (b, i) in enumerate(zip(self.layout.bearings, self._bearing_nodes(),
                                       strict=True)):
            if math.isfinite(b.radial_stiffness):
                reactions[j, :2] -= b.radial_stiffness * uu[i, :2]
            if math.isfinite(b.tilting_stiffness):
                reactions[j, 3:5] -= b.tilting_stiffness * uu[i, 3:5]
        torque = 0.0
        for row, who, val in zip(sup.rows, sup.owner, lam, strict=True):
            if who < 0:
                torque += val
            else:
                reactions[who, row % 6] += val
        return ShaftSolution(z=self.z.copy(), displacement=uu[:, :3].copy(),
                             rotation=uu[:, 3:].copy(), reactions=reactions,
                             torque_reaction=float(torque))

    def flexibility(self, z: np.ndarray) -> np.ndarray:
        """(6m, 6m) generalised displacements at the points ``z`` (m,) per unit generalised
        load at each of them, point-major (order of :data:`DOF_NAMES`); m/N, rad/N,
        m/(N m), rad/(N m). Symmetric (Maxwell); off-node points add nodes (exact)."""
        z = np.atleast_1d(np.asarray(z, float))
        model = self.with_nodes(z)
        if model is not self:
            return model.flexibility(z)
        b = self._supports.basis[_dofs(self.node(z)), :]
        return b @ self._factor.solve(b.T.toarray())

    def seat_stiffness(self) -> np.ndarray:
        """(6, 6) stiffness at the seat's centre (the inverse of its flexibility): the
        bearings and the shaft in series, torsion to the torque point; N/m, N, N m/rad.
        ``ValueError`` if a support holds the centre rigidly in some DOF (e.g. the axial
        bearing at a rigid seat's end)."""
        g = self.flexibility(np.array([self.layout.gear_position]))
        diag = np.diag(g)
        held = diag <= 1e-12 * np.max(diag)
        if held.any():
            raise ValueError(f"{self.layout.name}: the seat's centre is held rigidly in "
                             f"{DOF_NAMES[int(np.argmax(held))]}; its stiffness is infinite")
        return np.linalg.inv(g)
