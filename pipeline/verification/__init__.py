"""Verification: the catalogue of exact, published, independent-FE and convergence cases
the pipeline reproduces, run as one set (``gearpipe validate``).

Each case calls the pipeline's public functions with a documented input, compares the
results with reference values (an exact solution, a published table or worked example, an
independent FE model's committed results, or the pipeline itself over mesh refinements)
and returns them with the tolerance and its reason for every quantity; nothing here writes
files but :mod:`.writers` (called by the command).

- :mod:`.model` - the case model: quantities, convergence studies, plots, outcomes.
- :mod:`.results` - a case's result (status, time, message) and a run's totals.
- :mod:`.display` - display units and the formatting of values, errors, tolerances.
- :mod:`.catalogue` - the registry of cases with their tiers (``fast``, ``full``).
- :mod:`.runner` - runs a selection, times it, turns an exception into a failed case.
- :mod:`.context` - what cases share: the FE cache, the committed reference data.
- :mod:`.tables` - the results as rows with units (CSV, JSON).
- :mod:`.figures` - the figures of the cases (matplotlib).
- :mod:`.html` - the self-contained HTML report.
- :mod:`.writers` - HTML, JSON and CSV files.
- ``cases_*`` - the cases, one module per stage.
"""

from pipeline.verification.catalogue import CATALOGUE, Case, select
from pipeline.verification.context import Context
from pipeline.verification.model import Outcome, Quantity
from pipeline.verification.results import CaseResult, VerificationRun
from pipeline.verification.runner import run_cases

__all__ = ["CATALOGUE", "Case", "CaseResult", "Context", "Outcome", "Quantity",
           "VerificationRun", "run_cases", "select"]
