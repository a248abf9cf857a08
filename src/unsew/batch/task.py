"""One case of a batch, as run by a worker (a local process or a Ray task).

:func:`run_case` never raises for a failing fit: it returns a :class:`CaseRecord` with status
"failed" and a one-line reason, so the batch goes on. The fit itself is a parameter of the job
(``fit_fn``, default :func:`fit_case_dir`), so the orchestration can be tested without the
simulator; it must be a module-level function (it is pickled by reference).
"""

from __future__ import annotations

import contextlib
import os
import time
import traceback
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from unsew.batch.cases import read_garment, result_state
from unsew.body.case import load_case
from unsew.errors import UnsewError
from unsew.fit.run import run_fit

__all__ = ["CaseJob", "CaseRecord", "run_case", "fit_case_dir", "prepare_worker", "one_line"]


@dataclass(frozen=True)
class CaseJob:
    """What a worker needs to fit one case.

    name: case name (= result folder name); case_dir, out_dir: absolute paths (str, so the job
    pickles plainly); log_path: file receiving the fit's log lines and a failure's traceback;
    cfg: FitConfig; overwrite: replace a complete result (a fit resumes from
    ``out_dir.partial/checkpoint.pt`` whenever that exists); fit_fn: ``fit_fn(case_dir: Path,
    out: Path, cfg, *, resume: bool, overwrite: bool, log: Callable[[str], None]) -> dict``
    (the metrics written to metrics.json), None for :func:`fit_case_dir`.
    """

    name: str
    case_dir: str
    out_dir: str
    log_path: str
    cfg: object
    overwrite: bool = False
    fit_fn: Callable | None = None


@dataclass
class CaseRecord:
    """The outcome of one case of a batch.

    status: "done" (fitted now), "skipped" (complete from an earlier run), "failed",
    "interrupted" (stopped by Ctrl-C while fitting; resumes on a rerun) or "pending" (not
    started); reason: one line for failed/interrupted cases; time_s: wall time of this fit [s]
    (for skipped cases, the earlier fit's total from metrics.json); metrics: the metrics dict of
    the result folder (None unless done or skipped); resumed: the fit continued a checkpoint.
    """

    name: str
    case_dir: str
    out_dir: str
    garment: str = "?"
    status: str = "pending"
    reason: str = ""
    time_s: float | None = None
    resumed: bool = False
    metrics: dict | None = field(default=None, repr=False)


def one_line(exc: BaseException) -> str:
    """The one-line reason of a failure: an UnsewError's message, otherwise the exception's type
    and message."""
    msg = " ".join(str(exc).split())
    if isinstance(exc, UnsewError):
        return msg or type(exc).__name__
    return f"{type(exc).__name__}: {msg}" if msg else type(exc).__name__


def prepare_worker(*, ignore_sigint: bool = False) -> None:
    """Settings of a worker process, before it imports torch or numpy (shared/STACK.md): passive
    OpenMP waiting, one torch thread, and one BLAS/OpenMP thread (a worker is one core's worth of
    work; OpenBLAS threads also busy-wait). ``ignore_sigint``: leave Ctrl-C to the driver, which
    stops the worker itself (local pool)."""
    os.environ["OMP_WAIT_POLICY"] = "PASSIVE"
    for var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
        os.environ.setdefault(var, "1")
    if ignore_sigint:
        import signal

        signal.signal(signal.SIGINT, signal.SIG_IGN)
    import torch

    torch.set_num_threads(1)


def fit_case_dir(
    case_dir: Path,
    out: Path,
    cfg,
    *,
    resume: bool = False,
    overwrite: bool = False,
    log: Callable[[str], None] | None = None,
) -> dict:
    """The real fit of one case folder into ``out`` (load_case + run_fit, no progress bar).
    Returns the metrics dict. The fit's time limit counts from before the case is loaded."""
    started = time.perf_counter()
    case = load_case(case_dir)
    _, metrics = run_fit(
        case, cfg, out, resume=resume, overwrite=overwrite, progress=False, log=log, started=started
    )
    return metrics


def run_case(job: CaseJob) -> CaseRecord:
    """Fit one case; never raises for a failed fit (status "failed", reason one line, the
    traceback in ``job.log_path``)."""
    resume = result_state(job.out_dir) == "partial"
    rec = CaseRecord(job.name, job.case_dir, job.out_dir, garment=read_garment(job.case_dir), resumed=resume)
    fit_fn = job.fit_fn or fit_case_dir
    Path(job.log_path).parent.mkdir(parents=True, exist_ok=True)
    t0 = time.perf_counter()
    with open(job.log_path, "a", encoding="utf-8") as logf:

        def log(s: str) -> None:
            logf.write(s.rstrip("\n") + "\n")
            logf.flush()

        log(
            f"== {time.strftime('%Y-%m-%d %H:%M:%S')} fit {job.case_dir} -> {job.out_dir}"
            f"{' (resuming)' if resume else ''}"
        )
        try:
            with contextlib.redirect_stdout(logf), contextlib.redirect_stderr(logf):
                metrics = fit_fn(
                    Path(job.case_dir),
                    Path(job.out_dir),
                    job.cfg,
                    resume=resume,
                    overwrite=job.overwrite,
                    log=log,
                )
        except Exception as exc:  # the batch goes on; the reason is recorded
            rec.status, rec.reason = "failed", one_line(exc)
            log(traceback.format_exc())
        else:
            rec.status, rec.metrics = "done", metrics
        rec.time_s = time.perf_counter() - t0
        log(f"== {rec.status} in {rec.time_s:.1f} s{': ' + rec.reason if rec.reason else ''}")
    return rec
