"""Results of the loaded tooth contact solve: one mesh position, or a sweep of positions.

Mesh stiffness definitions (all in N/m, force along the line of action over
approach along it):

* ``mesh_stiffness_secant`` ``k_s = P / (x_s - x_0)`` with ``x_0 = min_i eps_i``,
  the approach at which the first point touches (the unloaded transmission
  error along the line of action). With ``eps = 0`` this is ``P / x_s``.
* ``mesh_stiffness_tangent`` ``k_t = dP/dx_s``, exact, from differentiating the
  compatibility equations on the loaded set ``A``:
  ``(G_AA + diag(du_c/dF)_A) dF_A = 1 dx_s`` and ``1^T dF_A = dP``, so
  ``k_t = 1^T (G_AA + D_A)^{-1} 1``. It holds the loaded set fixed, so it is the
  derivative wherever a small load change does not bring a point into or out of
  contact (everywhere except isolated loads). This is the stiffness a
  lumped-parameter dynamic model linearised about this load needs.
* ``mesh_stiffness_pointwise`` ``k_m = sum_{i in A} F_i / (x_s - eps_i)``, the
  sum of the secant stiffnesses of the loaded points (Yang et al. 2026, section 2.3).
  It equals ``k_s`` when ``eps = 0``, and ``k_t`` for a linear diagonal ``G``.

At zero load the three are the limits ``P -> 0+``: ``1^T G_AA^{-1} 1`` over the
first-touching points for a linear problem, and 0 with the Hertz approach
(whose compliance is infinite at zero load).

Loaded contact ratio. The contact summary's ``loaded_contact_ratio`` is the mean number of
tooth pairs carrying load over the cycle (the roll length over which a pair is loaded, over
the base pitch); at a light load it equals the geometric transverse contact ratio to the
sampling of the positions (1.755 for the seed 001 pair; 1.767 loaded at 340 N m). When it
is 1 within the sampling, one pair carries the whole load at a time and the load jumps
between pairs: a warning line gives the value and the TE (1 mm tip relief over 5 mm of roll
on both gears of the seed 001 pair: 1.017, TE 321 um peak to peak). A cycle read from the
cache warns again.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, fields

import numpy as np


def _readonly(a: np.ndarray, dtype: type = float) -> np.ndarray:
    out = np.array(a, dtype=dtype, copy=True)
    out.setflags(write=False)
    return out


@dataclass(frozen=True)
class ContactSolution:
    """Loaded contact state of one mesh position with ``n`` candidate points.

    Attributes
    ----------
    loads : (n,) normal loads F at the contact points, N; exactly 0 off contact.
    approach : x_s, loaded approach (static transmission error) along the line
        of action, m, in the reference of the initial separations ``eps``.
    active : (n,) bool, True where the point carries load (F > 0).
    gap : (n,) loaded separation ``G F + u_c(F) + eps - x_s``, m: ~0 on loaded
        points, >= 0 elsewhere, +inf for points out of mesh (``eps = inf``).
    contact_deformation : (n,) local contact approach u_c(F), m (0 if linear).
    total_load : P, N.
    residual : max violation of the complementarity conditions, m (see
        :func:`pipeline.contact.complementarity.complementarity_residual`).
    tolerance : the residual bound the solve was accepted against, m.
    iterations : total number of face (KKT) linear solves.
    newton_iterations : number of linearisations of u_c (0 for a linear problem).
    mesh_stiffness_secant : k_s, N/m (module docstring).
    mesh_stiffness_tangent : k_t = dP/dx_s, N/m (module docstring).
    mesh_stiffness_pointwise : k_m, N/m: the pointwise (slice-sum) mesh stiffness of
        Yang et al. (2026), section 2.3, sum of the loaded points' secant stiffnesses
        (module docstring); CSV column ``mesh_stiffness_pointwise [N/m]``.
    label : mesh-position label used in messages, or None.
    """

    loads: np.ndarray
    approach: float
    active: np.ndarray
    gap: np.ndarray
    contact_deformation: np.ndarray
    total_load: float
    residual: float
    tolerance: float
    iterations: int
    newton_iterations: int
    mesh_stiffness_secant: float
    mesh_stiffness_tangent: float
    mesh_stiffness_pointwise: float
    label: str | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "loads", _readonly(self.loads))
        object.__setattr__(self, "active", _readonly(self.active, bool))
        object.__setattr__(self, "gap", _readonly(self.gap))
        object.__setattr__(self, "contact_deformation", _readonly(self.contact_deformation))

    @property
    def n_active(self) -> int:
        """Number of loaded points."""
        return int(self.active.sum())

    @property
    def load_share(self) -> np.ndarray:
        """(n,) fraction of the total load on each point (-); zeros at zero load."""
        if self.total_load == 0.0:
            return np.zeros_like(self.loads)
        return self.loads / self.total_load


_STACKED = (
    "loads", "approach", "active", "gap", "contact_deformation", "total_load", "residual",
    "tolerance", "iterations", "newton_iterations", "mesh_stiffness_secant",
    "mesh_stiffness_tangent", "mesh_stiffness_pointwise",
)


@dataclass(frozen=True)
class ContactSweep:
    """Contact states of ``m`` mesh positions with ``n`` candidate points each.

    Attributes are the :class:`ContactSolution` fields stacked over positions:
    ``loads``, ``active``, ``gap``, ``contact_deformation`` have shape (m, n);
    ``approach``, ``total_load``, ``residual``, ``tolerance``, ``iterations``,
    ``newton_iterations`` and the three ``mesh_stiffness_*`` have shape (m,).
    Units as in :class:`ContactSolution`. ``labels`` holds the m labels.
    Index with ``sweep[k]`` to get position ``k`` as a :class:`ContactSolution`.
    """

    loads: np.ndarray
    approach: np.ndarray
    active: np.ndarray
    gap: np.ndarray
    contact_deformation: np.ndarray
    total_load: np.ndarray
    residual: np.ndarray
    tolerance: np.ndarray
    iterations: np.ndarray
    newton_iterations: np.ndarray
    mesh_stiffness_secant: np.ndarray
    mesh_stiffness_tangent: np.ndarray
    mesh_stiffness_pointwise: np.ndarray
    labels: tuple[str | None, ...] = ()

    @classmethod
    def from_solutions(cls, solutions: Sequence[ContactSolution]) -> ContactSweep:
        """Stack per-position solutions (all with the same ``n``)."""
        data = {}
        for name in _STACKED:
            dtype = bool if name == "active" else int if "iterations" in name else float
            data[name] = _readonly(np.array([getattr(s, name) for s in solutions]), dtype)
        return cls(**data, labels=tuple(s.label for s in solutions))

    def __len__(self) -> int:
        return int(self.approach.shape[0])

    def __getitem__(self, k: int) -> ContactSolution:
        kw = {f.name: getattr(self, f.name)[k] for f in fields(ContactSolution)
              if f.name in _STACKED}
        for name in ("approach", "total_load", "residual", "tolerance", "mesh_stiffness_secant",
                     "mesh_stiffness_tangent", "mesh_stiffness_pointwise"):
            kw[name] = float(kw[name])
        kw["iterations"] = int(kw["iterations"])
        kw["newton_iterations"] = int(kw["newton_iterations"])
        return ContactSolution(**kw, label=self.labels[k] if self.labels else None)


@dataclass(frozen=True)
class LoadedMeshCycle:
    """Loaded tooth contact over one mesh cycle (``m`` positions, ``K`` tooth pairs).

    Per position (shape (m,)):

    s0 : roll coordinate of the leading pair at z = 0, m (the mesh position).
    pinion_angle : pinion rotation from the first position, rad.
    transmission_error : loaded static transmission error x_s along the transverse
        line of action, m, relative to the unmodified error-free flanks (eps = 0);
        as a pinion angle: ``transmission_error / pair.pinion.base_radius`` (rad).
    mesh_stiffness : tangent mesh stiffness k = dP/dx_s, N/m (exact, from the loaded
        set; see :class:`ContactSolution`).
    mesh_stiffness_secant : P / (x_s - min eps), N/m.
    mesh_stiffness_pointwise : pointwise (slice-sum) mesh stiffness of Yang et al. (2026),
        k_m = sum F_i / (x_s - eps_i), N/m; CSV column ``mesh_stiffness_pointwise [N/m]``.
    residual, tolerance : complementarity residual and its accepted bound, m.
    newton_iterations : linearisations of the local contact approach.
    max_unit_load : largest unit load along any contact line, N/m.

    Per tooth pair (shape (m, K), columns ``pair_index``):

    pair_loads : load carried by each tooth pair, N; ``load_share = pair_loads / P``.

    Per candidate point (flat arrays of length ``n_total`` over all positions):

    point_position : index of the mesh position.
    point_s, point_z : roll coordinate and face position, m.
    point_pair : tooth-pair index k.
    point_width : face width the point stands for, m.
    point_load : load F (transverse, along the line of action), N: a tip corner's normal
        force ``F_n`` times its lever factor (:mod:`pipeline.geometry.tip_contact`).
    point_unit_load : p = F_n / width, normal load per unit length of contact line, N/m.
    point_separation : initial separation eps, m.
    point_contact_deformation : local contact approach u_c(F), m.
    point_lever : lever factor ``a = F / F_n`` (-), 1 on the path of contact.
    point_corner : 0 on the path of contact; beyond it the tip corner that touches:
        1 the pinion's (past the end of the path), 2 the gear's (before its start).
    point_pressure : Hertz maximum pressure, Pa (a tip corner: of its edge rounding,
        :func:`pipeline.contact.hertz.contact_pressures`).

    Scalars: ``load`` P (N), ``pair_index`` (K,), ``local_contact`` (model name).
    """

    s0: np.ndarray
    pinion_angle: np.ndarray
    transmission_error: np.ndarray
    mesh_stiffness: np.ndarray
    mesh_stiffness_secant: np.ndarray
    mesh_stiffness_pointwise: np.ndarray
    residual: np.ndarray
    tolerance: np.ndarray
    newton_iterations: np.ndarray
    max_unit_load: np.ndarray
    pair_index: np.ndarray
    pair_loads: np.ndarray
    point_position: np.ndarray
    point_s: np.ndarray
    point_z: np.ndarray
    point_pair: np.ndarray
    point_width: np.ndarray
    point_load: np.ndarray
    point_unit_load: np.ndarray
    point_separation: np.ndarray
    point_contact_deformation: np.ndarray
    point_lever: np.ndarray
    point_corner: np.ndarray
    point_pressure: np.ndarray
    load: float
    local_contact: str

    def __post_init__(self) -> None:
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, np.ndarray):
                object.__setattr__(self, f.name, _readonly(v, v.dtype))

    def __len__(self) -> int:
        return int(self.s0.size)

    @property
    def point_normal_load(self) -> np.ndarray:
        """Normal contact force of every point, N: ``point_load / point_lever``."""
        return self.point_load / self.point_lever

    @property
    def load_share(self) -> np.ndarray:
        """(m, K) fraction of the load on each tooth pair (-)."""
        return self.pair_loads / self.load

    @property
    def loaded_contact_ratio(self) -> float:
        """Mean number of tooth pairs carrying load over the cycle (-): the roll length over
        which a pair is loaded, over the base pitch. A loaded mesh has at least 1; 1 means
        one pair carries the whole load at a time and the load jumps between pairs."""
        return float((self.pair_loads > 0).sum(axis=1).mean())

    def physics_warnings(self) -> list[str]:
        """One line per condition the numbers are valid for but a design should not be in:
        a loaded contact ratio of 1 within the sampling (at most two of the positions have
        two pairs loaded, e.g. the hand-over instant), as with tip reliefs too long or
        too deep for the load; teeth touching at a tip corner beyond the path of contact
        (edge loading: its largest normal force and Hertz pressure)."""
        out = []
        tip = self.tip_contact_peak()
        if tip is not None:
            out.append(
                f"tip contact beyond the path of contact at {tip['positions']} of "
                f"{len(self)} positions: the {tip['corner']}'s tip corner carries up to "
                f"{tip['normal_load_N']:.4g} N ({tip['share']:.1%} of the load) at mesh "
                f"position {tip['position']}, Hertz pressure of its edge "
                f"{tip['pressure_Pa'] * 1e-6:.4g} MPa; a tip relief longer and deeper than "
                "the deflection keeps the teeth apart there")
        ratio, m = self.loaded_contact_ratio, len(self)
        if ratio > 1.0 + 2.0 / m:
            return out
        single = float(np.mean((self.pair_loads > 0).sum(axis=1) <= 1))
        te = self.transmission_error
        return out + [
            f"loaded contact ratio {ratio:.3f}: one tooth pair carries the whole load over "
            f"{single:.0%} of the mesh cycle, so the load jumps between pairs "
            f"(transmission error {(te.max() - te.min()) * 1e6:.3g} um peak to peak); "
            f"check the tip relief and the flank modifications"]

    def tip_contact_peak(self) -> dict | None:
        """The largest tip-corner contact of the cycle, or None when no tip corner carries
        load: ``normal_load_N`` (the corner's normal force summed over its tooth pair's
        points at that position, N), ``share`` (its line-of-action load over the
        position's load, -), ``pressure_Pa`` (the largest Hertz pressure of any corner
        point of the cycle), ``position`` (index), ``corner`` ("pinion" or "gear") and
        ``positions`` (how many positions have a loaded corner)."""
        tip = (self.point_corner > 0) & (self.point_load > 0)
        if not tip.any():
            return None
        key = self.point_position[tip] * (1 << 20) + (self.point_pair[tip] - self.point_pair.min())
        groups, inv = np.unique(key, return_inverse=True)
        normal = np.bincount(inv, weights=self.point_normal_load[tip])
        line = np.bincount(inv, weights=self.point_load[tip])
        g = int(np.argmax(normal))
        first = np.flatnonzero(inv == g)[0]
        pos = int(self.point_position[tip][first])
        total = float(self.point_load[self.point_position == pos].sum())
        return {"normal_load_N": float(normal[g]), "share": float(line[g]) / total,
                "pressure_Pa": float(self.point_pressure[tip].max()), "position": pos,
                "corner": "pinion" if self.point_corner[tip][first] == 1 else "gear",
                "positions": int(np.unique(self.point_position[tip]).size)}

    def summary(self) -> dict[str, float]:
        """Mean/max/min of the mesh stiffness and transmission error, the loaded contact
        ratio (SI; keys carry units)."""
        k, te = self.mesh_stiffness, self.transmission_error
        return {
            "load_N": self.load,
            "loaded_contact_ratio": self.loaded_contact_ratio,
            "mesh_stiffness_mean_N_per_m": float(k.mean()),
            "mesh_stiffness_max_N_per_m": float(k.max()),
            "mesh_stiffness_min_N_per_m": float(k.min()),
            "mesh_stiffness_secant_mean_N_per_m": float(self.mesh_stiffness_secant.mean()),
            "transmission_error_mean_m": float(te.mean()),
            "transmission_error_peak_to_peak_m": float(te.max() - te.min()),
            "max_unit_load_N_per_m": float(self.max_unit_load.max()),
            "max_residual_m": float(self.residual.max()),
        }

    def columns(self) -> dict[str, np.ndarray]:
        """Per-position columns over the cycle (shape (m,) each), named with their units."""
        cols = {
            "pinion_angle [rad]": self.pinion_angle,
            "roll_coordinate_s0 [m]": self.s0,
            "transmission_error [m]": self.transmission_error,
            "mesh_stiffness_tangent [N/m]": self.mesh_stiffness,
            "mesh_stiffness_secant [N/m]": self.mesh_stiffness_secant,
            "mesh_stiffness_pointwise [N/m]": self.mesh_stiffness_pointwise,
            "max_unit_load [N/m]": self.max_unit_load,
            "residual [m]": self.residual,
        }
        for j, k in enumerate(self.pair_index):
            cols[f"load_share_pair_{k} [-]"] = self.load_share[:, j]
        return cols

    def point_columns(self) -> dict[str, np.ndarray]:
        """Per-candidate-point columns over all positions (shape (n_total,) each)."""
        return {
            "position [-]": self.point_position,
            "roll_coordinate_s [m]": self.point_s,
            "face_position_z [m]": self.point_z,
            "tooth_pair [-]": self.point_pair,
            "slice_width [m]": self.point_width,
            "load [N]": self.point_load,
            "unit_load [N/m]": self.point_unit_load,
            "initial_separation [m]": self.point_separation,
            "contact_deformation [m]": self.point_contact_deformation,
            "normal_load [N]": self.point_normal_load,
            "tip_corner [-]": self.point_corner,
            "hertz_pressure [Pa]": self.point_pressure,
        }


def pairs_in_order_of_entry(pair_loads: np.ndarray) -> list[int]:
    """Columns of the loaded tooth pairs, ordered by their first loaded mesh position
    (the reader's "pair 1, 2, ..." instead of the internal indices -1, 0, 1)."""
    loaded = pair_loads != 0
    cols = [j for j in range(loaded.shape[1]) if loaded[:, j].any()]
    return sorted(cols, key=lambda j: int(np.argmax(loaded[:, j])))
