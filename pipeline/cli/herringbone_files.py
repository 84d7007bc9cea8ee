"""Files of a herringbone sun-planet mesh in a run: ``<prefix>herringbone.csv`` and the
left/right sun-flank load maps (VTU, and pyvista PNG with ``[contact] render``) of the
stage :func:`pipeline.run.herringbone.herringbone_stage` computed; written by
``gearpipe run`` and ``gearpipe report``.
"""

from __future__ import annotations

from pathlib import Path

from pipeline.run.herringbone import HerringboneStage

TORQUE_ENTRY_WORDS = {"right": "sun torque taken at the right end",
                      "left": "sun torque taken at the left end",
                      "both": "sun torque taken half at each end"}
"""How a load-map title says ``[herringbone] torque_entry``."""


def herringbone_map_title(side: str, kj: float, torque_entry: str, lo: float,
                          hi: float) -> str:
    """Title of one half's load map: the half (its sun and planet flanks), the groove's
    K_j (N m^2), where the sun torque leaves, and the loaded band's extremes (N/m in,
    N/mm shown)."""
    return (f"{side} helical half: sun and planet flanks (K_j = {kj:.3g} N m^2, "
            f"{TORQUE_ENTRY_WORDS[torque_entry]})\nunit load max {hi * 1e-3:.0f} / "
            f"min {lo * 1e-3:.0f} N/mm; one colour scale for both halves")


def write_herringbone(stage: HerringboneStage, out: Path, prefix: str, figures,
                      profile_points: int = 80, render: bool = True) -> list[Path]:
    """``<prefix>herringbone.csv`` (per position: loads, flank approaches, own and whole-mesh
    stiffness, groove twist and torque, sun axial position) and the left/right sun-flank
    load maps ``<prefix>herringbone_load_map_{left,right}.vtu`` and, with ``render``
    (``[contact] render``), their pyvista ``.png``; returns the files."""
    from pipeline.contact.herringbone_maps import (
        half_load_maps,
        half_pair,
        loaded_range,
        write_half_vtus,
    )
    from pipeline.io import write_csv
    from pipeline.viz.loadmap import render_load_map

    maps = half_load_maps(stage.cycle, stage.pair, profile_points)
    files = [write_csv(out / f"{prefix}herringbone.csv", stage.cycle.columns())]
    files += write_half_vtus(maps, stage.pair, out, f"{prefix}herringbone_load_map")
    if not render:
        return files
    top = max(m.unit_load.max() for m in maps.values()) * 1e-3
    for side, m in maps.items():
        lo, hi = loaded_range(m)
        title = herringbone_map_title(side, stage.groove.equivalent_Kj,
                                      stage.cycle.torque_entry, lo, hi)
        files.append(figures.save(out / f"{prefix}herringbone_load_map_{side}.png",
                                  render_load_map, half_pair(stage.pair, side), m, title,
                                  clim=(0.0, top)))
    return files
