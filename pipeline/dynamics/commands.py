"""``gearpipe modes|response|sweep CONFIG [--out DIR] [--json] [--full]``: the dynamics.

The model comes from the gearbox file: a pair's lateral-torsional model or a planetary
set's model (planar, or herringbone for herringbone gears) with masses, inertias, base
radii and phases derived from the geometry and the mesh excitation from the analytical
stiffness or the loaded contact at the operating point (``[dynamics]`` holds supports,
damping, ``excitation``, optional explicit mesh stiffness tables,
``[dynamics.response]`` and ``[dynamics.sweep]``), or a ``[lumped_model]``.
Writes CSV/PNG/JSON plus ``run.json`` to ``results/<file stem>/<command>``;
``--full`` uses the fine settings (more harmonics/segments, all sweep points).
"""

from __future__ import annotations

import argparse
import json

from pipeline.commands_common import add_common_arguments, load, output_dir
from pipeline.config import Gearbox
from pipeline.dynamics.analysis import analyse_modes, analyse_response, analyse_sweep
from pipeline.dynamics.options import PairDynamicsOptions, PlanetaryDynamicsOptions
from pipeline.dynamics.outputs import shown_meshes, write_modes, write_response, write_sweep
from pipeline.io import to_jsonable, write_json, write_run_record
from pipeline.validation import InputError


def _common(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    parser.add_argument("--full", action="store_true", help="fine settings instead of coarse")


add_modes_arguments = _common
add_response_arguments = _common
add_sweep_arguments = _common


def dynamics_options(box: Gearbox) -> PairDynamicsOptions | PlanetaryDynamicsOptions:
    """The ``[dynamics]`` options of a gearbox (defaults of its kind when the table is absent)."""
    if box.dynamics is not None:
        return box.dynamics
    return PlanetaryDynamicsOptions() if box.kind == "planetary" else PairDynamicsOptions()


def mesh_excitation(box: Gearbox, pair, operation, excitation: str, *, assembly_errors=None):
    """The excitation of one mesh of ``box``: ``"analytical"`` (stiffness stage) or
    ``"contact"`` (analytical slice compliance, loaded contact of the ``[contact]`` options).

    ``pair`` is the nominal pair (with ``assembly_errors``) for the stiffness stage and
    the pair as installed for the contact analysis.
    """
    if excitation == "contact":
        from pipeline.contact import analyse_contact, analytical_compliance
        from pipeline.dynamics.contact_excitation import excitation_from_contact

        source = analytical_compliance(pair, operation, box.contact, box.stiffness)
        cycle = analyse_contact(source, operation, box.contact)
        return excitation_from_contact(cycle, pair, operation, box.stiffness.friction_model)
    from pipeline.dynamics.mesh_input import excitation_from_stiffness
    from pipeline.stiffness.analysis import analyse_stiffness

    stiff = analyse_stiffness(pair, operation, box.stiffness, assembly_errors=assembly_errors)
    return excitation_from_stiffness(stiff.mesh)


def _planetary_model(box: Gearbox):
    from pipeline.dynamics.mesh_input import excitation_from_signal
    from pipeline.dynamics.models import planetary_gears as pg

    opts = dynamics_options(box)
    ps = box.planetary
    halves = 2 if ps.sun.herringbone else 1
    ops = pg.mesh_operations(ps, box.operation, halves)
    excitations = []
    for pair, op, given in ((ps.sun_planet, ops[0], opts.sun_mesh_stiffness),
                            (ps.planet_ring, ops[1], opts.ring_mesh_stiffness)):
        if given is not None:
            excitations.append(excitation_from_signal(given))
        else:
            excitations.append(mesh_excitation(box, pg.helical_half(pair), op, opts.excitation))
    build = (pg.herringbone_planetary_model_from_gears if halves == 2
             else pg.planetary_model_from_gears)
    return build(ps, box.bodies, box.carrier, box.operation, opts, *excitations)


def dynamic_model(box: Gearbox):
    """The dynamic model a gearbox file describes (composition of geometry, stiffness or
    contact, dynamics).

    A pair: :func:`~pipeline.dynamics.models.spur_pair.spur_pair_model` excited by the
    analytical stiffness or the loaded contact of the installed pair; a planetary set:
    :func:`~pipeline.dynamics.models.planetary_gears.planetary_model_from_gears` (or the
    herringbone model) excited by one sun-planet and one planet-ring mesh; a
    ``[lumped_model]``: that model.
    """
    from pipeline.dynamics.models.spur_pair import spur_pair_model

    if box.kind == "lumped":
        return box.lumped
    if box.kind == "gear":
        raise InputError(f"{box.name}: the file describes a single gear; a dynamic model needs "
                         "a gear pair ([pinion] and [gear]), a planetary set or a "
                         "[lumped_model]")
    if box.kind == "planetary":
        return _planetary_model(box)
    opts = dynamics_options(box)
    excitation = None
    if opts.mesh_stiffness is None or opts.friction:
        if opts.excitation == "contact":
            excitation = mesh_excitation(box, box.actual_pair, box.operation, "contact")
        else:
            excitation = mesh_excitation(box, box.pair, box.operation, "analytical",
                                         assembly_errors=box.assembly_errors)
    return spur_pair_model(box.actual_pair, (box.bodies["pinion"], box.bodies["gear"]),
                           box.operation, opts, excitation)


def _setup(args, command: str):
    box = load(args)
    model = dynamic_model(box)
    return box, model, output_dir(args, command)


def _emit(args, summary: dict, lines: list[str]) -> None:
    if args.json:
        print(json.dumps(to_jsonable(summary)))
    else:
        print("\n".join(lines))


def run_modes(args) -> int:
    """Natural frequencies, mode types and mode-shape plots of the configured model."""
    box, model, out = _setup(args, "modes")
    res = analyse_modes(model)
    files = write_modes(res, out, count=16 if args.full else 8)
    summary = {**res.summary(), "out": str(out)}
    write_run_record(out, box.to_dict(), files, f"gearpipe modes {args.config}")
    lines = [f"{len(res.dof_names)} DOF, results in {out}",
             "  #   f [Hz]      kind           mult"]
    lines += [
        f"{k:3d} {f:10.2f}  {kd:14s} {m}"
        for k, (f, kd, m) in enumerate(
            zip(res.frequencies, res.kinds, res.multiplicity, strict=True)
        )
    ]
    _emit(args, summary, lines)
    return 0


def run_response(args) -> int:
    """Steady dynamic response: DTE and mesh forces in time, DTE spectrum."""
    box, model, out = _setup(args, "response")
    result = analyse_response(model, dynamics_options(box).response,
                              refine=2 if args.full else 1)
    resp = result.response
    files = write_response(result, out, box.name)
    summary = {**result.summary(), "out": str(out)}
    write_json(out / "summary.json", summary)
    files.append(out / "summary.json")
    write_run_record(out, box.to_dict(), files, f"gearpipe response {args.config}")
    lines = [
        f"{box.name}: {resp.method}, mesh period {resp.period * 1e3:.4f} ms, results in {out}",
        "mesh            RMS force [N]   DTE p-p [um]",
    ]
    lines += [
        f"{m:14s} {v['rms_force_N']:14.1f} {v['dte_peak_to_peak_m'] * 1e6:14.4f}"
        for m, v in summary["meshes"].items()
    ]
    _emit(args, summary, lines)
    return 0


def run_sweep(args) -> int:
    """RMS dynamic mesh force against mesh frequency."""
    box, model, out = _setup(args, "sweep")
    res = analyse_sweep(model, dynamics_options(box).sweep, full=args.full,
                        show_progress=not args.json)
    freqs = res.frequencies
    files = write_sweep(res, out, box.name)
    shown = shown_meshes(res)
    peaks = {m: res.peaks(m) for m in shown}
    write_run_record(out, box.to_dict(), files, f"gearpipe sweep {args.config}")
    summary = {"points": int(freqs.size), "peaks_Hz": peaks, "out": str(out)}
    lines = [
        f"{box.name}: {freqs.size} points {freqs[0]:.0f}-{freqs[-1]:.0f} Hz, results in {out}"
    ]
    lines += [f"  {m}: peaks at {', '.join(f'{p:.0f}' for p in v)} Hz" for m, v in peaks.items()]
    _emit(args, summary, lines)
    return 0
