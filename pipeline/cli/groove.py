"""``gearpipe groove CONFIG [--out DIR] [--json] [--full]``: relief-groove stiffness.

Writes to ``DIR`` (default ``results/<config name>/groove``): ``groove_stiffness.json``
(the :class:`~pipeline.fem.groove.result.GrooveStiffness` the dynamic models
load), ``coupling_matrix.csv``, ``twist.png`` (the body under the sun torque,
coloured by shear stress) and ``run.json``. ``--full`` also runs the other teeth
model and the other coupling and writes ``comparison.csv``. ``--json`` prints the
result as JSON on stdout instead of a summary.
"""

from __future__ import annotations

import argparse
import dataclasses
from pathlib import Path

import numpy as np

from pipeline.cli.common import (
    add_cache_arguments,
    add_common_arguments,
    command_cache,
    emit,
    load,
    output_dir,
    record,
)
from pipeline.fem.groove.result import DOF_NAMES
from pipeline.fem.groove.spec import COUPLINGS, TEETH_MODELS, GrooveSpec
from pipeline.fem.groove.study import analyse_groove
from pipeline.io import write_csv
from pipeline.output_folder import staged_output
from pipeline.validation import InputError


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Add the ``groove`` sub-command arguments to ``parser``."""
    add_common_arguments(parser)
    add_cache_arguments(parser)
    parser.add_argument("--full", action="store_true",
                        help="also run the other teeth model and coupling, and compare")


def _summary(spec: GrooveSpec, res, shift) -> str:
    g = spec.gear
    lines = [
        f"relief groove of {g.name}: z = {g.teeth}, m_n = {g.module * 1e3:g} mm, "
        f"halves {g.half_width * 1e3:g} mm, groove {g.groove_width * 1e3:g} mm wide, "
        f"bottom diameter {spec.groove_bottom_diameter * 1e3:g} mm",
        f"  model: {spec.teeth_model}, {spec.coupling} coupling, {res.n_dof} DOF "
        f"(P2 tetrahedra, h = {spec.mesh_size * 1e3:g} mm), solver {res.solver}, "
        f"{res.timings['total']:.1f} s",
        f"  k_t  = {res.torsional_stiffness:.4e} N m/rad between O_L and O_R "
        f"(l_LR = {res.l_LR * 1e3:g} mm)",
        f"  K_j  = k_t l_LR = {res.equivalent_Kj:.4e} N m^2   (G J root cylinder "
        f"{res.section_Kj['root']:.4e}, groove bottom {res.section_Kj['groove']:.4e})",
        f"  k_LR x/y/z = {res.coupling_matrix[0, 0]:.4e} / {res.coupling_matrix[1, 1]:.4e} / "
        f"{res.coupling_matrix[2, 2]:.4e} N/m",
    ]
    if spec.sun_torque:
        lines.append(f"  T_s = {spec.sun_torque:g} N m: phi_LR = {shift.phi_LR:.4e} rad, "
                     f"lambda_LR = {shift.lambda_LR:.5f}")
    return "\n".join(lines)


def _write(analysis, rows: list, spec: GrooveSpec, out: Path) -> list[Path]:
    """The result JSON, coupling matrix, twist render and (``--full``) the comparison."""
    from pipeline.viz import save
    from pipeline.viz.groove import render_twisted_body

    res = rows[0]
    files = [res.save(out / "groove_stiffness.json")]
    files.append(write_csv(out / "coupling_matrix.csv",
                           {f"{n} [SI]": res.coupling_matrix[:, i] for i, n in
                            enumerate(DOF_NAMES)}))
    torque = spec.sun_torque or 1e3 * res.torsional_stiffness * 1e-6
    files.append(save(render_twisted_body(analysis, torque), out / "twist.png"))
    if len(rows) > 1:
        files.append(write_csv(out / "comparison.csv", {
            "teeth model (0 root cylinder, 1 helical teeth)": np.array(
                [TEETH_MODELS.index(r.teeth_model) for r in rows]),
            "coupling (0 distributed, 1 rigid, 2 tooth forces)": np.array(
                [COUPLINGS.index(r.coupling) for r in rows]),
            "k_t [N m/rad]": np.array([r.torsional_stiffness for r in rows]),
            "K_j [N m^2]": np.array([r.equivalent_Kj for r in rows]),
            "n_dof": np.array([r.n_dof for r in rows]),
        }))
    return files


def run(args: argparse.Namespace) -> int:
    """Run the command; returns the process exit code."""
    box = load(args)
    if box.groove is None:
        raise InputError(f"{args.config}: a relief-groove analysis needs a [groove] table "
                         "(bottom_diameter_mm, ...) and a herringbone gear")
    spec = box.groove
    target = output_dir(args, "groove")
    cache = command_cache(args)
    analysis = analyse_groove(spec, cache=cache,
                              progress=not args.json)
    res = analysis.result
    shift = res.phase_shift(spec.sun_torque)
    rows = [res]
    if args.full:
        for variant in (
            dataclasses.replace(spec, teeth_model=[t for t in TEETH_MODELS
                                                   if t != spec.teeth_model][0]),
            dataclasses.replace(spec, coupling="rigid" if spec.coupling == "distributed"
                                else "distributed"),
        ):
            rows.append(analyse_groove(variant, cache=cache,
                                       progress=not args.json).result)
    with staged_output(target) as out:
        files = _write(analysis, rows, spec, out)
        record(out, args, box, files)
    payload = {"result": res.to_dict(), "phase_shift": dataclasses.asdict(shift),
               "variants": [r.to_dict() for r in rows[1:]], "outdir": str(target)}
    lines = [_summary(spec, res, shift)] + [
        f"  variant {r.teeth_model}/{r.coupling}: k_t = {r.torsional_stiffness:.4e} "
        f"N m/rad ({r.torsional_stiffness / res.torsional_stiffness - 1:+.2%}), "
        f"K_j = {r.equivalent_Kj:.4e} N m^2, {r.n_dof} DOF" for r in rows[1:]]
    emit(args, payload, target, lines)
    return 0


