"""The GarmentCode benchmark's kept newton targets: a built case's drape survives a fresh clone, and is
restored only beside the very specification it was draped from."""

import json
from pathlib import Path

import pytest
from benchmarks_loader import load_benchmark


@pytest.fixture(scope="module")
def kept():
    return load_benchmark("gcd/kept")


def _case(root: Path, cid: str, status: str, spec: dict) -> Path:
    d = root / cid
    d.mkdir(parents=True)
    (d / "pattern_gt.json").write_text(json.dumps(spec, indent=1))
    meta = {"units": "m", "simulator": {"name": "newton"}, "checks": {"a": 1}}
    (d / "meta.json").write_text(json.dumps(meta))
    (d / "target.obj").write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n")
    (root / "_status").mkdir(exist_ok=True)
    (root / "_status" / f"{cid}.json").write_text(json.dumps({"case": cid, "status": status}))
    return d


def test_a_kept_target_comes_back_beside_its_own_specification_only(kept, tmp_path):
    spec = {"pattern": {"panels": {"a": {"vertices": [[0, 0], [1, 0], [0, 1]]}}}}
    built = tmp_path / "built"
    _case(built, "gc_s1_000", "built", spec)
    _case(built, "gc_s1_001", "failed", spec)
    store = tmp_path / "store"
    assert kept.keep(built, "gc_s1_000", store)
    assert not kept.keep(built, "gc_s1_001", store)  # a failed drape is not a target
    assert not kept.keep(built, "gc_s1_002", store)  # nor a case never built

    fresh = tmp_path / "fresh" / "gc_s1_000"
    fresh.mkdir(parents=True)
    # the same specification written with other spacing and key order, its numbers off in their
    # last bits (another processor's arithmetic), still matches
    noisy = [[0, 0], [1.0000000000000002, 0], [0, 0.9999999999999999]]
    spec_noisy = {"pattern": {"panels": {"a": {"vertices": noisy}}}}
    (fresh / "pattern_gt.json").write_text(json.dumps(spec_noisy, indent=3, sort_keys=True))
    (fresh / "meta.json").write_text(json.dumps({"units": "m"}))
    rec = kept.restore(tmp_path / "fresh", "gc_s1_000", store)
    assert rec["status"] == "built"
    assert (fresh / "target.obj").read_text() == (built / "gc_s1_000" / "target.obj").read_text()
    meta = json.loads((fresh / "meta.json").read_text())
    assert meta["units"] == "m" and meta["simulator"] == {"name": "newton"}

    other = tmp_path / "other" / "gc_s1_000"
    other.mkdir(parents=True)
    spec["pattern"]["panels"]["a"]["vertices"][1] = [1.0001, 0]  # a micrometre is another design
    (other / "pattern_gt.json").write_text(json.dumps(spec))
    (other / "meta.json").write_text("{}")
    assert kept.restore(tmp_path / "other", "gc_s1_000", store) is None
    assert not (other / "target.obj").exists()


def test_every_kept_target_names_its_specification_and_passed_checks(kept):
    """The committed store: each target's record is a built one with its specification's digest."""
    infos = sorted(kept.KEPT.glob("*.json"))
    assert infos, "no kept targets in benchmarks/gcd/targets"
    for p in infos:
        k = json.loads(p.read_text())
        assert k["record"]["status"] == "built" and len(k["spec_digest"]) == 64
        assert (kept.KEPT / f"{k['case']}.obj.gz").is_file()
        assert k["checks"]["inside_fraction"] < 0.005
