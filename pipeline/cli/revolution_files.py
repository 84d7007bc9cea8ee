"""Files of the full-revolution loaded contact (``gearpipe run`` with ``[contact.errors]``).

``revolution_te.csv`` (per position: pinion angle, mesh cycle, roll coordinate, TE, the
runouts' gap, mesh stiffness, largest unit load, residual; SI with units in the headers)
and ``revolution_te.png``; ``revolution_spectrum.csv`` (order per pinion revolution,
amplitude in m, order 0 the mean) and ``revolution_spectrum.png``;
``revolution_worst_pair.png`` (the tooth pair with the largest Hertz pressure along the
path, against every other pair) and ``revolution_worst_pair_load_map.png`` (its unit load
over the flank through its passage, as the mesh cycle's ``load_map_2d.png``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipeline.contact.loadmap import flank_load_map
from pipeline.contact.options import ContactOptions
from pipeline.contact.results import LoadedMeshCycle
from pipeline.geometry.pair import GearPair
from pipeline.io import write_csv
from pipeline.run.revolution import RevolutionStage
from pipeline.viz.figure_cache import NO_CACHE, FigureCache


def write_revolution(stage: RevolutionStage, cycle: LoadedMeshCycle, pair: GearPair,
                     opts: ContactOptions, title: str, out: Path, prefix: str = "",
                     figures: FigureCache = NO_CACHE) -> list[Path]:
    """The files of the module docstring; ``cycle`` is the error-free mesh cycle (its TE is
    drawn repeated for comparison), ``pair`` the installed pair, ``opts`` the contact
    options (grid of the load map, modifications in its title)."""
    from pipeline.viz.loadmap import plot_load_map_2d
    from pipeline.viz.revolution import (
        plot_revolution_spectrum,
        plot_revolution_te,
        plot_worst_pair,
    )

    rev = stage.revolution
    sp = rev.spectrum()
    worst = rev.worst_pair()
    lm = flank_load_map(rev.pair_cycle(worst["pinion_tooth"], worst["gear_tooth"]), pair,
                        opts.load_map_profile_points)
    map_title = (f"{title}\nunit load of pinion tooth {worst['pinion_tooth']} / gear tooth "
                 f"{worst['gear_tooth']} through its passage (the largest pressure of the "
                 f"span)\nmodifications: {opts.modifications.describe()}")
    head = (f"{title}\nfull revolution: {rev.mesh_cycles} mesh cycles ({rev.span}), "
            f"{rev.positions_per_cycle} positions each")
    return [
        write_csv(out / f"{prefix}revolution_te.csv", rev.columns()),
        figures.save(out / f"{prefix}revolution_te.png", plot_revolution_te, rev,
                     np.asarray(cycle.transmission_error), head),
        write_csv(out / f"{prefix}revolution_spectrum.csv", rev.spectrum_columns()),
        figures.save(out / f"{prefix}revolution_spectrum.png", plot_revolution_spectrum, sp,
                     int(rev.teeth[1]), head),
        figures.save(out / f"{prefix}revolution_worst_pair.png", plot_worst_pair, rev, head),
        figures.save(out / f"{prefix}revolution_worst_pair_load_map.png", plot_load_map_2d, lm,
                     map_title),
    ]
