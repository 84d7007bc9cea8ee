"""Files of the full-revolution loaded contact (``gearpipe run`` with ``[contact.errors]``).

``revolution_te.csv`` (per position: pinion angle, mesh cycle, roll coordinate, TE, the
runouts' gap, mesh stiffness, largest unit load, residual; SI with units in the headers)
and ``revolution_te.png``; ``revolution_spectrum.csv`` (order per pinion revolution,
amplitude in m) and ``revolution_spectrum.png``; ``revolution_worst_pair.png`` (the tooth
pair with the largest Hertz pressure along the path, against every other pair).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from pipeline.contact.results import LoadedMeshCycle
from pipeline.io import write_csv
from pipeline.run.revolution import RevolutionStage
from pipeline.viz.figure_cache import NO_CACHE, FigureCache


def write_revolution(stage: RevolutionStage, cycle: LoadedMeshCycle, title: str, out: Path,
                     prefix: str = "", figures: FigureCache = NO_CACHE) -> list[Path]:
    """The files of the module docstring; ``cycle`` is the error-free mesh cycle (its TE is
    drawn repeated for comparison)."""
    from pipeline.viz.revolution import (
        plot_revolution_spectrum,
        plot_revolution_te,
        plot_worst_pair,
    )

    rev = stage.revolution
    sp = rev.spectrum()
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
    ]
