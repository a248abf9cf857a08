"""dress() keeps the sounder of the guided and the straight sewing when the guided one is unsound."""

import dataclasses
from types import SimpleNamespace

import numpy as np

import unsew.dress as dress_mod
from unsew.body.body import default_body


def _fake(ok: bool, stretch: float, guided: int):
    """A stand-in drape: one right triangle, its 1 m leg along x drawn out to ``stretch`` m."""
    import torch

    tri = np.array([[0, 1, 2]])
    mesh = SimpleNamespace(faces=tri, faces_uv=tri, uv=np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]))
    x = torch.tensor([[0.0, 0.0, 0.0], [stretch, 0.0, 0.0], [0.0, 1.0, 0.0]], dtype=torch.float64)
    return SimpleNamespace(x=x, mesh=mesh, ok=ok, stats={"guided_seams": guided})


def _run(monkeypatch, guided_result):
    calls = []

    def fake_dress(job):
        calls.append(job.settings.seam_guide)
        return guided_result if job.settings.seam_guide else _fake(True, 1.1, 0)

    monkeypatch.setattr(dress_mod, "_dress_retried", fake_dress)
    monkeypatch.setattr(dress_mod, "check_dressed", lambda d, body=None: SimpleNamespace(ok=d.ok))
    monkeypatch.setattr(dress_mod, "mesh_pattern", lambda *a, **k: SimpleNamespace(uv=np.zeros((2, 2))))
    settings = dataclasses.replace(dress_mod.DRESS_SETTINGS, seam_guide=True)
    out = dress_mod.dress(object(), default_body(), sdf=object(), settings=settings)
    return out, calls


def test_an_exploded_guided_drape_gives_way_to_a_sound_straight_one(monkeypatch):
    out, calls = _run(monkeypatch, _fake(False, 4.0, 3))
    assert calls == [True, False]
    assert out.ok and out.stats["guide_dropped"] == 3


def test_a_sound_guided_drape_is_kept_without_a_second_drape(monkeypatch):
    guided = _fake(True, 1.2, 3)
    out, calls = _run(monkeypatch, guided)
    assert calls == [True] and out is guided


def test_a_worse_straight_drape_does_not_replace_the_guided_one(monkeypatch):
    guided = _fake(True, 1.6, 3)  # sound checks, an edge over 1.5: the straight one is tried

    def worse(job):
        return guided if job.settings.seam_guide else _fake(False, 1.2, 0)

    monkeypatch.setattr(dress_mod, "_dress_retried", worse)
    monkeypatch.setattr(dress_mod, "check_dressed", lambda d, body=None: SimpleNamespace(ok=d.ok))
    monkeypatch.setattr(dress_mod, "mesh_pattern", lambda *a, **k: SimpleNamespace(uv=np.zeros((2, 2))))
    out = dress_mod.dress(object(), default_body(), sdf=object())
    assert out is guided and "guide_dropped" not in out.stats
