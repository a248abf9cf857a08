"""The fit's grading drapes: dress() with the fit's settings, without the edges' fallback."""

from types import SimpleNamespace

import numpy as np


def test_the_fits_grading_drapes_turn_the_edge_fallback_off(monkeypatch):
    """unsew.fit.start grades with dress() drapes in the fit's drape settings but for the edges'
    fallback, which they skip (grading only reads lengths off them)."""
    import torch

    import unsew.fit.start as start_mod
    from unsew.sim.drape import DrapeSettings

    seen = []

    def fake_dress(p, b, *, sdf=None, mesh=None, material=None, settings=None, progress=None):
        seen.append(settings)
        return SimpleNamespace(x=torch.zeros((3, 3), dtype=torch.float64))

    def fake_grade(base, body, verts, faces, settings, *, mesh, x_init, drape_fn):
        x = drape_fn(base, mesh, body)
        return SimpleNamespace(note=None, x_draped=x, pattern=base, mesh=mesh, table=[])

    monkeypatch.setattr(start_mod, "dress", fake_dress)
    monkeypatch.setattr(start_mod, "grade", fake_grade)
    monkeypatch.setattr(
        start_mod,
        "_base_drape",
        lambda *a: (SimpleNamespace(faces=np.zeros((0, 3), int)), np.zeros((3, 3)), 0),
    )
    monkeypatch.setattr(start_mod, "_check_contours_compatible", lambda *a: None)
    monkeypatch.setattr(start_mod, "held_anchors", lambda *a: None)
    cfg = SimpleNamespace(grading=True, drape=DrapeSettings(), area=None, side_seams="none", band_gap=None)
    scene = SimpleNamespace(
        cfg=cfg,
        target=SimpleNamespace(contours=[], verts=None, faces=None, distance_mm=lambda x, f: 10.0),
        body=None,
        sdf=None,
    )
    start_mod.start(SimpleNamespace(panels={}, stitches=[]), scene, "cotton")
    assert len(seen) == 1 and seen[0].edge_fallback is False
    assert seen[0].replace(edge_fallback=True) == cfg.drape and cfg.drape.edge_fallback
