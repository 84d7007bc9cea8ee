"""The shafts sections of a mesh report: their deflection, the misalignment it opens across
the face and the line load with and without it; the dynamics with the shafts beside the
same without them."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from pipeline.report.content import quantity
from pipeline.report.model import Figure, Section

MODEL_NAMES = {"beam": "Timoshenko beam", "fe3d": "3D FE superelement"}


def shaft_section(stage: Any, k_rigid: float, k_coupled: float,
                  figures: Sequence[Figure], models: Mapping[str, str]) -> Section:
    """The :class:`pipeline.run.shafts.ShaftStage` of a pair, K_Hbeta on rigid supports and
    with the shafts (-); ``models``: each shaft's model by gear ("beam", "fe3d")."""
    rows = [
        quantity("misalignment", "misalignment from the shafts across the face", "um",
                 float(np.ptp(stage.gap)) * 1e6),
        quantity("approach", "rigid approach of the gears (adds to the TE only)", "um",
                 stage.approach * 1e6),
        quantity("K_Hbeta_rigid", "K_Hbeta on rigid supports", "-", k_rigid),
        quantity("K_Hbeta_shafts", "K_Hbeta with the shafts", "-", k_coupled),
        quantity("iterations", "fixed-point iterations (line load to 1e-3)", "-",
                 stage.iterations),
    ]
    for role, r in zip(("pinion", "gear"), stage.retreats, strict=True):
        if r is None or r.solution is None:
            continue
        rows.append(quantity(f"{role}_seat_translation", f"{role}: seat deflection along the "
                             "line of action (mean)", "um", float(r.translation.mean()) * 1e6))
        rows.append(quantity(f"{role}_seat_twist", f"{role}: twist at the base circle "
                             "(mean)", "um", float(r.twist.mean()) * 1e6))
        for i, row in enumerate(r.solution.reactions):
            rows.append(quantity(f"{role}_bearing_{i}", f"{role}: bearing {i} radial reaction",
                                 "N", float(np.hypot(row[0], row[1]))))
    used = ", ".join(f"{role}: {MODEL_NAMES[m]}" for role, m in models.items())
    notes = (f"Each shaft ({used}) is solved in its mesh frame (y along the line of action, "
             "away from the mate): the line load loads it as forces and moments F r_b across "
             "the seat, and the flank retreats by u_y + r_b theta_z; a helical mesh adds its "
             "axial force a F (a = -h tan beta_b, h = +1 for a right hand) and its moments "
             "about x and y, "
             "and the retreat a (u_z - d theta_x - r_b theta_y) (d the contact's distance "
             "from the tangent point); the gap the two shafts "
             "open (its mean taken out) is added to the flank modifications and the contact "
             "solved again until the line load changes by less than 1e-3.",)
    return Section("shafts", "Shafts and bearings", tuple(rows), figures=tuple(figures),
                   notes=notes)


def planetary_shaft_section(stage: Any, figures: Sequence[Figure]) -> Section:
    """The :class:`pipeline.run.planetary_shafts.PlanetaryMeshShafts` of one mesh of a
    planetary set: its misalignment and K_Hbeta with and without the shafts, the sun's and
    the planet pin's deflection."""
    k_rigid, k_shafts = stage.system.k_hbeta[stage.name]
    rows = [
        quantity("misalignment", "misalignment from the sun and the pins across the face",
                 "um", float(np.ptp(stage.gap)) * 1e6),
        quantity("approach", "rigid approach of the gears (adds to the TE only)", "um",
                 stage.approach * 1e6),
        quantity("K_Hbeta_rigid", "K_Hbeta on rigid supports", "-", k_rigid),
        quantity("K_Hbeta_shafts", "K_Hbeta with the sun's shaft and the pins", "-", k_shafts),
        quantity("iterations", "fixed-point iterations over both meshes (line loads to 1e-3)",
                 "-", stage.iterations),
    ]
    sun, pin = stage.system.sun, stage.system.pin
    if sun is not None and stage.name == "sun_planet":
        twist = sun.displacement[:, 5] * sun.base_radius
        rows += [
            quantity("sun_net_force", "sun: net transverse force of all its meshes", "N",
                     sun.net_force),
            quantity("sun_twist", "sun: twist at the base circle across the face", "um",
                     float(np.ptp(twist)) * 1e6),
            quantity("sun_misalignment_max", "sun: largest misalignment it opens at a planet",
                     "um", float(max(np.ptp(r) for r in sun.retreats)) * 1e6),
        ]
    if pin is not None:
        d = pin.displacement
        rows += [
            quantity("pin_tangential", "planet pin: seat deflection along the orbit's tangent",
                     "um", float(d[:, 0].mean()) * 1e6),
            quantity("pin_radial", "planet pin: seat deflection radially out", "um",
                     float(d[:, 1].mean()) * 1e6),
            quantity("pin_tilt", "planet pin: seat tilt", "mrad",
                     float(np.hypot(d[0, 3], d[0, 4])) * 1e3),
            quantity("planet_retreat", "planet: retreat across the face along this mesh", "um",
                     float(np.ptp(pin.retreats[stage.name])) * 1e6),
        ]
        if pin.solution is not None:
            for i, row in enumerate(pin.solution.reactions):
                rows.append(quantity(f"pin_support_{i}", f"planet pin: support {i} radial "
                                     "reaction", "N", float(np.hypot(row[0], row[1]))))
    notes = ("The sun's shaft carries every sun-planet mesh (each the first turned by the "
             "planets' angle: with equally spaced planets the forces cancel and the twist "
             "across the face remains); each planet turns freely on its pin, a Timoshenko "
             "beam in the carrier loaded by both of its meshes' forces along their lines of "
             "action; ring and carrier rigid. The gaps (means taken out) are added to both "
             "meshes' flank modifications and both contacts solved again until neither line "
             "load changes by more than 1e-3.",)
    return Section("shafts", "Sun shaft and planet pins", tuple(rows),
                   figures=tuple(figures), notes=notes)


def shaft_dynamics_section(summary: Mapping[str, Any], figures: Sequence[Figure]) -> Section:
    """Natural frequencies and the sweep's largest dynamic factor with the shafts and without
    them, from the run's dynamics summary
    (:meth:`pipeline.run.dynamics.DynamicsStages.summary` with its ``without_shafts``)."""
    rigid = summary["without_shafts"]
    with_fn = summary["natural_frequencies_Hz"]
    rigid_fn = rigid["natural_frequencies_Hz"]
    rows = [quantity(f"mode_{i + 1}", f"elastic mode {i + 1}", "Hz",
                     with_fn[i] if i < len(with_fn) else None,
                     rigid_fn[i] if i < len(rigid_fn) else None)
            for i in range(max(len(with_fn), len(rigid_fn)))]
    sweep = summary["sweep"]
    for mesh, k in sweep["max_dynamic_factor"].items():
        tag = "" if mesh == "mesh" else f" ({mesh})"
        rows.append(quantity(f"max_dynamic_factor_{mesh}", f"largest dynamic factor over the "
                             f"sweep{tag}", "-", k, rigid["max_dynamic_factor"][mesh]))
        rows.append(quantity(f"max_dynamic_factor_at_{mesh}", f"... at mesh frequency{tag}",
                             "Hz", sweep["max_dynamic_factor_at_Hz"][mesh],
                             rigid["max_dynamic_factor_at_Hz"][mesh]))
    notes = ("With the shafts each gear is held at its seat by its shaft (bearings and shaft "
             "bending in series, 1 / C_yy of the seat flexibility; a planet by its pin and "
             "its bearing in series) and, where [dynamics] gives a motor's or a driven "
             "machine's inertia, tied to it by the shaft's torsion between the seat and the "
             "torque point (1 / C_theta_z theta_z); the meshes are excited by the contact with "
             "the shafts' misalignment. Without the shafts: the same file without its shaft "
             "tables, its supports the typed [dynamics] bearing stiffnesses or their defaults, "
             "no motor or machine, the contact on rigid supports. The natural frequencies are "
             "the elastic ones up to the cut of the dynamics section; a dash: the model has "
             "fewer.",)
    return Section("shaft_dynamics", "Dynamics with and without the shafts",
                   tuple(rows), columns=("with the shafts", "without the shafts"),
                   figures=tuple(figures), notes=notes)
