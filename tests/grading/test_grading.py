"""Linear grading: contours on bones, matching, 2D curves, the edit, grade()."""

from __future__ import annotations

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.grading.alter import alter_pattern, open_edges
from unsew.grading.contours import hull_perimeter, match_contours, part_group, place_contours
from unsew.grading.curves import curves_of_contour, rest_length
from unsew.grading.grade import (
    GRADE_SETTINGS,
    TABLE_COLUMNS,
    GradingSettings,
    flat_drape,
    format_table,
    grade,
    source_girth,
)
from unsew.meshing.sew import mesh_pattern
from unsew.pattern.base import make_base_pattern
from unsew.pattern.params import PatternParams, check_inverted

EDGE = 0.04


@pytest.fixture(scope="module")
def body():
    return default_body()


@pytest.fixture(scope="module")
def tshirt():
    p = make_base_pattern("tshirt")
    return p, mesh_pattern(p, edge_length=EDGE)


def tube(bone, u0, u1, radius, *, n_around=24, n_rings=12, cap=False, pleat=0.0):
    """Open cylinder of ``radius`` [m] around ``bone`` from axial coordinate u0 to u1 (closed at
    u0 by a fan when ``cap``); ``pleat`` [m] pulls every other vertex of the u1 ring that much
    towards the bone (a crumpled cuff)."""
    d = bone.direction
    e1 = np.cross(d, [0.0, 0.0, 1.0] if abs(d[2]) < 0.9 else [1.0, 0.0, 0.0])
    e1 /= np.linalg.norm(e1)
    e2 = np.cross(d, e1)
    us = np.linspace(u0, u1, n_rings)
    th = np.linspace(0, 2 * np.pi, n_around, endpoint=False)
    v = np.array(
        [bone.a + u * (bone.b - bone.a) + radius * (np.cos(t) * e1 + np.sin(t) * e2) for u in us for t in th]
    )
    if pleat:
        last = np.arange((n_rings - 1) * n_around, n_rings * n_around, 2)
        axis = bone.a + us[-1] * (bone.b - bone.a)
        v[last] -= pleat * (v[last] - axis) / radius
    f = []
    for i in range(n_rings - 1):
        for j in range(n_around):
            a, b = i * n_around + j, i * n_around + (j + 1) % n_around
            c, dd = a + n_around, b + n_around
            f += [[a, b, dd], [a, dd, c]]
    if cap:
        v = np.vstack([v, bone.a + u0 * (bone.b - bone.a)])
        f += [[len(v) - 1, (j + 1) % n_around, j] for j in range(n_around)]
    return v, np.array(f)


def test_tube_contours_sit_on_the_arm_bone(body):
    sk = body.skeleton
    bone = sk.bone("left_elbow")
    v, f = tube(bone, 0.2, 0.7, 0.06)
    placed = place_contours(v, f, sk)
    assert len(placed) == 2
    for c in placed:
        assert c.part == "left_arm" and c.bone.name == "left_elbow"
        assert c.h < 1e-6
    pos = sorted(c.position for c in placed)
    assert pos == pytest.approx([sk.distance_to_root(bone, 0.2), sk.distance_to_root(bone, 0.7)], abs=1e-9)


def test_tube_match_measures_axial_distance_and_girth(body):
    sk = body.skeleton
    bone = sk.bone("left_elbow")
    vs, fs = tube(bone, 0.2, 0.6, 0.06)
    vt, ft = tube(bone, 0.2, 0.9, 0.07)  # cuff 0.3 bone lengths further out, 1 cm wider radius
    src, tgt = place_contours(vs, fs, sk), place_contours(vt, ft, sk)
    ms = match_contours(src, tgt, sk, garment_centre=vs.mean(axis=0))
    assert len(ms) == 2
    girth = 24 * 2 * np.sin(np.pi / 24) * 0.01  # perimeter change of the 24-gon
    by_u = {round(src[m.source].u, 1): m for m in ms}
    cuff, top = by_u[0.6], by_u[0.2]
    assert cuff.extension == pytest.approx(0.3 * bone.length, abs=1e-9)
    assert cuff.axial_distance == pytest.approx(0.3 * bone.length, abs=1e-9)
    assert top.extension == pytest.approx(0.0, abs=1e-9)
    assert cuff.girth_difference == pytest.approx(girth, abs=1e-9)


def test_caught_source_cuff_reads_its_girth_from_its_hull(body):
    sk = body.skeleton
    bone = sk.bone("left_elbow")
    vs, fs = tube(bone, 0.2, 0.6, 0.06, pleat=0.01)  # a pleated cuff: a longer loop around the same hull
    vt, ft = tube(bone, 0.2, 0.6, 0.06)
    src, tgt = place_contours(vs, fs, sk), place_contours(vt, ft, sk)
    ms = match_contours(src, tgt, sk, garment_centre=vs.mean(axis=0))
    cuff = next(m for m in ms if round(src[m.source].u, 1) == 0.6)
    s, t = src[cuff.source], tgt[cuff.target]
    assert s.crumple > 1.1 and t.crumple == pytest.approx(1.0, abs=0.02)
    assert cuff.girth_difference < -0.04  # read by its loop, the cuff would be narrowed by 4 cm
    # its cloth edge as long as the smooth loop: the drape stretched it into pleats
    girth, why = source_girth(s, t, rest=t.length)
    assert "hull" in why and abs(t.length - girth) < 0.005
    # its cloth edge as long as its loop: pleated by its own cloth, a girth to grade
    assert source_girth(s, t, rest=s.length) == (s.length, "")
    # no rest length known, or a crumpled target: the loop lengths
    assert source_girth(s, t, rest=None) == (s.length, "")
    assert source_girth(t, s, rest=0.5 * t.length) == (t.length, "")


def test_hull_perimeter_of_a_square_and_a_line():
    sq = np.array([[0, 0, 0], [1, 0, 0], [0.5, 0.5, 0], [1, 1, 0], [0, 1, 0]], dtype=float)
    assert hull_perimeter(sq) == pytest.approx(4.0)
    assert np.isnan(hull_perimeter(sq[:2]))
    assert np.isnan(hull_perimeter(np.array([[0, 0, 0], [1, 0, 0], [2, 0, 0]], dtype=float)))


def test_shorter_sleeve_is_a_negative_extension(body):
    sk = body.skeleton
    bone = sk.bone("left_elbow")
    vs, fs = tube(bone, 0.2, 0.8, 0.06)
    vt, ft = tube(bone, 0.2, 0.5, 0.06)
    ms = match_contours(
        place_contours(vs, fs, sk), place_contours(vt, ft, sk), sk, garment_centre=vs.mean(axis=0)
    )
    cuff = max(ms, key=lambda m: abs(m.extension))
    assert cuff.extension == pytest.approx(-0.3 * bone.length, abs=1e-9)


def test_extension_sign_follows_the_cloth_next_to_the_contour(body):
    """A long sleeve beside a lot of cloth far below (a dress's skirt): the garment's vertex mean
    then lies beyond the cuff along the arm bone; the cloth next to the cuff still tells that a
    cuff further down the arm is a longer sleeve."""
    sk = body.skeleton
    bone = sk.bone("left_elbow")
    vs, fs = tube(bone, 0.1, 0.5, 0.06)
    vt, ft = tube(bone, 0.1, 0.8, 0.06)
    skirt, sf = tube(sk.bone("spine"), -3.0, -1.0, 0.3, n_rings=40)  # far below, many vertices
    v_all = np.vstack([vs, skirt])
    f_all = np.vstack([fs, sf + len(vs)])
    centre = v_all.mean(axis=0)
    assert float((vs[-1] - centre) @ bone.direction) < 0  # the vertex mean would read it backwards
    src = place_contours(v_all, f_all, sk)
    tgt = place_contours(vt, ft, sk)
    ms = match_contours([c for c in src if c.part == "left_arm"], tgt, sk, garment_centre=centre)
    cuff = max(ms, key=lambda m: abs(m.axial_distance))
    assert cuff.extension == pytest.approx(0.3 * bone.length, abs=1e-9)


def _hem_tube(sk, drop):
    """A torso tube closed at the top of the spine bone, its hem ``drop`` [m] below the spine's
    start: one open contour, on the torso."""
    bone = sk.bone("spine")
    return tube(bone, 1.0, -drop / bone.length, 0.16, cap=True, n_rings=30)


def test_the_only_hems_match_across_more_than_the_centre_gate(body):
    """A long base's hem far below a short target's: each the only torso contour of its mesh,
    they match although their centres lie farther apart than MAX_CENTRE_DISTANCE (the tall thin
    shift's first grading pass left its hem alone at 0.47 m); farther than FAR_CENTRE_FACTOR times
    that, or beside a second torso contour, they do not."""
    from unsew.grading.contours import FAR_CENTRE_FACTOR, MAX_CENTRE_DISTANCE

    sk = body.skeleton
    vs, fs = _hem_tube(sk, 0.70)
    vt, ft = _hem_tube(sk, 0.10)
    src, tgt = place_contours(vs, fs, sk), place_contours(vt, ft, sk)
    assert [c.part for c in src] == [c.part for c in tgt] == ["torso"]
    gap = float(np.linalg.norm(src[0].centre - tgt[0].centre))
    assert MAX_CENTRE_DISTANCE < gap < FAR_CENTRE_FACTOR * MAX_CENTRE_DISTANCE
    (hem,) = match_contours(src, tgt, sk, garment_centre=vs.mean(axis=0))
    assert hem.extension == pytest.approx(-gap, abs=0.02)  # the target's hem is higher: shorten
    # too far even so
    assert match_contours(src, tgt, sk, garment_centre=vs.mean(axis=0), max_centre_distance=0.25 * gap) == []
    # a second torso contour on the target (a lining's hem round the waist): no longer the only one
    vl, fl = tube(sk.bone("spine"), 0.9, 0.3, 0.12, cap=True)
    two = place_contours(np.vstack([vt, vl]), np.vstack([ft, fl + len(vt)]), sk)
    assert sum(c.part == "torso" for c in two) == 2
    far = [
        m
        for m in match_contours(src, two, sk, garment_centre=vs.mean(axis=0))
        if np.linalg.norm(src[m.source].centre - two[m.target].centre) > MAX_CENTRE_DISTANCE
    ]
    assert far == []
    # not on the arms: a long sleeve's cuff far down the arm and a short one's, each alone there
    bone = sk.bone("left_elbow")
    vs, fs = tube(bone, 0.0, 2.2, 0.05, cap=True)
    vt, ft = tube(bone, 0.0, 0.4, 0.05, cap=True)
    src, tgt = place_contours(vs, fs, sk), place_contours(vt, ft, sk)
    assert len(src) == len(tgt) == 1 and src[0].part == tgt[0].part == "left_arm"
    assert (
        MAX_CENTRE_DISTANCE
        < float(np.linalg.norm(src[0].centre - tgt[0].centre))
        < FAR_CENTRE_FACTOR * MAX_CENTRE_DISTANCE
    )
    assert match_contours(src, tgt, sk, garment_centre=vs.mean(axis=0)) == []


def test_contour_across_bones_of_one_limb_uses_distance_along_the_chain(body):
    sk = body.skeleton
    upper, fore = sk.bone("left_elbow"), sk.bone("left_wrist")
    vs, fs = tube(upper, 0.3, 0.8, 0.06, cap=True)
    vt, ft = tube(fore, 0.05, 0.5, 0.06, cap=True)  # a target cuff on the forearm
    src, tgt = place_contours(vs, fs, sk), place_contours(vt, ft, sk)
    assert len(src) == len(tgt) == 1 and tgt[0].bone.name == "left_wrist"
    (cuff,) = match_contours(src, tgt, sk, garment_centre=vs.mean(axis=0), max_centre_distance=1.0)
    want = sk.distance_to_root(fore, 0.5) - sk.distance_to_root(upper, 0.8)
    assert cuff.extension == pytest.approx(want, abs=1e-9)


def test_tshirt_contours_parts_and_curves(body, tshirt):
    p, m = tshirt
    x = flat_drape(p, m)
    placed = place_contours(x, m.faces, body.skeleton)
    parts = sorted(c.part for c in placed)
    assert parts[:2] == ["left_arm", "right_arm"] or parts[1:3] == ["left_arm", "right_arm"]
    # neckline: neck or head
    assert sorted(part_group(q) for q in parts) == ["left_arm", "right_arm", "torso", "torso"]
    params = PatternParams.build(p, m)
    hem = max((c for c in placed if part_group(c.part) == "torso"), key=lambda c: c.length)
    curves = curves_of_contour(hem.contour.indices, x, p, m, params.controls)
    assert sorted((c.panel, c.edges[0]) for c in curves) == [("back", 0), ("front", 0)]
    assert sum(c.length3d for c in curves) == pytest.approx(hem.length, rel=1e-6)
    for c in curves:
        assert len(c.controls) == 2  # the hem's two corners
    cuff = next(c for c in placed if c.part == "left_arm")
    (curve,) = curves_of_contour(cuff.contour.indices, x, p, m, params.controls)
    assert curve.panel == "left_sleeve" and p.panels["left_sleeve"].edges[curve.edges[0]].label == "hem"
    hem = p.panels["left_sleeve"].edges[curve.edges[0]]
    chord = np.linalg.norm(
        p.panels["left_sleeve"].vertices[hem.end] - p.panels["left_sleeve"].vertices[hem.start]
    )
    assert rest_length(p, [curve]) >= chord - 1e-12 and rest_length(p, []) == 0.0
    assert rest_length(p, [curve, curve]) == pytest.approx(2 * rest_length(p, [curve]))


def _contour_by_part(x, faces, sk):
    """Part -> its longest contour (a neckline on the neck bone is torso too; the hem is longer)."""
    out = {}
    for c in place_contours(x, faces, sk):
        if c.part not in out or c.length > out[c.part].length:
            out[c.part] = c
    return out


def test_grade_flat_recovers_known_hem_and_sleeve_changes(body, tshirt):
    """Panels laid flat (no simulation): the edit recovers the known changes in 3D."""
    p, m = tshirt
    t = alter_pattern(p, open_edges(p, "hem", panels=["front", "back"]), length=0.10, girth=0.10)
    t = alter_pattern(t, open_edges(t, "hem", panels=["left_sleeve", "right_sleeve"]), length=-0.05)
    tm = mesh_pattern(t, edge_length=EDGE)
    tx = flat_drape(t, tm)
    # one pass: laid flat, the right sleeve sits shifted in its frame (below), which a second
    # pass from the flat "drape" would chase
    res = grade(p, body, tx, tm.faces, GradingSettings(passes=1), mesh=m, drape_fn=flat_drape)
    assert res.fraction == 1.0
    assert len(check_inverted(res.mesh.uv, res.mesh.faces_uv)) == 0
    sk = body.skeleton
    got, want = _contour_by_part(res.x_draped, res.mesh.faces, sk), _contour_by_part(tx, tm.faces, sk)
    before = _contour_by_part(res.x_init, m.faces, sk)
    for part in ("torso", "left_arm"):
        assert abs(got[part].position - want[part].position) < 0.01, part
    # the right sleeve is rebuilt from the left one about its own fixed centroid (symmetry), so
    # laid flat it sits shifted in its frame; its shape is the target's
    d = res.pattern.panels["right_sleeve"].vertices - t.panels["right_sleeve"].vertices
    np.testing.assert_allclose(d - d.mean(axis=0), 0.0, atol=2e-3)
    # laid flat, a sleeve's self-sewn underarm folds its cuff onto a line: girths only where open
    assert abs(got["torso"].length - want["torso"].length) < 0.02
    assert abs(before["torso"].position - want["torso"].position) > 0.09  # it had something to do
    assert set(res.table[0]) == set(TABLE_COLUMNS)
    assert "torso" in format_table(res.table)


def test_graded_pattern_is_meshed_afresh_unless_told_otherwise(body, tshirt):
    p, m = tshirt
    t = alter_pattern(p, open_edges(p, "hem", panels=["front", "back"]), length=0.02)
    tm = mesh_pattern(t, edge_length=EDGE)
    tx = flat_drape(t, tm)
    fresh = grade(p, body, tx, tm.faces, GradingSettings(passes=1), mesh=m, drape_fn=flat_drape)
    moved = grade(
        p, body, tx, tm.faces, GradingSettings(passes=1, remesh="stretched"), mesh=m, drape_fn=flat_drape
    )
    assert fresh.remeshed and not moved.remeshed
    # a 2 cm longer hem stretches no edge 1.5x: the base's triangles, moved with the pattern
    np.testing.assert_array_equal(moved.mesh.faces_uv, m.faces_uv)
    assert not np.allclose(moved.mesh.uv, m.uv)
    # the fresh mesh is the graded pattern's own, as mesh_pattern makes it
    own = mesh_pattern(fresh.pattern, edge_length=EDGE)
    np.testing.assert_allclose(fresh.mesh.uv, own.uv)
    np.testing.assert_array_equal(fresh.mesh.faces, own.faces)


def test_paired_sleeves_edit_is_averaged(body, tshirt):
    """Only the left cuff moves in the target: symmetry keeps the sleeves alike (half each)."""
    p, m = tshirt
    t = alter_pattern(p, open_edges(p, "hem", panels=["left_sleeve"]), length=0.06)
    tm = mesh_pattern(t, edge_length=EDGE)
    res = grade(p, body, flat_drape(t, tm), tm.faces, mesh=m, drape_fn=flat_drape)
    ls, rs = res.pattern.panels["left_sleeve"], res.pattern.panels["right_sleeve"]
    h = lambda panel: np.ptp(panel.vertices[:, 1])  # noqa: E731
    assert h(ls) == pytest.approx(h(rs), abs=1e-9)
    # least squares over both sleeves' control points: a compromise between 0 and 6 cm (not
    # exactly half: a paired panel is rebuilt about its source's centroid)
    assert 0.015 < h(ls) - h(p.panels["left_sleeve"]) < 0.045


def test_extra_hole_in_target_is_reported_and_left_alone(body, tshirt):
    p, m = tshirt
    t = alter_pattern(p, open_edges(p, "hem", panels=["front", "back"]), length=0.05)
    tm = mesh_pattern(t, edge_length=EDGE)
    tx = flat_drape(t, tm)
    # punch a hole: drop the triangles around the front panel's middle vertex
    front = tm.panel_names.index("front")
    inner = tm.interior(front)
    centre = inner[np.argmin(np.linalg.norm(tm.uv[inner] - tm.uv[inner].mean(0), axis=1))]
    keep = ~np.isin(tm.faces_uv, [centre]).any(axis=1)
    holed = tm.faces[keep]
    for length in ("axial", "cloth"):
        clean = grade(
            p, body, tx, tm.faces, GradingSettings(redrape=False, length=length), mesh=m, drape_fn=flat_drape
        )
        res = grade(
            p, body, tx, holed, GradingSettings(redrape=False, length=length), mesh=m, drape_fn=flat_drape
        )
        extra = [r for r in res.table if r["source_contour"] is None]
        assert len(extra) == 1 and "left alone" in extra[0]["warnings"][0]
        # the hole is never edited for; measured along the cloth, the hem's paths to the
        # neckline go round it, which moves the hem by under a millimetre
        np.testing.assert_allclose(res.K, clean.K, atol=1e-12 if length == "axial" else 1e-3)


def test_a_cuff_moved_past_the_sleeve_is_cut_not_collapsed(body, tshirt):
    """A target whose cuffs lie 40 cm further in than the base's (more than the sleeve is long):
    the move is cut so each sleeve keeps MIN_KEEP_LENGTH of its underarm seams (unsew.grading.
    guards), instead of folding the sleeve into a spike; the rest of the edit is whole."""
    from unsew.grading.guards import MIN_KEEP_LENGTH
    from unsew.pattern.curves import edge_length

    p, m = tshirt
    t = alter_pattern(p, open_edges(p, "hem", panels=["left_sleeve", "right_sleeve"]), length=-0.10)
    tm = mesh_pattern(t, edge_length=EDGE)
    tx = flat_drape(t, tm)
    sk = body.skeleton
    shift = np.zeros_like(tx)
    for side in ("left", "right"):
        idx = np.flatnonzero(tm.uv_panel == tm.panel_names.index(f"{side}_sleeve"))
        shift[tm.x_of_u[idx]] = -0.3 * sk.bone(f"{side}_elbow").direction
    res = grade(
        p,
        body,
        tx + shift,
        tm.faces,
        GradingSettings(redrape=False, max_centre_distance=1.0),
        mesh=m,
        drape_fn=flat_drape,
    )
    assert len(check_inverted(res.mesh.uv, res.mesh.faces_uv)) == 0
    assert sum("move cut" in w for r in res.table for w in r["warnings"]) >= 2  # both sleeves
    for side in ("left", "right"):
        panel = res.pattern.panels[f"{side}_sleeve"]
        hem = next(i for i, e in enumerate(panel.edges) if e.label == "hem")
        n = len(panel.edges)
        for nb in ((hem - 1) % n, (hem + 1) % n):  # the underarm seams beside the cuff
            assert edge_length(panel, nb) > MIN_KEEP_LENGTH - 0.005, (side, nb)
            # it did shorten
            assert edge_length(panel, nb) < edge_length(p.panels[f"{side}_sleeve"], nb) - 0.05


def test_safe_fraction_scales_back_an_inverting_edit(tshirt):
    """An edit that turns a sleeve inside out is scaled back to the largest fraction that
    inverts no triangle."""
    import torch

    from unsew.grading.edit import safe_fraction

    p, m = tshirt
    params = PatternParams.build(p, m)
    K0 = params.K0
    C = params.control_points(K0).detach().cpu().numpy()
    cidx = params.controls.of_panel(m.panel_names.index("left_sleeve"))
    C[cidx, 1] = 2 * C[cidx, 1].mean() - C[cidx, 1]  # the sleeve mirrored top to bottom: inside out
    K1 = params.k_from_control_points(C)
    f = safe_fraction(params, K0, K1)
    assert 0.0 < f < 1.0
    with torch.no_grad():
        assert len(check_inverted(params.uv(K0 + f * (K1 - K0)), m.faces_uv)) == 0
        assert len(check_inverted(params.uv(K1), m.faces_uv)) > 0


def test_bad_target_is_refused(body, tshirt):
    from unsew.errors import InputError

    p, m = tshirt
    with pytest.raises(InputError):
        grade(p, body, np.zeros((0, 3)), np.zeros((0, 3), dtype=int), mesh=m, drape_fn=flat_drape)
    x = flat_drape(p, m)
    with pytest.raises(InputError, match="remesh"):
        grade(p, body, x, m.faces, GradingSettings(remesh="sometimes"), mesh=m, drape_fn=flat_drape)
    with pytest.raises(InputError, match="length"):
        grade(p, body, x, m.faces, GradingSettings(length="bone"), mesh=m, drape_fn=flat_drape)


def _grade_simulated(body, garment, changes, edge):
    """Target draped by our simulator (``dress``) from ``garment`` altered by ``changes``
    ({group: (length [m], relative girth)}); the base pattern graded to it with the default
    drape. Returns (result, target verts, target mesh, target pattern)."""
    from unsew.body.sdf import BodySDF
    from unsew.grading.alter import alteration_groups
    from unsew.grading.grade import dress_drape

    sdf = BodySDF.build(body)
    p = make_base_pattern(garment)
    groups = alteration_groups(p)
    t = p
    for key, (dl, dg) in changes.items():
        t = alter_pattern(t, groups[key], length=dl, girth=dg)
    tm = mesh_pattern(t, edge_length=edge)
    tx = dress_drape(t, tm, body, sdf=sdf)
    # cholespy pinned, as when these figures were measured: on CHOLMOD the small skirt's second pass
    # moves its hem 1.0 cm instead of 1.3, and the pattern, 3 mm apart, drapes 9.3 mm from the
    # target instead of 5.3 (x0.70 of the base's distance instead of x0.40)
    settings = GRADE_SETTINGS.replace(edge_length=edge, backend="cholespy")

    def drape_fn(p_, m_, b_):
        return dress_drape(p_, m_, b_, sdf=sdf, settings=settings)

    res = grade(p, body, tx, tm.faces, GradingSettings(drape=settings), drape_fn=drape_fn)
    return res, tx, tm, t


def _chamfers(res, tx, tm, n=20000):
    from unsew.metrics.surface import chamfer_mm

    before = chamfer_mm(res.x_init, res.mesh_init.faces, tx, tm.faces, n_samples=n).mean_mm
    after = chamfer_mm(res.x_draped, res.mesh.faces, tx, tm.faces, n_samples=n).mean_mm
    return before, after


def test_grade_simulated_skirt_small(body):
    """Small mode through the real drape (5 cm mesh): a skirt 12 cm longer with a 10 % narrower
    hem, which hangs 7 cm lower on the body; grading finds the pattern's length and brings the
    drape closer to the target."""
    res, tx, tm, t = _grade_simulated(body, "skirt", {"hem": (0.12, -0.10)}, 0.05)
    sk = body.skeleton
    got, want = _contour_by_part(res.x_draped, res.mesh.faces, sk), _contour_by_part(tx, tm.faces, sk)
    before = _contour_by_part(res.x_init, res.mesh_init.faces, sk)
    hem = min(want, key=lambda k: want[k].centre[1])  # the lowest contour is the hem
    assert abs(before[hem].position - want[hem].position) > 0.05
    assert abs(got[hem].position - want[hem].position) < 0.02
    b, a = _chamfers(res, tx, tm, n=5000)
    assert a < 0.7 * b
    # in the pattern: the panel within 1 cm of the target's length, read from the cloth length
    # (unsew.grading.cloth; the hem's axial distance under-reads it: the waist rides up the hips)
    assert abs(_panel_length(res.pattern, "front") - _panel_length(t, "front")) < 0.01


def _panel_length(pattern, name: str) -> float:
    """A panel's extent [m] along its own 2D y axis (a skirt panel's waist-to-hem length)."""
    v = pattern.panels[name].vertices
    return float(v[:, 1].max() - v[:, 1].min())


@pytest.mark.slow
def test_grade_simulated_tshirt_recovers_known_changes(body):
    """One case: target draped by our simulator from a t-shirt whose hem is
    10 cm longer and 10 % wider; grading recovers the hem within 1 cm / 2 cm and halves the
    Chamfer distance."""
    res, tx, tm, _ = _grade_simulated(body, "tshirt", {"hem": (0.10, 0.10)}, EDGE)
    sk = body.skeleton
    got, want = _contour_by_part(res.x_draped, res.mesh.faces, sk), _contour_by_part(tx, tm.faces, sk)
    assert abs(got["torso"].position - want["torso"].position) < 0.01
    assert abs(got["torso"].length - want["torso"].length) < 0.02
    before, after = _chamfers(res, tx, tm)
    assert after <= 0.5 * before


def test_later_pass_scales_by_the_drapes_measured_response():
    """A contour that moved 4 cm for a 7 cm edit gets its remaining offset scaled by 7/4; one that
    moved fully, the wrong way, or too little to tell, is left at gain 1; the gain is capped."""
    from unsew.grading.contours import ContourMatch
    from unsew.grading.grade import MAX_PASS_GAIN, response_gains

    def m(target, ext):
        return ContourMatch(
            source=target,
            target=target,
            part="torso",
            bone="b",
            axial_distance=-ext,
            extension=ext,
            girth_difference=0.0,
            cost=0.0,
        )

    before = [m(0, 0.07), m(1, 0.05), m(2, 0.05), m(3, 0.05), m(4, 0.10), m(5, 0.002)]
    applied = {0: 0.07, 1: 0.05, 2: 0.05, 3: 0.05, 4: 0.10, 5: 0.002}
    after = [m(0, 0.03), m(1, 0.0), m(2, 0.06), m(3, 0.045), m(4, 0.09), m(5, 0.0)]
    gains = response_gains(before, applied, after)
    assert gains[0] == pytest.approx(0.07 / 0.04)
    assert 1 not in gains and 2 not in gains and 5 not in gains  # answered fully, wrong way, no edit
    assert 3 not in gains  # 10 % response: noise, not a slow answer
    assert 4 not in gains  # 10 % response
    before[4], after[4] = m(4, 0.10), m(4, 0.075)  # 25 % response: capped
    assert response_gains(before, applied, after)[4] == MAX_PASS_GAIN


def test_hold_tops_moves_the_length_change_to_the_hem():
    """A skirt panel whose waist curve is edited upward is translated back along its upright
    direction: the waist keeps its placed height, the hem takes the whole change; a panel whose
    top is not an edited curve is left as edited."""
    from unsew.grading.grade import _hold_tops
    from unsew.pattern.controls import find_control_points

    p = make_base_pattern("skirt")
    controls = find_control_points(p)
    C0 = controls.positions
    front = controls.panel_names.index("front")
    back = controls.panel_names.index("back")
    cf = controls.of_panel(front)
    panel = p.panels["front"]
    h = panel.to_world(C0[cf])[:, 1]
    top = [int(g) for g, y in zip(cf, h) if y >= h.max() - 1e-9]
    bottom = [int(g) for g in cf if g not in top]
    up = panel.rotation_matrix()[1, :2] / np.linalg.norm(panel.rotation_matrix()[1, :2])
    delta = np.zeros_like(C0)
    delta[top] += 0.035 * up  # the waist curve moved up 3.5 cm
    delta[bottom] -= 0.07 * up  # the hem down 7 cm
    cb = controls.of_panel(back)
    delta[cb] += 0.01  # the back panel edited, but not on a curve through its top
    out, held = _hold_tops(p, controls, C0, delta, {front: [(set(top), 0, 0.0)], back: [(set(), 1, 0.0)]})
    assert held == {}
    assert np.allclose(out[top] @ up, 0.0, atol=1e-12)
    assert np.allclose(out[bottom] @ up, -0.105, atol=1e-12)  # the panel grew by the same 10.5 cm
    assert np.allclose(out[cb], delta[cb])


def _skirt_band_top():
    """The base skirt_band, its control points (ControlPoints, positions (Nc, 2) [m]), the front
    band's panel index and control points, those of its top, and its upright unit direction (2,)."""
    from unsew.pattern.controls import find_control_points

    p = make_base_pattern("skirt_band")
    controls = find_control_points(p)
    C0 = controls.positions
    band = controls.panel_names.index("waistband_front")
    cb = controls.of_panel(band)
    panel = p.panels["waistband_front"]
    h = panel.to_world(C0[cb])[:, 1]
    top = [int(g) for g, y in zip(cb, h) if y >= h.max() - 1e-9]
    up = panel.rotation_matrix()[1, :2] / np.linalg.norm(panel.rotation_matrix()[1, :2])
    return p, controls, C0, band, cb, top, up


def test_hold_tops_keeps_a_band_and_lengthens_the_panels_below():
    """A waistband (open only along its top) whose waist curve is edited upward keeps its height,
    with its girth edit; the panels sewn to its bottom take the waist's rise below their tops, so
    the garment grows by the same length as when the band took it (held like the other panels,
    bands grew from 4 to 7.6 cm)."""
    from unsew.grading.grade import _hold_tops

    p, controls, C0, band, cb, top, up = _skirt_band_top()
    side = np.array([up[1], -up[0]])
    delta = np.zeros_like(C0)
    delta[top] += 0.03 * up + 0.01 * side  # the waist moved up 3 cm and widened
    out, held = _hold_tops(p, controls, C0, delta, {band: [(set(top), 0, 0.005)]})
    assert held == {}
    assert np.allclose(out[cb] @ up, 0.0, atol=1e-12)  # the band keeps its height
    assert np.allclose(out[top] @ side, 0.01, atol=1e-12)  # and its girth edit
    below = [n for n in controls.panel_names if not n.startswith("waistband")]
    assert below
    moved = 0
    for name in below:
        q = controls.panel_names.index(name)
        cq = controls.of_panel(q)
        pq = p.panels[name]
        uq = pq.rotation_matrix()[1, :2] / np.linalg.norm(pq.rotation_matrix()[1, :2])
        hq = pq.to_world(C0[cq])[:, 1]
        tq = [int(g) for g, y in zip(cq, hq) if y >= hq.max() - 0.01]
        lq = [int(g) for g in cq if g not in tq]
        assert np.allclose(out[tq], 0.0)  # their tops stay sewn to the band
        if any({s.a.panel, s.b.panel} == {"waistband_front", name} for s in p.stitches):
            assert np.allclose(out[lq] @ uq, -0.03, atol=1e-12)  # the rest moves down 3 cm
            moved += 1
    assert moved >= 1


def test_hold_tops_does_not_carry_a_rise_the_band_girth_explains():
    """A band top higher on the target and tighter by more than PASS_GIRTH_TOL (or lower and
    looser) is a band that sits where its girth meets the body: its rise is not carried down (the
    panels below keep their length) and the contour is named in a warning; the same rise with
    the girths agreeing, or the band also looser, is carried down."""
    from unsew.grading.grade import PASS_GIRTH_TOL, _hold_tops

    p, controls, C0, band, cb, top, up = _skirt_band_top()
    front = controls.of_panel(controls.panel_names.index("front"))
    for rise, dg, carried in (
        (0.05, -2 * PASS_GIRTH_TOL, False),
        (-0.05, 2 * PASS_GIRTH_TOL, False),
        (0.05, -0.5 * PASS_GIRTH_TOL, True),
        (0.05, 2 * PASS_GIRTH_TOL, True),
    ):
        delta = np.zeros_like(C0)
        delta[top] += rise * up
        out, held = _hold_tops(p, controls, C0, delta, {band: [(set(top), 7, dg)]})
        assert np.allclose(out[cb] @ up, 0.0, atol=1e-12)  # the band keeps its height either way
        assert (np.abs(out[front]).max() > 0.5 * abs(rise)) == carried, (rise, dg)
        assert (7 in held) == (not carried) and all("\n" not in w for w in held.values())


def test_carry_down_keeps_the_darts():
    """A waist's rise carried below the top of a darted skirt lengthens the panel but not its
    darts: their tips stay with the top, and the edit inverts no rest triangle (carried down
    with the rest, a 6.5 cm rise dragged the mesh across the dart legs: only 64 % of it was safe)."""
    from unsew.grading.edit import project_edit, safe_fraction
    from unsew.grading.grade import _carry_down, _dart_tips
    from unsew.pattern.params import PatternParams

    p = make_base_pattern("skirt_darts")
    params = PatternParams.build(p, mesh_pattern(p, edge_length=0.025))
    controls = params.controls
    C0 = params.control_points(params.K0).detach().numpy()
    out = np.zeros_like(C0)
    for name in ("front", "back"):
        _carry_down(p, controls, C0, out, name, 0.065)
    for name in ("front", "back"):
        panel = p.panels[name]
        ys = panel.to_world(panel.vertices)[:, 1]
        tips = _dart_tips(p, name, ys, ys.max() - 0.01)
        assert tips == {5, 8}  # the two dart tips of the panel's outline
        cq = controls.of_panel(controls.panel_names.index(name))
        for g in cq:
            v, moved = int(controls.vertex[g]), float(np.linalg.norm(out[g]))
            low = ys[v] < ys.max() - 0.01
            assert moved == pytest.approx(0.065 if low and v not in tips else 0.0, abs=1e-12), (name, v)
    assert safe_fraction(params, params.K0, project_edit(params, C0 + out)) == 1.0


def test_area_scaling_beyond_its_bound_is_said_in_one_line(body, tshirt):
    """GradingSettings.area sizes the pattern to the target's area; a target area the bounded
    scaling cannot reach leaves the pattern short of it with a one-line note, a reachable one none."""
    from unsew.grading.area import MAX_AREA_SCALE, pattern_area

    p, m = tshirt
    tx = flat_drape(p, m)
    a0 = pattern_area(p)
    for factor, warned in ((1.2, False), (4.0, True)):
        res = grade(
            p, body, tx, m.faces, GradingSettings(passes=1, area=factor * a0), mesh=m, drape_fn=flat_drape
        )
        assert (res.note is not None) == warned and "\n" not in (res.note or "")
        reached = pattern_area(res.pattern) / (factor * a0)
        assert (reached < 0.99) == warned, reached
    assert res.area_scales == [MAX_AREA_SCALE]


def test_a_waistband_is_a_strip():
    """waistbands(): the bands of the banded bases (4 cm high, a panel's girth wide), not
    GarmentCode's pencil-dress bodice halves, which are also open only above and sewn below at
    the waist but taller than wide (0.57 x 0.29 m)."""
    import warnings
    from pathlib import Path

    from unsew.grading.grade import BAND_ASPECT, waistbands
    from unsew.io.garmentcode import load_pattern

    assert waistbands(make_base_pattern("skirt_darts")) == ["waistband_front", "waistband_back"]
    case = (
        Path(__file__).resolve().parents[2] / "benchmarks" / "foreign" / "cases" / "dress_pencil_gc__default"
    )
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # its own seams differ in length; not what is tested
        dress = load_pattern(case / "pattern_gt.json")
    assert waistbands(dress) == []
    p = make_base_pattern("skirt_band")
    band = p.panels["waistband_front"]
    v = band.vertices.copy()
    up = band.rotation_matrix()[1, :2] / np.linalg.norm(band.rotation_matrix()[1, :2])
    width = np.ptp(v @ np.array([up[1], -up[0]]))
    band.vertices = v + np.outer((v - v.mean(axis=0)) @ up, up) * (0.6 * width / np.ptp(v @ up) - 1.0)
    # 0.6 x as high as wide
    assert 0.6 * width > width / BAND_ASPECT and "waistband_front" not in waistbands(p)


def _curve_of(p, controls, panel, label):
    """The OpenCurve of one labelled open edge of ``panel`` (its two end control points)."""
    from unsew.grading.curves import OpenCurve

    pi = controls.panel_names.index(panel)
    e = next(i for i, ed in enumerate(p.panels[panel].edges) if ed.label == label)
    edge = p.panels[panel].edges[e]
    cidx = controls.of_panel(pi)
    ends = [int(next(g for g in cidx if int(controls.vertex[g]) == v)) for v in (edge.start, edge.end)]
    return OpenCurve(
        panel=panel,
        panel_index=pi,
        edges=[e],
        start=int(edge.start),
        end=int(edge.end),
        controls=np.asarray(ends, dtype=np.int64),
        length3d=0.2,
    )


def test_an_armhole_moved_by_an_arm_contour_deepens():
    """A sleeveless bodice's armhole found further down a hanging arm lowers its underarm end by
    the whole move and keeps its shoulder end; a sleeve's hem, an armhole moved by a torso
    contour and one moved along a T-pose's level arm keep the paper's outward move."""
    import dataclasses

    from unsew.grading.edit import curve_edit, edit_directions
    from unsew.grading.grade import armhole_down, upright
    from unsew.pattern.controls import find_control_points

    p = make_base_pattern("tshirt_sleeveless")
    controls = find_control_points(p)
    C0 = controls.positions
    arm = _curve_of(p, controls, "front", "left_armhole")
    up = upright(p.panels["front"])
    bones = {b.name: b for b in default_body().skeleton.bones()}
    elbow = bones["left_elbow"]  # the default body's A-pose arm hangs
    down = armhole_down(p, C0, arm, controls, elbow)
    np.testing.assert_allclose(down, -up, atol=1e-12)
    assert armhole_down(p, C0, arm, controls, bones["spine"]) is None
    level = dataclasses.replace(elbow, b=elbow.a + np.array([elbow.length, 0.0, 0.0]))  # a T-pose arm
    assert armhole_down(p, C0, arm, controls, level) is None
    assert armhole_down(p, C0, arm, controls, None) is None
    delta = curve_edit(p, C0, arm, controls, extension=0.03, girth_change=0.0, deepen=down)
    h = C0[arm.controls] @ up
    low, high = arm.controls[np.argmin(h)], arm.controls[np.argmax(h)]
    np.testing.assert_allclose(delta[low], -0.03 * up, atol=1e-12)  # the underarm 3 cm lower
    np.testing.assert_allclose(delta[high], 0.0, atol=1e-12)  # the shoulder stays
    # the paper's edit of the same curve moves both ends out and up (what flared the underarm)
    d, _, _ = edit_directions(p, C0, arm, controls)
    assert d @ up > 0
    # a sleeve's hem runs down the arm already: no deepening
    ps = make_base_pattern("tshirt")
    cs = find_control_points(ps)
    hem = _curve_of(ps, cs, "left_sleeve", "hem")
    assert armhole_down(ps, cs.positions, hem, cs, elbow) is None
