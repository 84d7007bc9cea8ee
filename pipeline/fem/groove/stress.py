"""Torsional shear stress in the twisted sun body (element means, for pictures and checks)."""

from __future__ import annotations

import numpy as np

from pipeline.fem.groove.study import GrooveAnalysis


def torsional_shear_stress(analysis: GrooveAnalysis, u: np.ndarray) -> np.ndarray:
    """Element-mean shear stress tau_theta_z (Pa), shape (n_elements,), for displacement u (m)."""
    basis = analysis.model.basis
    lam, mu = analysis.model.lam, analysis.model.mu
    grad = basis.interpolate(u).grad  # (3, 3, n_el, n_q)
    w = basis.dx / basis.dx.sum(axis=1, keepdims=True)
    g = np.einsum("ijeq,eq->eij", grad, w)  # element means
    eps = 0.5 * (g + g.transpose(0, 2, 1))
    sigma = 2 * mu * eps + lam * np.trace(eps, axis1=1, axis2=2)[:, None, None] * np.eye(3)
    mesh = analysis.mesh.mesh
    c = mesh.p[:, mesh.t].mean(axis=1)  # (3, n_el) centroids
    r = np.hypot(c[0], c[1])
    e_theta = np.stack([-c[1], c[0], 0 * r]) / np.where(r > 0, r, 1.0)
    return np.einsum("ie,eij,j->e", e_theta, sigma, np.array([0.0, 0.0, 1.0]))
