"""The newton targets kept in the repository, so that a clone has the sample without hours of draping.

    python -m benchmarks gcd keep --out CASES      store every built case's target in targets/
    python -m benchmarks gcd build --no-drape      restores a kept target beside each placed case

A kept target is ``targets/<case>.obj.gz`` (the drape as build wrote it) and ``targets/<case>.json``:
its build record, meta.json's simulator and checks, and the SHA-256 of the specification it was
draped from, its numbers rounded to SPEC_DECIMALS. It is restored only where the freshly sampled
``pattern_gt.json`` has that digest, so a changed sampler, sizing or body never pairs a design with
another design's drape, while the last bits that another processor's arithmetic gives the sampler's
numbers do not count (GarmentCode's programs size with numpy's trigonometry, whose last bit
differs between CPUs).
"""

from __future__ import annotations

import gzip
import hashlib
import json
import shutil
from pathlib import Path

HERE = Path(__file__).resolve().parent
KEPT = HERE / "targets"


#: Decimals a specification's numbers (cm) keep in its digest: 10 nm, far above a last bit's noise.
SPEC_DECIMALS = 6


def _rounded(value):
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return round(float(value), SPEC_DECIMALS) + 0.0  # 1 and 1.0, -0.0 and 0.0 alike
    if isinstance(value, list):
        return [_rounded(v) for v in value]
    if isinstance(value, dict):
        return {k: _rounded(v) for k, v in value.items()}
    return value


def spec_digest(spec_path: Path) -> str:
    """SHA-256 of a specification's content, its numbers rounded to SPEC_DECIMALS (JSON
    re-serialised: key order and spacing don't count)."""
    spec = _rounded(json.loads(Path(spec_path).read_text()))
    return hashlib.sha256(json.dumps(spec, sort_keys=True).encode()).hexdigest()


def keep(out: Path, cid: str, store: Path = KEPT) -> bool:
    """Store case ``cid``'s target from the build folder ``out``; False where it is not built."""
    d, st = Path(out) / cid, Path(out) / "_status" / f"{cid}.json"
    if not (d / "target.obj").is_file() or not st.is_file():
        return False
    rec = json.loads(st.read_text())
    if rec.get("status") != "built":
        return False
    meta = json.loads((d / "meta.json").read_text())
    store.mkdir(parents=True, exist_ok=True)
    with open(d / "target.obj", "rb") as src, gzip.GzipFile(store / f"{cid}.obj.gz", "wb", mtime=0) as dst:
        shutil.copyfileobj(src, dst)
    kept = {
        "case": cid,
        "spec_digest": spec_digest(d / "pattern_gt.json"),
        "record": rec,
        "simulator": meta.get("simulator"),
        "checks": meta.get("checks"),
    }
    (store / f"{cid}.json").write_text(json.dumps(kept, indent=1) + "\n")
    return True


def restore(out: Path, cid: str, store: Path = KEPT) -> dict | None:
    """Put the kept target of ``cid`` into the placed case folder ``out/cid`` (target.obj and
    meta.json's simulator and checks); returns its build record, or None where none is kept or
    the kept one was draped from another specification than the folder's."""
    d, info = Path(out) / cid, store / f"{cid}.json"
    if not info.is_file() or not (d / "pattern_gt.json").is_file():
        return None
    kept = json.loads(info.read_text())
    if kept.get("spec_digest") != spec_digest(d / "pattern_gt.json"):
        return None
    with gzip.open(store / f"{cid}.obj.gz", "rb") as src, open(d / ".target.obj.tmp", "wb") as dst:
        shutil.copyfileobj(src, dst)
    meta = json.loads((d / "meta.json").read_text())
    meta |= {"simulator": kept["simulator"], "checks": kept["checks"]}
    (d / "meta.json").write_text(json.dumps(meta, indent=1))
    (d / ".target.obj.tmp").replace(d / "target.obj")
    return dict(kept["record"], restored_from="benchmarks/gcd/targets")
