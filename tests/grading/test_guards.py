"""unsew.grading.guards: grading keeps every panel meshable and a waist above the hips, and an
internal failure of grading is never reported as a fault of the input (fast: flat drapes)."""

from __future__ import annotations

import numpy as np
import pytest

import unsew.grading.grade as grade_module
from unsew.body.body import default_body
from unsew.errors import InputError, PatternError
from unsew.grading.alter import alter_pattern, open_edges
from unsew.grading.cloth import top_contour
from unsew.grading.contours import place_contours
from unsew.grading.grade import GradingError, GradingSettings, flat_drape, grade
from unsew.grading.guards import (
    MIN_KEEP_WIDTH,
    WAIST_ABOVE_HIP,
    WAIST_HIP_EASE,
    WaistBound,
    bounded_girth,
    bounded_waist,
    waist_bound,
)
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.base import make_base_pattern

EDGE = 0.04


@pytest.fixture(scope="module")
def body():
    return default_body()


@pytest.fixture(scope="module")
def skirt():
    p = make_base_pattern("skirt")
    return p, mesh_pattern(p, edge_length=EDGE)


def _top_row(res):
    return next(r for r in res.table if r["edits"] and any(":waist" in e for e in r["edits"]))


def test_a_waist_is_not_moved_below_the_hips(body, skirt):
    """A target whose waist lies 35 cm lower than the base's (below the hips): the waist moves
    down only to WAIST_ABOVE_HIP above the hip joints."""
    p, m = skirt
    t = alter_pattern(p, open_edges(p, "waist"), length=-0.35)
    tm = mesh_pattern(t, edge_length=EDGE)
    x0 = flat_drape(p, m)
    res = grade(
        p,
        body,
        flat_drape(t, tm),
        tm.faces,
        GradingSettings(passes=1, redrape=False, length="axial"),
        mesh=m,
        drape_fn=flat_drape,
    )
    row = _top_row(res)
    assert row["extension_m"] < -0.3  # what the target asked
    assert any("waist move cut" in w for w in row["warnings"])
    wb = waist_bound(body)
    top_y = float(top_contour(place_contours(x0, m.faces, body.skeleton)).centre[1])  # the base's waist
    room = top_y - (wb.hip_height + WAIST_ABOVE_HIP)
    h0 = np.ptp(p.panels["front"].vertices[:, 1])
    h1 = np.ptp(res.pattern.panels["front"].vertices[:, 1])
    assert 0 < room < 0.3
    assert h0 - h1 == pytest.approx(room, abs=0.002)  # the panel shortened from the top by the room only


def test_a_waist_is_not_widened_past_the_hips():
    bound = WaistBound(hip_height=0.86, shoulder_height=1.29, hip_girth=0.90)
    ext, dg, notes = bounded_waist(bound, 1.0, -0.05, girth=0.78, girth_change=0.40)
    assert ext == -0.05 and dg == pytest.approx(0.90 - WAIST_HIP_EASE - 0.78) and len(notes) == 1
    # already too wide: not widened
    assert bounded_waist(bound, 1.0, 0.0, girth=0.95, girth_change=0.10)[1] == 0.0
    assert bounded_waist(bound, 1.0, 0.0, girth=0.95, girth_change=-0.10)[1] == -0.10  # narrowing is free
    # a neckline (nearer the shoulders) is no waist: left alone
    assert bounded_waist(bound, 1.25, -0.5, girth=0.4, girth_change=2.0) == (-0.5, 2.0, [])
    assert bounded_waist(None, 1.0, -0.5, girth=0.4, girth_change=2.0) == (-0.5, 2.0, [])


def test_a_narrowing_keeps_the_curve_open(skirt):
    """A hem asked to shrink by more than its length keeps MIN_KEEP_WIDTH of it; a milder
    narrowing and any widening pass unchanged."""
    from unsew.grading.curves import OpenCurve
    from unsew.pattern.curves import edge_length

    p, _ = skirt
    hem = next(i for i, e in enumerate(p.panels["front"].edges) if e.label == "hem")
    e = p.panels["front"].edges[hem]
    curve = OpenCurve("front", 0, [hem], e.start, e.end, np.array([0, 1]), 0.8)
    length = edge_length(p.panels["front"], hem)
    dg, note = bounded_girth(p, curve, -2.0)
    assert dg == pytest.approx(-(length - MIN_KEEP_WIDTH)) and "narrowing cut" in note
    assert bounded_girth(p, curve, -0.5 * length) == (-0.5 * length, "")
    assert bounded_girth(p, curve, 0.3) == (0.3, "")


def test_an_unmeshable_graded_pattern_is_scaled_back(body, skirt, monkeypatch):
    """When the graded pattern cannot be meshed, the edit is halved until it can; when even the
    undone edit fails, a GradingError says it is grading's failure, not the input's."""
    p, m = skirt
    t = alter_pattern(p, open_edges(p, "hem"), length=0.05)
    tm = mesh_pattern(t, edge_length=EDGE)
    tx = flat_drape(t, tm)
    real = grade_module.mesh_pattern
    calls = []

    def fails_twice(pattern, **kw):
        calls.append(1)
        if len(calls) <= 2:
            raise PatternError("panel 'front': outline folds back on itself (test)")
        return real(pattern, **kw)

    monkeypatch.setattr(grade_module, "mesh_pattern", fails_twice)
    res = grade(
        p,
        body,
        tx,
        tm.faces,
        GradingSettings(passes=1, redrape=False, length="axial"),
        mesh=m,
        drape_fn=flat_drape,
    )
    assert res.fraction == pytest.approx(0.25) and len(calls) == 3
    assert any("scaled back to 25%" in w for r in res.table for w in r["warnings"])

    def always(pattern, **kw):
        raise PatternError("panel 'front': outline folds back on itself (test)")

    monkeypatch.setattr(grade_module, "mesh_pattern", always)
    with pytest.raises(GradingError, match="not of the input") as err:
        grade(
            p,
            body,
            tx,
            tm.faces,
            GradingSettings(passes=1, redrape=False, length="axial"),
            mesh=m,
            drape_fn=flat_drape,
        )
    assert not isinstance(err.value, InputError)


def _hem_with_slits(depth: float, n: int = 120, wave: float = 0.0, slope: float = 0.0) -> np.ndarray:
    """A 30 x 20 cm elliptic hem at y = 0 walked counter-clockwise (k, 3) [m], with optional
    folds (``wave``: radial amplitude [m], 12 waves), a slope (``slope`` [m] from front to
    back) and, when ``depth`` > 0, a slit at each side (x = +-15 cm): from a hem vertex straight
    up ``depth`` [m] in 8 steps, across to above the next hem vertex and down to it."""
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    r = 1 + wave / 0.15 * np.sin(12 * t)
    pts = np.stack([0.15 * r * np.cos(t), slope * (0.5 + 0.5 * np.sin(t)), 0.10 * r * np.sin(t)], axis=1)
    out = []
    for k, p in enumerate(pts):
        out.append(p)
        if depth > 0 and k in (0, n // 2):
            q = pts[k + 1]
            out += [p + [0, depth * s / 8, 0] for s in range(1, 9)] + [
                q + [0, depth * (8 - s) / 8, 0] for s in range(8)
            ]
    return np.asarray(out)


def test_slits_are_cut_from_a_hem_and_folds_or_slopes_are_not():
    """grading.contours.slits: a hem with a 17 cm slit at each side (the pencil dress's) loses
    both climbs and returns (2 x 2 x 17 cm) and keeps the rest; a folded or sloped hem keeps all of
    its length, and a climb out of the cloth is no slit."""
    from unsew.grading.contours import slits

    up = np.array([0.0, 1.0, 0.0])
    slit = _hem_with_slits(0.17)
    kept, cut = slits(slit, up)
    assert kept is not None and (~kept).sum() == 2 * 16
    assert cut == pytest.approx(4 * 0.17, rel=1e-6)
    assert slits(slit[::-1], up)[1] == pytest.approx(cut)  # walked the other way
    # a neckline's slit goes down into the cloth
    assert slits(slit * [1, -1, 1], -up)[1] == pytest.approx(cut)
    assert slits(slit, -up) == (None, 0.0)
    for other in (_hem_with_slits(0.0, wave=0.03), _hem_with_slits(0.0, slope=0.12), _hem_with_slits(0.03)):
        assert slits(other, up) == (None, 0.0)  # folds, a sloped hem, a 3 cm notch
    # a tall narrow loop, all climb and return but its two lowest vertices: no rim left, no slit
    # (cut from it, place_contours found the plane of two points and failed)
    narrow = np.array(
        [
            [0.0, 0.0, 0.0],
            [0.02, 0.0, 0.0],
            [0.021, 0.1, 0.0],
            [0.022, 0.2, 0.0],
            [0.0, 0.2, 0.0],
            [-0.001, 0.1, 0.0],
        ]
    )
    assert slits(narrow, up) == (None, 0.0)


def _skirt_tube(slit_rows: int):
    """A 40 cm tall tube of radius 0.22 m about the default body's hips (rings every 2.5 cm from
    y = 0.50 m, 80 vertices round) with, when ``slit_rows`` > 0, a slit at each side: that many
    rows of one column of faces left out from the hem up. Returns (verts (V, 3), faces (F, 3))."""
    n, rows = 80, 17
    t = 2 * np.pi * np.arange(n) / n
    v = np.concatenate(
        [
            np.stack([0.22 * np.cos(t), np.full(n, 0.5 + 0.025 * i), 0.22 * np.sin(t)], axis=1)
            for i in range(rows)
        ]
    )
    f = []
    for i in range(rows - 1):
        for j in range(n):
            if i < slit_rows and j in (0, n // 2):
                continue
            a, b = i * n + j, i * n + (j + 1) % n
            f += [[a, b, b + n], [a, b + n, a + n]]
    return v, np.array(f)


def test_a_slitted_hem_is_placed_as_the_hem_without_its_slits(body):
    """place_contours on a tube with a 15 cm slit at each side: the hem's length, centre height,
    plane and cloth length to the top are the plain tube's, and its rim leaves the slits out."""
    from unsew.grading.cloth import cloth_lengths

    plain = place_contours(*_skirt_tube(0), body.skeleton)
    v, f = _skirt_tube(6)
    slit = place_contours(v, f, body.skeleton)
    hem0 = min(plain, key=lambda c: c.centre[1])
    hem = min(slit, key=lambda c: c.centre[1])
    assert hem.contour.length > hem0.length + 4 * 0.14  # the loop itself climbs both slits
    assert hem.kept is not None and hem0.kept is None and hem0.slit_cut == 0.0
    assert hem.length == pytest.approx(hem0.length, abs=0.02)
    assert hem.centre[1] == pytest.approx(0.5, abs=0.005) and hem.contour.centre[1] > 0.52
    assert abs(hem.normal[1]) > 0.999
    assert np.all(v[hem.rim, 1] < 0.5 + 1e-9)
    _, lengths = cloth_lengths(v, f, slit)
    _, lengths0 = cloth_lengths(*_skirt_tube(0), plain)
    assert lengths[hem.index] == pytest.approx(lengths0[hem0.index], abs=0.005)


def test_a_band_is_never_lengthened_past_the_target_top_loop(body):
    """bounded_band: a waistband's top is graded to no more than the target's top loop (a band
    drapes stretched or at rest, never gathered shorter than its cloth); a top without a band,
    and a band graded shorter than the loop, keep the drapes' difference."""
    from dataclasses import replace

    from unsew.grading.contours import ContourMatch
    from unsew.grading.curves import curves_of_contour, rest_length
    from unsew.grading.guards import bounded_band
    from unsew.pattern.params import PatternParams

    assert bounded_band(0.80, 0.82, 0.05)[0] == pytest.approx(0.02)  # cut to the loop
    assert bounded_band(0.80, 0.82, 0.01) == (0.01, "")  # shorter than the loop: untouched
    assert bounded_band(0.0, 0.82, 0.05) == (0.05, "")  # no cloth known: untouched

    def graded_change(name):
        p = make_base_pattern(name)
        mesh = mesh_pattern(p, edge_length=EDGE)
        x = flat_drape(p, mesh, body)
        top = top_contour(place_contours(x, mesh.faces, body.skeleton))
        params = PatternParams.build(p, mesh)
        rest = rest_length(p, curves_of_contour(top.contour.indices, x, p, mesh, params.controls))
        # the source loop drapes 3 cm shorter than its cloth, the target's 1 cm shorter
        s = replace(top, slit_cut=top.contour.length - (rest - 0.03))
        t = replace(top, slit_cut=top.contour.length - (rest - 0.01))
        m = ContourMatch(0, 0, "torso", "spine", 0.0, 0.0, 0.02, 0.0)
        return grade_module._item(m, [s], [t], x, params, mesh)

    banded = graded_change("skirt_band")
    assert banded.girth_difference == pytest.approx(-0.01)  # +2 cm wanted, cut to the loop's length
    assert sum(banded.shares) == pytest.approx(-0.01 * sum(banded.weights))
    assert any("no longer than the target's loop" in w for w in banded.warnings)
    plain = graded_change("skirt")
    assert plain.girth_difference == pytest.approx(0.02)  # no band: the drapes' difference
    assert not any("target's loop" in w for w in plain.warnings)
