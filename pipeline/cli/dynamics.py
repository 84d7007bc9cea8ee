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

from pipeline.cli.common import (
    add_cache_arguments,
    add_common_arguments,
    command_cache,
    emit,
    load,
    output_dir,
    record,
)
from pipeline.cli.dynamics_files import shown_meshes, write_modes, write_response, write_sweep
from pipeline.dynamics.analysis import analyse_modes, analyse_response, analyse_sweep
from pipeline.dynamics.layout import model_layout
from pipeline.io import write_json
from pipeline.output_folder import staged_output
from pipeline.run.dynamics import dynamics_options, operating_frequency
from pipeline.run.runner import gearbox_dynamic_model


def _common(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    add_cache_arguments(parser)
    parser.add_argument("--full", action="store_true", help="fine settings instead of coarse")


add_modes_arguments = _common
add_response_arguments = _common
add_sweep_arguments = _common


def _setup(args, command: str):
    box = load(args)
    target = output_dir(args, command)
    cache = command_cache(args)
    return box, gearbox_dynamic_model(box, cache), target


def run_modes(args) -> int:
    """Natural frequencies, mode types and mode-shape plots of the configured model."""
    box, model, out = _setup(args, "modes")
    res = analyse_modes(model)
    with staged_output(out) as staging:
        files = write_modes(res, staging, model_layout(model), title=box.name)
        record(staging, args, box, files)
    summary = {**res.summary(), "out": str(out)}
    shares = res.energy_shares()
    lines = [f"{res.counts()}; each mode's kinetic energy in "
             "in-plane translation, rotation and axial translation (%)",
             "  #   f [Hz]      kind           mult  in-plane [%]  rotation [%]  axial [%]"]
    lines += [
        f"{k:3d} {f:10.2f}  {kd:14s} {m:<4d} {100 * ip:12.1f}  {100 * rot:12.1f}  {100 * ax:9.1f}"
        for k, (f, kd, m, ip, rot, ax) in enumerate(
            zip(res.frequencies, res.kinds, res.multiplicity, shares["in-plane"],
                shares["rotation"], shares["axial"], strict=True)
        )
    ]
    emit(args, summary, out, lines)
    return 0


def run_response(args) -> int:
    """Steady dynamic response: DTE and mesh forces in time, DTE spectrum."""
    box, model, out = _setup(args, "response")
    result = analyse_response(model, dynamics_options(box).response,
                              refine=2 if args.full else 1)
    resp = result.response
    summary = {**result.summary(), "out": str(out)}
    with staged_output(out) as staging:
        files = write_response(result, staging, box.name,
                               operating=operating_frequency(box, model))
        files.append(write_json(staging / "summary.json", summary))
        record(staging, args, box, files)
    lines = [
        f"{box.name}: {resp.method}, mesh period {resp.period * 1e3:.4f} ms",
        "mesh            RMS force [N]   DTE p-p [um]",
    ]
    lines += [
        f"{m:14s} {v['rms_force_N']:14.1f} {v['dte_peak_to_peak_m'] * 1e6:14.4f}"
        for m, v in summary["meshes"].items()
    ]
    emit(args, summary, out, lines)
    return 0


def run_sweep(args) -> int:
    """RMS dynamic mesh force against mesh frequency."""
    box, model, out = _setup(args, "sweep")
    fn = analyse_modes(model).frequencies
    res = analyse_sweep(model, dynamics_options(box).sweep, full=args.full,
                        show_progress=not args.json, natural_frequencies=fn)
    freqs = res.frequencies
    operating = operating_frequency(box, model)
    with staged_output(out) as staging:
        files = write_sweep(res, staging, box.name, natural_frequencies=fn,
                            operating=operating)
        record(staging, args, box, files)
    shown = shown_meshes(res)
    peaks = {m: res.peaks(m) for m in shown}
    summary = {"points": int(freqs.size), "f_min_Hz": float(freqs[0]),
               "f_max_Hz": float(freqs[-1]), "operating_point": operating.summary(),
               "peaks_Hz": peaks, "out": str(out)}
    lines = [
        f"{box.name}: {freqs.size} points {freqs[0]:.4g}-{freqs[-1]:.4g} Hz (operating mesh "
        f"frequency {operating.mesh_frequency:.4g} Hz)"
    ]
    lines += [f"  {m}: peaks at {', '.join(f'{p:.0f}' for p in v)} Hz" for m, v in peaks.items()]
    emit(args, summary, out, lines)
    return 0
