"""Waist darts (V notches sewn shut) and the waist-seamed dress's waistband in the design space."""

import sys
from pathlib import Path

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.pattern.base._band import BAND_HEIGHT
from unsew.pattern.curves import edge_length
from unsew.pattern.design import Design, design_name, draft
from unsew.pattern.measurements import Measurements
from unsew.pattern.validate import validate_pattern

DARTED = [
    Design(garment="tshirt", sleeves="none", darts=True, length=0.05, hem_girth=0.8),
    Design(garment="tshirt", sleeves="long", sleeve_pieces=2, cuffs=True, darts=True, hem_girth=0.8),
    Design(garment="dress", waist_seam=True, waistband=True, darts=True, sleeves="short"),
    Design(garment="dress", waist_seam=True, waistband=True, darts=True, skirt="circle", panels=4),
    Design(garment="skirt", skirt="pencil", darts=True),
    Design(garment="skirt", skirt="pencil", darts=True, waistband=True, length=0.5, hem_girth=0.9),
    Design(garment="pants", darts=True),
    Design(garment="shorts", darts=True, waistband=True),
]


def _sewn_length(p, panel: str, prefix: str) -> float:
    """The summed length [m] of a panel's edges labelled ``prefix`` or ``prefix_<j>`` (no dart legs)."""
    pan = p.panels[panel]
    return sum(
        edge_length(pan, i)
        for i, e in enumerate(pan.edges)
        if (e.label == prefix or e.label.startswith(prefix + "_")) and "dart" not in e.label
    )


@pytest.mark.parametrize("design", DARTED, ids=design_name)
def test_a_darted_design_validates_and_every_stitch_joins_equal_lengths(design):
    p = draft(design, Measurements())
    validate_pattern(p)
    for st in p.stitches:
        a = edge_length(p.panels[st.a.panel], st.a.edge)
        b = edge_length(p.panels[st.b.panel], st.b.edge)
        assert a == pytest.approx(b, abs=1e-6), st.label  # to a micrometre
    darts = [st for st in p.stitches if "dart" in st.label]
    assert darts and all(st.a.panel == st.b.panel for st in darts)
    for st in darts:  # a dart's legs meet at its tip: a's end is b's start
        pan = p.panels[st.a.panel]
        assert pan.edges[st.a.edge].end == pan.edges[st.b.edge].start


@pytest.mark.parametrize(
    "design, panel, edge",
    [
        (Design(garment="tshirt", sleeves="none", length=0.05, hem_girth=0.8), "front", "hem"),
        (Design(garment="skirt", skirt="pencil"), "front", "waist"),
        (Design(garment="pants"), "right_back", "waist"),
    ],
)
def test_darts_keep_the_sewn_edge_and_take_in_the_cut(design, panel, edge):
    """Sewn shut, a darted edge is as long as the undarted design's; the panel is cut wider there
    (the darts' cloth)."""
    m = Measurements()
    plain, darted = draft(design, m), draft(design.replace(darts=True), m)
    assert _sewn_length(darted, panel, edge) == pytest.approx(_sewn_length(plain, panel, edge), rel=1e-9)

    def cut_width(p):  # the x span of the edge's ends (the hem at y = 0, a skirt's top highest)
        v = p.panels[panel].vertices
        y = 0.0 if edge == "hem" else v[:, 1].max()
        return np.ptp(v[np.abs(v[:, 1] - y) < 1e-9, 0])

    assert cut_width(darted) > cut_width(plain) + 0.01


def test_a_top_as_wide_at_its_hem_as_at_the_bust_has_no_waist_to_dart():
    d = Design(garment="tshirt", darts=True, hem_girth=1.2)
    assert not [st for st in draft(d).stitches if "dart" in st.label]


def test_a_banded_dress_sits_its_band_between_bodice_and_skirt():
    m = Measurements()
    d = Design(garment="dress", waist_seam=True, waistband=True, panels=4, sleeves="none")
    p = draft(d, m)
    assert {"waistband_front", "waistband_back"} <= set(p.panels)
    plain = draft(d.replace(waistband=False), m)
    lowest = lambda q, n: q.panels[n].to_world(q.panels[n].vertices)[:, 1].min()  # noqa: E731
    assert lowest(p, "front") == pytest.approx(lowest(plain, "front") + BAND_HEIGHT, abs=1e-6)
    band = p.panels["waistband_front"].to_world(p.panels["waistband_front"].vertices)
    assert np.ptp(band[:, 1]) == pytest.approx(BAND_HEIGHT)
    assert design_name(d).split("-")[1:4] == ["seam", "alinex4", "band"]


@pytest.mark.parametrize(
    "design",
    [
        Design(garment="dress", darts=True),  # one piece
        Design(garment="dress", waist_seam=True, darts=True),  # no band for the darts to end in
        Design(garment="skirt", skirt="aline", darts=True),
        Design(garment="skirt", skirt="pencil", panels=4, darts=True),
        Design(garment="jumpsuit", darts=True),
        Design(garment="skirt", skirt="darted", waistband=True, darts=True),
    ],
    ids=design_name,
)
def test_darts_where_the_space_cuts_none_are_refused(design):
    with pytest.raises(InputError):
        draft(design)


def test_the_benchmark_reads_the_new_pieces_from_their_names():
    """benchmarks/gcd/truth.py's choices_of_spec (what score.py reads a recovered pattern's choices
    with) sees the dress's waistband and the sleeves' and trouser legs' cuffs by name."""
    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks" / "gcd"))
    from truth import choices_of_spec

    from unsew.io.garmentcode import pattern_to_dict

    d = Design(garment="dress", waist_seam=True, waistband=True, darts=True, sleeves="long", cuffs=True)
    ch = choices_of_spec(pattern_to_dict(draft(d)))
    assert ch["waistband"] and ch["cuffs"] and ch["sleeves"]
    assert not choices_of_spec(pattern_to_dict(draft(d.replace(waistband=False, darts=False))))["waistband"]
    trousers = Design(garment="pants", leg_cuffs=True)
    assert choices_of_spec(pattern_to_dict(draft(trousers)))["cuffs"]
    assert not choices_of_spec(pattern_to_dict(draft(trousers.replace(leg_cuffs=False))))["cuffs"]
