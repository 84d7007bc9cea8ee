"""Compliance sources: where the loaded-contact solver gets its candidate points and ``G``.

A compliance source describes one gear pair at any mesh position: which flank
points may touch (the *candidate points*) and the structural compliance matrix
``G`` (m/N) between them, without the local contact (Hertz) deformation, which
the solver adds itself (:mod:`pipeline.contact.hertz`). Two sources implement
the :class:`ComplianceSource` protocol:

* :class:`SliceCompliance` (here): the analytical slice potential-energy method
  of Yang et al. (2026) (section 2.1-2.4) on the tooth models of :mod:`pipeline.stiffness`;
* the FE influence coefficients of :mod:`pipeline.fem` (FE-enriched stiffness).

Conventions (the same as :mod:`pipeline.stiffness.mesh`)
--------------------------------------------------------
* A *mesh position* is the roll coordinate ``s0`` (m) of the leading tooth pair
  at face position ``z = 0``, in ``[s_start, s_start + p_bt)`` for one mesh cycle
  (:meth:`GearPair.mesh_cycle`). Tooth pair ``k`` (``k`` from
  :meth:`GearPair.pair_indices`) touches at ``s = s0 + k p_bt + z tan(beta_b)``.
* Loads and approaches are along the transverse line of action: ``F_i`` is the
  transverse component of the normal load carried by point ``i`` (N), and
  ``G_ij`` the approach along the line of action at ``i`` per unit such load at
  ``j`` (m/N). The normal load on the flank is ``F_i / cos(beta_b)`` and the
  contact line through a point of face width ``w_i`` is ``w_i / cos(beta_b)``
  long, so the unit load along the contact line is ``p_i = F_i / w_i`` (N/m).

Slice coupling. Yang et al. (2026) treat the slices as independent cantilevers: its
compliance matrix ``lambda_g`` (eq. 28) is diagonal, ``lambda_g,ii`` the
bending + shear + axial compression + foundation compliance of both teeth of
slice ``i`` (eq. 25 without the Hertz term). That is the default here
(``coupling = 0``). As an option (not in Yang et al. 2026) neighbouring slices of the
same tooth can be coupled: ``G = D^{1/2} (I - kappa L) D^{1/2}``, with ``D`` the
diagonal slice compliance and ``L`` the graph Laplacian of the chain of slices
in contact on each tooth. Rows of ``I - kappa L`` sum to one, so a uniformly
loaded tooth deflects as the independent slices do (the slice method's
stiffness is kept) while a load on one slice also deflects its neighbours;
``G`` is positive definite for ``0 <= kappa < 1/4`` (eigenvalues of ``L`` lie in
[0, 4)). Like a plate, the coupled tooth resists *curved* deflection: under an
imposed approach with a peak (crowning) or at a loaded face end (misalignment)
it concentrates load slightly more than independent slices do. It does not
model the softer free ends of a real tooth; kappa is not calibrated here (the
FE influence coefficients are the way to get the real coupling).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Protocol, runtime_checkable

import numpy as np

from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at, tip_zone
from pipeline.stiffness.friction import friction_direction
from pipeline.stiffness.mesh import (
    FrictionModel,
    OperatingPoint,
    PairModel,
    friction_coefficients,
)
from pipeline.stiffness.tooth import tooth_compliance
from pipeline.validation import InputError, check_int_range, check_range


@dataclass(frozen=True)
class ContactPoints:
    """Candidate contact points of one mesh position (``n`` points).

    Attributes
    ----------
    s : (n,) roll coordinate on the transverse line of action where the tooth pair's
        (extended) involutes cross it, m: inside ``[s_start, s_end]`` the contact is on
        the line of action; in the tip zone beyond either end
        (:func:`candidate_zone`) it is a tip corner against the mate's flank
        (:mod:`pipeline.geometry.tip_contact`).
    z : (n,) face position from the pinion's reference face, m, in ``[0, b]``.
    pair : (n,) int, tooth-pair index ``k`` (see :meth:`GearPair.pair_indices`).
    width : (n,) face width each point stands for (slice width), m, > 0.
    """

    s: np.ndarray
    z: np.ndarray
    pair: np.ndarray
    width: np.ndarray

    def __post_init__(self) -> None:
        arrays = {}
        for name, dtype in (("s", float), ("z", float), ("pair", int), ("width", float)):
            a = np.array(getattr(self, name), dtype=dtype).reshape(-1)
            a.setflags(write=False)
            arrays[name] = a
            object.__setattr__(self, name, a)
        n = arrays["s"].size
        for name, a in arrays.items():
            if a.size != n:
                raise InputError(f"contact points: {name} has {a.size} entries; expected {n}")
        if n and (~np.isfinite(arrays["width"]) | (arrays["width"] <= 0.0)).any():
            raise InputError("contact points: width must be finite and > 0 m")

    def __len__(self) -> int:
        return int(self.s.size)


@runtime_checkable
class ComplianceSource(Protocol):
    """What the loaded-contact solver needs from a compliance model of a gear pair.

    Attributes
    ----------
    pair : the (actual) gear pair; fixes the path of contact, curvature radii
        and the mesh cycle.
    tip_contact : whether the candidate points reach beyond the path of contact into
        the tip zones (:func:`candidate_range`), where teeth touch at a tip corner.

    Methods
    -------
    points(position) -> ContactPoints
        candidate points at mesh position ``position`` (roll coordinate ``s0`` of
        the leading pair at ``z = 0``, m). Their order is the order of ``G``.
    matrix(position) -> (n, n) ndarray
        structural compliance ``G`` (m/N) between those points, symmetric
        positive (semi)definite, *without* the local contact (Hertz) approach.
    """

    pair: GearPair
    tip_contact: bool

    def points(self, position: float) -> ContactPoints: ...

    def matrix(self, position: float) -> np.ndarray: ...


DEFAULT_SLICES = 30
"""Slices across a helical face when a source is built without a count."""


def slice_count(pair: GearPair, slices: int | None) -> int:
    """``slices`` as given; ``None``: :data:`DEFAULT_SLICES` for a helical pair, one for a
    spur pair (a gearbox file's contact decides by its modifications too,
    :meth:`~pipeline.contact.options.ContactOptions.face_slices`)."""
    if slices is not None:
        return slices
    return DEFAULT_SLICES if pair.pinion.is_helical else 1


def slice_grid(pair: GearPair, slices: int | None, position: float, tip_contact: bool = True
               ) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Slice contact grid at mesh ``position`` (m of roll of the leading pair).

    Returns roll coordinates (K, N) in m, slice centres z (N,) in m, tooth pair
    indices (K,) (:meth:`GearPair.pair_indices` with ``beyond = tip_contact``) and the
    slice width in m, for ``slices`` slices across the face (:func:`slice_count`).
    """
    n = slice_count(pair, slices)
    dz = pair.face_width / n
    z = (np.arange(n) + 0.5) * dz
    k = pair.pair_indices(tip_contact)
    s = (float(position) + k * pair.base_pitch)[:, None] + z[None, :] * math.tan(
        pair.pinion.base_helix_angle)
    return s, z, k, dz


TIP_GAP = 200e-6
"""Largest rigid tip-corner gap of a candidate point beyond the path of contact, m: far
more than any elastic approach the contact solve accepts (it refuses an approach that
would close it, :func:`pipeline.contact.ltca.loaded_mesh_cycle`)."""


@lru_cache(maxsize=64)
def candidate_zone(pair: GearPair) -> tuple[float, float]:
    """Roll coordinates ``(s_lo, s_hi)``, m, of the candidate points: the path of contact
    widened at each end to where a tip corner's rigid gap reaches :data:`TIP_GAP`
    (:func:`pipeline.geometry.tip_contact.tip_zone`)."""
    return tip_zone(pair, TIP_GAP)


def candidate_range(pair: GearPair, tip_contact: bool) -> tuple[float, float]:
    """Roll coordinates ``(s_lo, s_hi)``, m, of the candidate points: the path of contact,
    widened by the tip zones (:func:`candidate_zone`) when teeth may touch beyond it."""
    return candidate_zone(pair) if tip_contact else (pair.s_start, pair.s_end)


def slice_points(pair: GearPair, slices: int | None, position: float,
                 tip_contact: bool = True) -> ContactPoints:
    """Slice contact points of every tooth pair that can touch, ordered by pair, then by z:
    on the path of contact and, with ``tip_contact``, in the tip zones beyond it
    (:func:`candidate_range`)."""
    s, z, k, dz = slice_grid(pair, slices, position, tip_contact)
    lo, hi = candidate_range(pair, tip_contact)
    inside = (s >= lo) & (s <= hi)
    kk, jj = np.nonzero(inside)
    return ContactPoints(s=s[kk, jj], z=z[jj], pair=k[kk], width=np.full(kk.size, dz))


@dataclass(frozen=True)
class SliceCompliance:
    """Analytical slice compliance (Yang et al. 2026, section 2.1-2.4) as a
    :class:`ComplianceSource`.

    Attributes
    ----------
    model : tooth models of the pair (:class:`~pipeline.stiffness.mesh.PairModel`).
    slices : slices across the face width, or ``None``: 30 across a helical face, one for a
        spur pair (:func:`slice_count`). :func:`~pipeline.contact.analysis.
        analytical_compliance` gives the count of the contact options.
    friction : friction model (sign convention of :mod:`pipeline.stiffness.friction`);
        friction changes the bending/compression split of each slice (Yang et al. 2026, eqs.
        19-23).
    operating : operating point (driver, and load/speed for the EHL friction coefficient).
    foundation_correction : factor on the body stiffness while more than one tooth
        pair is in contact, as in :func:`pipeline.stiffness.mesh.stiffness_at`.
    coupling : kappa in [0, 0.25), coupling of neighbouring slices (module docstring);
        0 is Yang et al. (2026)'s independent slices.
    tip_contact : candidate points beyond the path of contact too (tip corners,
        :func:`candidate_range`); False keeps them on the path.
    """

    model: PairModel
    slices: int | None = None
    friction: FrictionModel = field(default_factory=FrictionModel)
    operating: OperatingPoint = field(default_factory=OperatingPoint)
    foundation_correction: float = 1.0
    coupling: float = 0.0
    tip_contact: bool = True

    def __post_init__(self) -> None:
        if self.slices is not None:
            check_int_range("contact.slices", self.slices, 1, 10_000)
        check_range("contact.foundation_correction", self.foundation_correction, 0.5, 2.0)
        check_range("contact.slice_coupling", self.coupling, 0.0, 0.25, hi_open=True)
        if self.model.pair.pinion.herringbone:
            raise InputError("contact: herringbone pairs are not supported yet; analyse one "
                             "helical half (herringbone = false, face width of one half)")

    @property
    def pair(self) -> GearPair:
        return self.model.pair

    def _grid(self, position: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
        """Roll coordinates (K, N), face positions (N,), pair indices (K,), slice width (m)."""
        return slice_grid(self.pair, self.slices, position, self.tip_contact)

    def points(self, position: float) -> ContactPoints:
        """Candidate slice points (:func:`slice_points`), ordered by pair, then by z."""
        return slice_points(self.pair, self.slices, position, self.tip_contact)

    def diagonal(self, position: float) -> np.ndarray:
        """Independent-slice compliance of the candidate points, m/N, shape (n,).

        Bending + shear + axial + foundation of both teeth (Yang et al. 2026, eq. 25 without
        the Hertz term), per slice: the per-unit-width compliance over the slice width.
        """
        pair = self.pair
        s, _, _, dz = self._grid(position)
        lo, hi = candidate_range(pair, self.tip_contact)
        cand = (s >= lo) & (s <= hi)
        inside = (s >= pair.s_start) & (s <= pair.s_end)
        sc = np.where(cand, s, pair.s_pitch)[None]  # (1, K, N)
        lam = friction_direction(sc, pair.s_pitch, self.operating.driver)
        # friction acts on the line of action only (a tip corner: none)
        mu = friction_coefficients(pair, sc, inside[None], self.friction, self.operating, dz)
        r1, r2 = contact_radii_at(pair, sc)
        c1 = tooth_compliance(self.model.pinion, r1, mu, lam)
        c2 = tooth_compliance(self.model.gear, r2, mu, lam)
        corr = self.foundation_correction if np.any(inside, axis=1).sum() > 1 else 1.0
        per_width = c1.tooth + c2.tooth + (c1.foundation + c2.foundation) / corr
        return per_width[0][cand] / dz

    def matrix(self, position: float) -> np.ndarray:
        """``G`` (m/N), (n, n): diagonal slice compliance, optionally slice-coupled."""
        d = self.diagonal(position)
        G = np.diag(d)
        if self.coupling == 0.0 or d.size < 2:
            return G
        pts = self.points(position)
        # neighbours: consecutive slices of the same tooth pair (points are ordered by pair, z)
        nb = (pts.pair[1:] == pts.pair[:-1]) & np.isclose(
            np.diff(pts.z), pts.width[1:], rtol=1e-9)
        i = np.flatnonzero(nb)
        lap = np.zeros(d.size)
        np.add.at(lap, i, 1.0)
        np.add.at(lap, i + 1, 1.0)
        sq = np.sqrt(d)
        G[np.diag_indices(d.size)] = d * (1.0 - self.coupling * lap)
        off = self.coupling * sq[i] * sq[i + 1]
        G[i, i + 1] = off
        G[i + 1, i] = off
        return G

    def hertz_compliance(self, position: float) -> np.ndarray:
        """Constant Hertz compliance of each slice, m/N, (n,): ``4 (1 - nu^2) / (pi E w)``.

        The load-independent local contact term of the slice method (Yang et al. 2026, eq. 7,
        the assembly-error paper), the one :mod:`pipeline.stiffness.mesh` adds to every slice.
        """
        pts = self.points(position)
        return self.model.hertz / pts.width


@dataclass(frozen=True)
class UniformSlices:
    """A spur pair cut into ``slices`` independent slices of stiffness ``c0`` per unit face
    width per tooth pair (N/m^2), on the nominal path of contact (``tip_contact`` False):
    the uniform mesh stiffness of Harris's (1958) light-load analysis and of ISO 6336-1's
    linear face load, a compliance source whose loaded contact has closed forms."""

    pair: GearPair
    slices: int
    c0: float
    tip_contact: bool = False

    def points(self, position: float) -> ContactPoints:
        dz = self.pair.face_width / self.slices
        z = (np.arange(self.slices) + 0.5) * dz
        k = self.pair.pair_indices(beyond=False)
        s = position + k * self.pair.base_pitch
        kk = k[(s >= self.pair.s_start) & (s <= self.pair.s_end)]
        return ContactPoints(s=np.repeat(position + kk * self.pair.base_pitch, z.size),
                             z=np.tile(z, kk.size), pair=np.repeat(kk, z.size),
                             width=np.full(kk.size * z.size, dz))

    def matrix(self, position: float) -> np.ndarray:
        """Diagonal compliance 1 / (c0 w) of each slice (m/N)."""
        return np.diag(1.0 / (self.c0 * self.points(position).width))


@dataclass(frozen=True)
class FrictionCorrected:
    """A normal-load compliance source (e.g. FE) with the slice model's friction effect.

    FE influence coefficients are computed for loads normal to the flank. Friction
    tilts the tooth load (Yang et al. 2026, eqs. 19-23) and so changes the bending and
    compression of each tooth; that change is taken from the analytical slice model as
    a ratio, the structural slice compliance with friction over the one without,
    ``r_i = c_i(mu) / c_i(0)`` (Hertz excluded from both: the FE tables hold no Hertz
    term either), and applied congruently: ``G' = D G D`` with ``D = diag(sqrt(r))``.

    Why a ratio and not the difference ``c_i(mu) - c_i(0)`` on the diagonal. The slice
    compliance is that of an independent slice, ``1 / width`` of the per-unit-width
    compliance, so its friction change grows with the number of slices; a 3D source's
    coupled points share their load across the face and their diagonal does not (the demo
    pair's 3D G at 30 slices: diagonal 1.0-1.9e-8 m/N against the slices' 1.57e-7 m/N, so
    the difference, -3.7e-9 m/N, was -46 % of a diagonal entry where the slices' own change
    is -2.4 %, and it made the semidefinite G indefinite). The ratio is the same at any
    slicing; the congruent form keeps ``G`` semidefinite whenever ``G`` and ``r`` are
    (Sylvester's law of inertia) and scales each point's coupling with its own
    compliance, so a dry coupled slice source corrected this way equals the slice source
    with friction exactly (its off-diagonal is ``kappa sqrt(c_i c_j)``). Both sources must
    use the same candidate points (same slices), which is checked at every position.

    Attributes
    ----------
    base : the normal-load source (its ``pair`` must be the slices' pair).
    slices : analytical slice compliance *with* the friction model to apply.
    """

    base: ComplianceSource
    slices: SliceCompliance

    @property
    def pair(self) -> GearPair:
        return self.base.pair

    @property
    def tip_contact(self) -> bool:
        return self.base.tip_contact

    def points(self, position: float) -> ContactPoints:
        return self.base.points(position)

    def friction_ratio(self, position: float) -> np.ndarray:
        """Structural compliance with friction over the one without, shape (n,): the
        slice model's ``c_i(mu) / c_i(0)`` at each candidate point (1 where no friction
        acts, < 1 in approach, > 1 in recess)."""
        dry = dataclasses.replace(self.slices, friction=FrictionModel(mu=0.0))
        a, b = self.base.points(position), self.slices.points(position)
        if a.s.shape != b.s.shape or not (np.allclose(a.s, b.s, rtol=0, atol=1e-12)
                                          and np.allclose(a.z, b.z, rtol=0, atol=1e-12)):
            raise ValueError("FrictionCorrected: base and slice sources use different "
                             "candidate points; give both the same number of slices")
        return self.slices.diagonal(position) / dry.diagonal(position)

    def matrix(self, position: float) -> np.ndarray:
        G = np.array(self.base.matrix(position), dtype=float)
        d = np.sqrt(self.friction_ratio(position))
        return d[:, None] * G * d[None, :]
