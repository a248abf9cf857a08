"""Run a fit into a result folder: work in RESULT_DIR.partial (with a checkpoint after every
iteration), rename onto RESULT_DIR only when every file is written."""

from __future__ import annotations

import os
import shutil
import sys
from pathlib import Path

from unsew.errors import InputError
from unsew.fit.fit import fit
from unsew.fit.outputs import write_result
from unsew.fit.start import with_garment_read

__all__ = ["run_fit", "partial_dir"]


def partial_dir(out: Path) -> Path:
    """The work folder of a result folder: ``RESULT_DIR.partial`` beside it."""
    out = Path(out)
    return out.with_name(out.name + ".partial")


def run_fit(case, cfg, out: Path, *, resume: bool = False, overwrite: bool = False, log=None, **fit_options):
    """Fit ``case`` with ``cfg`` and write the result folder ``out``. Returns (FitResult, metrics).

    fit_options: ``progress`` (True/False or a :class:`~unsew.fit.progress.Progress`; default
    True), ``callback`` (called with each phase-two iteration), ``started`` (when the command
    began: the time limit counts from it), as :func:`unsew.fit.fit.fit` takes them.

    Ctrl-C or a crash leaves ``out.partial`` with ``checkpoint.pt``; ``resume=True`` continues.
    """
    log = log or (lambda s: print(s, file=sys.stderr))
    out = Path(out)
    work = partial_dir(out)
    _prepare(out, work, resume=resume, overwrite=overwrite, log=log)
    # before the work folder: a type we cannot fit leaves nothing
    case = with_garment_read(case, cfg, log=log)
    work.mkdir(parents=True, exist_ok=True)
    result = _fit_in(work, case, cfg, resume=resume, log=log, **fit_options)
    (work / "checkpoint.pt").unlink(missing_ok=True)
    if result.drape_check is not None and not result.drape_check.ok:
        # a garment fallen, off the body, exploded or inside it is no result: nothing is written
        shutil.rmtree(work, ignore_errors=True)
        result.drape_check.raise_if_bad("fit")
    metrics = write_result(work, result, case, cfg, report=cfg.output.report)
    if out.exists():
        shutil.rmtree(out)
    os.replace(work, out)
    s = metrics["surface"]
    log(
        f"fit done in {result.timings['total_s']:.0f} s, {result.iterations} iterations: "
        f"Chamfer {s['chamfer_mm']:.2f} mm, normal error {s['normal_error_deg']:.1f} deg -> {out}"
    )
    if not metrics.get("ok", True):
        log(f'warning: {metrics["miss"]} (metrics.json: "ok": false)')
    return result, metrics


def _prepare(out: Path, work: Path, *, resume: bool, overwrite: bool, log) -> None:
    """Refuse an existing ``out`` unless ``overwrite``; clear the work folder unless ``resume``."""
    if out.exists() and not overwrite:
        raise InputError(f"result folder {out} exists; pass --overwrite or choose another --out")
    if work.exists() and not resume:
        shutil.rmtree(work)
    if resume and not (work / "checkpoint.pt").is_file():
        log(f"no checkpoint in {work}; starting afresh")


def _fit_in(work: Path, case, cfg, *, resume: bool, log, progress=True, callback=None, started=None):
    """:func:`unsew.fit.fit.fit` with its checkpoint in ``work``; on Ctrl-C or a crash the work
    folder is kept only if it holds a checkpoint to resume from."""
    try:
        return fit(
            case,
            cfg,
            progress=progress,
            checkpoint=work / "checkpoint.pt",
            resume=resume,
            log=log,
            callback=callback,
            started=started,
        )
    except BaseException:
        if not (work / "checkpoint.pt").is_file():
            shutil.rmtree(work, ignore_errors=True)
        else:
            log(f"interrupted: rerun with --resume to continue from {work / 'checkpoint.pt'}")
        raise
