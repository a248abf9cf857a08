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


def test_a_number_across_a_rounding_edge_is_the_same_specification(kept, tmp_path):
    """Two processors' numbers 2e-8 cm apart on either side of the digest's sixth decimal's
    rounding edge: the digests differ, the kept specification says they are one design."""
    edge = 12.3456785  # rounds to 12.345678 or 12.345679 as its last bits fall
    spec = {"pattern": {"panels": {"a": {"vertices": [[0, 0], [edge - 1e-8, 0], [0, 1]]}}}}
    built = tmp_path / "built"
    _case(built, "gc_s1_000", "built", spec)
    store = tmp_path / "store"
    assert kept.keep(built, "gc_s1_000", store)

    fresh = tmp_path / "fresh" / "gc_s1_000"
    fresh.mkdir(parents=True)
    spec["pattern"]["panels"]["a"]["vertices"][1][0] = edge + 1e-8
    (fresh / "pattern_gt.json").write_text(json.dumps(spec))
    (fresh / "meta.json").write_text("{}")
    first = kept.spec_digest(built / "gc_s1_000" / "pattern_gt.json")
    assert kept.spec_digest(fresh / "pattern_gt.json") != first
    assert kept.restore(tmp_path / "fresh", "gc_s1_000", store)["status"] == "built"

    # without the kept specification the digest is all there is to go by
    (store / "gc_s1_000.spec.json.gz").unlink()
    (fresh / "target.obj").unlink()
    assert kept.restore(tmp_path / "fresh", "gc_s1_000", store) is None
    assert not (fresh / "target.obj").exists()


def test_specifications_differ_in_structure_text_or_a_micrometre(kept):
    a = {"panels": {"a": {"vertices": [[0, 0], [1, 0]], "name": "front"}}, "flag": True}
    assert kept.same_spec(a, json.loads(json.dumps(a)))
    reordered = {"flag": True, "panels": {"a": {"name": "front", "vertices": [[0.0, 0], [1, 0.0]]}}}
    assert kept.same_spec(a, reordered)
    assert not kept.same_spec(a, {**a, "flag": 1})
    assert not kept.same_spec(a, {**a, "panels": {"a": {"vertices": [[0, 0], [1, 0]], "name": "back"}}})
    assert not kept.same_spec(a, {**a, "panels": {"a": {"vertices": [[0, 0]], "name": "front"}}})
    assert not kept.same_spec(a, {**a, "panels": {"a": {"vertices": [[0, 0], [1.0001, 0]], "name": "front"}}})
    assert not kept.same_spec(a, {**a, "extra": 0})


def test_every_kept_target_names_its_specification_and_passed_checks(kept):
    """The committed store: each target's record is a built one with its specification's digest."""
    infos = sorted(kept.KEPT.glob("*.json"))
    assert infos, "no kept targets in benchmarks/gcd/targets"
    for p in infos:
        k = json.loads(p.read_text())
        assert k["record"]["status"] == "built" and len(k["spec_digest"]) == 64
        assert (kept.KEPT / f"{k['case']}.obj.gz").is_file()
        assert k["checks"]["inside_fraction"] < 0.005


def test_a_target_moves_to_another_mesh_of_its_pattern_through_pattern_coordinates(kept, tmp_path):
    """A drape of one mesh of a pattern, carried to another mesh of it (as Triangle refines a
    panel otherwise on another CPU), puts each new vertex where the drape's surface is."""
    import numpy as np
    from meshing.handmade_patterns import nonconvex_panel

    from unsew.meshing import mesh_pattern

    pat = nonconvex_panel()  # one panel: a seam's vertex would have two places in this test's roll
    old, new = mesh_pattern(pat, edge_length=0.03), mesh_pattern(pat, edge_length=0.022)
    r = 0.2  # the panel rolled round a cylinder of this radius [m]

    def rolled(mesh):
        x = np.zeros((mesh.n_x, 3))
        u, v = mesh.uv[:, 0], mesh.uv[:, 1]
        x[mesh.x_of_u] = np.c_[r * np.sin(u / r), v, r * np.cos(u / r)]
        return x

    kept.save_rest(tmp_path / "old.rest.npz", old)
    with np.load(tmp_path / "old.rest.npz") as z:
        rest = {k: z[k] for k in z.files}
    moved = kept.moved_to_mesh(rolled(old), rest, new)
    err = np.linalg.norm(moved - rolled(new), axis=1)
    # the longest rest edge (4 cm here) sags 1.0 mm under a 20 cm radius: interpolation within that
    assert err.max() < 1.3e-3 and np.median(err) < 3e-4
    # the identity where the mesh is the same
    assert np.abs(kept.moved_to_mesh(rolled(old), rest, old) - rolled(old)).max() < 1e-12
