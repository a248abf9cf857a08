"""The Ray backend (``unsew batch --ray ADDRESS``): the same per-case work as Ray tasks.

Each case is one task pinned to one CPU (``num_cpus=1``), or to one GPU as well when the fit's
device is CUDA (``num_gpus=1``). The task writes the case's result folder itself, so on a cluster
of several machines RESULTS_DIR (and CASES_DIR) must be on a filesystem every node sees at the
same path (NFS, a cluster volume); the driver collects the tasks' records and writes the summary.

Ray is optional (``pip install 'unsew[ray]'``) and imported only here, when asked for.
"""

from __future__ import annotations

import contextlib
from dataclasses import dataclass
from typing import Callable, Iterator, Sequence

from unsew.batch.task import CaseJob, CaseRecord, one_line, prepare_worker, run_case
from unsew.errors import InputError

__all__ = ["run_ray", "ray_session", "ray_available", "RayCluster"]


def ray_available() -> bool:
    """Whether Ray can be imported."""
    import importlib.util

    return importlib.util.find_spec("ray") is not None


def _task(job: CaseJob) -> CaseRecord:
    prepare_worker()
    return run_case(job)


def _import_ray():
    try:
        import ray
    except ImportError:
        raise InputError("--ray needs Ray, which is not installed; pip install 'unsew[ray]'") from None
    return ray


@dataclass(frozen=True)
class RayCluster:
    """Where a batch runs on Ray: ``address`` as :func:`ray_session` takes it ("auto", "local",
    "host:6379", "ray://host:10001") and extra ``ray.init`` arguments (e.g. num_cpus for a
    local instance)."""

    address: str = "auto"
    init_kwargs: dict | None = None


@contextlib.contextmanager
def ray_session(address: str = "auto", *, init_kwargs: dict | None = None) -> Iterator[None]:
    """Connect to (or start) Ray for the block; disconnect (or stop it) afterwards.

    address: "auto" (a running cluster, e.g. after ``ray start --head``), "local" (start a Ray
    instance on this machine for the batch) or a cluster address ("ray://host:10001",
    "host:6379"). init_kwargs: extra ``ray.init`` arguments (e.g. num_cpus for a local
    instance). If Ray is already initialised in this process, that instance is used and left
    running. Raises InputError (one line) if Ray is missing or cannot be reached.
    """
    ray = _import_ray()
    if ray.is_initialized():
        yield
        return
    kw = {
        "runtime_env": {"env_vars": {"OMP_WAIT_POLICY": "PASSIVE"}},
        "include_dashboard": False,
        "log_to_driver": False,
        **(init_kwargs or {}),
    }
    if address != "local":
        kw["address"] = address
    try:
        ray.init(**kw)
    except (ConnectionError, ValueError, RuntimeError) as exc:
        raise InputError(f"cannot start or reach Ray at {address!r}: {one_line(exc)}") from None
    try:
        yield
    finally:
        ray.shutdown()


def run_ray(jobs: Sequence[CaseJob], *, device: str = "cpu", on_done: Callable[[CaseRecord], None]) -> None:
    """Run ``jobs`` as Ray tasks on the Ray instance this process is connected to (see
    :func:`ray_session`); call ``on_done(record)`` in the driver as each case ends.

    device: the fit's torch device; "cuda..." asks one GPU per task besides its CPU. A task whose
    worker dies is retried once by Ray, then recorded as failed. On KeyboardInterrupt the tasks
    are cancelled (forcibly) and the interrupt re-raised.
    """
    ray = _import_ray()
    opts = {"num_cpus": 1, "max_retries": 1}
    if str(device).startswith("cuda"):
        opts["num_gpus"] = 1
    remote = ray.remote(_task).options(**opts)
    refs: dict = {}
    try:
        for job in jobs:
            refs[remote.remote(job)] = job
        while refs:
            done, _ = ray.wait(list(refs), num_returns=1)
            for ref in done:
                job = refs.pop(ref)
                try:
                    rec = ray.get(ref)
                except Exception as exc:  # the task's worker died or Ray failed it
                    rec = CaseRecord(
                        job.name,
                        job.case_dir,
                        job.out_dir,
                        status="failed",
                        reason=f"Ray task failed: {one_line(exc)}"[:300],
                    )
                on_done(rec)
    except BaseException:
        for ref in refs:
            try:
                ray.cancel(ref, force=True)
            except Exception:
                pass
        raise
