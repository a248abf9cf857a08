"""render_mesh / render_views / render_comparison: size, projection, views, depth order, colours."""

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.report.render import (
    Layout,
    project,
    render_comparison,
    render_mesh,
    render_views,
    view_rotation,
)


def _bbox(mask):
    rows = np.flatnonzero(mask.any(axis=1))
    cols = np.flatnonzero(mask.any(axis=0))
    return rows[0], rows[-1], cols[0], cols[-1]


def test_png_has_requested_size(tmp_path, meshes):
    v, f = meshes.box((0.3, 0.5, 0.2))
    for size in [(320, 240), (200, 360)]:
        p = render_mesh(tmp_path / f"b{size[0]}.png", v, f, size_px=size)
        img = meshes.read_png(p)
        assert img.shape[:2] == (size[1], size[0])


def test_view_frames_are_right_handed_and_follow_the_convention():
    # front: looking along -Z at the front, screen right = +X (the body's left), up = +Y
    np.testing.assert_allclose(view_rotation("front"), np.eye(3), atol=1e-12)
    np.testing.assert_allclose(view_rotation("back")[0], [-1, 0, 0], atol=1e-12)
    np.testing.assert_allclose(view_rotation("side")[2], [1, 0, 0], atol=1e-12)  # camera at +X
    for view in ("front", "side", "back", "three_quarter"):
        R = view_rotation(view)
        np.testing.assert_allclose(R @ R.T, np.eye(3), atol=1e-12)
        assert np.linalg.det(R) == pytest.approx(1.0)
    # a point in front of the body is nearer the viewer than one behind it, in the front view
    d = project(np.array([[0, 0, 0.3], [0, 0, -0.3]]), "front")[:, 2]
    assert d[0] > d[1]


@pytest.mark.parametrize("view,width", [("front", 0.4), ("side", 0.2), ("back", 0.4)])
def test_silhouette_is_centred_with_the_projected_aspect(tmp_path, meshes, view, width):
    # a 0.4 (X) x 0.8 (Y) x 0.2 (Z) m box away from the origin: framed, it is centred, its
    # height fills 1 / (1 + 2 margin) of the drawing area, and its width follows the projection
    v, f = meshes.box((0.4, 0.8, 0.2), center=(0.1, 1.0, -0.05))
    margin = 0.1
    p = render_mesh(tmp_path / "s.png", v, f, view=view, size_px=(400, 400), margin=margin)
    mask = meshes.ink_mask(meshes.read_png(p))
    r0, r1, c0, c1 = _bbox(mask)
    h, w = r1 - r0 + 1, c1 - c0 + 1
    assert (r0 + r1) / 2 == pytest.approx(199.5, abs=2.0)
    assert (c0 + c1) / 2 == pytest.approx(199.5, abs=2.0)
    assert w / h == pytest.approx(width / 0.8, rel=0.03)
    drawable = 400 - 24  # the renderer keeps a 12 px border on each side
    assert h == pytest.approx(drawable / (1 + 2 * margin), abs=4)


def test_views_put_the_bodys_left_where_the_convention_says(tmp_path, meshes):
    # a big box and a small marker box on the body's left (+X) front (+Z)
    bv, bf = meshes.box((0.4, 0.6, 0.2))
    mv, mf = meshes.box((0.1, 0.1, 0.1), center=(0.3, 0.0, 0.15))
    v = np.concatenate([bv, mv])
    f = np.concatenate([bf, mf + len(bv)])
    colour = np.r_[np.zeros(len(bv)), np.ones(len(mv))]  # the marker is yellow in viridis
    p = render_views(
        tmp_path / "v.png",
        v,
        f,
        vertex_values=colour,
        layout=Layout(views=("front", "back", "side"), size_px=(900, 400)),
    )
    img = meshes.read_png(p)
    yellow = (img[..., 0] > 0.6) & (img[..., 1] > 0.6) & (img[..., 2] < 0.45)
    cols = np.flatnonzero(yellow.any(axis=0))
    thirds = [cols[(cols >= k * 300) & (cols < (k + 1) * 300)] - k * 300 for k in range(3)]
    assert all(len(t) for t in thirds), "the marker is seen in every view"
    assert thirds[0].mean() > 150  # front: the body's left is on the viewer's right
    assert thirds[1].mean() < 150  # back: on the viewer's left
    assert thirds[2].mean() < 150  # side, seen from the left: the front (+Z) is on screen left


def test_painter_hides_what_is_behind(tmp_path, meshes):
    # the garment is a small box in front of (+Z) a big body box: seen from the front its colour
    # is at the centre; seen from the back the body hides it
    gv, gf = meshes.box((0.2, 0.2, 0.05), center=(0, 0, 0.2))
    bv, bf = meshes.box((0.5, 0.5, 0.2), n=6)
    common = dict(body=(bv, bf), frame="all", size_px=(200, 200), color=(0.1, 0.3, 0.9))
    front = meshes.read_png(render_mesh(tmp_path / "f.png", gv, gf, view="front", **common))
    back = meshes.read_png(render_mesh(tmp_path / "b.png", gv, gf, view="back", **common))
    cf, cb = front[100, 100], back[100, 100]
    assert cf[2] > cf[0] + 0.2  # blue garment
    assert abs(cb[0] - cb[2]) < 0.03 and cb[0] > 0.3  # grey body


def test_colour_map_is_monotonic_along_the_values(tmp_path, meshes):
    v, f = meshes.plane(0.6, 0.3, n=30)
    vals = v[:, 0] * 10.0  # increases to the right in the front view
    p = render_mesh(
        tmp_path / "c.png", v, f, vertex_values=vals, cmap="gray", size_px=(400, 300), colorbar_label="x [dm]"
    )
    img = meshes.read_png(p)
    mask = meshes.ink_mask(img, tol=0.0) & (img.std(axis=2) < 0.02)
    r0, r1, c0, c1 = _bbox(mask[:200])  # the plane (the colour bar is at the bottom)
    row = img[(r0 + r1) // 2, c0 + 3 : c1 - 3].mean(axis=1)
    assert row[-1] - row[0] > 0.3, "the values span a visible range"
    # faces are flat-coloured, so compare at the scale of a face (about 10 px here)
    samples = [row[max(k - 4, 0) : k + 5].mean() for k in np.linspace(0, len(row) - 1, 16).astype(int)]
    assert np.all(np.diff(samples) > 0), "brightness goes up with the value"
    assert np.all(np.diff(row) > -0.04), "no pixel-level dip beyond a face's colour step"
    # without values the plane is one flat colour
    p2 = render_mesh(tmp_path / "u.png", v, f, size_px=(400, 300))
    flat = meshes.read_png(p2)
    r = (r0 + r1) // 2
    assert np.ptp(flat[r, c0 + 5 : c1 - 5], axis=0).max() < 0.03


def test_values_outside_vmin_vmax_are_clipped(tmp_path, meshes):
    v, f = meshes.plane(0.6, 0.3, n=30)
    vals = v[:, 0] * 10.0  # -3 .. 3
    p = render_mesh(
        tmp_path / "c.png", v, f, vertex_values=vals, cmap="gray", vmin=-1, vmax=1, size_px=(400, 300)
    )
    img = meshes.read_png(p)
    row = img[100]
    ink = np.flatnonzero(meshes.ink_mask(img[:200]).any(axis=0))
    left, right = row[ink[0] + 3 : ink[0] + 30].mean(), row[ink[-1] - 30 : ink[-1] - 3].mean()
    assert left < 0.1 and right > 0.5
    assert np.ptp(row[ink[-1] - 60 : ink[-1] - 3]) < 0.03  # saturated at vmax


def test_overlay_body_and_comparison(tmp_path, meshes):
    gv, gf = meshes.box((0.3, 0.5, 0.2), n=6)
    tv = gv * 1.05
    bv, bf = meshes.box((0.25, 0.8, 0.15), n=6)
    base = meshes.read_png(render_mesh(tmp_path / "g.png", gv, gf, size_px=(200, 250)))
    for style in ("ghost", "wire"):
        p = render_mesh(
            tmp_path / f"{style}.png",
            gv,
            gf,
            overlay=(tv, gf),
            overlay_style=style,
            body=(bv, bf),
            size_px=(200, 250),
        )
        img = meshes.read_png(p)
        assert img.shape == base.shape
        assert np.abs(img - base).max() > 0.2  # the overlay shows
    d = np.linalg.norm(tv - gv, axis=1) * 1000
    p = render_comparison(
        tmp_path / "cmp.png",
        (tv, gf),
        (gv, gf),
        distance_mm=d,
        body=(bv, bf),
        layout=Layout(views=("front", "three_quarter"), title="target vs result"),
    )
    img = meshes.read_png(p)
    assert img.shape[1] == 720 and meshes.ink_mask(img).mean() > 0.1


def test_bad_input_is_a_clear_error(tmp_path, meshes):
    v, f = meshes.box((0.3, 0.5, 0.2))
    with pytest.raises(InputError, match="faces index vertices"):
        render_mesh(tmp_path / "x.png", v, f + 1000)
    with pytest.raises(InputError, match="unknown view"):
        render_mesh(tmp_path / "x.png", v, f, view="top")
    with pytest.raises(InputError, match="vertex_values"):
        render_mesh(tmp_path / "x.png", v, f, vertex_values=np.zeros(3))
    with pytest.raises(InputError, match=r"shape \(V, 3\)"):
        render_mesh(tmp_path / "x.png", v[:, :2], f)
    with pytest.raises(InputError, match="NaN"):
        render_mesh(tmp_path / "x.png", np.where(v > 0.1, np.nan, v), f)
    assert not (tmp_path / "x.png").exists()
