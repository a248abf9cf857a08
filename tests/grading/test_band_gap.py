"""Waistbands sized for unsew's contact (grading's ``band_gap="target"``): the target loop's
contact excess (unsew.grading.band_gap) and the band's girth edit carried down its sides
(unsew.grading.grade._band_girth_down)."""

from __future__ import annotations

import numpy as np
import pytest
import trimesh

from unsew.errors import InputError
from unsew.grading.band_gap import OWN_GAP, PRESSED_TOL, pressed_loop_excess
from unsew.pattern.base import make_base_pattern


class _Body:
    """A closed cylinder of radius ``r`` [m] about the y axis (verts, faces, as a Body has)."""

    def __init__(self, r: float):
        m = trimesh.creation.cylinder(radius=r, height=1.0, sections=256)
        m.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 2, [1, 0, 0]))
        self.verts = np.asarray(m.vertices, dtype=np.float64)
        self.faces = np.asarray(m.faces)


class _Loop:
    def __init__(self, index, indices):
        self.index = index

        class _C:
            pass

        self.contour = _C()
        self.contour.indices = np.asarray(indices)


def _target(r: float, gaps):
    """Target vertices (rings of 200 points each, at y 0.1 k, ``gaps[k]`` [m] off the cylinder
    of radius ``r``) and one loop per ring, plus a patch of many points pressed at the first gap
    so the target's 1st percentile reads it."""
    pts, loops = [], []
    for k, g in enumerate(gaps):
        a = np.linspace(0, 2 * np.pi, 200, endpoint=False)
        ring = np.stack([(r + g) * np.cos(a), np.full_like(a, 0.1 * k - 0.2), (r + g) * np.sin(a)], axis=1)
        loops.append(_Loop(k, np.arange(len(pts) * 200, (len(pts) + 1) * 200)))
        pts.append(ring)
    return np.concatenate(pts), loops


def test_a_pressed_loop_owes_its_gap_and_a_loose_one_nothing():
    """On a cylinder, a loop pressed at the target's gap of 4 mm owes 2 pi (4 - 1) mm (newton's
    cloth against unsew's), one 1 mm farther out the same (the gap, not its own distance), one
    beyond PRESSED_TOL (a hem) nothing; a target resting as near as unsew's own cloth nothing."""
    body = _Body(0.13)
    tv, loops = _target(0.13, [0.004, 0.004, 0.005, 0.004 + PRESSED_TOL + 0.004])
    ex = pressed_loop_excess(tv, loops, body)
    want = 2 * np.pi * (0.004 - OWN_GAP)
    assert ex[0] == pytest.approx(want, rel=0.02)
    assert ex[1] == pytest.approx(want, rel=0.02)
    assert ex[2] == pytest.approx(want, rel=0.02)  # a loop with 1 mm of ease keeps it
    assert 3 not in ex
    tv, loops = _target(0.13, [OWN_GAP * 0.8, OWN_GAP * 0.8])
    assert pressed_loop_excess(tv, loops, body) == {}


def _band_edit(name: str, narrow: float):
    """The base ``name`` (a banded pattern), its control points and C0, and an edit that moves
    the front band's two top corners ``narrow`` [m] inward each (world x), as a girth edit does."""
    from unsew.pattern.controls import find_control_points

    p = make_base_pattern(name)
    controls = find_control_points(p)
    C0 = controls.positions
    band = p.panels["waistband_front"]
    cb = controls.of_panel(controls.panel_names.index("waistband_front"))
    w = band.to_world(C0[cb])
    top = cb[w[:, 1] >= w[:, 1].max() - 1e-9]
    ex = band.rotation_matrix()[0, :2]
    delta = np.zeros_like(C0)
    for g in top:
        sign = -1.0 if band.to_world(C0[[g]])[0, 0] > 0 else 1.0
        delta[g] += sign * narrow * ex / float(ex @ ex)
    return p, controls, C0, delta, cb


def _world_dx(p, controls, out, name):
    q = controls.of_panel(controls.panel_names.index(name))
    R = p.panels[name].rotation_matrix()
    return q, (out[q] @ R[:, :2].T)[:, 0]


@pytest.mark.parametrize("name", ["skirt_darts", "pants_band"])
def test_a_band_narrowed_at_its_top_narrows_its_bottom_and_the_waist_seam_below(name):
    """The band's top corners moved 1 cm inward each: its bottom corners move with them, and the
    vertex sewn to each bottom corner on the panels below moves as far across the body; the back
    band (sewn at the band's sides) and every other vertex stay; without ``band_whole`` only the
    top moves (a trapezoid over the base's waist seam)."""
    from unsew.grading.grade import _hold_tops

    p, controls, C0, delta, cb = _band_edit(name, 0.01)
    band_i = controls.panel_names.index("waistband_front")
    top = {int(g) for g in np.flatnonzero(np.abs(delta).sum(axis=1) > 0)}
    for whole in (False, True):
        out, _ = _hold_tops(p, controls, C0, delta, {band_i: [(top, 0, -0.02)]}, band_whole=whole)
        _, dx = _world_dx(p, controls, out, "waistband_front")
        w = p.panels["waistband_front"].to_world(C0[cb])
        low = w[:, 1] <= w[:, 1].min() + 1e-9
        corners = low & ((w[:, 0] == w[low, 0].min()) | (w[:, 0] == w[low, 0].max()))
        assert np.allclose(np.abs(dx[corners]), 0.01 if whole else 0.0, atol=1e-12)
        assert np.allclose(dx[low & ~corners], 0.0)
        # inward
        assert np.allclose(dx[corners] * np.sign(w[corners, 0]), -0.01 if whole else 0.0, atol=1e-12)
        moved_below = 0
        for other in controls.panel_names:
            if other == "waistband_front":
                continue
            q, odx = _world_dx(p, controls, out, other)
            if other.startswith("waistband"):
                assert np.allclose(out[q], 0.0)
                continue
            hit = np.flatnonzero(np.abs(odx) > 1e-12)
            assert np.allclose(np.abs(odx[hit]), 0.01, atol=1e-12)
            ow = p.panels[other].to_world(C0[q])
            assert np.all(ow[hit, 1] >= ow[:, 1].max() - 0.01)  # only its top
            moved_below += len(hit)
        assert (moved_below >= 2) == whole


def test_the_band_edit_keeps_the_waist_seam_matched_and_meshable():
    """Narrowed as a whole with the skirt's waist, the darted skirt's band takes the top's 2.4 cm
    at its bottom too, stays sewn to edges as long as its own, and the edit inverts no rest
    triangle."""
    from unsew.grading.edit import project_edit, safe_fraction
    from unsew.grading.grade import _hold_tops
    from unsew.meshing.sew import mesh_pattern
    from unsew.pattern.params import PatternParams
    from unsew.pattern.curves import edge_length
    from unsew.pattern.seams import stitch_length_ratios

    p, _, _, _, _ = _band_edit("skirt_darts", 0.012)
    params = PatternParams.build(p, mesh_pattern(p, edge_length=0.025))
    controls = params.controls
    C0 = params.control_points(params.K0).detach().numpy()
    delta, edited = np.zeros_like(C0), {}
    for name in ("waistband_front", "waistband_back"):  # both pieces, as their contour edits them
        band = p.panels[name]
        cb = controls.of_panel(controls.panel_names.index(name))
        w = band.to_world(C0[cb])
        top = cb[w[:, 1] >= w[:, 1].max() - 1e-9]
        ex = band.rotation_matrix()[0, :2]
        for g in top:
            delta[g] -= np.sign(band.to_world(C0[[g]])[0, 0]) * 0.012 * ex / float(ex @ ex)
        edited[controls.panel_names.index(name)] = [({int(g) for g in top}, 0, -0.024)]
    out, _ = _hold_tops(p, controls, C0, delta, edited, band_whole=True)
    K1 = project_edit(params, C0 + out)
    assert safe_fraction(params, params.K0, K1) == 1.0
    graded = params.to_pattern(K1)
    r = stitch_length_ratios(graded)
    assert np.all(np.abs(r - 1.0) < 0.02), r

    def bottom(pat):  # the front band's bottom edges [m]: the waist seam
        b = pat.panels["waistband_front"]
        ys = b.to_world(b.vertices)[:, 1]
        return sum(
            edge_length(b, k)
            for k, e in enumerate(b.edges)
            if ys[e.start] < ys.mean() and ys[e.end] < ys.mean()
        )

    assert bottom(graded) == pytest.approx(bottom(p) - 0.024, abs=1e-3)


def test_grade_refuses_an_unknown_band_gap():
    from unsew.grading.grade import GradingSettings, grade

    with pytest.raises(InputError, match="band_gap"):
        grade(
            make_base_pattern("skirt_darts"),
            None,
            np.zeros((3, 3)),
            np.array([[0, 1, 2]]),
            GradingSettings(band_gap="loose"),
        )


def test_the_fit_config_takes_band_gap():
    from unsew.fit.config import FitConfig, load_config

    assert FitConfig().band_gap == "target"  # the default (docs/decisions/009)
    assert load_config(band_gap="none").band_gap == "none"
    with pytest.raises(InputError, match="band_gap"):
        load_config(band_gap="tight")


def test_only_a_garment_hanging_from_its_band_is_sized_for_the_contact():
    """A skirt (open contours on the torso only) hangs from its band; trousers and shorts (a
    contour on each leg) are held by their crotch too, and keep their band as measured."""
    from unsew.grading.band_gap import hangs_from_band

    class C:
        def __init__(self, part):
            self.part = part

    assert hangs_from_band([C("torso"), C("torso")])
    assert not hangs_from_band([C("torso"), C("left_leg"), C("right_leg")])
    assert hangs_from_band([])
