"""The default backend: a local pool of worker processes (spawn context, one torch thread each).

Jobs are handed out one at a time per worker, so at most ``workers`` cases are in flight. A
worker that dies (killed, out of memory) breaks the pool: every case then in flight is tried once
more, alone in a fresh pool, and recorded as failed if its worker dies again (so a crash is pinned
on the case that caused it, not on the cases that happened to run beside it). Ctrl-C reaches the driver only
(workers ignore SIGINT); the driver terminates the workers and re-raises, leaving each interrupted fit's
checkpoint for a rerun.
"""

from __future__ import annotations

import multiprocessing
from collections import deque
from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from typing import Callable, Sequence

from unsew.batch.task import CaseJob, CaseRecord, prepare_worker, run_case

__all__ = ["run_local"]


def _init_worker() -> None:
    prepare_worker(ignore_sigint=True)


def _new_pool(workers: int) -> ProcessPoolExecutor:
    return ProcessPoolExecutor(
        max_workers=workers, mp_context=multiprocessing.get_context("spawn"), initializer=_init_worker
    )


def _stop(pool: ProcessPoolExecutor) -> None:
    """Terminate the pool's processes now (shutdown alone waits for running fits)."""
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        if p.is_alive():
            p.terminate()
    for p in procs:
        p.join(timeout=5)
        if p.is_alive():
            p.kill()
            p.join(timeout=5)


def run_local(jobs: Sequence[CaseJob], *, workers: int, on_done: Callable[[CaseRecord], None]) -> None:
    """Run ``jobs`` on ``workers`` local processes; call ``on_done(record)`` in the driver as each
    case ends (in completion order). Raises KeyboardInterrupt after stopping the workers if
    interrupted (the cases then in flight keep their checkpoints)."""
    workers = max(1, int(workers))
    pending = deque((job, False) for job in jobs)  # (job, solo): solo jobs run alone in the pool
    running: dict = {}
    pool = _new_pool(workers)
    try:
        while pending or running:
            while pending and len(running) < workers:
                job, solo = pending[0]
                if running and (solo or any(s for _, s in running.values())):
                    break  # a suspect runs alone, so a crash is pinned on the case that caused it
                pending.popleft()
                running[pool.submit(run_case, job)] = (job, solo)
            done, _ = wait(running, return_when=FIRST_COMPLETED)
            lost = []  # jobs whose worker pool broke under them
            for fut in done:
                job, solo = running.pop(fut)
                try:
                    rec = fut.result()
                except BrokenProcessPool:
                    lost.append((job, solo))
                else:
                    on_done(rec)
            if lost:  # every case in flight went down with the pool
                lost += list(running.values())
                running.clear()
                _stop(pool)
                pool = _new_pool(workers)
                for job, solo in reversed(lost):
                    if not solo:  # a suspect: tried again, alone
                        pending.appendleft((job, True))
                    else:
                        on_done(
                            CaseRecord(
                                job.name,
                                job.case_dir,
                                job.out_dir,
                                status="failed",
                                reason="a worker process died while fitting it (killed, or out of memory)",
                            )
                        )
    except BaseException:
        _stop(pool)
        raise
    pool.shutdown(wait=True)
