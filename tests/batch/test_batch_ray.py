"""unsew batch on a local Ray instance, with the stand-in fit: the same outcomes as the local pool.
Skipped when Ray (the optional extra unsew[ray]) is not installed."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

ray = pytest.importorskip(
    "ray", reason="Ray is optional (pip install 'unsew[ray]'); the Ray backend is untested here"
)

import batch.fakes as fakes  # noqa: E402
from unsew.batch import run_batch  # noqa: E402
from unsew.errors import InputError  # noqa: E402
from unsew.fit.config import load_config  # noqa: E402

CFG = load_config(optimizer={"iterations": 3}, output={"report": False})


def test_unreachable_cluster_is_one_line_and_writes_nothing(tmp_path, monkeypatch):
    if ray.is_initialized():
        pytest.skip("a Ray instance is already running in this process")
    if Path("/tmp/ray/ray_current_cluster").exists():
        pytest.skip("a Ray cluster is running on this machine ('auto' would reach it)")
    monkeypatch.delenv("RAY_ADDRESS", raising=False)
    fakes.make_fake_case(tmp_path / "cases" / "a")
    with pytest.raises(InputError, match="cannot start or reach Ray at 'auto'"):  # no cluster is running
        run_batch(tmp_path / "cases", tmp_path / "out", ray="auto", fit_fn=fakes.fake_fit, progress=False)
    assert not (tmp_path / "out").exists()


@pytest.fixture(scope="module")
def ray_local():
    # Ray's workers do not see tests/ on their path: ship the stand-in fit's module by value.
    from ray import cloudpickle

    cloudpickle.register_pickle_by_value(fakes)
    ray.init(
        num_cpus=2,
        include_dashboard=False,
        log_to_driver=False,
        runtime_env={"env_vars": {"OMP_WAIT_POLICY": "PASSIVE"}},
    )
    yield
    ray.shutdown()
    cloudpickle.unregister_pickle_by_value(fakes)


def test_ray_batch_matches_local_pool(tmp_path, ray_local):
    cases = tmp_path / "cases"
    for i in range(3):
        fakes.make_fake_case(cases / f"case{i}", value=float(i + 1))
    fakes.make_fake_case(cases / "broken", garment="sweater")
    a = run_batch(cases, tmp_path / "local", cfg=CFG, workers=2, fit_fn=fakes.fake_fit, progress=False)
    b = run_batch(cases, tmp_path / "ray", cfg=CFG, ray="local", fit_fn=fakes.fake_fit, progress=False)
    assert [(r.name, r.status, r.reason) for r in a.records] == [
        (r.name, r.status, r.reason) for r in b.records
    ]
    for i in range(3):
        ma = json.loads((tmp_path / "local" / f"case{i}" / "metrics.json").read_text())
        mb = json.loads((tmp_path / "ray" / f"case{i}" / "metrics.json").read_text())
        assert ma == mb
    assert (tmp_path / "ray" / "summary.csv").is_file() and (tmp_path / "ray" / "index.html").is_file()
    c = run_batch(cases, tmp_path / "ray", cfg=CFG, ray="local", fit_fn=fakes.fake_fit, progress=False)
    assert {r.name: r.status for r in c.records} == {
        "broken": "failed",
        "case0": "skipped",
        "case1": "skipped",
        "case2": "skipped",
    }
