"""benchmarks/bench_damaged.py's damage(): the damaged copy has the promised faults, and loading
cleans it back to the clean triangles (fast; no fit)."""

import warnings

import numpy as np

from benchmarks_loader import load_benchmark


def _module():
    return load_benchmark("bench_damaged")


def test_damage_is_cleaned_back_to_the_clean_triangles(tmp_path):
    mod = _module()  # puts benchmarks/ on sys.path
    import _meshes

    from unsew.geometry.topology import unique_edges
    from unsew.io.mesh import read_garment, write_obj

    v, f = _meshes.tube_with_verts(2000)
    vd, fd = mod.damage(v, f, duplicates=50, seed=1)
    assert len(fd) == len(f) + 50 + 3 + 1 and len(vd) == len(v) + 3
    assert (unique_edges(fd)[2] == 3).sum() >= 1  # the fin's edge: three faces
    write_obj(tmp_path / "d.obj", vd, fd)
    write_obj(tmp_path / "c.obj", v, f)
    vc, fc, _ = read_garment(tmp_path / "c.obj")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        vb, fb, rep = read_garment(tmp_path / "d.obj")
    assert (rep.duplicate_faces, rep.fin_faces, rep.degenerate_faces) == (50, 3, 1)
    assert np.array_equal(vb, vc)
    key = lambda a: np.sort(np.sort(a, axis=1), axis=0)  # noqa: E731
    assert np.array_equal(key(fb), key(fc))
