"""unsew batch with the real fit on tiny known-truth t-shirt cases: a batch gives the same results as
single fits (fits are deterministic with a fixed seed), a broken case is reported without stopping
the others, and a rerun skips finished cases.

The default suite runs a small mode (one real case + one broken case, 1 iteration); the 3-case
batch on 2 local workers and on a local Ray instance is marked slow."""

from __future__ import annotations

import csv
import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest

from unsew.batch import fit_case_dir, run_batch
from unsew.batch.ray_backend import RayCluster
from unsew.fit.config import load_config
from unsew.fit.demo import DemoTruth, make_truth_case

#: tiny fits: coarse panels, few sewing/settling/drape steps, a small Chamfer subset
TINY = {
    "drape.edge_length": 0.05,
    "drape.sew_steps": 10,
    "drape.settle_steps": 5,
    "drape.steps": 3,
    "loss.target_points": 1000,
    "output.report": False,
    "material.start": "cotton",
}
TRUTHS = [
    DemoTruth(),
    DemoTruth(hem_length=0.03, hem_girth=0.02, sleeve_length=0.01),
    DemoTruth(hem_length=0.09, hem_girth=0.08, sleeve_length=0.05, material="cotton"),
]


def _leaves(d, prefix=""):
    if isinstance(d, dict):
        for k, v in d.items():
            yield from _leaves(v, f"{prefix}/{k}")
    elif isinstance(d, list):
        for i, v in enumerate(d):
            yield from _leaves(v, f"{prefix}[{i}]")
    else:
        yield prefix, d


#: metrics.json keys that measure the run itself, not the result
_RUN_MEASURES = ("/timings_s", "/peak_memory_mb", "/peak_memory_stages_mb")


def assert_same_metrics(a: dict, b: dict, *, rtol: float = 1e-9) -> None:
    """Every metric equal to ``rtol`` (timings and peak memory, which measure the run, excepted); the
    message lists the ones that differ."""
    la = {k: v for k, v in _leaves(a) if not k.startswith(_RUN_MEASURES)}
    lb = {k: v for k, v in _leaves(b) if not k.startswith(_RUN_MEASURES)}
    assert la.keys() == lb.keys()
    bad = [
        (k, la[k], lb[k])
        for k in la
        if la[k] != lb[k]
        and not (
            isinstance(la[k], float)
            and isinstance(lb[k], float)
            and abs(la[k] - lb[k]) <= rtol * max(abs(la[k]), abs(lb[k]))
        )
    ]
    assert not bad, f"{len(bad)} metrics differ, e.g. {bad[:5]}"


def _broken_copy(src: Path, dst: Path) -> None:
    shutil.copytree(src, dst)
    meta = json.loads((dst / "meta.json").read_text())
    meta["garment"] = "sweater"
    (dst / "meta.json").write_text(json.dumps(meta))


def _metrics(out: Path) -> dict:
    return json.loads((out / "metrics.json").read_text())


def test_small_batch_equals_single_fit_and_reports_broken_case(tmp_path):
    cfg = load_config(**TINY, **{"optimizer.iterations": 1})
    cases = tmp_path / "cases"
    make_truth_case(cases / "tshirt", settings=cfg.drape)
    _broken_copy(cases / "tshirt", cases / "broken")
    single = fit_case_dir(cases / "tshirt", tmp_path / "single", cfg)
    res = run_batch(cases, tmp_path / "out", cfg=cfg, workers=2, progress=False)
    st = {r.name: (r.status, r.reason) for r in res.records}
    assert st["tshirt"] == ("done", "")
    assert st["broken"][0] == "failed" and "garment 'sweater'" in st["broken"][1]
    assert_same_metrics(_metrics(tmp_path / "out" / "tshirt"), single)

    def no_time(m):
        return {
            k: v for k, v in m.items() if k not in ("timings_s", "peak_memory_mb", "peak_memory_stages_mb")
        }

    # bitwise, in fact
    assert no_time(_metrics(tmp_path / "out" / "tshirt")) == no_time(json.loads(json.dumps(single)))
    # the rerun, through the CLI: the finished case is skipped, the broken one fails again (exit 1)
    p = subprocess.run(
        [
            sys.executable,
            "-m",
            "unsew",
            "batch",
            str(cases),
            "--out",
            str(tmp_path / "out"),
            "--workers",
            "2",
            "--no-progress",
        ],
        capture_output=True,
        text=True,
        timeout=300,
        env={**os.environ, "OMP_WAIT_POLICY": "PASSIVE"},
    )
    assert p.returncode == 1, p.stderr
    assert (
        "skipped" in p.stdout
        and "failed: garment 'sweater'" in p.stdout
        and "1 skipped, 1 failed" in p.stdout
    )
    with open(tmp_path / "out" / "summary.csv", newline="") as f:
        rows = {r["case"]: r for r in csv.DictReader(f)}
    assert rows["tshirt"]["status"] == "skipped"
    assert float(rows["tshirt"]["chamfer_mm"]) == single["surface"]["chamfer_mm"]


@pytest.fixture(scope="module")
def three_cases(tmp_path_factory):
    root = tmp_path_factory.mktemp("real3")
    cfg = load_config(**{**TINY, "optimizer.iterations": 2, "output.report": True})
    for i, truth in enumerate(TRUTHS):
        make_truth_case(root / "cases" / f"tshirt{i}", truth=truth, settings=cfg.drape)
    _broken_copy(root / "cases" / "tshirt0", root / "cases" / "broken")
    singles = {
        f"tshirt{i}": fit_case_dir(root / "cases" / f"tshirt{i}", root / "single" / f"tshirt{i}", cfg)
        for i in range(3)
    }
    return root, cfg, singles


def _check_batch(res, out: Path, singles: dict) -> None:
    st = {r.name: r.status for r in res.records}
    assert st == {"broken": "failed", "tshirt0": "done", "tshirt1": "done", "tshirt2": "done"}
    for name, m in singles.items():
        assert_same_metrics(_metrics(out / name), m)
        assert (out / name / "report.html").is_file()
    html = (out / "index.html").read_text()
    assert all(f"href='{n}/report.html'" in html for n in singles)


@pytest.mark.slow
def test_three_cases_two_local_workers_equal_single_fits(three_cases):
    root, cfg, singles = three_cases
    out = root / "local"
    res = run_batch(root / "cases", out, cfg=cfg, workers=2, progress=False)
    _check_batch(res, out, singles)
    res2 = run_batch(root / "cases", out, cfg=cfg, workers=2, progress=False)
    assert [r.status for r in res2.records] == ["failed", "skipped", "skipped", "skipped"]


@pytest.mark.slow
def test_three_cases_on_local_ray_equal_single_fits(three_cases):
    pytest.importorskip("ray", reason="Ray is optional (pip install 'unsew[ray]')")
    root, cfg, singles = three_cases
    out = root / "ray"
    res = run_batch(root / "cases", out, cfg=cfg, ray=RayCluster("local", {"num_cpus": 2}), progress=False)
    _check_batch(res, out, singles)
