"""gearpipe: a finite-element-enriched gear stiffness pipeline.

Stages (one sub-package each): ``geometry`` -> ``stiffness`` (analytical) and
``fem`` (Gmsh + scikit-fem) -> ``contact`` (loaded tooth contact) -> ``dynamics``
(lumped-parameter models) -> ``viz`` (plots, load maps, reports).

Everything inside the package is in SI units (m, N, Pa, rad, s); conversion to
mm, deg, N m and rpm happens only at the edges (``config``, reports).
"""

__version__ = "0.1.0"
