"""The material choice checked by a drape from scratch (unsew.fit.material._checked): phase two
starts from the cotton-graded start when the chosen fabric's drape from scratch lies clearly
farther than its, else the choice stands as made; the table says both (fast: the dress is faked)."""

from types import SimpleNamespace

import numpy as np
import torch

from unsew.fit import material as mat_mod
from unsew.fit.config import load_config
from unsew.fit.scene import Scene
from unsew.fit.progress import Progress
from unsew.fit.start import Start
from unsew.sim.material import get_material


def _start(name, x0):
    mesh = SimpleNamespace(faces=np.zeros((1, 3), dtype=np.int64), uv=None, faces_uv=None)
    return Start(
        base=None,
        graded=f"pattern graded in {name}",
        mesh=mesh,
        x=np.full((3, 3), x0),
        grade_table=[],
        x_base=np.zeros((3, 3)),
        mesh_base=mesh,
        material=get_material(name),
    )


def _run(monkeypatch, fresh_value, failed="", settled_failed=""):
    """The check with the chosen fabric's drape from scratch at ``fresh_value`` (a target whose
    distance is the drape's first coordinate; its check failing with ``failed`` when given)
    against the cotton start at 7.0; the chosen start's settled drape failing the result's check
    with ``settled_failed`` when given."""
    dressed = []
    monkeypatch.setattr(
        mat_mod, "check_dressed", lambda d, body: SimpleNamespace(ok=not failed, reason=failed)
    )
    monkeypatch.setattr(
        mat_mod,
        "check_drape",
        lambda x, **kw: SimpleNamespace(ok=not settled_failed, reason=settled_failed),
    )
    monkeypatch.setattr(mat_mod, "held_anchors", lambda *a: "anchors of the drape from scratch")

    def fake_dress(pattern, body, **kw):
        dressed.append((pattern, kw["material"]))
        return SimpleNamespace(x=torch.full((3, 3), fresh_value, dtype=torch.float64))

    monkeypatch.setattr(mat_mod, "dress", fake_dress)
    target = SimpleNamespace(distance_mm=lambda x, faces: float(np.asarray(x)[0, 0]))
    first, chosen = _start("cotton", 7.0), _start("polyester", 4.0)  # settled: 4.0 mm
    table = [
        {
            "material": "polyester (stretch x0.5, bending x1)",
            "chamfer_mm": 4.0,
            "pattern": "graded in polyester",
        }
    ]
    cfg = load_config(None)
    lines = []
    s, rows = mat_mod._checked(
        first, chosen, table, Scene(None, target, None, cfg, progress=Progress(False), log=lines.append)
    )
    assert dressed == [("pattern graded in polyester", chosen.material)]
    return first, chosen, s, rows, lines


def test_a_settled_choice_that_does_not_dress_as_close_gives_way_to_cotton(monkeypatch):
    first, _, s, rows, lines = _run(monkeypatch, 11.0)
    assert s is first
    assert rows[0] == {
        "material": "cotton",
        "chamfer_mm": 7.0,
        "pattern": "graded in cotton, dressed from scratch",
    }
    assert rows[1]["chamfer_mm"] == 11.0 and rows[1]["pattern"] == "graded in polyester, dressed from scratch"
    assert rows[2]["chamfer_mm"] == 4.0  # the settled row stays in the table
    assert lines and lines[0].endswith("phase two starts from cotton")


def test_a_choice_that_dresses_about_as_close_stands_as_made(monkeypatch):
    for fresh in (5.0, 7.6):  # closer than cotton's 7.0, or farther by less than 0.7 mm (10 %)
        _, chosen, s, rows, _ = _run(monkeypatch, fresh)
        assert s is chosen  # its settled drape, as the choice made it
        assert rows[0]["material"].startswith("polyester") and rows[0]["chamfer_mm"] == fresh
    first, _, s, _, _ = _run(monkeypatch, 7.8)  # farther by more than the margin
    assert s is first


def test_a_choice_whose_drape_from_scratch_fails_its_check_gives_way_to_cotton(monkeypatch):
    """An exploded drape can lie close to the target (a neckline torn round the neck): its
    distance decides nothing."""
    torn = "exploded: an edge is stretched to 6.2 times its pattern length (bound 3)"
    first, _, s, rows, lines = _run(monkeypatch, 5.0, failed=torn)
    assert s is first and rows[0]["material"] == "cotton"
    assert rows[1]["chamfer_mm"] == 5.0 and rows[1]["pattern"].endswith(
        f"dressed from scratch (failed: {torn})"
    )
    assert "failed (exploded" in lines[0] and lines[0].endswith("phase two starts from cotton")


def test_a_settled_drape_that_fails_the_results_check_gives_way_to_its_drape_from_scratch(monkeypatch):
    """The fabric stands, but phase two (and a fit stopped before its first step) starts from a
    drape that passes the check the result must pass, not from a settled one with a torn edge."""
    torn = "exploded: an edge is stretched to 4.2 times its pattern length (bound 3)"
    _, chosen, s, rows, lines = _run(monkeypatch, 5.0, settled_failed=torn)
    assert s.material is chosen.material and s.graded == chosen.graded
    assert np.all(s.x == 5.0) and s.anchors == "anchors of the drape from scratch"
    assert rows[0]["material"].startswith("polyester")
    assert any(torn in line and line.endswith("its drape from scratch kept") for line in lines)


def test_a_material_choice_past_the_time_limit_is_made_only_to_mend_an_unsound_graded_drape(monkeypatch):
    """With no time left for the fabrics' drapes, the cotton-graded start is kept and the cut
    said when its drape passes a result's checks; when it fails them (an exploded graded drape:
    the fit would end on it), the fabrics are draped past the limit until one drapes soundly,
    and the limit stops the rest."""
    from unsew.fit.budget import TimeBudget

    first = _start("cotton", 7.0).replace(dress_s=100.0)
    scene = Scene(
        None,
        SimpleNamespace(distance_mm=lambda x, faces: 9.0),
        None,
        load_config(**{"material.start": "auto"}),
        progress=Progress(False),
        log=lambda s: None,
    )
    names = ["silk", "wool", "jersey", "cotton", "polyester", "denim"]
    draped = []

    def fake_choose(_names, dress_in, objective, *, progress=None, room=None):
        for k, name in enumerate(names):
            if k and not room(1.0):
                break
            draped.append(name)
            objective(np.full((3, 3), float(k)))  # fabric k's drape
        return first.material, first.x, [{"material": "cotton", "chamfer_mm": 7.0}]

    torn = "exploded: an edge is stretched to 5.4 times its pattern length"
    monkeypatch.setattr(mat_mod, "choose_material", fake_choose)
    monkeypatch.setattr(mat_mod, "_dresser", lambda s, sc: None)
    monkeypatch.setattr(mat_mod, "_checked", lambda first, cur, table, scene: (cur, table))
    for graded_sound, sound_fabric in ((True, None), (False, 2), (False, None)):

        def verdict(x, graded_sound=graded_sound, sound_fabric=sound_fabric, **k):
            graded = bool(np.all(x == 7.0))
            ok = graded_sound if graded else (sound_fabric is not None and x[0, 0] == sound_fabric)
            return SimpleNamespace(ok=ok, reason="" if ok else torn)

        monkeypatch.setattr(mat_mod, "check_drape", verdict)
        budget = TimeBudget(540.0, log=lambda s: None, clock=iter([0.0] + [530.0] * 50).__next__)
        draped.clear()
        choice = mat_mod.choose_start(first, scene, budget=budget)
        if graded_sound:
            assert choice.start is first and choice.table == [] and not draped
            assert budget.cuts == ["material choice: cotton kept (draping the fabrics would overrun)"]
        elif sound_fabric is not None:  # jersey mends it: the three after it are not draped
            assert draped == names[: sound_fabric + 1]
            assert "material choice: the other fabrics not draped (they would overrun)" in budget.cuts
        else:  # none mends it: every fabric draped, past the limit
            assert draped == names and not any("fabrics" in c for c in budget.cuts)
