"""Cases of the FE elasticity layer: the Timoshenko cantilever (exact 2D elasticity), its
L2 convergence rate, and the torsion of a round shaft by 3D FE (G J / L).

The cantilever (Timoshenko & Goodier, *Theory of Elasticity*, 3rd ed. 1970, sec. 21, in
the form of Augarde & Deeks, Finite Elem. Anal. Des. 44 (2008) 595-600): a beam
0 <= x <= L, |y| <= D/2, unit thickness, end shear P with parabolic distribution at x = L,
plane stress,

    u_x = -P y / (6 E I) [(6 L - 3 x) x + (2 + nu) (y^2 - D^2/4)]
    u_y =  P / (6 E I) [3 nu y^2 (L - x) + (4 + 5 nu) D^2 x / 4 + (3 L - x) x^2],

plane strain with E -> E / (1 - nu^2), nu -> nu / (1 - nu). The exact displacement is
prescribed at x = 0 and the exact traction at x = L, so the FE solution converges to it.
"""

from __future__ import annotations

import math

import numpy as np

from pipeline.geometry.gear import Material
from pipeline.verification.context import Context
from pipeline.verification.display import UM
from pipeline.verification.model import Convergence, Outcome, Plot, Quantity, Series

CANTILEVER = {"length_m": 1.0, "depth_m": 0.1, "load_N": 1000.0}
"""Length L, depth D (unit thickness) and end load P of the cantilever."""
CANTILEVER_MATERIAL = Material(youngs_modulus=2.0e11, poisson_ratio=0.3)
TIMOSHENKO_SOURCE = ("Timoshenko & Goodier (1970), Theory of Elasticity, sec. 21 (exact "
                     "plane elasticity; Augarde & Deeks 2008, Finite Elem. Anal. Des. 44)")


def cantilever_constants(kind: str) -> tuple[float, float]:
    """E (Pa) and nu of the exact solution for ``kind`` "plane_stress" or "plane_strain"
    (E / (1 - nu^2), nu / (1 - nu); Timoshenko & Goodier 1970, sec. 21)."""
    E, nu = CANTILEVER_MATERIAL.youngs_modulus, CANTILEVER_MATERIAL.poisson_ratio
    if kind == "plane_strain":
        E, nu = E / (1 - nu**2), nu / (1 - nu)
    return E, nu


def cantilever_exact_u(x: np.ndarray, y: np.ndarray, kind: str) -> np.ndarray:
    """Exact displacement (2, ...) in m at the points (x, y) (m), module docstring."""
    L, D, P = CANTILEVER["length_m"], CANTILEVER["depth_m"], CANTILEVER["load_N"]
    E, nu = cantilever_constants(kind)
    inertia = D**3 / 12.0
    ux = -P * y / (6 * E * inertia) * ((6 * L - 3 * x) * x + (2 + nu) * (y**2 - D**2 / 4))
    uy = P / (6 * E * inertia) * (3 * nu * y**2 * (L - x) + (4 + 5 * nu) * D**2 * x / 4
                                  + (3 * L - x) * x**2)
    return np.array([ux, uy])


def cantilever_exact_tip(kind: str) -> float:
    """u_y(L, 0) = P L^3 / (3 E I) + (4 + 5 nu) P D^2 L / (24 E I), m."""
    L, D, P = CANTILEVER["length_m"], CANTILEVER["depth_m"], CANTILEVER["load_N"]
    E, nu = cantilever_constants(kind)
    inertia = D**3 / 12.0
    return P * L**3 / (3 * E * inertia) + (4 + 5 * nu) * P * D**2 * L / (24 * E * inertia)


def cantilever_fe(nx: int, ny: int, kind: str, order: int = 2):
    """The FE cantilever on nx x ny rectangles (each cut into two triangles) of P``order``
    elements, the exact displacement prescribed at x = 0 (lifted into the load) and the
    exact parabolic shear traction at x = L: (its basis, the displacement (N,) in m at
    the basis's DOFs, the :class:`~pipeline.fem.linear_static.StaticSolution` with the
    clamp's reactions)."""
    from skfem import FacetBasis, LinearForm, MeshTri

    from pipeline.fem.linear_static import build_model, solve_static

    L, D, P = CANTILEVER["length_m"], CANTILEVER["depth_m"], CANTILEVER["load_N"]
    inertia = D**3 / 12.0
    mesh = MeshTri.init_tensor(np.linspace(0, L, nx + 1), np.linspace(-D / 2, D / 2, ny + 1))
    mesh = mesh.with_boundaries({"clamp": lambda x: x[0] < 1e-12,
                                 "tip": lambda x: x[0] > L - 1e-12})
    model = build_model(mesh, CANTILEVER_MATERIAL, order=order, kind=kind)
    basis = model.basis
    fb = FacetBasis(mesh, basis.elem, facets=mesh.boundaries["tip"], intorder=4)

    @LinearForm
    def traction(v, w):
        return P / (2 * inertia) * (D**2 / 4 - w.x[1] ** 2) * v[1]

    clamp = basis.get_dofs("clamp").flatten()
    xy = basis.doflocs[:, clamp]
    comp = np.arange(basis.N)[clamp] % 2
    u0 = np.zeros(basis.N)
    # the exact (non-zero) displacement on the clamp, lifted into the load
    u0[clamp] = cantilever_exact_u(xy[0], xy[1], kind)[comp, np.arange(clamp.size)]
    sol = solve_static(model, traction.assemble(fb) - model.stiffness @ u0, clamp)
    return basis, sol.displacements[:, 0] + u0, sol


def cantilever_tip(basis, u: np.ndarray) -> float:
    """Tip deflection u_y(L, 0) (m) of the displacement ``u`` (m) on ``basis``."""
    return float((basis.probes(np.array([[CANTILEVER["length_m"]], [0.0]])) @ u)[1])


def cantilever_l2_error(basis, u: np.ndarray, kind: str) -> float:
    """L2 norm (m^2) of ``u`` (m, on ``basis``) less the exact displacement."""
    from skfem import Functional

    @Functional
    def err(w):
        ue = cantilever_exact_u(w.x[0], w.x[1], kind)
        return (w["uh"][0] - ue[0]) ** 2 + (w["uh"][1] - ue[1]) ** 2

    return float(np.sqrt(err.assemble(basis, uh=basis.interpolate(u))))


def solve_cantilever(nx: int, ny: int, kind: str, order: int = 2) -> tuple[float, float]:
    """The FE cantilever (:func:`cantilever_fe`): (tip deflection u_y(L, 0) in m, L2 norm
    of the displacement error in m^2)."""
    basis, u, _ = cantilever_fe(nx, ny, kind, order)
    return cantilever_tip(basis, u), cantilever_l2_error(basis, u, kind)


def _cantilever_inputs(mesh: str) -> tuple[tuple[str, str], ...]:
    m = CANTILEVER_MATERIAL
    return (("length L, depth D, thickness", "1000 mm, 100 mm, 1 (unit)"),
            ("end load P (parabolic shear)", f"{CANTILEVER['load_N']:g} N"),
            ("E, nu", f"{m.youngs_modulus / 1e9:g} GPa, {m.poisson_ratio:g}"),
            ("mesh", mesh))


def case_cantilever_tip(context: Context) -> Outcome:
    """Tip deflection of the 2D FE cantilever against exact elasticity, plane stress and
    plane strain (P2 triangles, 40 x 4 cells)."""
    reason = ("the discretisation error of 40 x 4 P2 cells (measured 6.5e-6); the tests "
              "hold 1e-3")
    quantities = []
    for kind in ("plane_stress", "plane_strain"):
        tip, _ = solve_cantilever(40, 4, kind)
        quantities.append(Quantity(f"tip deflection u_y(L, 0), {kind.replace('_', ' ')}",
                                   "m", cantilever_exact_tip(kind), tip, "relative", 1e-3,
                                   reason, UM))
    return Outcome(TIMOSHENKO_SOURCE, _cantilever_inputs("40 x 4 cells, P2 triangles"),
                   tuple(quantities))


def case_cantilever_convergence(context: Context, levels: tuple[int, ...] = (2, 4, 8),
                                order: int = 2) -> Outcome:
    """L2 displacement error of the FE cantilever on 10n x n cells: its fitted rate
    against the a-priori order p + 1 (P2: 3)."""
    D = CANTILEVER["depth_m"]
    hs, errs, tips = [], [], []
    for n in levels:
        tip, err = solve_cantilever(10 * n, n, "plane_stress", order)
        hs.append(D / n)
        errs.append(err)
        tips.append(tip)
    rate = float(np.polyfit(np.log(hs), np.log(errs), 1)[0])
    expected = order + 1.0
    why = (f"a-priori L2 rate of P{order} elements on a smooth solution, h^(p+1) = "
           f"h^{expected:g} (Ciarlet 1978); the structured meshes beat it (measured 3.6), "
           "so the rate is a lower bound, 0.1 below it for the fit over three meshes")
    conv = Convergence("element size h [m]", tuple(hs), "tip deflection u_y(L, 0) [m]",
                       tuple(tips), tuple(errs), "L2 norm of u_h - u_exact [m^2]", rate,
                       expected, why)
    tip_exact = cantilever_exact_tip("plane_stress")
    quantities = (
        Quantity("fitted L2 convergence rate", "-", expected, rate, "lower_bound", 0.1, why),
        Quantity("tip deflection on the finest mesh", "m", tip_exact, tips[-1], "relative",
                 1e-4, "the finest mesh's discretisation error (measured below 1e-6)", UM),
    )
    ref = np.array(hs) ** expected * errs[0] / hs[0] ** expected
    plot = Plot("Timoshenko cantilever: L2 displacement error (plane stress, P2)",
                "element size h [m]", "||u_h - u||_L2 [m^2]",
                (Series("FE", hs, errs), Series(f"h^{expected:g} (a priori)", hs, ref, "--")),
                loglog=True)
    return Outcome(TIMOSHENKO_SOURCE,
                   _cantilever_inputs(", ".join(f"{10 * n} x {n}" for n in levels)
                                      + " cells, P2"),
                   quantities, conv, (plot,))


SHAFT = {"radius_m": 0.05, "length_m": 0.2, "bore_m": 0.02, "mesh_size_m": 0.04}
"""The hollow shaft twisted between its end faces (the groove FE chain's end coupling)."""


def case_shaft_torsion(context: Context) -> Outcome:
    """Torsional stiffness of a hollow round shaft by 3D FE (P2 tetrahedra, the relief
    groove chain's rigid end coupling) against G J / L."""
    from pipeline.fem.groove.body import CoaxialBody, Segment
    from pipeline.fem.groove.coupling import couple_two_surfaces
    from pipeline.fem.groove.mesh import MeshSettings, mesh_coaxial_body
    from pipeline.fem.linear_static import build_model
    from pipeline.fem.tetmesh import to_skfem

    mat = Material()
    R, L, bore = SHAFT["radius_m"], SHAFT["length_m"], SHAFT["bore_m"]
    body = CoaxialBody((Segment("shaft", 0.0, L, R),), bore)
    sk = to_skfem(mesh_coaxial_body(body, MeshSettings(SHAFT["mesh_size_m"],
                                                       curvature_points=16)))
    res = couple_two_surfaces(build_model(sk.mesh, mat), sk.triangles["end:left"],
                              sk.triangles["end:right"], [0, 0, 0.0], [0, 0, L], "rigid")
    ref = mat.shear_modulus * math.pi * (R**4 - bore**4) / 2 / L
    q = Quantity("torsional stiffness k_t", "N m/rad", ref, res.torsional_stiffness,
                 "relative", 1e-4,
                 "G J / L is exact in 3D elasticity for a circular section; what remains is "
                 "the polygonal approximation of the circles by 16 points (measured 1e-5)")
    inputs = (("outer / bore diameter, length", f"{2 * R * 1e3:g} / {2 * bore * 1e3:g} mm, "
                                                 f"{L * 1e3:g} mm"),
              ("G", f"{mat.shear_modulus / 1e9:.4g} GPa"),
              ("mesh", f"P2 tetrahedra, size {SHAFT['mesh_size_m'] * 1e3:g} mm, ends rigid"))
    return Outcome("Timoshenko, Strength of Materials I, ch. IX: k_t = G J / L, "
                   "J = pi (D^4 - d^4) / 32", inputs, (q,))
