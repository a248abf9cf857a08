"""A lower garment's placement chosen by draping (unsew.grading.placement)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from unsew.errors import SimulationError
from unsew.grading.grade import flat_drape
from unsew.grading.placement import LIFT_TOL, choose_lift, is_lower, lifted, lifted_mesh, top_height
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.base import make_base_pattern


@pytest.fixture(scope="module")
def skirt():
    p = make_base_pattern("skirt")
    return p, mesh_pattern(p, edge_length=0.05)


def _drape(pattern, mesh, body):
    """The flat panels where the mesh places them: a drape that answers the placement exactly."""
    return flat_drape(pattern, mesh)


def test_lifted_moves_every_panel_and_keeps_shapes(skirt):
    p, m = skirt
    q, mq = lifted(p, 0.03), lifted_mesh(m, 0.03)
    for name, panel in p.panels.items():
        np.testing.assert_allclose(q.panels[name].translation - panel.translation, [0.0, 0.03, 0.0])
        np.testing.assert_array_equal(q.panels[name].vertices, panel.vertices)
    np.testing.assert_allclose(mq.uv_placed3d - m.uv_placed3d, np.tile([0.0, 0.03, 0.0], (len(m.uv), 1)))
    np.testing.assert_array_equal(mq.uv, m.uv)
    assert p.panels[p.panel_order[0]].translation[1] != q.panels[p.panel_order[0]].translation[1]  # a copy


def test_top_height_is_the_highest_opening(skirt):
    p, m = skirt
    x = flat_drape(p, m)
    assert top_height(x + [0.0, 0.05, 0.0], m.faces) == pytest.approx(top_height(x, m.faces) + 0.05)
    assert top_height(x, m.faces) > float(np.median(x[:, 1]))


def test_is_lower_only_without_arm_openings():
    c = lambda part: SimpleNamespace(part=part)  # noqa: E731
    assert is_lower([c("torso"), c("leg"), c("leg")])
    assert not is_lower([c("torso"), c("arm"), c("arm"), c("torso")])
    assert not is_lower([])


def test_choose_lift_finds_a_target_placed_higher(skirt):
    p, m = skirt
    x = flat_drape(p, m)
    tx = flat_drape(lifted(p, 0.04), lifted_mesh(m, 0.04))
    q, mq, xq, row = choose_lift(p, m, x, None, _drape, tx, m.faces)
    assert row["lift_m"] == pytest.approx(0.04, abs=1e-3)
    assert row["tried_m"] == pytest.approx([0.0, 0.02, 0.04], abs=1e-3)
    assert row["chamfer_mm"][2] < 1.0 < row["chamfer_mm"][0]
    np.testing.assert_allclose(xq, tx, atol=1e-3)
    name = p.panel_order[0]
    assert q.panels[name].translation[1] - p.panels[name].translation[1] == pytest.approx(0.04, abs=1e-3)


def test_choose_lift_keeps_the_placement_within_tolerance_or_when_lifts_fail(skirt):
    p, m = skirt
    x = flat_drape(p, m)
    tx = x + [0.0, 0.5 * LIFT_TOL, 0.0]
    q, mq, xq, row = choose_lift(p, m, x, None, _drape, tx, m.faces)
    assert row is None and q is p and mq is m and xq is x

    def failing(pattern, mesh, body):
        raise SimulationError("diverged")

    tx = x + [0.0, 0.04, 0.0]
    q, mq, xq, row = choose_lift(p, m, x, None, failing, tx, m.faces)
    assert q is p and xq is x and row["lift_m"] == 0.0 and row["tried_m"] == [0.0]


def test_grade_places_a_skirt_at_a_higher_target(skirt):
    from unsew.body.body import default_body
    from unsew.grading.grade import GradingSettings, grade

    p, m = skirt
    tx = flat_drape(lifted(p, 0.04), lifted_mesh(m, 0.04))
    g = grade(p, default_body(), tx, m.faces, GradingSettings(passes=1), mesh=m, drape_fn=_drape)
    rows = [r for r in g.table if any(e.startswith("placement") for e in r["edits"])]
    assert len(rows) == 1
    name = p.panel_order[0]
    lift = g.pattern.panels[name].translation[1] - p.panels[name].translation[1]
    assert lift > 0.01
    # the returned mesh is placed as the returned pattern (a fresh dress of it starts there)
    fresh = mesh_pattern(g.pattern, edge_length=g.mesh.edge_length)
    assert g.mesh.uv_placed3d[:, 1].max() == pytest.approx(fresh.uv_placed3d[:, 1].max(), abs=1e-9)
    off = grade(
        p, default_body(), tx, m.faces, GradingSettings(passes=1, lift=False), mesh=m, drape_fn=_drape
    )
    assert not any(e.startswith("placement") for r in off.table for e in r["edits"])
    assert off.pattern.panels[name].translation[1] == pytest.approx(p.panels[name].translation[1])


def test_choose_lift_drapes_no_lift_the_room_refuses(skirt):
    """A lift refused room (a fit's time limit) is not draped, nor is any after it; the placement
    stays the input's, and what was left out is said."""
    p, m = skirt
    x = flat_drape(p, m)
    tx = flat_drape(lifted(p, 0.04), lifted_mesh(m, 0.04))
    draped, asked = [], []

    def counting(pattern, mesh, body):
        draped.append(pattern)
        return _drape(pattern, mesh, body)

    def room(what):
        asked.append(what)
        return len(asked) < 2  # the first lift has room, the second not

    q, mq, xq, row = choose_lift(p, m, x, None, counting, tx, m.faces, room)
    assert len(draped) == 1 and len(asked) == 2 and "lift of +4.0 cm not draped" in asked[1]
    assert row["tried_m"] == pytest.approx([0.0, 0.02], abs=1e-3)
    assert row["lift_m"] == pytest.approx(0.02, abs=1e-3)  # the nearer of the two tried


def test_grade_drapes_no_further_pass_nor_lift_without_room(skirt):
    """Grading under a room that refuses everything optional drapes its first pass only, and asks
    with that drape's duration as the estimate."""
    from unsew.body.body import default_body
    from unsew.grading.grade import GradingSettings, grade

    p, m = skirt
    tx = flat_drape(lifted(p, 0.04), lifted_mesh(m, 0.04))
    draped, asked = [], []

    def counting(pattern, mesh, body):
        draped.append(pattern)
        return _drape(pattern, mesh, body)

    def refuse(seconds, what):
        asked.append((seconds, what))
        return False

    def grade_with(room):
        draped.clear()
        settings = GradingSettings(passes=3, room=room)
        x0 = flat_drape(p, m)  # the base's drape given: grading's own drapes are counted
        return grade(
            p, default_body(), tx * [1.1, 1.0, 1.1], m.faces, settings, mesh=m, x_init=x0, drape_fn=counting
        )

    grade_with(None)
    assert len(draped) > 1  # further passes or lifts were worth a drape
    g = grade_with(refuse)
    assert len(draped) == 1
    assert asked and all(s >= 0.0 for s, _ in asked)
    assert "grading: passes 2-3 not draped" in [w for _, w in asked]
    assert any(w.startswith("placement: a lift of") for _, w in asked)
    (kept,) = [e for r in g.table for e in r["edits"] if e.startswith("placement")]
    assert kept.startswith("placement kept") and "drapes +0.0 cm" in kept  # no lift draped
    name = p.panel_order[0]
    assert g.pattern.panels[name].translation[1] == pytest.approx(p.panels[name].translation[1], abs=1e-9)
