"""The side seams graded by girth (unsew.grading.profile; grade(GradingSettings(side_seams="girth")))."""

from __future__ import annotations

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.fit.config import FitConfig, load_config
from unsew.grading.grade import GradingSettings, grade
from unsew.grading.profile import MAX_MOVE, SideSeams, side_seam_moves, side_seam_points, torso_girth
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.base import make_base_pattern
from unsew.pattern.controls import find_control_points
from unsew.pattern.validate import validate_pattern


def cylinder(radius, y0, y1, *, centre=(0.0, 0.0), n_around=48, n_rings=21):
    """An open vertical tube of ``radius`` [m] about ``centre`` (x, z) from height y0 to y1:
    (V, 3) vertices and (F, 3) faces."""
    th = np.linspace(0, 2 * np.pi, n_around, endpoint=False)
    ys = np.linspace(y0, y1, n_rings)
    v = np.array(
        [[centre[0] + radius * np.cos(t), y, centre[1] + radius * np.sin(t)] for y in ys for t in th]
    )
    f = []
    for r in range(n_rings - 1):
        for k in range(n_around):
            a, b = r * n_around + k, r * n_around + (k + 1) % n_around
            f += [[a, b, b + n_around], [a, b + n_around, a + n_around]]
    return v, np.array(f)


def test_torso_girth_goes_round_the_torso_and_leaves_an_arm_out():
    v, f = cylinder(0.15, 0.8, 1.4)
    arm_v, arm_f = cylinder(0.04, 0.8, 1.2, centre=(0.3, 0.0), n_around=16)
    both_v, both_f = np.vstack([v, arm_v]), np.vstack([f, arm_f + len(v)])
    ring = 48 * 2 * 0.15 * np.sin(np.pi / 48)  # the tube's polygon perimeter
    assert torso_girth(v, f, 1.0, np.zeros(2)) == pytest.approx(ring, rel=1e-6)
    assert torso_girth(both_v, both_f, 1.0, np.zeros(2)) == pytest.approx(ring, rel=1e-6)
    # around the arm's own axis the arm counts, and the torso does not
    arm = torso_girth(both_v, both_f, 1.0, np.array([0.3, 0.0]))
    assert arm == pytest.approx(16 * 2 * 0.04 * np.sin(np.pi / 16), rel=1e-6)
    assert torso_girth(v, f, 1.6, np.zeros(2)) is None  # above the garment


def test_side_seam_points_are_the_side_seams_joins_not_hems_armholes_or_darts():
    plain, waisted = (
        make_base_pattern("dress_sleeveless"),
        make_base_pattern("dress_sleeveless", waist_point=True),
    )
    for p, n in ((plain, 4), (waisted, 8)):  # the hips; the hips and the waist, front and back, both sides
        c = find_control_points(p)
        pts = side_seam_points(p, c)
        assert len(pts) == n
        for g, d in pts:
            assert c.panel_names[int(c.panel[g])] in ("front", "back")
            assert np.sign(d[0]) == np.sign(c.positions[g][0]) and abs(d[0]) == pytest.approx(1.0)
    # sleeved, the underarm and the shoulder tip join two seams too: the graded heights leave them
    # out (up to 5 cm under the armpit)
    sleeved = make_base_pattern("dress", waist_point=True)
    c = find_control_points(sleeved)
    assert len(side_seam_points(sleeved, c)) == 8 + 8
    # a skirt's darts: their tips are sewn to their own panel, and are no side-seam points
    skirt = make_base_pattern("skirt_darts")
    c = find_control_points(skirt)
    for g, _ in side_seam_points(skirt, c):
        name = c.panel_names[int(c.panel[g])]
        panel = skirt.panels[name]
        v = int(c.vertex[g])
        for i, e in enumerate(panel.edges):
            if v in (e.start, e.end):
                partners = {s.b.panel for s in skirt.stitches if (s.a.panel, s.a.edge) == (name, i)}
                partners |= {s.a.panel for s in skirt.stitches if (s.b.panel, s.b.edge) == (name, i)}
                assert partners - {name}


def test_the_waisted_dress_with_its_waist_as_a_vertex_keeps_its_outline_heights():
    plain, waisted = make_base_pattern("dress"), make_base_pattern("dress", waist_point=True)
    validate_pattern(waisted)
    mesh_pattern(waisted, edge_length=0.04)
    a, b = np.asarray(plain.panels["front"].vertices), np.asarray(waisted.panels["front"].vertices)
    assert len(b) == len(a) + 2  # one more vertex on each side seam
    assert b[:, 1].max() == pytest.approx(a[:, 1].max()) and b[:, 1].min() == pytest.approx(a[:, 1].min())
    # the other bases take no waist point
    assert (
        make_base_pattern("dress_straight", waist_point=True).panels["front"].vertices.shape
        == make_base_pattern("dress_straight").panels["front"].vertices.shape
    )


def _moves(drape_r, target_r, lo=0.9, hi=1.3):
    p = make_base_pattern("dress_sleeveless", waist_point=True)
    c = find_control_points(p)
    x, f = cylinder(drape_r, 0.6, 1.5)
    tv, tf = cylinder(target_r, 0.6, 1.5)
    # each side-seam point sewn to the tube's vertex at its own height: hips at 1.0 m, waist at 1.2 m
    pts = side_seam_points(p, c)
    mid = np.mean([c.positions[g][1] for g, _ in pts])
    ys = {g: 1.0 if c.positions[g][1] < mid else 1.2 for g, _ in pts}
    control_x = np.zeros(len(c), dtype=np.int64)
    for g, y in ys.items():
        control_x[g] = int(np.argmin(np.abs(x[:, 1] - y) + np.abs(x[:, 0] - drape_r)))
    ctx = SideSeams(tv, tf, lo, hi, np.zeros(2))
    return p, c, pts, side_seam_moves(p, c, control_x, x, f, ctx)


def test_side_seam_moves_share_the_girth_difference_at_each_height():
    p, c, pts, (delta, notes) = _moves(0.15, 0.16)
    per_ring = 48 * 2 * np.sin(np.pi / 48)
    share = per_ring * 0.01 / 4  # front and back, left and right
    assert len(notes) == 2 and all("4 points" in n for n in notes)
    for g, d in pts:
        assert delta[g] == pytest.approx(share * d, abs=1e-9)
    others = np.setdiff1d(np.arange(len(c)), [g for g, _ in pts])
    assert np.all(delta[others] == 0.0)
    # tighter: moved in; far off: each move bounded; outside the graded heights: left alone
    _, _, pts, (delta, _) = _moves(0.16, 0.15)
    assert all(delta[g] @ d < 0 for g, d in pts)
    _, _, pts, (delta, _) = _moves(0.10, 0.20)
    assert all(delta[g] @ d == pytest.approx(MAX_MOVE) for g, d in pts)
    _, c, pts, (delta, notes) = _moves(0.15, 0.16, lo=1.1, hi=1.3)
    assert len(notes) == 1 and sum(bool(np.any(delta[g])) for g, _ in pts) == 4


def test_side_seams_mode_is_checked():
    p = make_base_pattern("dress")
    v, f = cylinder(0.15, 0.6, 1.5)
    with pytest.raises(InputError, match="side_seams"):
        grade(p, None, v, f, GradingSettings(side_seams="curved"))
    assert FitConfig().side_seams == "girth"


def test_side_seams_in_a_config_file(tmp_path):
    (tmp_path / "c.yaml").write_text("side_seams: girth\n", encoding="utf-8")
    assert load_config(tmp_path / "c.yaml").side_seams == "girth"
    (tmp_path / "bad.yaml").write_text("side_seams: curved\n", encoding="utf-8")
    with pytest.raises(InputError, match="side_seams"):
        load_config(tmp_path / "bad.yaml")
