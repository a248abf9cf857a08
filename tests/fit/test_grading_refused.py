"""A graded drape that lands far from the target is refused: phase two starts from the base."""

from types import SimpleNamespace

import numpy as np
import pytest


ROWS = [{"part": "torso", "edits": ["hem +5.0 cm"], "warnings": []}]


def _sheet(n: int = 12, size: float = 0.5):
    """A flat square sheet (n*n, 3) [m] in the x-y plane and its faces."""
    u = np.linspace(0.0, size, n)
    xx, yy = np.meshgrid(u, u, indexing="ij")
    verts = np.stack([xx.ravel(), yy.ravel(), np.zeros(n * n)], axis=1)
    idx = np.arange(n * n).reshape(n, n)
    a, b, c, d = idx[:-1, :-1].ravel(), idx[1:, :-1].ravel(), idx[1:, 1:].ravel(), idx[:-1, 1:].ravel()
    faces = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)])
    return verts, faces


def _start_with_graded_drape(monkeypatch, lift_m: float):
    """unsew.fit.start.start on a target sheet whose base drape lies 1 cm off it and whose graded
    drape lies ``lift_m`` [m] off it; (Start, log lines, base, graded pattern)."""
    import unsew.fit.start as start_mod
    from unsew.fit.target import Target
    from unsew.sim.drape import DrapeSettings

    tv, tf = _sheet()
    mesh = SimpleNamespace(faces=tf)
    base, graded = SimpleNamespace(name="base"), SimpleNamespace(name="graded")

    def fake_grade(b, body, verts, faces, settings, *, mesh, x_init, drape_fn):
        return SimpleNamespace(note=None, x_draped=tv + [0, 0, lift_m], pattern=graded, mesh=mesh, table=ROWS)

    monkeypatch.setattr(start_mod, "grade", fake_grade)
    monkeypatch.setattr(start_mod, "_base_drape", lambda *a: (mesh, tv + [0, 0, 0.01], 0.0))
    monkeypatch.setattr(start_mod, "_check_contours_compatible", lambda *a: None)
    monkeypatch.setattr(start_mod, "held_anchors", lambda *a: None)
    cfg = SimpleNamespace(grading=True, drape=DrapeSettings(), area=None, side_seams="none", band_gap=None)
    target = Target(tv, tf, [], 0)
    scene = SimpleNamespace(cfg=cfg, target=target, body=None, sdf=None)
    lines = []
    s = start_mod.start(base, scene, "cotton", log=lines.append)
    return s, lines, base, graded


def test_a_graded_drape_far_off_the_target_is_refused(monkeypatch):
    s, lines, base, _ = _start_with_graded_drape(monkeypatch, 0.3)
    assert s.graded is base
    assert np.allclose(s.x[:, 2], 0.01)
    assert any(line.startswith("grading refused") for line in lines)
    # the report's grading notes say the edits were not kept
    assert s.grade_table[0]["edits"] == ["hem +5.0 cm"]
    assert s.grade_table[0]["warnings"][0].startswith("refused, none of these edits kept")
    assert ROWS[0]["warnings"] == []  # grading's own rows are not changed


@pytest.mark.parametrize("lift_m", [0.002, 0.02])
def test_a_graded_drape_near_the_base_is_kept(monkeypatch, lift_m):
    """Closer than the base (2 mm) or farther but within the bound (20 mm against 10): kept."""
    s, lines, _, graded = _start_with_graded_drape(monkeypatch, lift_m)
    assert s.graded is graded
    assert np.allclose(s.x[:, 2], lift_m)
    assert not lines and s.grade_table == ROWS


def test_the_bound_is_both_a_ratio_and_a_margin():
    from unsew.fit.start import graded_astray

    assert graded_astray(37.7, 301.4)  # twice as far and 20 mm more: refused
    assert not graded_astray(6.7, 20.0)  # three times as far, 13 mm more: kept
    assert not graded_astray(30.0, 55.0)  # 25 mm more but under twice: kept
    assert graded_astray(30.0, float("nan"))
    assert not graded_astray(float("nan"), 30.0)
