"""The two-node Timoshenko beam element of a round shaft along ``z``: stiffness and mass.

Degrees of freedom per node, in this order (the shaft frame of :mod:`pipeline.shaft.model`)::

    0 u_x   1 u_y   2 u_z   3 theta_x   4 theta_y   5 theta_z        (m, rad)

and per element ``[node 1 (0-5), node 2 (6-11)]``. A right-handed rotation carries the
axis so that, in the Euler-Bernoulli limit, ``u_x' = theta_y`` and ``u_y' = -theta_x``.
Four uncoupled actions on a straight round beam:

* bending in the x-z plane on ``(u_x1, theta_y1, u_x2, theta_y2)`` and in the y-z plane
  on ``(u_y1, -theta_x1, u_y2, -theta_x2)``: the exact Timoshenko element with shear
  deformation, ``Phi = 12 E I / (kappa G A L^2)`` (Przemieniecki 1968, *Theory of Matrix
  Structural Analysis*, ch. 5)::

      K = E I / ((1 + Phi) L^3) [[ 12,  6L,          -12,  6L         ],
                                 [ 6L,  (4 + Phi)L^2, -6L,  (2 - Phi)L^2],
                                 [-12, -6L,           12, -6L         ],
                                 [ 6L,  (2 - Phi)L^2, -6L,  (4 + Phi)L^2]]

  It is the static condensation of the exact solution, so nodal values are exact for
  loads at nodes, whatever the mesh;
* torsion ``G J / L [[1, -1], [-1, 1]]`` with ``J = pi (D^4 - d^4) / 32`` (exact for round
  sections, no warping); axial ``E A / L`` likewise.

The consistent mass integrates the interdependent interpolation (IIE) shape functions of
Friedman & Kosmatka (1993, *Computers & Structures* 47(3), 473-481), which solve the
homogeneous Timoshenko equations exactly: translational inertia ``rho A`` on the
deflection shape functions, rotary inertia ``rho I`` on the rotation shape functions,
``rho J`` (polar) on linear twist and ``rho A`` on linear axial displacement. Gauss
quadrature with four points is exact for these polynomials (degree 6); the result is
Przemieniecki's (1968, ch. 11) closed-form Timoshenko mass, and the same shape functions
give the stiffness above (both checked in the tests).

The shear coefficient of a hollow round section is Cowper's (1966, *J. Appl. Mech.* 33,
335-340, Table 1), with ``m = d / D``::

    kappa = 6 (1 + nu) (1 + m^2)^2 / ((7 + 6 nu) (1 + m^2)^2 + (20 + 12 nu) m^2)

(solid: ``6 (1 + nu) / (7 + 6 nu)``; thin tube: ``2 (1 + nu) / (4 + 3 nu)``).

Everything is vectorised over elements: arrays of ``ne`` properties in, ``(ne, 12, 12)``
out.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

#: the element's DOFs of bending in the x-z plane, (u_x, theta_y) at both nodes
XZ = np.array([0, 4, 6, 10])
#: bending in the y-z plane, (u_y, theta_x) at both nodes; theta_x enters with a minus sign
YZ = np.array([1, 3, 7, 9])
YZ_SIGN = np.array([1.0, -1.0, 1.0, -1.0])
AXIAL = np.array([2, 8])
TORSION = np.array([5, 11])


def shear_coefficient(poisson_ratio: float, outer_diameter: np.ndarray,
                      inner_diameter: np.ndarray) -> np.ndarray:
    """Cowper's (1966) shear coefficient kappa (-) of a hollow round section.

    Parameters
    ----------
    poisson_ratio : nu (-).
    outer_diameter, inner_diameter : D and d (m), broadcastable; ``d = 0`` for solid.
    """
    m2 = (np.asarray(inner_diameter, float) / np.asarray(outer_diameter, float)) ** 2
    nu = poisson_ratio
    return 6.0 * (1.0 + nu) * (1.0 + m2) ** 2 / (
        (7.0 + 6.0 * nu) * (1.0 + m2) ** 2 + (20.0 + 12.0 * nu) * m2)


@dataclass(frozen=True)
class Sections:
    """Per-element properties of round beam elements (all arrays ``(ne,)``).

    Attributes
    ----------
    length : L, m.
    area : A, m^2.
    second_moment : I about a diameter, m^4 (polar J = 2 I).
    shear_coefficient : kappa (-).
    youngs_modulus, shear_modulus : E, G in Pa.
    density : rho, kg/m^3.
    """

    length: np.ndarray
    area: np.ndarray
    second_moment: np.ndarray
    shear_coefficient: np.ndarray
    youngs_modulus: float
    shear_modulus: float
    density: float

    @property
    def phi(self) -> np.ndarray:
        """Shear-flexibility ratio Phi = 12 E I / (kappa G A L^2) (-)."""
        return 12.0 * self.youngs_modulus * self.second_moment / (
            self.shear_coefficient * self.shear_modulus * self.area * self.length**2)


def bending_stiffness(s: Sections) -> np.ndarray:
    """(ne, 4, 4) bending stiffness on (v1, theta1, v2, theta2) with v' = theta (module
    docstring), N/m, N, N m."""
    L, phi = s.length, s.phi
    c = s.youngs_modulus * s.second_moment / ((1.0 + phi) * L**3)
    one = np.ones_like(L)
    k = np.array([
        [12 * one, 6 * L, -12 * one, 6 * L],
        [6 * L, (4 + phi) * L**2, -6 * L, (2 - phi) * L**2],
        [-12 * one, -6 * L, 12 * one, -6 * L],
        [6 * L, (2 - phi) * L**2, -6 * L, (4 + phi) * L**2],
    ])
    return np.moveaxis(k, -1, 0) * c[:, None, None]


def shape_functions(xi: np.ndarray, length: np.ndarray, phi: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray]:
    """IIE shape functions of Friedman & Kosmatka (1993) at ``xi = z / L`` in [0, 1].

    Returns ``(N_v, N_theta)``, each (ne, nq, 4) on (v1, theta1, v2, theta2): the
    deflection (m per DOF unit) and the cross-section rotation (rad per DOF unit).
    """
    x = np.asarray(xi)[None, :]
    L, p = length[:, None], phi[:, None]
    d = 1.0 / (1.0 + p)
    nv = np.stack([
        d * (2 * x**3 - 3 * x**2 - p * x + 1 + p),
        d * L * (x**3 - (2 + p / 2) * x**2 + (1 + p / 2) * x),
        d * (-2 * x**3 + 3 * x**2 + p * x),
        d * L * (x**3 - (1 - p / 2) * x**2 - p / 2 * x),
    ], axis=-1)
    nt = np.stack([
        6 * d / L * (x**2 - x),
        d * (3 * x**2 - (4 + p) * x + 1 + p),
        -6 * d / L * (x**2 - x),
        d * (3 * x**2 - (2 - p) * x),
    ], axis=-1)
    return nv, nt


def bending_mass(s: Sections) -> np.ndarray:
    """(ne, 4, 4) consistent bending mass on (v1, theta1, v2, theta2): translational
    ``rho A`` plus rotary ``rho I`` inertia, kg, kg m, kg m^2."""
    xg, wg = np.polynomial.legendre.leggauss(4)
    xi, w = 0.5 * (xg + 1.0), 0.5 * wg
    nv, nt = shape_functions(xi, s.length, s.phi)
    rho_l = s.density * s.length
    return (np.einsum("q,eqi,eqj->eij", w, nv, nv) * (rho_l * s.area)[:, None, None]
            + np.einsum("q,eqi,eqj->eij", w, nt, nt)
            * (rho_l * s.second_moment)[:, None, None])


def _two_node(c: np.ndarray, pattern: np.ndarray) -> np.ndarray:
    return c[:, None, None] * pattern[None, :, :]


def element_stiffness(s: Sections) -> np.ndarray:
    """(ne, 12, 12) element stiffness on the 12 DOFs of the module docstring."""
    k = np.zeros((s.length.size, 12, 12))
    kb = bending_stiffness(s)
    k[:, XZ[:, None], XZ] = kb
    k[:, YZ[:, None], YZ] = kb * np.outer(YZ_SIGN, YZ_SIGN)
    bar = np.array([[1.0, -1.0], [-1.0, 1.0]])
    k[:, AXIAL[:, None], AXIAL] = _two_node(s.youngs_modulus * s.area / s.length, bar)
    k[:, TORSION[:, None], TORSION] = _two_node(
        s.shear_modulus * 2.0 * s.second_moment / s.length, bar)
    return k


def element_mass(s: Sections) -> np.ndarray:
    """(ne, 12, 12) consistent element mass on the 12 DOFs of the module docstring."""
    m = np.zeros((s.length.size, 12, 12))
    mb = bending_mass(s)
    m[:, XZ[:, None], XZ] = mb
    m[:, YZ[:, None], YZ] = mb * np.outer(YZ_SIGN, YZ_SIGN)
    linear = np.array([[2.0, 1.0], [1.0, 2.0]]) / 6.0
    rho_l = s.density * s.length
    m[:, AXIAL[:, None], AXIAL] = _two_node(rho_l * s.area, linear)
    m[:, TORSION[:, None], TORSION] = _two_node(rho_l * 2.0 * s.second_moment, linear)
    return m
