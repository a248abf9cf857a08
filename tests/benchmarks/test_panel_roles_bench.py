"""benchmarks/bench_panel_roles.py: the wrapped start's panel roles against GarmentCode's names."""

import pytest
from benchmarks_loader import load_benchmark


def test_small_mode_every_role_agrees_with_its_name():
    """GarmentCode's four sample patterns on their mean body: every arm piece (a sleeve half, a
    cuff) is placed as a sleeve and no other panel is; the arm pieces lie out past the centre
    plane, the others reach it."""
    mod = load_benchmark("bench_panel_roles")
    rows, n = mod.gather(small=True)
    if not rows:
        pytest.skip("GarmentCode's sample patterns and bodies are not beside the checkout")
    text, bad = mod.summary(rows, n)
    assert n == 4 and bad == [], bad
    arm = [r for r in rows if r["out_by_arm"] and r["part"] == "arm"]
    assert arm and min(r["inner"] for r in arm) > 0.6, text


def test_a_misplaced_sleeve_is_listed():
    """A sleeve half placed as the torso disagrees with its name and is listed."""
    mod = load_benchmark("bench_panel_roles")
    rows = [
        dict(tag="t", panel="left_sleeve_f", part="arm", role="torso", out_by_arm=True, inner=0.59),
        dict(tag="t", panel="left_ftorso", part="other", role="torso", out_by_arm=False, inner=0.0),
    ]
    _, bad = mod.summary(rows, 1)
    assert [r["panel"] for r in bad] == ["left_sleeve_f"]
