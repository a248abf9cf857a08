"""GarmentCode's sampler, as the gcd benchmark calls it, gives the same specification for the same seed."""

import importlib
import json
import shutil
from pathlib import Path

import pytest

from benchmarks.gcd import build

ROOT = Path(__file__).resolve().parents[2]
SHARED = next((p / "shared" for p in ROOT.parents if (p / "shared" / "garmentcode").is_dir()), None)


def _sampler_missing() -> list[str]:
    missing = []
    for name in ("svgwrite", "svgpathtools", "psutil", "yaml", "scipy"):
        try:
            importlib.import_module(name)
        except Exception:
            missing.append(name)
    return missing


def test_canonical_order_ignores_panel_and_stitch_order(tmp_path):
    """Two files with the same panels and stitches listed in other orders are written identically."""
    panels = {n: {"translation": [i, 0.5, -1.0], "vertices": [[0, 0], [i, 1]]} for i, n in enumerate("cab")}
    stitches = [
        [{"panel": "a", "edge": 1}, {"panel": "b", "edge": 0}],
        [{"panel": "c", "edge": 2}, {"panel": "a", "edge": 0}, "right_wrong"],
        [{"panel": "b", "edge": 3}, {"panel": "c", "edge": 1}],
    ]
    one, two = tmp_path / "one.json", tmp_path / "two.json"
    one.write_text(json.dumps({"pattern": {"panels": panels, "stitches": stitches}}))
    shuffled = {"panels": dict(reversed(list(panels.items()))), "stitches": stitches[::-1]}
    two.write_text(json.dumps({"pattern": shuffled}))
    build.canonical_order(one)
    build.canonical_order(two)
    assert one.read_bytes() == two.read_bytes()
    back = json.loads(one.read_text())["pattern"]
    assert list(back["panels"]) == ["a", "b", "c"] and back["panels"]["c"] == panels["c"]
    assert sorted(map(json.dumps, back["stitches"])) == sorted(map(json.dumps, stitches))


@pytest.mark.skipif(SHARED is None, reason="needs shared/garmentcode beside the checkout")
def test_same_seed_samples_the_same_specification(tmp_path, monkeypatch):
    """Seed 3's first design (20 panels, whose order GarmentCode's own run changes from run to run)
    sampled twice into two folders: identical specification and design parameters."""
    if _sampler_missing():
        pytest.skip(f"GarmentCode's sampler needs {', '.join(_sampler_missing())}")
    monkeypatch.setenv("UNSEW_SHARED", str(SHARED))
    body = tmp_path / "body"
    body.mkdir()
    shutil.copyfile(SHARED / "garmentcode" / "assets" / "bodies" / "mean_all_tpose.yaml", body / "body.yaml")
    runs = [build.sample_seed(3, 1, body, tmp_path / k) for k in ("a", "b")]
    files = [sorted(p.relative_to(r) for p in r.glob("gc_s3_000/*")) for r in runs]
    assert files[0] == files[1] and Path("gc_s3_000/gc_s3_000_specification.json") in files[0]
    for f in files[0]:
        assert (runs[0] / f).read_bytes() == (runs[1] / f).read_bytes(), f
