"""Many fits at once: ``unsew batch CASES_DIR --out RESULTS_DIR`` over a folder of case folders,
on a local process pool by default or on a Ray cluster (``unsew[ray]``).

- :func:`run_batch` (runner): the batch, resumable, one progress bar, summary files.
- :mod:`unsew.batch.local`: the local process pool; :mod:`unsew.batch.ray_backend`: Ray tasks.
- :mod:`unsew.batch.task`: one case (``run_case``, the default fit ``fit_case_dir``).
- :mod:`unsew.batch.summary`: summary.csv, the printed table, index.html.

Importing this package is cheap (no torch, no Ray).
"""

from unsew.batch.cases import find_cases, result_state
from unsew.batch.runner import BatchResult, default_workers, run_batch
from unsew.batch.task import CaseJob, CaseRecord, fit_case_dir

__all__ = [
    "run_batch",
    "BatchResult",
    "default_workers",
    "find_cases",
    "result_state",
    "CaseJob",
    "CaseRecord",
    "fit_case_dir",
]
