"""fit/outputs.pattern_errors: the final, base and graded patterns each judged against the true one,
panels without a counterpart reported rather than sinking the metrics (fast: hand-made patterns)."""

from types import SimpleNamespace

import numpy as np

from unsew.fit.outputs import pattern_errors
from unsew.pattern.model import Edge, Panel, Pattern


def _rect(name, w, h, z):
    v = np.array([[0, 0], [w, 0], [w, h], [0, h]], float)
    return Panel(name, v, [Edge(i, (i + 1) % 4) for i in range(4)], np.array([0.0, 0.0, z]), np.zeros(3))


def test_pattern_errors_with_a_waistband_the_base_lacks():
    gt = Pattern(
        "gt",
        {
            "front": _rect("front", 0.4, 0.5, 0.2),
            "back": _rect("back", 0.4, 0.5, -0.2),
            "waistband": _rect("waistband", 0.8, 0.05, 0.0),
        },
    )
    base = Pattern("base", {"front": _rect("front", 0.3, 0.5, 0.2), "back": _rect("back", 0.3, 0.5, -0.2)})
    graded = Pattern(
        "graded", {"front": _rect("front", 0.4, 0.55, 0.2), "back": _rect("back", 0.4, 0.55, -0.2)}
    )
    result = SimpleNamespace(pattern=graded, base_pattern=base, graded_pattern=graded)
    m = pattern_errors(result, gt)
    assert set(m) == {"pattern", "pattern_base", "pattern_graded"}
    for key in m:
        assert m[key]["unmatched"] == {"estimated": [], "true": ["waistband"]}
    # graded: front/back 0.22 m^2 each against 0.20, the 0.04 m^2 waistband missing: total area exact
    assert abs(m["pattern_graded"]["area_error_total_rel"]) < 1e-9
    assert abs(m["pattern_graded"]["area_error_weighted_rel"] - 0.08 / 0.44) < 1e-9
    assert abs(m["pattern_base"]["area_error_weighted_rel"] - (0.1 + 0.04) / 0.44) < 1e-9
    assert m["pattern"]["area_error_weighted_rel"] < m["pattern_base"]["area_error_weighted_rel"]


def test_pattern_errors_keeps_the_others_when_one_cannot_be_compared():
    gt = Pattern("gt", {"front": _rect("front", 0.4, 0.5, 0.2)})
    empty = Pattern("empty", {})
    result = SimpleNamespace(pattern=gt.copy(), base_pattern=empty, graded_pattern=None)
    m = pattern_errors(result, gt)
    assert "error" in m["pattern_base"] and "pattern_graded" not in m
    assert m["pattern"]["area_error_weighted_rel"] == 0.0


def test_the_exported_pattern_is_placed_where_it_draped():
    """Each panel of the exported pattern facing front or back moves within its own plane to
    where the fit's drape has it: a tee draped 8 cm higher, 2 cm to the side and 5 cm forward
    than its placement is exported 8 cm higher and 2 cm to the side, its front and back no nearer
    the body; a sleeve turned out of the front plane keeps its placement."""
    from unsew.fit.outputs import placed_where_draped
    from unsew.meshing import mesh_pattern
    from unsew.pattern.base import make_base_pattern

    p = make_base_pattern("tshirt")
    p.stitches = []  # every rest vertex its own: the drape is the placement shifted, exactly
    mesh = mesh_pattern(p, edge_length=0.05)
    shift = np.array([0.02, 0.08, 0.05])
    x = np.zeros((mesh.n_x, 3))
    x[np.asarray(mesh.x_of_u)] = np.asarray(mesh.uv_placed3d) + shift
    out = placed_where_draped(p, mesh, mesh.uv, x)
    for name, pan in out.panels.items():
        moved = pan.translation - p.panels[name].translation
        n = pan.rotation_matrix()[:, 2]
        facing = abs(n[2]) > np.cos(np.radians(30.0))
        assert np.allclose(moved, shift - (shift @ n) * n if facing else 0.0, atol=1e-9), name
        assert np.allclose(pan.rotation, p.panels[name].rotation) and np.allclose(
            pan.vertices, p.panels[name].vertices
        )
    assert np.allclose(out.panels["front"].translation - p.panels["front"].translation, [0.02, 0.08, 0.0])
    assert any(abs(pan.rotation_matrix()[2, 2]) < 0.99 for pan in out.panels.values())  # a turned panel
    assert np.allclose(p.panels["front"].translation, make_base_pattern("tshirt").panels["front"].translation)


def test_a_panel_hanging_from_its_open_top_is_placed_at_the_height_it_drapes():
    """A drafted skirt hangs from its band's open top. Exported, the band is placed so that top
    lies where the drape has it: held where placed (within a few millimetres), it stays however
    the hem below hangs; draped 5 cm lower (grading lifted its start, or the drape slid free),
    it goes 5 cm down and not sideways, so a simulator that holds that edge where the file
    places it hangs the skirt where the fit's drape hangs."""
    from unsew.fit.outputs import placed_where_draped
    from unsew.meshing import mesh_pattern
    from unsew.pattern.design import Design, draft

    p = draft(Design(garment="skirt", waistband=True))
    held = {n for n, pa in p.panels.items() for e in pa.edges if e.label == "lower_interface"}
    assert held and held < set(p.panels)
    mesh = mesh_pattern(p, edge_length=0.05)
    placed = np.zeros((mesh.n_x, 3))
    placed[np.asarray(mesh.x_of_u)] = np.asarray(mesh.uv_placed3d)
    band = np.isin(np.asarray(mesh.uv_panel), [mesh.panel_names.index(n) for n in held])
    below = placed[:, 1] < placed[np.asarray(mesh.x_of_u)[band], 1].min()
    out = placed_where_draped(p, mesh, mesh.uv, placed - np.where(below[:, None], [0.0, 0.05, 0.0], 0.0))
    for name in held:
        assert np.allclose(out.panels[name].translation, p.panels[name].translation, atol=1e-9), name
    out = placed_where_draped(p, mesh, mesh.uv, placed - [0.0, 0.002, 0.0])  # held, 2 mm lower
    for name in held:
        assert np.allclose(out.panels[name].translation, p.panels[name].translation, atol=1e-9), name
    shift = np.array([0.03, -0.05, 0.02])
    out = placed_where_draped(p, mesh, mesh.uv, placed + shift)
    for name, pan in out.panels.items():
        moved = pan.translation - p.panels[name].translation
        if name in held:
            assert np.allclose(moved, [0.0, -0.05, 0.0], atol=1e-9), (name, moved)
        else:  # a gore moves within its plane (its top's seam copies take the band's positions)
            n = pan.rotation_matrix()[:, 2]
            assert np.allclose(moved, shift - (shift @ n) * n, atol=1e-3), (name, moved)


def test_a_sleeves_halves_are_exported_laid_round_the_arm():
    """Given the wearer, the front and back halves of a two-piece sleeve are exported as another
    simulator sews them round the arm: each turned onto where it drapes (here unsew's wrapped
    start stands for the drape), its long side along the upper arm, in front of the arm and
    behind it, every vertex of its drape between the flat half and the arm's bone. Without the
    wearer they stay where their drape's centroid puts them in their own plane, as before."""
    from unsew.body.body import default_body
    from unsew.body.placement import panel_roles, place_garment
    from unsew.fit.outputs import placed_where_draped
    from unsew.meshing import mesh_pattern
    from unsew.pattern.design import Design, draft

    body = default_body()
    p = draft(Design(garment="tshirt", sleeves="short", sleeve_pieces=2))
    mesh = mesh_pattern(p, edge_length=0.03)
    xu = np.asarray(place_garment(p, mesh, body))  # (Nu, 3) the panels wrapped round the body
    x = np.zeros((mesh.n_x, 3))
    x[np.asarray(mesh.x_of_u)] = xu
    roles = panel_roles(p, body)
    halves = [n for n, r in roles.items() if r.endswith("_sleeve")]
    assert len(halves) == 4
    out = placed_where_draped(p, mesh, mesh.uv, x, body)
    on = np.asarray(mesh.uv_panel)
    for name in halves:
        side = roles[name].split("_")[0]
        sh, el = body.skeleton.position(f"{side}_shoulder"), body.skeleton.position(f"{side}_elbow")
        axis = (el - sh) / np.linalg.norm(el - sh)
        pan = out.panels[name]
        n = pan.rotation_matrix()[:, 2]
        assert abs(n @ axis) < 0.35, name  # the half lies along the arm
        draped = xu[on == mesh.panel_names.index(name)]
        flat = pan.to_world(np.asarray(mesh.uv)[on == mesh.panel_names.index(name)])
        c = flat.mean(axis=0)
        out_dir = (c - sh) - ((c - sh) @ axis) * axis
        n_out = n if n @ out_dir > 0 else -n
        assert ((draped - c) @ n_out).max() <= 1e-9, name  # the drape between it and the bone
        assert ((flat - sh) @ n_out).min() > 0.0, name  # the flat half outside the bone
    fronts = [out.panels[n].to_world(out.panels[n].vertices)[:, 2].mean() for n in halves if "front" in n]
    backs = [out.panels[n].to_world(out.panels[n].vertices)[:, 2].mean() for n in halves if "back" in n]
    assert min(fronts) > 0.0 > max(backs)
    free = placed_where_draped(p, mesh, mesh.uv, x)
    assert all(np.allclose(free.panels[n].rotation, p.panels[n].rotation) for n in halves)
