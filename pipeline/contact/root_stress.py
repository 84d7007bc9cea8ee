"""Tooth root stress under the solved contact loads (FE 2D), beside ISO 6336-3's nominal value.

:func:`analyse_root_stress` follows one tooth of each gear through the mesh: at every mesh
position ``i`` of a :class:`~pipeline.contact.results.LoadedMeshCycle` the tooth of pair
``k`` carries the loads of pair ``k`` and its neighbours those of pairs ``k +- 1, ...``
(the tooth mapping of :mod:`pipeline.contact.fe2d_source`: pinion tooth ``mid - k``, gear
tooth ``mid + k``), so the states ``(i, k)`` over one cycle are the tooth's passage
through the mesh from its entry into contact until it has left it (the tooth pairs of
:meth:`GearPair.pair_indices`). In each transverse section
(slice ``z``) the stress along the loaded-side root of the tooth is the superposition of
the FE stress table of the whole gear (:mod:`pipeline.fem.fillet_stress`, unit line loads
on the flanks of the tooth and its neighbours) weighted by the slices' normal line loads ``F_n /
width`` (N/m, interpolated linearly in the involute arc coordinate), and the largest
principal stress is taken of the sum: plane 2D sections, as the FE 2D contact compliance.
A tip corner touching beyond the path of contact loads its tooth at the tip radius (the
table's last flank point lies 0.11 m_n of arc below it: extrapolated linearly) and the
mate's flank below the start of its active profile, each as a unit load normal to that
tooth's own flank (the corner force is a few degrees off it, 2.5 deg at 1 mm of roll past
the end on the demo pair).

The nominal root stress of ISO 6336-3 (method B, :mod:`pipeline.contact.iso_root_stress`)
is for the same load: ``F_t = P cos(alpha_t)`` at the reference circle, all of it on one
tooth at the outer point of single pair contact; the difference ``(FE - ISO) / ISO`` is
reported. Checks (``tests/test_root_stress.py``): the ISO geometry (30 deg tangent chord,
fillet radius, bending arm) against the exact generated profile, and a single tooth under a
tip load, converged under refinement, against ISO with the load at the same diameter.

The FE model is the whole gear in 2D (graded P2, flank and fillet elements m_n / 24), its
stress tables per unit flank load cached by content hash; ISO 6336-3 method B takes Y_F,
Y_S, Y_beta from the basic rack and the virtual spur gear, with Y_B = Y_DT = 1. Measured:
ISO's 30 deg tangent chord, fillet radius and bending arm equal those of the exact
generated profile to 4e-9, 2e-5 and 1.4e-7; one tooth of a whole z 30 gear under a tip load
gives 1161.9 / 1163.7 / 1163.9 / 1162.7 / 1162.1 / 1162.2 Pa per N/m at refinement 0.5 / 1
/ 2 / 4 / 8 / 12 (within 0.15 % from refinement 1 on), 5.7 % below ISO with the load at the
same diameter. Ring gears have FE root stress, no ISO value (method B is implemented for
external gears). Measured values on the example gearboxes: :mod:`pipeline.report`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from pipeline.cache.folder import DEFAULT_CACHE, Cache
from pipeline.contact._interpolation import linear_weights
from pipeline.contact.iso_root_stress import IsoRootStress, iso_root_stress
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.gear import GearSpec
from pipeline.geometry.pair import GearPair
from pipeline.geometry.tip_contact import contact_radii_at
from pipeline.operation import OperatingPoint
from pipeline.progress import progress


@dataclass(frozen=True)
class GearRootStress:
    """Root stress of one gear over the mesh cycle.

    Attributes
    ----------
    name : "pinion" or "gear" (the role in the pair).
    arc : (n_f,) arc length of the root points along the profile from the middle of the
        tooth space, m; radius : (n_f,) their radius, m.
    envelope : (n_f,) largest principal stress at each root point over the tooth's passage
        through the mesh and the face, Pa.
    max_stress : its maximum, Pa; max_radius : radius of that root point, m;
        max_arc : its arc length, m.
    max_load_roll : roll coordinate s of the tooth's own contact (at z = 0) when the maximum
        occurs, m; max_load_radius : the radius of that contact on this gear, m;
        max_face_position : the slice z, m.
    passage_roll : (n_s,) roll coordinate of the tooth's own contact at z = 0 over its passage
        (ascending), m; passage_stress : (n_s,) largest principal root stress at each, Pa.
    position_max : (m,) largest root stress of any tooth at each mesh position, Pa.
    face_z : (n_z,) face positions of the slices, m; face_envelope : (n_z,) largest
        principal root stress over the fillet, the tooth's passage and the cycle in each
        slice, Pa (its maximum is ``max_stress``).
    iso : ISO 6336-3 method B for the same load, or None (internal gears).
    label : how figures name the gear: the role, with the gear's own name when it differs
        ("pinion (sun)").
    """

    name: str
    arc: np.ndarray
    radius: np.ndarray
    envelope: np.ndarray
    max_stress: float
    max_radius: float
    max_arc: float
    max_load_roll: float
    max_load_radius: float
    max_face_position: float
    passage_roll: np.ndarray
    passage_stress: np.ndarray
    position_max: np.ndarray
    face_z: np.ndarray
    face_envelope: np.ndarray
    iso: IsoRootStress | None
    label: str = ""

    @property
    def difference_to_iso(self) -> float:
        """(FE - ISO) / ISO (-), NaN without an ISO value."""
        return math.nan if self.iso is None else self.max_stress / self.iso.sigma_f0 - 1.0


@dataclass(frozen=True)
class RootStress:
    """Root stress of both gears (``pinion``, ``gear``) and how it was computed.

    Attributes
    ----------
    pinion, gear : per gear.
    kind : "plane_strain" or "plane_stress"; refinement : FE flank size m_n / (12 ref.).
    tangential_load : F_t of the ISO comparison, N.
    n_dof : unknowns of the two FE models.
    """

    pinion: GearRootStress
    gear: GearRootStress
    kind: str
    refinement: float
    tangential_load: float
    n_dof: tuple[int, int]

    def summary(self) -> dict[str, Any]:
        """FE maximum, where, ISO value and difference per gear (SI; keys carry units)."""
        out: dict[str, Any] = {"kind": self.kind, "refinement": self.refinement,
                               "tangential_load_N": self.tangential_load}
        for g in (self.pinion, self.gear):
            out[g.name] = {"fe_max_principal_Pa": g.max_stress,
                           "fe_max_radius_m": g.max_radius,
                           "fe_max_load_radius_m": g.max_load_radius,
                           "iso6336_3_sigma_F0_Pa": None if g.iso is None else g.iso.sigma_f0,
                           "difference_to_iso": g.difference_to_iso}
        return out

    def curves(self) -> list[tuple[str, np.ndarray, np.ndarray, float | None]]:
        """(name, arc mm, envelope MPa, ISO MPa or None) per gear, for the report figure."""
        return [(g.label, g.arc * 1e3, g.envelope * 1e-6,
                 None if g.iso is None else g.iso.sigma_f0 * 1e-6) for g in (self.pinion,
                                                                             self.gear)]

    def cycle_columns(self) -> dict[str, np.ndarray]:
        """Per mesh position: the largest root stress of any tooth of each gear."""
        return {f"root_stress_max_{g.name} [Pa]": g.position_max for g in (self.pinion,
                                                                           self.gear)}


def _gear_states(cycle: LoadedMeshCycle, pair: GearPair, gear: GearSpec, sign: int,
                 table) -> tuple[np.ndarray, np.ndarray]:
    """Largest principal root stress (n_f, m, K, n_z), Pa, and the slice positions (n_z,)."""
    from pipeline.fem.fillet_stress import principal_stress

    k_all = np.asarray(cycle.pair_index)
    zq = np.round(cycle.point_z, 12)
    z, iz = np.unique(zq, return_inverse=True)
    r = contact_radii_at(pair, cycle.point_s)[0 if sign < 0 else 1]  # a corner: its tip
    rb = gear.base_radius
    arc = (r * r - rb * rb) / (2.0 * rb)
    w = cycle.point_unit_load  # normal load, N/m of face width
    ki, wi = linear_weights(table.load_arc, arc)
    S = table.stress  # (3, n_f, n_t, n_r)
    n_off = table.load_offsets.size // 2
    acc = np.zeros((3, S.shape[1], len(cycle), k_all.size, z.size))
    loaded = w > 0.0
    for delta in range(-n_off, n_off + 1):  # delta = k_point - k_tracked
        k_tr = cycle.point_pair - delta
        ok = loaded & np.isin(k_tr, k_all)
        if not ok.any():
            continue
        t = n_off + sign * delta  # table column of the loaded tooth (offset from the middle)
        col = S[:, :, t, :]  # (3, n_f, n_r)
        vals = ((1.0 - wi[ok]) * col[:, :, ki[ok]] + wi[ok] * col[:, :, ki[ok] + 1]) * w[ok]
        idx = (cycle.point_position[ok], np.searchsorted(k_all, k_tr[ok]), iz[ok])
        np.add.at(acc, (slice(None), slice(None)) + idx, vals)
    return principal_stress(acc[0], acc[1], acc[2]), z


def _gear_result(name: str, cycle: LoadedMeshCycle, pair: GearPair, gear: GearSpec,
                 sign: int, table, iso: IsoRootStress | None) -> GearRootStress:
    sig, z = _gear_states(cycle, pair, gear, sign, table)  # (n_f, m, K, n_z)
    n_f, m, K, nz = sig.shape
    env = sig.reshape(n_f, -1).max(axis=1)
    f, i, k, j = np.unravel_index(int(np.argmax(sig)), sig.shape)
    k_all = np.asarray(cycle.pair_index)
    roll = cycle.s0[:, None] + k_all[None, :] * pair.base_pitch  # (m, K) tracked contact
    per_state = sig.max(axis=(0, 3))  # (m, K)
    order = np.argsort(roll.ravel())
    s_max = float(roll[i, k])
    r_load = contact_radii_at(pair, s_max)[0 if sign < 0 else 1]
    return GearRootStress(
        name=name, arc=table.arc, radius=table.radius, envelope=env,
        max_stress=float(sig[f, i, k, j]), max_radius=float(table.radius[f]),
        max_arc=float(table.arc[f]), max_load_roll=s_max, max_load_radius=float(r_load),
        max_face_position=float(z[j]), passage_roll=roll.ravel()[order],
        passage_stress=per_state.ravel()[order], position_max=per_state.max(axis=1),
        face_z=z, face_envelope=sig.max(axis=(0, 1, 2)), iso=iso,
        label=name if gear.name in (name, "") else f"{name} ({gear.name})")


def fillet_settings(pair_index: np.ndarray, fe: Any = None) -> Any:
    """The :class:`~pipeline.fem.fillet_stress.FilletStressSettings` that
    :func:`analyse_root_stress` takes by default for a cycle of the tooth pairs
    ``pair_index`` (its ``pair_index``): refinement 2, 20 flank points per tooth, the
    neighbours that a tooth's passage loads (``min(3, max(1, ptp(pair_index)))`` on each
    side), and ``fe.kind`` (plane strain or stress; plane strain for other sources)."""
    from pipeline.fem.fillet_stress import FilletStressSettings

    kind = getattr(fe, "kind", "plane_strain")
    kind = kind if kind in ("plane_strain", "plane_stress") else "plane_strain"
    k_all = np.asarray(pair_index)
    return FilletStressSettings(kind=kind, offsets=int(min(3, max(1, np.ptp(k_all)))))


def analyse_root_stress(cycle: LoadedMeshCycle, pair: GearPair, operation: OperatingPoint,
                        fe: Any = None, *, settings: Any = None, cache: Cache = DEFAULT_CACHE,
                        show_progress: bool = False
                        ) -> RootStress:
    """Root stress of both gears under the loads of ``cycle`` (module docstring).

    Parameters
    ----------
    cycle : loaded contact over one mesh cycle, solved on ``pair``.
    pair : the (actual) pair.
    operation : the operating point (the ISO comparison takes the cycle's load P).
    fe : the FE settings of the run's compliance source; their ``kind`` (plane strain or
        stress) is used when given.
    settings : :class:`pipeline.fem.fillet_stress.FilletStressSettings` (default:
        :func:`fillet_settings` of the cycle's tooth pairs).
    cache : the on-disk cache of the FE stress tables.
    show_progress : progress on stderr.
    """
    from pipeline.fem.fillet_stress import build_fillet_stress

    del operation  # the load is the cycle's own (checked by load_distribution)
    if settings is None:
        settings = fillet_settings(cycle.pair_index, fe)
    f_t = cycle.load * math.cos(pair.pinion.transverse_pressure_angle)
    out, dofs = [], []
    for name, gear, sign in progress((("pinion", pair.pinion, -1), ("gear", pair.gear, 1)),
                                     "root stress (FE 2D)", enabled=show_progress):
        table = build_fillet_stress(gear, settings, cache=cache)
        iso = None if gear.internal else iso_root_stress(gear, pair, f_t)
        out.append(_gear_result(name, cycle, pair, gear, sign, table, iso))
        dofs.append(table.n_dof)
    return RootStress(out[0], out[1], settings.kind, settings.refinement, f_t,
                      (dofs[0], dofs[1]))
