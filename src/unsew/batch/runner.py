"""``run_batch``: one fit per case folder of CASES_DIR into RESULTS_DIR/<case>/, on a local
process pool (default) or on Ray, resumable, with one progress bar and a summary.

Rerunning the same batch continues it: complete result folders are skipped (their metrics are
read back into the summary), interrupted fits resume from their checkpoint, failed and pending
cases are tried again. Each case's log (the fit's messages, a failure's traceback) is appended to
RESULTS_DIR/<case>.log.
"""

from __future__ import annotations

import contextlib
import json
import os
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from unsew.batch.cases import find_cases, read_garment, result_state
from unsew.batch.local import run_local
from unsew.batch.ray_backend import RayCluster, ray_session, run_ray
from unsew.batch.summary import write_index_html, write_summary_csv
from unsew.batch.task import CaseJob, CaseRecord
from unsew.errors import InputError
from unsew.fit.config import FitConfig

__all__ = ["run_batch", "BatchResult", "default_workers"]


@dataclass
class BatchResult:
    """What a batch did. records: one per case, in case-name order; interrupted: stopped by
    Ctrl-C (the summary holds what finished); summary_csv, index_html: the files written;
    wall_s: wall time of the batch [s]."""

    records: list[CaseRecord]
    out: Path
    summary_csv: Path
    index_html: Path
    interrupted: bool = False
    wall_s: float = 0.0
    counts: dict = field(default_factory=dict)


def default_workers(n_cases: int) -> int:
    """min(CPU count, number of cases), at least 1."""
    return max(1, min(os.cpu_count() or 1, n_cases))


def _read_metrics(out: Path) -> dict | None:
    try:
        return json.loads((out / "metrics.json").read_text())
    except (OSError, ValueError):
        return None


def run_batch(
    cases_dir: str | os.PathLike,
    out: str | os.PathLike,
    *,
    cfg=None,
    workers: int | None = None,
    ray: str | RayCluster | None = None,
    overwrite: bool = False,
    fit_fn: Callable | None = None,
    progress: bool = True,
) -> BatchResult:
    """Fit every case folder of ``cases_dir`` into ``out/<case name>/`` and write
    ``out/summary.csv`` and ``out/index.html``.

    cfg: FitConfig for every case (default FitConfig()); workers: local processes (default
    min(CPU count, cases to fit)); ray: None for the local pool, else a Ray address ("auto",
    "local", "host:6379", "ray://host:10001"; see :func:`unsew.batch.ray_backend.ray_session`)
    or a :class:`~unsew.batch.ray_backend.RayCluster` (an address and extra ``ray.init``
    arguments);
    overwrite: refit cases whose result is complete (otherwise they are skipped); fit_fn: the
    per-case fit, a module-level function like :func:`unsew.batch.task.fit_case_dir` (the
    default); progress: one tqdm bar on stderr for the batch when stderr is a terminal, else a
    plain line per finished case (:func:`unsew.fit.progress.is_terminal`).

    A failing case is recorded (status "failed", one-line reason) and the batch goes on. On
    Ctrl-C the workers are stopped, the summary of what finished is written and the result has
    ``interrupted=True``; rerunning continues. Raises InputError for a bad cases folder, an
    existing ``out`` that is not a folder, or a Ray that is missing or cannot be reached (before
    anything is written).
    """
    cfg = cfg if cfg is not None else FitConfig()
    cases = find_cases(cases_dir)
    out = Path(out).resolve()
    if out.exists() and not out.is_dir():
        raise InputError(f"--out {out} exists and is not a folder")
    if workers is not None and workers < 1:
        raise InputError(f"--workers must be at least 1, got {workers}")
    session = contextlib.ExitStack()
    if ray:  # connect first: a bad address fails before anything is written
        cluster = ray if isinstance(ray, RayCluster) else RayCluster(ray)
        session.enter_context(ray_session(cluster.address, init_kwargs=cluster.init_kwargs))
    opts = _Options(
        cfg=cfg, workers=workers, ray=bool(ray), overwrite=overwrite, fit_fn=fit_fn, progress=progress
    )
    with session:
        return _run(cases, cases_dir, out, opts)


@dataclass(frozen=True)
class _Options:
    """run_batch's arguments as the batch uses them (``ray``: whether it runs on Ray)."""

    cfg: FitConfig
    workers: int | None
    ray: bool
    overwrite: bool
    fit_fn: Callable | None
    progress: bool


def _plan(cases, out: Path, opts: _Options) -> tuple[dict[str, CaseRecord], list[CaseJob]]:
    """A record per case (skipped: complete and not overwritten; failed: a folder in the way)
    and the jobs of the cases to fit."""
    records: dict[str, CaseRecord] = {}
    jobs: list[CaseJob] = []
    for c in cases:
        c = c.resolve()
        res = out / c.name
        rec = CaseRecord(c.name, str(c), str(res), garment=read_garment(c))
        state = result_state(res)
        if state == "complete" and not opts.overwrite:
            rec.status, rec.metrics = "skipped", _read_metrics(res)
            rec.time_s = ((rec.metrics or {}).get("timings_s") or {}).get("total_s")
        elif state == "blocked" and not opts.overwrite:
            rec.status = "failed"
            rec.reason = (
                f"{res} exists but is not a complete result (no metrics.json); remove it or pass --overwrite"
            )
        else:
            job = CaseJob(
                c.name,
                str(c),
                str(res),
                str(out / f"{c.name}.log"),
                opts.cfg,
                overwrite=opts.overwrite,
                fit_fn=opts.fit_fn,
            )
            jobs.append(job)
        records[c.name] = rec
    return records, jobs


class _Progress:
    """The batch's progress on stderr: a tqdm bar on a terminal, else a line per finished case
    (nothing without ``progress``); :meth:`done` records a finished case in ``records``."""

    def __init__(self, records: dict[str, CaseRecord], n_cases: int, n_jobs: int, progress: bool):
        from unsew.fit.progress import is_terminal

        self.records, self.n_cases = records, n_cases
        self.bar, self.lines = None, progress and not is_terminal(sys.stderr)
        if progress and not self.lines:
            from tqdm import tqdm

            self.bar = tqdm(
                total=n_cases,
                initial=n_cases - n_jobs,
                desc="batch",
                unit="case",
                dynamic_ncols=True,
                file=sys.stderr,
            )
        self.counts = {
            "done": 0,
            "failed": sum(r.status == "failed" for r in records.values()),
            "skipped": sum(r.status == "skipped" for r in records.values()),
        }
        if self.lines:
            print(
                f"batch: {n_cases} cases, {n_jobs} to fit ({self.counts['skipped']} skipped, "
                f"{self.counts['failed']} failed before fitting)",
                file=sys.stderr,
                flush=True,
            )
        self.finished = n_cases - n_jobs
        if self.bar is not None:
            self.bar.set_postfix(done=0, failed=self.counts["failed"], skipped=self.counts["skipped"])

    def done(self, rec: CaseRecord) -> None:
        counts = self.counts
        self.records[rec.name] = rec
        counts[rec.status] = counts.get(rec.status, 0) + 1
        self.finished += 1
        if self.bar is not None:
            self.bar.set_postfix(
                done=counts["done"], failed=counts["failed"], skipped=counts["skipped"], refresh=False
            )
            self.bar.update(1)
        elif self.lines:
            why = f": {rec.reason}" if rec.status != "done" and rec.reason else ""
            print(
                f"batch: {self.finished}/{self.n_cases} {rec.name} {rec.status}{why}",
                file=sys.stderr,
                flush=True,
            )

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()


def _run(cases, cases_dir, out: Path, opts: _Options) -> BatchResult:
    out.mkdir(parents=True, exist_ok=True)
    records, jobs = _plan(cases, out, opts)
    prog = _Progress(records, len(cases), len(jobs), opts.progress)
    t0 = time.perf_counter()
    interrupted = False
    try:
        if jobs:
            if opts.ray:
                run_ray(jobs, device=opts.cfg.device, on_done=prog.done)
            else:
                run_local(jobs, workers=opts.workers or default_workers(len(jobs)), on_done=prog.done)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        prog.close()
    wall = time.perf_counter() - t0
    for job in jobs:  # cases that never finished
        rec = records[job.name]
        if rec.status == "pending" and result_state(job.out_dir) == "partial":
            rec.status, rec.reason = "interrupted", "stopped before it finished; rerun the batch to resume it"
    final = [records[c.name] for c in cases]

    csv_path = write_summary_csv(final, out / "summary.csv")
    html_path = write_index_html(final, out / "index.html", title=f"unsew batch: {Path(cases_dir).name}")
    n = {}
    for r in final:
        n[r.status] = n.get(r.status, 0) + 1
    return BatchResult(final, out, csv_path, html_path, interrupted=interrupted, wall_s=wall, counts=n)
