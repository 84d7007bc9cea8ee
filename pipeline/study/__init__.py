"""Design studies: the pipeline over design axes of a base gearbox file, on dask.distributed.

* :mod:`.spec` - the study file (base file, fixed changes, axes, sampling, outputs).
* :mod:`.points` - the numbered design points (grid or Latin hypercube).
* :mod:`.kpis` - the KPI table (name with unit -> function of a point's result).
* :mod:`.evaluate` - one point: gearbox document -> KPI row (pure); FE tables per geometry.
* :mod:`.execute` - points checked first, FE tables once per geometry, batches on Dask or
  serially; :func:`run_study`.
* :mod:`.store` - the results folder: atomic part files, manifest, resume check, Parquet/CSV.
* :mod:`.plots` - one-at-a-time sensitivity and KPI trade-off figures.
* :mod:`.harris` - Harris maps (``kind = "harris"``): TE against load per modification
  variant, on the study machinery.
* :mod:`.optimise` - gearbox keys optimised over a load range (``kind = "optimise"``),
  differential evolution with its evaluations on Dask.
* the command ``gearpipe study`` is :mod:`pipeline.cli.study`.
"""

from pipeline.study.execute import StudyOptions, run_study
from pipeline.study.kpis import KPIS, PointResult
from pipeline.study.spec import StudySpec, study_from_file

__all__ = ["KPIS", "PointResult", "StudyOptions", "StudySpec", "run_study", "study_from_file"]
