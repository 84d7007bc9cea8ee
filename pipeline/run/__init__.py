"""The whole pipeline on one gearbox (``gearpipe run``): :func:`run_pipeline`."""

from pipeline.run.chain import MeshCase, MeshStages, RunOptions
from pipeline.run.runner import RunResult, run_pipeline

__all__ = ["MeshCase", "MeshStages", "RunOptions", "RunResult", "run_pipeline"]
