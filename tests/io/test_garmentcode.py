"""GarmentCode JSON: lossless round trips, unit conversion, legacy forms, malformed files."""

import json
import warnings
from pathlib import Path

import numpy as np
import pytest

from helpers import assert_close
from unsew.errors import InputError, PatternError
from unsew.io.garmentcode import load_pattern, pattern_from_dict, save_pattern
from unsew.pattern.base import GARMENTS, make_base_pattern
from unsew.pattern.curves import relative_to_absolute
from unsew.pattern.model import pattern_diff

DATA = Path(__file__).parent.parent / "data"
HANDMADE = DATA / "handmade_specification.json"
LEGACY = DATA / "legacy_absolute_specification.json"


def _round_trip(p, tmp_path):
    a = tmp_path / "a.json"
    save_pattern(p, a)
    q = load_pattern(a)
    b = tmp_path / "b.json"
    save_pattern(q, b)
    r = load_pattern(b)
    return q, r, a, b


@pytest.mark.parametrize("garment", GARMENTS)
def test_base_pattern_round_trip(garment, tmp_path):
    p = make_base_pattern(garment)
    q, r, a, b = _round_trip(p, tmp_path)
    # metres -> cm -> metres: equal to the last bits of float64
    assert pattern_diff(p, q, rtol=1e-12, atol=1e-15) == []
    assert pattern_diff(q, r) == []  # a second save/load changes nothing at all
    assert a.read_text() == b.read_text()


def test_handmade_file_round_trip_keeps_everything(tmp_path):
    p = load_pattern(HANDMADE)
    kinds = {e.curvature.kind for pan in p.panels.values() for e in pan.edges if e.curvature}
    assert kinds == {"quadratic", "cubic", "circle"}
    q, r, a, _ = _round_trip(p, tmp_path)
    assert pattern_diff(p, q, rtol=1e-12) == []
    assert pattern_diff(q, r) == []
    saved = json.loads(a.read_text())
    orig = json.loads(HANDMADE.read_text())
    # Extra keys of edges, panels, stitch sides, stitch tails and the top level survive.
    assert saved["pattern"]["panels"]["front"]["edges"][2]["note"] == "kept"
    assert saved["pattern"]["panels"]["back"]["custom"] == {"made_by": "hand"}
    assert saved["pattern"]["stitches"][1] == orig["pattern"]["stitches"][1]
    assert saved["parameters"] == {} and saved["parameter_order"] == []
    assert saved["properties"] == orig["properties"]
    assert saved["unsew"]["format_version"] == 1 and saved["unsew"]["units"] == "m"
    # The file's numbers come back as they were (cm).
    for name in ("front", "back"):
        assert_close(
            saved["pattern"]["panels"][name]["vertices"],
            orig["pattern"]["panels"][name]["vertices"],
            rtol=1e-12,
        )
        assert_close(
            saved["pattern"]["panels"][name]["translation"],
            orig["pattern"]["panels"][name]["translation"],
            rtol=1e-12,
        )
    assert saved["pattern"]["panels"]["front"]["edges"][0]["curvature"] == {
        "type": "circle",
        "params": [80.0, 0, 1],
    }


def test_units_converted_to_metres():
    p = load_pattern(HANDMADE)
    assert_close(p.panels["front"].vertices[1], [0.30, 0.0], rtol=1e-12)
    assert_close(p.panels["front"].translation, [0.0, 0.95, 0.15], rtol=1e-12)
    assert p.panels["front"].edges[0].curvature.params == [0.8, False, True]  # radius 80 cm -> 0.8 m
    assert_close(p.panels["back"].rotation, [0.0, 180.0, 0.0])


def test_legacy_absolute_curvature_made_relative():
    p = load_pattern(LEGACY)  # units_in_meter 1000 (mm), absolute [x, y] control points
    assert p.properties["curvature_coords"] == "relative"
    pan = p.panels["panel"]
    e = pan.edges[1]
    assert e.curvature.kind == "quadratic"
    c = relative_to_absolute(pan.vertices[e.start], pan.vertices[e.end], np.array(e.curvature.params[0]))
    assert_close(c, [0.45, 0.15], rtol=1e-12)
    assert_close(pan.vertices[2], [0.4, 0.3], rtol=1e-12)


def test_saved_file_is_in_the_patterns_units(tmp_path):
    p = load_pattern(LEGACY)
    save_pattern(p, tmp_path / "x.json")
    d = json.loads((tmp_path / "x.json").read_text())
    assert d["properties"]["units_in_meter"] == 1000
    assert_close(d["pattern"]["panels"]["panel"]["vertices"][2], [400.0, 300.0], rtol=1e-12)


def test_unsew_block_and_stitch_labels_kept(tmp_path):
    p = make_base_pattern("tshirt")
    p.unsew["material"] = {"density": 0.15}
    save_pattern(p, tmp_path / "t.json")
    q = load_pattern(tmp_path / "t.json")
    assert q.unsew == {"material": {"density": 0.15}}
    assert [s.label for s in q.stitches] == [s.label for s in p.stitches]
    assert q.name == "tshirt"


@pytest.mark.parametrize(
    "text, match",
    [
        ("", "empty"),
        ("   \n", "empty"),
        ("{not json", "not valid JSON"),
        ("[1, 2]", "'pattern' object"),
        ('{"pattern": {"panels": []}}', "pattern.panels"),
        ('{"pattern": {"panels": {}}}', "no panels"),
    ],
)
def test_malformed_files_raise_one_line(tmp_path, text, match):
    f = tmp_path / "bad.json"
    f.write_text(text)
    with pytest.raises((InputError, PatternError), match=match) as ei:
        load_pattern(f)
    assert "\n" not in str(ei.value)


def test_missing_file(tmp_path):
    with pytest.raises(InputError, match="not found"):
        load_pattern(tmp_path / "nope.json")


def _handmade_dict():
    return json.loads(HANDMADE.read_text())


def test_open_loop_names_panel_and_edge():
    d = _handmade_dict()
    d["pattern"]["panels"]["back"]["edges"][2]["endpoints"] = [2, 0]
    with pytest.raises(
        PatternError,
        match=r"panel 'back' is not a closed loop: edge 2 ends at vertex 0 but edge 3 starts at vertex 3",
    ):
        pattern_from_dict(d)


def test_missing_stitch_target():
    d = _handmade_dict()
    d["pattern"]["stitches"][0][1] = {"panel": "sleeve", "edge": 0}
    with pytest.raises(PatternError, match="missing panel 'sleeve'"):
        pattern_from_dict(d)
    d = _handmade_dict()
    d["pattern"]["stitches"][0][1] = {"panel": "back", "edge": 7}
    with pytest.raises(PatternError, match="edge 7 of panel 'back'"):
        pattern_from_dict(d)


def test_bad_values_are_input_errors():
    d = _handmade_dict()
    d["pattern"]["panels"]["front"]["edges"][1]["curvature"] = {"type": "spline", "params": []}
    with pytest.raises(InputError, match="unknown curvature type 'spline'"):
        pattern_from_dict(d)
    d = _handmade_dict()
    d["properties"]["units_in_meter"] = 0
    with pytest.raises(InputError, match="units_in_meter"):
        pattern_from_dict(d)
    d = _handmade_dict()
    d["pattern"]["panels"]["front"]["vertices"][0] = ["a", 0]
    with pytest.raises(InputError, match="vertices"):
        pattern_from_dict(d)


def test_clockwise_file_mirrored_with_warning():
    """A panel drawn clockwise (seen from inside, GarmentCode's way for backs and right halves)
    with rotation 0 is read as the same cloth at the same place, counter-clockwise, with the
    same edge numbers and stitches."""
    d = _handmade_dict()
    pan = d["pattern"]["panels"]["back"]
    # The counter-clockwise back at rotation (0, 180, 0) is, point for point, the mirrored
    # outline at rotation 0: x -> -x, arcs bulge to the other side, quadratic t -> -t.
    pan["rotation"] = [0.0, 0.0, 0.0]
    pan["vertices"] = [[-x, y] for x, y in pan["vertices"]]
    pan["edges"][0]["curvature"]["params"][2] = 0
    for k in (1, 3):
        pan["edges"][k]["curvature"]["params"][0][1] *= -1
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        p = pattern_from_dict(d)
    assert any("'back' was clockwise" in str(x.message) for x in w)
    ref = pattern_from_dict(_handmade_dict())
    from unsew.pattern.curves import sample_edge

    a, b = p.panels["back"], ref.panels["back"]
    for i in range(len(b.edges)):
        assert (a.edges[i].start, a.edges[i].end) == (b.edges[i].start, b.edges[i].end)
        assert_close(a.to_world(sample_edge(a, i, 12)), b.to_world(sample_edge(b, i, 12)), atol=1e-12)
    assert [(s.a, s.b) for s in p.stitches] == [(s.a, s.b) for s in ref.stitches]
