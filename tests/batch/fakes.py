"""A stand-in for the real fit, so the batch orchestration is tested in seconds.

``fake_fit`` behaves like unsew.fit.run.run_fit on disk: it works in OUT.partial/ with a
checkpoint written after every iteration and renames to OUT once metrics.json is written.
meta.json steers it: garment outside GARMENT_TYPES -> InputError; "crash": true -> the worker
process dies; "sleep": seconds per iteration; "value": the number the metrics derive from.
"""

from __future__ import annotations

import json
import os
import shutil
import time
from pathlib import Path

from unsew.errors import InputError
from unsew.io.case import GARMENT_TYPES

__all__ = ["fake_fit", "make_fake_case"]


def make_fake_case(d: Path, *, garment: str = "tshirt", value: float = 1.0, **extra) -> Path:
    d.mkdir(parents=True, exist_ok=True)
    (d / "meta.json").write_text(json.dumps({"garment": garment, "units": "m", "value": value, **extra}))
    return d


def fake_fit(
    case_dir: Path, out: Path, cfg, *, resume: bool = False, overwrite: bool = False, log=None
) -> dict:
    meta = json.loads((Path(case_dir) / "meta.json").read_text())
    if meta.get("garment") not in GARMENT_TYPES:
        raise InputError(
            f"garment {meta.get('garment')!r} in {case_dir}/meta.json must be one of "
            f"{', '.join(GARMENT_TYPES)}"
        )
    if meta.get("crash"):
        os._exit(3)
    out = Path(out)
    if out.exists() and not overwrite:
        raise InputError(f"result folder {out} exists")
    work = out.with_name(out.name + ".partial")
    if work.exists() and not resume:
        shutil.rmtree(work)
    work.mkdir(parents=True, exist_ok=True)
    ckpt = work / "checkpoint.pt"
    start = int(ckpt.read_text()) if resume and ckpt.is_file() else 0
    if log:
        log(f"fake fit from iteration {start}")
    for it in range(start, cfg.optimizer.iterations):
        time.sleep(float(meta.get("sleep", 0.0)))
        tmp = work / "ckpt.tmp"
        tmp.write_text(str(it + 1))
        os.replace(tmp, ckpt)
    v = float(meta.get("value", 1.0))
    metrics = {
        "surface": {"chamfer_mm": 10.0 * v, "normal_error_deg": 5.0 * v},
        "loss_final": {"total": v / 3.0, "chamfer": v / 7.0},
        "iterations": cfg.optimizer.iterations,
        "timings_s": {"total_s": 0.5},
        "resumed_from": start,
    }
    if meta.get("pattern_gt"):
        metrics["pattern"] = {"area_error_rel_mean": 0.01 * v, "turning_distance_mean": 0.1 * v}
    (work / "report.html").write_text("<html>fake</html>")
    (work / "metrics.json").write_text(json.dumps(metrics))
    ckpt.unlink()
    if out.exists():
        shutil.rmtree(out)
    os.replace(work, out)
    return metrics
