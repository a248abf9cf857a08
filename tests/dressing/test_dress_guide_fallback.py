"""dress() keeps the sounder of the guided and the straight sewing when the guided one is unsound,
of that and a drape from the pattern's own placement when it is still unsound, and of that and
the same fallbacks with the body repelling the mesh edges too when it is unsound still."""

import dataclasses
from types import SimpleNamespace

import numpy as np

import unsew.dress as dress_mod
from unsew.body.body import default_body

#: a pattern with no labelled hanging edge (dress() holds nothing)
_UNLABELLED = SimpleNamespace(panels={}, stitches=[])


def _fake(ok: bool, stretch: float, guided: int):
    """A stand-in drape: one right triangle, its 1 m leg along x drawn out to ``stretch`` m."""
    import torch

    tri = np.array([[0, 1, 2]])
    mesh = SimpleNamespace(faces=tri, faces_uv=tri, uv=np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]))
    x = torch.tensor([[0.0, 0.0, 0.0], [stretch, 0.0, 0.0], [0.0, 1.0, 0.0]], dtype=torch.float64)
    return SimpleNamespace(x=x, mesh=mesh, ok=ok, stats={"guided_seams": guided})


def _run(monkeypatch, guided_result, given_result=None, retried=None, **changes):
    """dress() with its drapes stood in for: the guided sewing gives ``guided_result``, the
    straight one a sound drape (or ``retried(job)`` gives both), the pattern's own placement
    ``given_result`` (an explosion when None). Returns (drape, the calls in order: seam_guide or
    "given", as ("edges", call) with the edges repelled)."""
    calls = []
    given = given_result or _fake(False, 9.0, 0)

    def note(job, call):
        calls.append(("edges", call) if job.settings.edge_contact else call)

    def fake_dress(job):
        note(job, job.settings.seam_guide)
        if retried is not None:
            return retried(job)
        return guided_result if job.settings.seam_guide else _fake(True, 1.1, 0)

    def fake_once(job, force_meet, given=False):
        note(job, "given")
        return given_drape

    given_drape = given
    monkeypatch.setattr(dress_mod, "_dress_retried", fake_dress)
    monkeypatch.setattr(dress_mod, "_dress_once", fake_once)
    monkeypatch.setattr(dress_mod, "check_dressed", lambda d, body=None: SimpleNamespace(ok=d.ok))
    monkeypatch.setattr(dress_mod, "mesh_pattern", lambda *a, **k: SimpleNamespace(uv=np.zeros((2, 2))))
    settings = dataclasses.replace(dress_mod.DRESS_SETTINGS, seam_guide=True, **changes)
    out = dress_mod.dress(_UNLABELLED, default_body(), sdf=object(), settings=settings)
    return out, calls


def test_an_exploded_guided_drape_gives_way_to_a_sound_straight_one(monkeypatch):
    out, calls = _run(monkeypatch, _fake(False, 4.0, 3))
    assert calls == [True, False]  # the straight drape is sound: the pattern's own start is not tried
    assert out.ok and out.stats["guide_dropped"] == 3


def test_a_sound_guided_drape_is_kept_without_a_second_drape(monkeypatch):
    guided = _fake(True, 1.2, 3)
    out, calls = _run(monkeypatch, guided)
    assert calls == [True] and out is guided


def test_a_worse_straight_drape_does_not_replace_the_guided_one(monkeypatch):
    guided = _fake(True, 1.6, 3)  # sound checks, an edge over 1.5: the straight one is tried

    def worse(job):
        return guided if job.settings.seam_guide else _fake(False, 1.2, 0)

    out, calls = _run(monkeypatch, guided, retried=worse)
    assert out is guided and "guide_dropped" not in out.stats and "edge_contact" not in out.stats
    # still over 1.5: the pattern's own start tried, then all three with the edges repelled, none kept
    assert calls == [True, False, "given", ("edges", True), ("edges", False), ("edges", "given")]


def test_a_drape_unsound_after_every_fallback_gives_way_to_one_with_the_edges_repelled(monkeypatch):
    """Guided, straight and the pattern's own start all unsound (cloth caught across a limb):
    dressed again with the body repelling the edges' midpoints, sound, and that is kept."""
    edged = _fake(True, 1.3, 3)

    def caught(job):
        return edged if job.settings.edge_contact else _fake(True, 1.8, 3)

    out, calls = _run(monkeypatch, None, given_result=_fake(False, 5.0, 0), retried=caught)
    assert out is edged and out.stats["edge_contact"] and out.stats["held"] == 0
    assert calls == [True, False, "given", ("edges", True)]  # sound at once: no more fallbacks


def test_without_the_edge_fallback_an_unsound_drape_is_not_dressed_again(monkeypatch):
    """The fit's grading drapes turn the edges' fallback off: the same unsound drapes end at the
    pattern's own placement's verdict, no drape with the edges repelled."""
    edged = _fake(True, 1.3, 3)

    def caught(job):
        return edged if job.settings.edge_contact else _fake(True, 1.8, 3)

    out, calls = _run(monkeypatch, None, _fake(False, 5.0, 0), caught, edge_fallback=False)
    assert out is not edged and "edge_contact" not in out.stats
    assert calls == [True, False, "given"]


def test_an_unsound_drape_gives_way_to_a_sounder_one_from_the_patterns_own_placement(monkeypatch):
    """Both sewings unsound (an explosion, then a fall): the drape from the pattern's own
    placement is tried and kept when it passes its checks."""
    mine = _fake(True, 1.3, 0)

    def both_bad(job):
        return _fake(False, 4.0, 3) if job.settings.seam_guide else _fake(False, 1.2, 0)

    out, calls = _run(monkeypatch, None, given_result=mine, retried=both_bad)
    assert out is mine and out.stats["start_given"] and calls == [True, False, "given"]


def test_a_worse_drape_from_the_patterns_own_placement_is_not_kept(monkeypatch):
    guided = _fake(True, 1.6, 3)
    out, _ = _run(monkeypatch, guided, given_result=_fake(True, 1.9, 0), retried=lambda job: guided)
    assert out is guided and "start_given" not in out.stats


def test_a_diverging_drape_from_the_patterns_own_placement_leaves_the_first_verdict(monkeypatch):
    """The fallback's drape diverging (SimulationError) does not replace the unsound drape's
    verdict with a crash: dress() returns the drape it had."""
    from unsew.errors import SimulationError

    guided = _fake(False, 4.0, 3)
    _run(monkeypatch, guided, retried=lambda job: guided)  # installs the stand-ins

    def diverge(job, force_meet, given=False):
        raise SimulationError("simulation diverged at step 3")

    monkeypatch.setattr(dress_mod, "_dress_once", diverge)
    out = dress_mod.dress(_UNLABELLED, default_body(), sdf=object())
    assert out is guided and "start_given" not in out.stats


def _run_held(monkeypatch, held_result):
    """dress() of a pattern with a held edge, its drapes stood in for: held gives ``held_result``
    (raised when an exception), free a sound drape. Returns (drape, the calls: "held" / "free")."""
    import torch

    calls = []

    def fake_dress(job):
        held = job.cloth.anchors is not None
        calls.append("held" if held else "free")
        if held and isinstance(held_result, Exception):
            raise held_result
        return held_result if held else _fake(True, 1.1, 0)

    anchors = (torch.tensor([0, 1]), torch.tensor([1.0, 1.0], dtype=torch.float64))
    monkeypatch.setattr(dress_mod, "attached_vertices", lambda *a: anchors)
    monkeypatch.setattr(dress_mod, "_dress_retried", fake_dress)
    monkeypatch.setattr(dress_mod, "check_dressed", lambda d, body=None: SimpleNamespace(ok=d.ok))
    monkeypatch.setattr(dress_mod, "mesh_pattern", lambda *a, **k: SimpleNamespace(uv=np.zeros((2, 2))))
    return dress_mod.dress(_UNLABELLED, default_body(), sdf=object()), calls


def test_a_sound_held_drape_is_kept(monkeypatch):
    out, calls = _run_held(monkeypatch, _fake(True, 1.2, 0))
    assert calls == ["held"] and out.stats["held"] == 2


def test_an_unsound_or_diverged_held_drape_gives_way_to_a_sound_free_one(monkeypatch):
    from unsew.errors import SimulationError

    out, calls = _run_held(monkeypatch, _fake(False, 4.0, 0))
    assert calls == ["held", "free"] and out.ok and out.stats["held"] == 0
    out, calls = _run_held(monkeypatch, SimulationError("exploded"))
    assert calls == ["held", "free"] and out.ok and out.stats["held"] == 0


def _retry_run(monkeypatch, first_ok: bool):
    """dress()'s first drape (seam copies where the placement left them) stood in for, sound or
    torn, and the one with the copies met at their midpoint sound. Returns (drape, force_meet of
    each drape in order)."""
    calls = []

    def fake_once(job, force_meet, given=False):
        calls.append(force_meet)
        d = _fake(first_ok or force_meet, 1.1 if first_ok or force_meet else 3.6, 0)
        d.stats.update(met_seams=force_meet, seam_gap=0.0)
        return d

    def verdict(d, body=None):
        return SimpleNamespace(ok=d.ok, reason="" if d.ok else "exploded: an edge is stretched to 3.6 times")

    monkeypatch.setattr(dress_mod, "_dress_once", fake_once)
    monkeypatch.setattr(dress_mod, "check_dressed", verdict)
    return dress_mod._dress_retried(SimpleNamespace(body=None, placed_top=None)), calls


def test_a_start_that_tears_is_dressed_again_with_the_seam_copies_met(monkeypatch):
    out, calls = _retry_run(monkeypatch, first_ok=False)
    assert calls == [False, True] and out.ok
    assert "stretched" in out.stats["placement_retry"]
    out, calls = _retry_run(monkeypatch, first_ok=True)
    assert calls == [False] and out.ok and "placement_retry" not in out.stats


def test_a_straight_drape_that_diverges_leaves_the_guided_one_in_hand(monkeypatch):
    """A second try that blows up is no reason to lose the drape already made: dress() goes on
    with it (here to the pattern's own start) and says what diverged."""
    from unsew.errors import SimulationError

    guided = _fake(False, 4.0, 3)

    def straight_bursts(job):
        if not job.settings.seam_guide:
            raise SimulationError("simulation diverged at step 27")
        return guided

    out, calls = _run(monkeypatch, guided, retried=straight_bursts, edge_fallback=False)
    assert calls == [True, False, "given"]
    assert out is guided and guided.stats["diverged"] == ["the drape sewn straight"]


def test_a_placement_retry_that_diverges_keeps_the_first_drape(monkeypatch):
    """The retry with the seam copies started at their midpoint, made because the first drape tore
    an edge, diverges: the first drape is returned, not the error."""
    from unsew.errors import SimulationError

    first = _fake(False, 3.0, 0)
    first.stats["met_seams"] = False

    def once(job, force_meet, given=False):
        if force_meet:
            raise SimulationError("simulation diverged at step 27")
        return first

    monkeypatch.setattr(dress_mod, "_dress_once", once)
    monkeypatch.setattr(dress_mod, "_sewing_fault", lambda d, body: "an edge torn")
    out = dress_mod._dress_retried(SimpleNamespace(body=None, placed_top=None))
    assert out is first and first.stats["diverged"] == ["the retry with the seam copies met"]


def _fallen_run(monkeypatch, *, judge: bool):
    """dress() whose wrapped starts (guided and straight) both drape sound by the body's checks but
    end with their top under the pattern's own placement of it, and whose drape from that
    placement hangs where it puts it. Returns (drape, the calls in order)."""
    fallen = _fake(True, 1.2, 3)
    fallen.fallen = True
    own = _fake(True, 1.4, 0)
    own.fallen = False
    calls = []

    def verdict(d, body=None, placed_top_m=None, seam_gap_max=None, sleeves=None):
        calls.append(("verdict", placed_top_m))
        return SimpleNamespace(ok=d.ok and not (placed_top_m is not None and d.fallen))

    _run(monkeypatch, None, given_result=own, retried=lambda job: fallen)  # installs the stand-ins
    monkeypatch.setattr(dress_mod, "check_dressed", verdict)
    monkeypatch.setattr(dress_mod, "placed_top", lambda *a, **k: 1.3)
    monkeypatch.setattr(dress_mod, "sleeve_vertices", lambda *a, **k: {})

    def once(job, force_meet, given=False):
        calls.append("given")
        return own

    monkeypatch.setattr(dress_mod, "_dress_once", once)
    settings = dress_mod.DRESS_SETTINGS.replace(judge_placement=judge)
    return dress_mod.dress(_UNLABELLED, default_body(), sdf=object(), settings=settings), calls


def test_judged_by_its_placement_a_fallen_drape_gives_way_to_one_from_the_patterns_own_start(monkeypatch):
    """``judge_placement`` (what ``unsew drape`` asks): a drape sound on the body but fallen from
    where the pattern puts it is unsound, so the drape from the pattern's own placement is made
    and kept. Without it the fallen drape is sound and returned as it is."""
    out, calls = _fallen_run(monkeypatch, judge=True)
    assert out.stats.get("start_given") and not out.fallen
    assert ("verdict", 1.3) in calls and "given" in calls
    out, calls = _fallen_run(monkeypatch, judge=False)
    assert out.fallen and "given" not in calls
    assert all(c == ("verdict", None) for c in calls)
