"""``gearpipe fe CONFIG``: 2D sector FE of both gears -> mesh, influence matrix, compliance.

Composes :func:`pipeline.fem.sector_analysis.analyse_sector` for each gear of the
pair and writes its results. For each gear: the 2D sector mesh (``--teeth`` teeth,
``--refinement``),
the structural influence matrix of ``--points`` points per flank on every tooth
(summary: size, symmetry, timings, rim coupling), the single-tooth FE compliance
along the profile against the analytical tooth compliance (bending + shear +
axial + Sainsot foundation, :mod:`pipeline.stiffness.tooth`), PNGs of the mesh
and of the sector deformed by a unit load at the pitch radius. Writes CSV/JSON/PNG
and ``run.json`` to ``results/<config>/fe/``. Works for internal gears (ring sectors:
teeth pointing inwards, clamped on the rim circle ``rim_outer_radius``). A refinement
whose model would not fit the machine is refused before meshing with its estimated
size (:mod:`pipeline.fem.sector2d_size`).
"""

from __future__ import annotations

import argparse
import dataclasses
import warnings
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
from pipeline.fem.sector2d_size import check_size
from pipeline.fem.sector_analysis import SectorResult, analyse_sector, sector_settings
from pipeline.fem.settings import PLANE_KINDS, SECTOR_TEETH, FE2DSettings, FE3DSettings
from pipeline.io import atomic_write, write_csv, write_json
from pipeline.output_folder import staged_output
from pipeline.progress import progress
from pipeline.validation import InputError, InputWarning


def add_arguments(parser: argparse.ArgumentParser) -> None:
    add_common_arguments(parser)
    add_cache_arguments(parser)
    parser.add_argument("--teeth", type=int, default=None,
                        help=f"teeth in the sector (default: [fe] teeth, else {SECTOR_TEETH})")
    parser.add_argument("--points", type=int, default=None,
                        help=f"points per flank (default: [fe] points, else "
                             f"{FE2DSettings.points})")
    parser.add_argument("--refinement", type=float, default=None,
                        help="mesh refinement, flank size m_n / (12 refinement) "
                             f"(default: [fe] refinement, else {FE2DSettings.refinement:g})")
    parser.add_argument("--kind", choices=PLANE_KINDS, default=None,
                        help="2D model (default: [fe] kind, else plane_strain)")


def write_gear(res: SectorResult, out: Path, tag: str) -> list[Path]:
    """Compliance CSV, influence matrix (.npy), mesh, compliance and deformed-sector PNGs."""
    from pipeline.viz import save
    from pipeline.viz.fem import plot_compliance, plot_deformed, plot_sector_mesh

    g, opts = res.gear, res.options
    cols = res.columns()
    files = [write_csv(out / f"{tag}_tooth_compliance.csv", cols)]
    files.append(atomic_write(out / f"{tag}_influence_m2_per_N.npy",
                              lambda p: np.save(p, res.influence.structural)))
    title = f"{g.name}: z {g.teeth}, m_n {g.module * 1e3:g} mm, {opts.sector_teeth}-tooth sector"
    files.append(save(plot_sector_mesh(res.sector, title), out / f"{tag}_mesh.png"))
    files.append(save(plot_compliance(res.radii, [
        ("FE structural (" + opts.kind + ")", cols["fe_structural [m^2/N]"]),
        ("analytical b+s+a+foundation", cols["analytical_total [m^2/N]"])], title),
        out / f"{tag}_tooth_compliance.png"))
    u = res.pitch_load_displacement(1e3)  # 1 N/mm at the pitch radius of the middle tooth
    scale = 0.05 * g.module / max(np.abs(u).max(), 1e-30)
    files.append(save(plot_deformed(res.sector, u, scale,
                                    title + ", 1 N/mm at the pitch radius"),
                      out / f"{tag}_deformed.png"))
    return files


def options(box_fe: FE2DSettings | FE3DSettings, args: argparse.Namespace) -> FE2DSettings:
    """The ``[fe]`` table's 2D model with the command-line options that were given on top
    (a file whose ``[fe]`` describes the 3D model: the 2D defaults)."""
    given = {k: getattr(args, k) for k in ("teeth", "points", "refinement", "kind")
             if getattr(args, k) is not None}
    base = box_fe if isinstance(box_fe, FE2DSettings) else FE2DSettings()
    try:
        return dataclasses.replace(base, **given)
    except InputError as exc:  # name the option as typed on the command line
        name = (exc.field or "").rsplit(".", 1)[-1]
        if name in given and exc.bounds is not None:
            lo, hi = exc.bounds[:2]
            raise InputError(f"--{name} = {given[name]} is outside the allowed range "
                             f"[{lo:g}, {hi:g}]") from None
        raise


def run(args: argparse.Namespace) -> int:
    box = load(args)
    pair = box.require_pair()
    if isinstance(box.fe, FE3DSettings) and "fe" in box.tables:
        warnings.warn('[fe] describes the 3D model ([contact] compliance = "fe3d"): gearpipe fe '
                      "analyses 2D sectors with the 2D defaults and its own options",
                      InputWarning, stacklevel=1)
    opts = options(box.fe, args)
    target = output_dir(args, "fe")
    cache = command_cache(args)
    for gear in (pair.pinion, pair.gear):  # refuse models too big for the machine up front
        check_size(gear, sector_settings(gear, opts))
    summary = {}
    with staged_output(target) as out:
        files = []
        for tag, gear in progress((("pinion", pair.pinion), ("gear", pair.gear)),
                                  "2D sector FE"):
            res = analyse_sector(gear, opts, cache=cache)
            summary[tag] = res.summary()
            files += write_gear(res, out, tag)
        files.append(write_json(out / "fe_summary.json", summary))
        record(out, args, box, files, inputs={"gearbox": box.to_dict(), "fe": opts})
    emit(args, summary, target)
    return 0
