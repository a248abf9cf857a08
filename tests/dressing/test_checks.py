"""check_drape: a good drape passes; exploded, fallen, off-the-body, inside-the-body and crumpled
drapes fail with one line naming why; unsew drape stops on a bad verdict and writes no --out."""

import numpy as np
import torch
import pytest

from unsew.body.body import default_body
from unsew.body.sdf import BodySDF
from unsew.errors import SimulationError
from unsew.sim.checks import (
    DROP_MAX,
    FAR_DIST,
    RISE_DIST,
    SEAM_GAP_MAX,
    STRETCH_MAX,
    TOP_DROP_MAX,
    SLEEVE_COVER_MIN,
    check_drape,
    check_dressed,
    sleeve_cover,
    sleeve_vertices,
    sleeves_judged,
)


@pytest.fixture(scope="module")
def body_sdf():
    b = default_body()
    return b, BodySDF.build(b)


def _tube(body, *, a=0.19, b=0.14, cz=0.02, y0=0.92, y1=1.1, n_around=48, n_up=8):
    """An elliptic cylinder of cloth round the waist (semi-axes a, b [m], centre z = cz [m]),
    clear of the arms: faces (F, 3), its flat pattern uv (Nu, 2) [m] (the same vertices: the
    cut at the back stays open) and 3D positions x (Nu, 3) [m] at rest (uv's first coordinate
    is the length along the polygon round the ellipse: every edge keeps its length)."""
    th = np.linspace(0.0, 2 * np.pi, n_around, endpoint=False)
    ring = np.stack([a * np.sin(th), b * np.cos(th) + cz], axis=1)  # (n_around, 2) x, z
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(ring, axis=0), axis=1))])
    y = np.linspace(y0, y1, n_up)
    S, Y = np.meshgrid(s, y)  # (n_up, n_around)
    uv = np.stack([S.ravel(), Y.ravel()], axis=1)
    R = np.tile(ring, (n_up, 1))
    x = np.stack([R[:, 0], uv[:, 1], R[:, 1]], axis=1)
    idx = np.arange(n_up * n_around).reshape(n_up, n_around)
    i, j, k, m = idx[:-1, :-1], idx[:-1, 1:], idx[1:, 1:], idx[1:, :-1]
    faces = np.concatenate([np.stack([i, j, k], -1).reshape(-1, 3), np.stack([i, k, m], -1).reshape(-1, 3)])
    return faces, uv, x


def _check(body, sdf, x, faces, uv, **kw):
    return check_drape(x, faces=faces, uv=uv, faces_uv=faces, body=body, sdf=sdf, **kw)


def test_good_drape_passes(body_sdf):
    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    v = _check(body, sdf, x, faces, uv, start_height=float(x[:, 1].mean()) + 0.03)
    assert v.ok and v.reason == "", v
    assert v.inside_pct == 0.0 and v.far_pct == 0.0
    assert v.stretch_max == pytest.approx(1.0, abs=0.01)
    assert v.y_min == pytest.approx(0.92) and v.y_max == pytest.approx(1.1)
    assert v.drop == pytest.approx(0.03) and v.area_ratio == pytest.approx(1.0, abs=0.01)
    v.raise_if_bad()  # no error


def test_exploded(body_sdf):
    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    bad = x.copy()
    bad[7] = np.nan
    v = _check(body, sdf, bad, faces, uv)
    assert not v.ok and v.reason.startswith("exploded") and "NaN" in v.reason and not v.finite
    with pytest.raises(SimulationError, match="drape failed: exploded"):
        v.raise_if_bad()
    # one vertex pulled far out: its edges stretch beyond the bound
    bad = x.copy()
    bad[100] += [0.0, 0.0, 0.3]
    v = _check(body, sdf, bad, faces, uv)
    assert not v.ok and v.reason.startswith("exploded") and v.stretch_max > STRETCH_MAX


def test_fallen(body_sdf):
    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    # at the feet: the top is below the crotch
    v = _check(body, sdf, x - [0.0, 0.8, 0.0], faces, uv)
    assert not v.ok and v.reason.startswith("fallen") and "crotch" in v.reason
    # through the floor
    v = _check(body, sdf, x - [0.0, 1.3, 0.0], faces, uv)
    assert not v.ok and v.reason.startswith("fallen") and "feet" in v.reason
    # slid 0.2 m down from where it was put on: still on the hips, but fallen
    v = _check(body, sdf, x, faces, uv, start_height=float(x[:, 1].mean()) + 0.2)
    assert not v.ok and "slid 0.20 m down" in v.reason
    # the same, judged vertex by vertex
    v = _check(body, sdf, x, faces, uv, start_y=x[:, 1] + 0.2)
    assert not v.ok and "slid 0.20 m down" in v.reason
    # cloth reaching over the shoulders whose top third (a hood put on above the head) fell
    # 0.5 m onto the head, the rest staying: the mean height dropped 0.17 m, the top 0.5 m, but
    # the garment did not slide
    shoulder = min(body.skeleton.position(j)[1] for j in ("left_shoulder", "right_shoulder"))
    faces_up, uv_up, x_up = _tube(body, a=0.26, b=0.18, y0=shoulder - 0.25, y1=shoulder + 0.05)
    y0 = x_up[:, 1].copy()
    y0[y0 > np.quantile(y0, 2 / 3)] += 0.5
    assert float((y0 - x_up[:, 1]).mean()) > DROP_MAX
    v = _check(body, sdf, x_up, faces_up, uv_up, start_y=y0)
    assert v.ok and v.drop == pytest.approx(0.0) and v.top_drop == pytest.approx(0.5), v.reason
    # the same fall ending round the waist: the top slid off the shoulders into a heap at the
    # hips, though most of the cloth (sleeves wrapped round the body) kept its height
    y0 = x[:, 1].copy()
    y0[y0 > np.quantile(y0, 2 / 3)] += 0.5
    v = _check(body, sdf, x, faces, uv, start_y=y0)
    assert v.drop == pytest.approx(0.0)
    assert not v.ok and "top slid 0.50 m down" in v.reason, v.reason
    # a top drop under TOP_DROP_MAX is settling, not sliding
    y0 = x[:, 1].copy()
    y0[y0 > np.quantile(y0, 2 / 3)] += 0.5 * TOP_DROP_MAX
    assert _check(body, sdf, x, faces, uv, start_y=y0).ok


def test_fallen_from_where_the_pattern_places_it(body_sdf):
    """A garment that started low and stayed there drops nothing from its start: judged against
    the pattern's own placement too, its top 0.3 m under that placement's (and under the
    shoulders) is fallen; 0.1 m under it is settling."""
    from types import SimpleNamespace

    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    mesh = SimpleNamespace(faces=faces, uv=uv, faces_uv=faces)
    d = SimpleNamespace(x=x, mesh=mesh, sdf=sdf, stats={}, x_start=x.copy())
    top = float(np.quantile(x[:, 1], 0.98))
    assert check_dressed(d, body=body).ok
    assert check_dressed(d, body=body, placed_top_m=top + 0.5 * TOP_DROP_MAX).ok
    v = check_dressed(d, body=body, placed_top_m=top + 0.3)
    assert not v.ok and v.reason.startswith("fallen")
    assert "0.30 m below where the pattern places it" in v.reason


def test_unsewn(body_sdf):
    """A drape whose sewing left a seam open wider than the bound asked for is unsewn (its
    garment merged from panels that never met); under the bound, or not asked, it passes."""
    from types import SimpleNamespace

    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    mesh = SimpleNamespace(faces=faces, uv=uv, faces_uv=faces)
    d = SimpleNamespace(x=x, mesh=mesh, sdf=sdf, stats={"seam_gap": 0.028}, x_start=x.copy())
    assert check_dressed(d, body=body).ok
    v = check_dressed(d, body=body, seam_gap_max=SEAM_GAP_MAX)
    assert not v.ok and v.reason.startswith("unsewn") and "28 mm open" in v.reason, v.reason
    d.stats["seam_gap"] = 0.008  # the widest of nineteen sound true-pattern drapes
    assert check_dressed(d, body=body, seam_gap_max=SEAM_GAP_MAX).ok


def _arm_ring(body, side, *, radius=0.08, sector=2 * np.pi, along=(0.3, 0.45, 0.6)):
    """Points (k, 3) [m] round the ``side`` upper arm's bone at ``radius``, over the angle ``sector``
    [rad] (the whole way round, or a sleeve bunched to one side of the arm), at the fractions
    ``along`` of the bone from shoulder to elbow."""
    a = np.asarray(body.skeleton.position(f"{side}_shoulder"))
    b = np.asarray(body.skeleton.position(f"{side}_elbow"))
    ax = (b - a) / np.linalg.norm(b - a)
    u = np.cross(ax, [0.0, 0.0, 1.0])
    u /= np.linalg.norm(u)
    w = np.cross(ax, u)
    th = np.linspace(0.0, sector, 48, endpoint=False)
    ring = np.cos(th)[:, None] * u + np.sin(th)[:, None] * w
    return np.concatenate([a + t * (b - a) + radius * ring for t in along])


def test_off_the_arm(body_sdf):
    """A sleeve whose cloth lies round its upper arm passes; the same cloth bunched to one side
    of the arm (the arm outside the sleeve) is off the arm; a sleeve with no cloth along the upper
    arm passes where it lies at the shoulder (a cap sleeve), and fails where it slid down off the
    arm."""
    from types import SimpleNamespace

    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    mesh = SimpleNamespace(faces=faces, uv=uv, faces_uv=faces)
    on, off = _arm_ring(body, "left"), _arm_ring(body, "left", sector=np.pi / 3)
    assert sleeve_cover(on, np.arange(len(on)), body, "left") == pytest.approx(1.0)
    assert sleeve_cover(off, np.arange(len(off)), body, "left") < SLEEVE_COVER_MIN
    for ring, ok in ((on, True), (off, False)):
        xs = np.concatenate([x, ring])
        d = SimpleNamespace(x=xs, mesh=mesh, sdf=sdf, stats={}, x_start=xs.copy())
        sleeves = {"left": np.arange(len(x), len(xs))}
        v = check_dressed(d, body=body, sleeves=sleeves)
        assert v.ok == ok, v.reason
        if not ok:
            assert v.reason.startswith("off the arm: the left sleeve covers 17 %"), v.reason
        # the fit's last verdict: the body's checks, then the sleeves
        w = sleeves_judged(_check(body, sdf, xs, faces, uv), xs, sleeves, body)
        assert (w.ok, w.reason) == (v.ok, v.reason)
    cap = _arm_ring(body, "left", along=(0.05, 0.12))
    assert np.isnan(sleeve_cover(cap, np.arange(len(cap)), body, "left"))
    cap = _arm_ring(body, "left", radius=0.1, along=(0.05, 0.12))
    with torch.no_grad():  # the cap's cloth outside the body: a ring there cuts into the torso
        cap = cap[sdf.query(torch.as_tensor(cap))[0].numpy() > 0.005]
    slid = _arm_ring(body, "left", along=(1.2, 1.3))  # down past the elbow, round the forearm
    assert np.isnan(sleeve_cover(slid, np.arange(len(slid)), body, "left"))
    for ring, ok in ((cap, True), (slid, False)):
        xs = np.concatenate([x, ring])
        d = SimpleNamespace(x=xs, mesh=mesh, sdf=sdf, stats={}, x_start=xs.copy())
        v = check_dressed(d, body=body, sleeves={"left": np.arange(len(x), len(xs))})
        assert v.ok == ok, v.reason
        if not ok:
            assert v.reason.startswith("off the arm: the left sleeve lies 0."), v.reason


def test_sleeve_vertices_of_a_placed_tee(body_sdf):
    """A tee's sleeves, as the wrapped start puts them round the arms, cover their upper arms; its
    torso's vertices are no sleeve's."""
    from unsew.body.placement import place_garment
    from unsew.meshing import mesh_pattern
    from unsew.pattern.base import make_base_pattern

    body, sdf = body_sdf
    pat = make_base_pattern("tshirt")
    mesh = mesh_pattern(pat, edge_length=0.04)
    sleeves = sleeve_vertices(pat, mesh, body)
    assert set(sleeves) == {"left", "right"}
    torso = [mesh.panel_names.index(n) for n in ("front", "back")]
    torso_x = set(mesh.x_of_u[np.isin(mesh.uv_panel, torso)].tolist())
    for idx in sleeves.values():  # the sleeve's own vertices, beyond the armhole seam it shares
        assert len(set(idx.tolist()) - torso_x) > 0.8 * len(idx)
    x_u = np.asarray(place_garment(pat, mesh, body, sdf=sdf))
    x = np.zeros((mesh.n_x, 3))
    x[mesh.x_of_u] = x_u
    for side, idx in sleeves.items():
        assert sleeve_cover(x, idx, body, side) >= 0.9, side


def test_rose(body_sdf):
    body, sdf = body_sdf
    chest = float(body.skeleton.position("chest")[1])
    faces, uv, x = _tube(body)  # round the waist, below the chest
    # put on hanging 0.3 m lower (its lower half): risen, but below the chest (a circle skirt's
    # hem flaring out rises as much)
    y0 = x[:, 1].copy()
    y0[y0 < np.median(y0)] -= 0.3
    v = _check(body, sdf, x, faces, uv, start_y=y0)
    assert v.ok and v.rise_pct == 0.0, v.reason
    # the same cloth ending round the shoulders, above the chest: gathered up round the neck
    up = [0.0, chest + 0.05 - float(x[:, 1].min()), 0.0]
    v = _check(body, sdf, x + up, faces, uv, start_y=y0 + up[1])
    assert not v.ok and v.reason.startswith("rose") and v.rise_pct > 40.0
    # lifted by less than RISE_DIST there: not risen
    v = _check(body, sdf, x + up, faces, uv, start_y=x[:, 1] + up[1] - 0.5 * RISE_DIST)
    assert v.rise_pct == 0.0 and not v.reason.startswith("rose")
    # without the start's heights there is no rise check
    assert np.isnan(_check(body, sdf, x, faces, uv).rise_pct)


def test_off_the_body(body_sdf):
    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    v = _check(body, sdf, x + [1.0, 0.0, 0.0], faces, uv)
    assert not v.ok and v.reason.startswith("off the body") and v.far_pct == 100.0
    assert FAR_DIST < 1.0


def test_hem_free_of_the_legs(body_sdf):
    """A skirt flaring out below the crotch (its hem 0.36 m further out than its waist) is on the
    body."""
    body, sdf = body_sdf
    from unsew.sim.checks import _crotch_height

    crotch = _crotch_height(body)
    ys = np.linspace(crotch - 0.6, 1.1, 24)
    out = 0.6 * np.maximum(crotch - ys, 0.0)  # (24,) flare [m]
    th = np.linspace(0.0, 2 * np.pi, 48, endpoint=False)
    rings = [np.stack([(0.19 + o) * np.sin(th), (0.14 + o) * np.cos(th) + 0.02], 1) for o in out]
    arc = [np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(r, axis=0), axis=1))]) for r in rings]
    x = np.concatenate([np.stack([r[:, 0], np.full(48, y), r[:, 1]], 1) for r, y in zip(rings, ys)])
    # the pattern: a flared panel, each row as wide as its ring round, as long as the slant
    slant = np.concatenate([[0.0], np.cumsum(np.hypot(np.diff(ys), np.diff(out)))])
    uv = np.concatenate([np.stack([a, np.full(48, t)], 1) for a, t in zip(arc, slant)])
    idx = np.arange(24 * 48).reshape(24, 48)
    i, j, k, m = idx[:-1, :-1], idx[:-1, 1:], idx[1:, 1:], idx[1:, :-1]
    faces = np.concatenate([np.stack([i, j, k], -1).reshape(-1, 3), np.stack([i, k, m], -1).reshape(-1, 3)])
    v = _check(body, sdf, x, faces, uv)
    assert v.ok, v.reason
    assert v.far_pct == 0.0 and v.area_ratio > 0.95
    # the same skirt lifted 0.6 m, its flare now above the crotch: that flare counts
    v = _check(body, sdf, x + [0.0, 0.6, 0.0], faces, uv)
    assert v.far_pct > 20.0


def test_inside_the_body(body_sdf):
    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    c = np.array([0.0, 0.0, 0.02])
    shrunk = c + (x - c) * [0.3, 1.0, 0.3]  # a 6 x 4 cm tube in the belly
    v = _check(body, sdf, shrunk, faces, uv)
    assert not v.ok and v.reason.startswith("inside the body") and v.inside_pct > 90.0


def test_crumpled(body_sdf):
    """A tube pushed together to 60 % of its height (its cloth gathered into a band, no fold
    to take it up) is crumpled; the same tube folded into pleats round the waist, every edge
    kept, is not."""
    body, sdf = body_sdf
    faces, uv, x = _tube(body)
    squashed = x.copy()
    squashed[:, 1] = 1.01 + 0.6 * (x[:, 1] - 1.01)
    v = _check(body, sdf, squashed, faces, uv)
    assert not v.ok and v.reason.startswith("crumpled"), v.reason
    assert v.area_ratio == pytest.approx(0.6, abs=0.02)
    # pleats: each ring's points pushed in and out by turns, the pattern cut from that pleated ring
    faces, uv, x = _tube(body, a=0.21, b=0.16)
    pleat = 1.0 + 0.08 * (np.arange(len(x)) % 2)
    px = np.stack([x[:, 0] * pleat, x[:, 1], 0.02 + (x[:, 2] - 0.02) * pleat], 1)
    ring = px[:48][:, [0, 2]]
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(ring, axis=0), axis=1))])
    puv = np.stack([np.tile(s, 8), uv[:, 1]], 1)
    v = _check(body, sdf, px, faces, puv)
    assert v.area_ratio == pytest.approx(1.0, abs=0.02), v
    assert not v.reason.startswith("crumpled"), v.reason


def test_drape_cli_refuses_a_bad_drape(tmp_path, capsys, monkeypatch):
    """A drape whose verdict is bad exits non-zero with one line and leaves no --out; with
    --keep-failed the garment is kept under a name that says so."""
    import unsew.sim.checks as checks
    from unsew.cli import main
    from unsew.io.garmentcode import save_pattern
    from unsew.pattern.base import make_base_pattern

    pj = tmp_path / "skirt.json"
    save_pattern(make_base_pattern("skirt"), pj)
    out = tmp_path / "garment.obj"
    small = ["--edge-length", "0.06", "--sew-steps", "5", "--settle-steps", "0", "--no-progress"]
    monkeypatch.setattr(checks, "INSIDE_MAX_PCT", -1.0)  # every drape now counts as inside the body
    assert main(["drape", str(pj), "--body", "default", *small, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "drape of skirt failed: inside the body" in err[0]
    assert not out.exists() and not (tmp_path / "garment.failed.obj").exists()
    assert main(["drape", str(pj), "--body", "default", *small, "--keep-failed", "--out", str(out)]) == 2
    assert not out.exists() and (tmp_path / "garment.failed.obj").is_file()
