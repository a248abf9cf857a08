"""Algorithm 1: inter-panel pairs, intra-panel mirrors, K, and the rebuild of all control points."""

from __future__ import annotations

import numpy as np
import pytest
from helpers import assert_close
from meshing.handmade_patterns import (
    curved_panel,
    loop_edges,
    mini_shirt,
    nonconvex_panel,
    pentagon,
    two_squares,
)

from unsew.pattern.controls import find_control_points
from unsew.pattern.model import Panel, Pattern
from unsew.pattern.symmetry import Symmetry, detect_symmetry, procrustes
from unsew.tolerances import REBUILD_ATOL


def _rot(t):
    return np.array([[np.cos(t), -np.sin(t)], [np.sin(t), np.cos(t)]])


def test_procrustes_recovers_rotation_and_reflection():
    rng = np.random.default_rng(1)
    x = rng.normal(size=(7, 2))
    x -= x.mean(0)
    r = _rot(0.7)
    R, err = procrustes(x, x @ r.T, det=1)
    assert_close(R, r, atol=1e-12)
    assert err < 1e-12
    f = r @ np.diag([1.0, -1.0])
    R, err = procrustes(x, x @ f.T, det=-1)
    assert_close(R, f, atol=1e-12)
    assert err < 1e-12
    _, err = procrustes(x, x @ f.T, det=1)  # a reflection is no rotation
    assert err > 0.1


def test_pentagon_mirror_with_apex_on_axis():
    s = detect_symmetry(pentagon())
    assert s.pairs == [] and len(s.mirrors) == 1
    m = s.mirrors[0]
    assert abs(abs(m.direction[1]) - 1) < 1e-12  # vertical axis
    assert_close(m.point[0], 0.2, atol=1e-12)
    assert m.on_axis.tolist() == [3]
    assert sorted(map(tuple, m.pairs.tolist())) == [(0, 1), (2, 4)]
    assert s.n_k == 3 and s.k_indices.tolist() == [0, 2, 3]


def test_asymmetric_panel_has_no_mirror():
    s = detect_symmetry(nonconvex_panel())
    assert s.mirrors == [] and s.n_k == s.n_control


def test_mini_shirt_sleeves_pair_and_torso_mirrors():
    s = detect_symmetry(mini_shirt())
    # front and back have the same corners but different necklines: not a pair
    assert [(p.source, p.target, p.mirrored) for p in s.pairs] == [("lsleeve", "rsleeve", True)]
    assert {m.panel for m in s.mirrors} == {"front", "back", "lsleeve"}
    assert s.n_k <= s.n_control // 2


def test_rotated_copy_is_paired_without_reflection():
    v = nonconvex_panel().panels["L"].vertices.copy()
    v[4, 1] = 0.6  # an L with unequal arms: no mirror symmetry of its own
    w = (v - v.mean(0)) @ _rot(1.1).T + [1.0, 2.0]
    pat = Pattern(
        "two", {"H": Panel("H", v, loop_edges(6)), "G": Panel("G", np.roll(w, 2, axis=0), loop_edges(6))}
    )
    s = detect_symmetry(pat)
    assert len(s.pairs) == 1 and not s.pairs[0].mirrored
    assert_close(s.pairs[0].matrix, _rot(1.1), atol=1e-9)
    assert_close(s.rebuild(s.k0()), s.c0, atol=REBUILD_ATOL)


def test_scaled_copy_is_not_a_pair():
    v = nonconvex_panel().panels["L"].vertices
    pat = Pattern("two", {"A": Panel("A", v, loop_edges(6)), "B": Panel("B", v * 1.1, loop_edges(6))})
    assert detect_symmetry(pat).pairs == []


@pytest.mark.parametrize("make", [two_squares, curved_panel, pentagon, nonconvex_panel, mini_shirt])
def test_rebuild_is_exact_and_symmetric(make):
    pat = make()
    s = detect_symmetry(pat)
    L, b = s.rebuild_map()
    assert L.shape == (2 * s.n_control, 2 * s.n_k)
    assert_close(s.rebuild(s.k0()), s.c0, atol=REBUILD_ATOL, what="rebuild at K0: ")
    # move K at random: the symmetries hold for the rebuilt points
    rng = np.random.default_rng(0)
    K = s.k0() + rng.normal(scale=0.02, size=(s.n_k, 2))
    C = s.rebuild(K)
    assert_close(
        C[s.k_indices][[i for i, g in enumerate(s.k_indices) if not _on_axis(s, g)]],
        K[[i for i, g in enumerate(s.k_indices) if not _on_axis(s, g)]],
        atol=1e-12,
    )
    for m in s.mirrors:
        o = s.offsets[s.panel_names.index(m.panel)]
        d = m.direction
        H = 2 * np.outer(d, d) - np.eye(2)
        for i, j in m.pairs:
            assert_close(C[o + j] - m.point, (C[o + i] - m.point) @ H.T, atol=1e-12, what="mirror: ")
        for j in m.on_axis:
            rel = C[o + j] - m.point
            assert abs(rel[0] * d[1] - rel[1] * d[0]) < 1e-12
    for p in s.pairs:
        ps, pt = s.panel_names.index(p.source), s.panel_names.index(p.target)
        cs = C[s.offsets[ps] : s.offsets[ps + 1]]
        ct = C[s.offsets[pt] : s.offsets[pt + 1]]
        # the target is the source moved rigidly: pairwise distances agree
        ds = np.linalg.norm(cs[p.perm][:, None] - cs[p.perm][None], axis=-1)
        dt = np.linalg.norm(ct[:, None] - ct[None], axis=-1)
        assert_close(dt, ds, atol=1e-12, what="pair: ")


def _on_axis(s, g):
    for m in s.mirrors:
        o = s.offsets[s.panel_names.index(m.panel)]
        if g - o in m.on_axis.tolist() and s.panel_names.index(m.panel) == _panel_of(s, g):
            return True
    return False


def _panel_of(s, g):
    return int(np.searchsorted(s.offsets, g, side="right") - 1)


def test_near_symmetric_rebuild_keeps_small_asymmetry():
    pat = pentagon()
    pat.panels["H"].vertices[3, 0] += 0.002  # apex 2 mm off the axis: still symmetric within tol
    s = detect_symmetry(pat)
    assert len(s.mirrors) == 1
    assert_close(s.rebuild(s.k0()), s.c0, atol=REBUILD_ATOL)
    pat.panels["H"].vertices[3, 0] += 0.05  # 5 cm off: not symmetric
    assert detect_symmetry(pat).mirrors == []


def test_dict_round_trip():
    s = detect_symmetry(mini_shirt())
    d = s.to_dict()
    import json

    s2 = Symmetry.from_dict(json.loads(json.dumps(d)))
    assert s2.to_dict() == d
    L1, b1 = s.rebuild_map()
    L2, b2 = s2.rebuild_map()
    assert_close(L2, L1, atol=0)
    assert_close(b2, b1, atol=0)


def test_controls_argument_is_used():
    pat = pentagon()
    c = find_control_points(pat)
    assert detect_symmetry(pat, controls=c).n_control == len(c)


# --- base patterns (unsew.pattern.base) ---


def test_tshirt_sleeves_pair_and_torso_panels_mirror():
    from unsew.pattern.base import make_base_pattern

    pat = make_base_pattern("tshirt")
    s = detect_symmetry(pat)
    pairs = {frozenset((p.source, p.target)) for p in s.pairs}
    sleeves = [n for n in pat.panel_order if "sleeve" in n]
    assert len(sleeves) == 2 and frozenset(sleeves) in pairs
    assert all(p.mirrored for p in s.pairs if frozenset((p.source, p.target)) == frozenset(sleeves))
    mirrored = {m.panel for m in s.mirrors}
    for torso in ("front", "back"):
        assert torso in mirrored, f"{torso} panel not found mirror-symmetric"
        m = next(m for m in s.mirrors if m.panel == torso)
        assert abs(abs(m.direction[1]) - 1.0) < 1e-9  # the vertical centre line
    assert 2 * s.n_k <= s.n_control
    assert_close(s.rebuild(s.k0()), s.c0, atol=REBUILD_ATOL)


@pytest.mark.parametrize("garment", ["dress", "pants", "shorts", "skirt"])
def test_other_base_patterns_rebuild_exactly(garment):
    from unsew.pattern.base import make_base_pattern

    s = detect_symmetry(make_base_pattern(garment))
    assert s.pairs or s.mirrors
    assert 2 * s.n_k <= s.n_control
    assert_close(s.rebuild(s.k0()), s.c0, atol=REBUILD_ATOL)


def test_cli_symmetry(tmp_path):
    import json
    import subprocess
    import sys

    from unsew.io.garmentcode import save_pattern
    from unsew.pattern.base import make_base_pattern

    path = tmp_path / "t.json"
    save_pattern(make_base_pattern("tshirt"), path)
    r = subprocess.run(
        [sys.executable, "-m", "unsew", "pattern", "symmetry", str(path), "--json"],
        capture_output=True,
        text=True,
    )
    assert r.returncode == 0, r.stderr
    rep = json.loads(r.stdout)
    assert 2 * rep["K"] <= rep["control_points"]
    assert {m["panel"] for m in rep["mirror_axes"]} >= {"front", "back"}
    r = subprocess.run(
        [sys.executable, "-m", "unsew", "pattern", "symmetry", str(path)], capture_output=True, text=True
    )
    assert r.returncode == 0 and "effective K" in r.stdout
    r = subprocess.run(
        [sys.executable, "-m", "unsew", "pattern", "symmetry", str(tmp_path / "missing.json")],
        capture_output=True,
        text=True,
    )
    assert r.returncode != 0 and "Traceback" not in r.stderr and len(r.stderr.strip().splitlines()) == 1


def test_paired_panel_follows_the_source_translation():
    """A rigid copy moves with its source: translating the source's K by t translates the copy by
    M t (a copy pinned at its own centroid would be shifted against its source, and placed and
    sewn at another height)."""
    v = nonconvex_panel().panels["L"].vertices.copy()
    v[4, 1] = 0.6
    w = (v - v.mean(0)) @ _rot(1.1).T + [1.0, 2.0]
    pat = Pattern(
        "two", {"H": Panel("H", v, loop_edges(6)), "G": Panel("G", np.roll(w, 2, axis=0), loop_edges(6))}
    )
    s = detect_symmetry(pat)
    (pr,) = s.pairs
    t = np.array([0.03, -0.05])
    src = [
        i
        for i, g in enumerate(s.k_indices)
        if s.panel_names[int(np.searchsorted(s.offsets, g, side="right") - 1)] == pr.source
    ]
    K = s.k0()
    K[src] += t
    C = s.rebuild(K)
    pt = s.panel_names.index(pr.target)
    moved = C[s.offsets[pt] : s.offsets[pt + 1]] - s.c0[s.offsets[pt] : s.offsets[pt + 1]]
    assert_close(moved, np.tile(pr.matrix @ t, (len(moved), 1)), atol=1e-12)
