"""Hertz line contact and the nonlinear local contact approach of tooth slices.

Classical Hertz theory of two parallel cylinders (Johnson, Contact Mechanics,
1985, section 4.3): with load ``w`` per unit length (N/m), effective radius
``R = rho1 rho2 / (rho1 + rho2)`` and contact modulus
``1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2``,

    half-width        a  = sqrt(4 w R / (pi E*))              (Johnson eq. 4.43)
    maximum pressure  p0 = 2 w / (pi a) = sqrt(w E* / (pi R))  (Johnson eq. 4.45)

In 2-D the approach of two bodies is not defined by the contact region alone
(the half-plane displacement is logarithmic); it depends on where the
displacement is measured. Weber and Banaschek (Formänderung und
Profilrücknahme bei gerad- und schrägverzahnten Rädern, Vieweg, 1953; used by
Cornell, J. Mech. Des. 103 (1981) 447-459) measure it relative to the tooth
centreline, a distance ``h_k`` from the contact point along the normal, giving
for body ``k``

    u_k = 2 w (1 - nu_k^2) / (pi E_k) * (ln(2 h_k / a) - nu_k / (2 (1 - nu_k))).

This is the integral of the plane-strain normal strain along the symmetry axis
of a half-plane under the Hertz pressure, from the surface to depth ``h_k``, to
leading order in ``(a / h_k)^2`` (checked by quadrature of the Flamant solution
in tests/test_hertz.py). For two equal materials the sum ``u_1 + u_2`` is eq. (24)
of Yang et al. (2026):

    u_c = 4 F (1 - nu^2) / (pi E b) * (ln(2 sqrt(h1 h2) / a) - nu / (2 (1 - nu))),

with ``F = w b`` the slice load and ``b`` the slice width, and ``a`` as above
(Yang et al. 2026 write ``a = sqrt(8 F rho_eq (1 - nu^2) / (pi E b))``, the same thing).

``u_c`` is zero at zero load, increasing and concave in ``F`` (its tangent
``du_c/dF = u_c/F - (2/(pi b)) sum_k (1 - nu_k^2)/E_k / 2`` falls like ``ln F``),
with infinite tangent compliance at ``F -> 0``. The tangent stays positive up
to :meth:`HertzLineContact.max_valid_load`, where the contact half-width
reaches the order of ``h_k``; beyond it the formula is outside its validity.

The constant Hertz term of the stiffness stage does not depend on curvature; this local
contact does, and for an internal pair (concave gear flank) takes the effective radius
``rho1 |rho2| / (|rho2| - rho1)``.

Shapes: the geometric inputs of :class:`HertzLineContact` are arrays of shape
``(n,)`` (one mesh position, ``n`` contact points) or ``(m, n)`` (``m`` mesh
positions); loads passed to its methods broadcast against them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Protocol, runtime_checkable

import numpy as np
from numpy.typing import ArrayLike

from pipeline.geometry.gear import Material
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import curvature_radii_at
from pipeline.validation import InputError


@runtime_checkable
class LocalCompliance(Protocol):
    """Nonlinear local contact deformation ``u_c(F)`` of the contact points.

    Implementations are vectorised: ``loads`` has shape (n,) (N) and both methods
    return shape (n,). ``approach(0) = 0``; ``approach`` must be nondecreasing and
    ``tangent`` positive for loads up to the total load, which makes the contact
    problem convex (see :mod:`pipeline.contact.complementarity`).
    """

    def approach(self, loads: np.ndarray) -> np.ndarray:
        """Local approach u_c (m) of each point, shape (n,)."""
        ...

    def tangent(self, loads: np.ndarray) -> np.ndarray:
        """Tangent compliance du_c/dF (m/N) of each point, shape (n,); +inf allowed at F = 0."""
        ...


def effective_radius(radius_1: ArrayLike, radius_2: ArrayLike) -> np.ndarray:
    """Effective radius ``R = rho1 rho2 / (rho1 + rho2)``, m (inputs in m, broadcast)."""
    r1 = np.asarray(radius_1, dtype=float)
    r2 = np.asarray(radius_2, dtype=float)
    return r1 * r2 / (r1 + r2)


def contact_modulus(material_1: Material, material_2: Material) -> float:
    """Contact modulus ``E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)``, Pa (Johnson eq. 4.22)."""
    return 1.0 / (1.0 / material_1.plane_strain_modulus + 1.0 / material_2.plane_strain_modulus)


def hertz_half_width(
    load_per_length: ArrayLike, effective_radius: ArrayLike, contact_modulus: float
) -> np.ndarray:
    """Hertz line-contact half-width ``a = sqrt(4 w R / (pi E*))``, m (Johnson eq. 4.43).

    Parameters
    ----------
    load_per_length : w, N/m, >= 0 (any shape).
    effective_radius : R, m, > 0 (broadcast with ``w``).
    contact_modulus : E*, Pa.
    """
    w = np.asarray(load_per_length, dtype=float)
    R = np.asarray(effective_radius, dtype=float)
    return np.sqrt(4.0 * w * R / (math.pi * contact_modulus))


def hertz_max_pressure(
    load_per_length: ArrayLike, effective_radius: ArrayLike, contact_modulus: float
) -> np.ndarray:
    """Hertz line-contact maximum pressure ``p0 = sqrt(w E* / (pi R))``, Pa (Johnson eq. 4.45).

    Parameters as :func:`hertz_half_width`.
    """
    w = np.asarray(load_per_length, dtype=float)
    return np.sqrt(w * contact_modulus / (math.pi * np.asarray(effective_radius, dtype=float)))


def _positive_array(field_name: str, value: ArrayLike) -> np.ndarray:
    arr = np.array(value, dtype=float)
    if arr.ndim not in (0, 1, 2):
        raise InputError(f"{field_name} has shape {arr.shape}; expected (n,) or (positions, n)")
    bad = ~np.isfinite(arr) | (arr <= 0.0)
    if bad.any():
        i = np.argwhere(bad)[0]
        raise InputError(
            f"{field_name}[{', '.join(map(str, i))}] = {float(arr[tuple(i)]):.6g} m is outside "
            f"the allowed range (0, inf) m"
        )
    arr.setflags(write=False)
    return arr


@dataclass(frozen=True)
class HertzLineContact:
    """Weber-Banaschek local approach of ``n`` slice contacts (Yang et al. 2026, eq. 24).

    Attributes
    ----------
    slice_width : b, contact length of each slice along the contact line, m;
        shape (n,) or (m, n), or a scalar.
    radius_1, radius_2 : profile curvature radii rho1, rho2 of the driving and
        driven flank at each point, m (for an involute, the distance from the
        point to the base-circle tangency point). Same shapes.
    depth_1, depth_2 : h1, h2, distance from the contact point along the contact
        normal to the centreline of the driving and driven tooth, m. Same shapes.
    material_1, material_2 : driving and driven gear materials.

    All geometric arrays broadcast to one shape (n,) or (m, n); ``m`` mesh positions
    can be split with :meth:`for_position`.
    """

    slice_width: ArrayLike
    radius_1: ArrayLike
    radius_2: ArrayLike
    depth_1: ArrayLike
    depth_2: ArrayLike
    material_1: Material = field(default_factory=Material)
    material_2: Material = field(default_factory=Material)

    def __post_init__(self) -> None:
        names = ("slice_width", "radius_1", "radius_2", "depth_1", "depth_2")
        arrays = [_positive_array(f"hertz.{nm}", getattr(self, nm)) for nm in names]
        try:
            shape = np.broadcast_shapes(*(a.shape for a in arrays))
        except ValueError:
            raise InputError(
                "hertz geometry arrays do not broadcast: shapes "
                + ", ".join(f"{nm} {a.shape}" for nm, a in zip(names, arrays, strict=True))
            ) from None
        for nm, a in zip(names, arrays, strict=True):
            b = np.broadcast_to(a, shape).copy()
            b.setflags(write=False)
            object.__setattr__(self, nm, b)

    # -- derived constants -------------------------------------------------
    @property
    def shape(self) -> tuple[int, ...]:
        """Shape of the point arrays: () , (n,) or (m, n)."""
        return np.shape(self.slice_width)

    @property
    def n_positions(self) -> int | None:
        """Number of mesh positions ``m`` for (m, n) arrays, else None."""
        return self.shape[0] if len(self.shape) == 2 else None

    def for_position(self, k: int) -> HertzLineContact:
        """The (n,) model of mesh position ``k`` from an (m, n) model."""
        if self.n_positions is None:
            return self
        return HertzLineContact(
            self.slice_width[k], self.radius_1[k], self.radius_2[k], self.depth_1[k],
            self.depth_2[k], self.material_1, self.material_2,
        )

    @property
    def effective_radius(self) -> np.ndarray:
        """R = rho1 rho2 / (rho1 + rho2), m, shape ``self.shape``."""
        return effective_radius(self.radius_1, self.radius_2)

    @property
    def contact_modulus(self) -> float:
        """E*, Pa."""
        return contact_modulus(self.material_1, self.material_2)

    def _weights(self) -> tuple[float, float, float, float]:
        m1, m2 = self.material_1, self.material_2
        w1, w2 = 1.0 / m1.plane_strain_modulus, 1.0 / m2.plane_strain_modulus
        c1 = m1.poisson_ratio / (2.0 * (1.0 - m1.poisson_ratio))
        c2 = m2.poisson_ratio / (2.0 * (1.0 - m2.poisson_ratio))
        return w1, w2, c1, c2

    def _log_terms(self, loads: np.ndarray) -> np.ndarray:
        """``sum_k (1-nu_k^2)/E_k (ln(2 h_k / a) - c_k)`` for F > 0 (1/Pa); F = 0 gives +inf."""
        w1, w2, c1, c2 = self._weights()
        F = np.asarray(loads, dtype=float)
        pos = F > 0.0
        a = self.half_width(np.where(pos, F, 1.0))
        t = w1 * (np.log(2.0 * self.depth_1 / a) - c1) + w2 * (np.log(2.0 * self.depth_2 / a) - c2)
        return np.where(pos, t, np.inf)

    # -- Hertz quantities --------------------------------------------------
    def half_width(self, loads: ArrayLike) -> np.ndarray:
        """Hertz half-width a (m) at slice loads F (N); broadcast with ``self.shape``."""
        F = np.asarray(loads, dtype=float)
        return hertz_half_width(F / self.slice_width, self.effective_radius, self.contact_modulus)

    def approach(self, loads: ArrayLike) -> np.ndarray:
        """Local contact approach u_c (m) at slice loads F (N), Yang et al. (2026), eq. (24);
        u_c(0) = 0."""
        F = np.asarray(loads, dtype=float)
        pos = F > 0.0
        t = self._log_terms(F)
        return np.where(pos, 2.0 * F / (math.pi * self.slice_width) * np.where(pos, t, 0.0), 0.0)

    def tangent(self, loads: ArrayLike) -> np.ndarray:
        """Tangent compliance du_c/dF (m/N) at slice loads F (N); +inf at F = 0."""
        w1, w2, _, _ = self._weights()
        t = self._log_terms(loads)  # d(F ln(1/a))/dF = ln(1/a) - 1/2 since a ~ sqrt(F)
        return 2.0 / (math.pi * self.slice_width) * (t - 0.5 * (w1 + w2))

    def max_valid_load(self) -> np.ndarray:
        """Slice load (N) at which ``du_c/dF`` reaches zero, shape ``self.shape``.

        From ``sum_k w_k (ln(2 h_k / a) - c_k - 1/2) = 0`` with ``w_k = (1-nu_k^2)/E_k``:
        ``ln a* = sum_k w_k (ln 2 h_k - c_k - 1/2) / sum_k w_k`` and
        ``F* = b pi E* a*^2 / (4 R)``. Above it the half-width is comparable to the
        tooth depth and the formula no longer describes a local contact.
        """
        w1, w2, c1, c2 = self._weights()
        log_a = (w1 * (np.log(2.0 * self.depth_1) - c1 - 0.5)
                 + w2 * (np.log(2.0 * self.depth_2) - c2 - 0.5)) / (w1 + w2)
        a = np.exp(log_a)
        return (self.slice_width * math.pi * self.contact_modulus * a * a
                / (4.0 * self.effective_radius))


@dataclass(frozen=True)
class LinearLocalCompliance:
    """Load-independent local compliance ``u_c = c F`` (e.g. the constant Hertz
    compliance ``4 (1 - nu^2) / (pi E b)`` of the assembly-error paper per slice).

    Attributes
    ----------
    compliance : c, m/N, shape (n,) or scalar, >= 0.
    """

    compliance: ArrayLike

    def __post_init__(self) -> None:
        c = np.array(self.compliance, dtype=float)
        if (~np.isfinite(c) | (c < 0.0)).any():
            raise InputError(f"local compliance = {self.compliance!r} m/N must be finite and >= 0")
        c.setflags(write=False)
        object.__setattr__(self, "compliance", c)

    def approach(self, loads: np.ndarray) -> np.ndarray:
        """u_c = c F, m."""
        return self.compliance * np.asarray(loads, dtype=float)

    def tangent(self, loads: np.ndarray) -> np.ndarray:
        """du_c/dF = c, m/N, broadcast to the shape of ``loads``."""
        return np.broadcast_to(self.compliance, np.shape(loads)).astype(float)


@dataclass(frozen=True)
class LeverScaled:
    """A local contact model seen through lever factors ``a`` (shape (n,)): the approach
    along the line of action of a point whose force ``F = Ft / a`` acts off it
    (:mod:`pipeline.geometry.tip_contact`): ``ut(Ft) = u(Ft / a) / a``, tangent
    ``u'(Ft / a) / a^2``; still the gradient of a convex potential, as the solve needs.

    Attributes
    ----------
    model : the local model in the points' own normal directions.
    lever : (n,) factors ``a`` in (0, 1], 1 on the line of action.
    """

    model: LocalCompliance
    lever: np.ndarray

    def approach(self, loads: np.ndarray) -> np.ndarray:
        return self.model.approach(np.asarray(loads, dtype=float) / self.lever) / self.lever

    def tangent(self, loads: np.ndarray) -> np.ndarray:
        return self.model.tangent(np.asarray(loads, dtype=float) / self.lever) / self.lever**2

    def max_valid_load(self) -> np.ndarray:
        return np.asarray(self.model.max_valid_load()) * self.lever


def contact_pressures(pair: GearPair, s: ArrayLike, unit_load: ArrayLike) -> np.ndarray:
    """Hertz maximum pressure (Pa) at contact points of ``pair`` crossing the line of action
    at ``s`` (m) under normal unit loads ``unit_load`` along the contact line (N/m; same
    shape): the flanks' curvatures on the path, a tip corner's edge rounding against the
    mate's flank beyond it (:func:`~pipeline.geometry.tip_contact.curvature_radii_at`), in
    the normal section (effective radius ``R_t / cos(beta_b)``); 0 where unloaded."""
    rho1, rho2 = curvature_radii_at(pair, s)
    radius = effective_radius(rho1, rho2) / math.cos(pair.pinion.base_helix_angle)
    e_star = contact_modulus(pair.pinion.material, pair.gear.material)
    p = np.maximum(np.asarray(unit_load, dtype=float), 0.0)
    return np.where(p > 0.0, hertz_max_pressure(p, np.maximum(radius, 1e-300), e_star), 0.0)
