"""A pattern's open edges labelled as the edges it hangs from (GarmentCode's ``lower_interface``,
``strapless_top``) are held at the height its own placement gives them."""

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.body.sdf import BodySDF
from unsew.dress import DRESS_SETTINGS, attached_vertices, dress, held_anchors, settle
from unsew.meshing import mesh_pattern
from unsew.pattern.base import make_base_pattern
from unsew.sim.checks import check_dressed

SETTINGS = DRESS_SETTINGS.replace(edge_length=0.04)


@pytest.fixture(scope="module")
def body_sdf():
    b = default_body()
    return b, BodySDF.build(b)


def _edge(pattern, label: str) -> int:
    """The edge number labelled ``label`` in each panel of unsew's skirt (the same in both)."""
    (k,) = {i for pa in pattern.panels.values() for i, e in enumerate(pa.edges) if e.label == label}
    return k


def _waist_heights(d, mesh, waist: int) -> np.ndarray:
    v = np.concatenate([mesh.edge_verts[(name, waist)] for name in d.pattern.panels])
    return d.x.numpy()[np.asarray(mesh.x_of_u)[v], 1]


@pytest.fixture(scope="module")
def skirts(body_sdf):
    """unsew's skirt with its waist labelled ``lower_interface`` and without, both dressed."""
    body, sdf = body_sdf
    plain = make_base_pattern("skirt")
    waist = _edge(plain, "waist")
    held = make_base_pattern("skirt")
    for pa in held.panels.values():
        pa.edges[waist].label = "lower_interface"
    d_plain = dress(plain, body, sdf=sdf, settings=SETTINGS)
    d_held = dress(held, body, sdf=sdf, settings=SETTINGS)
    return waist, d_plain, d_held


def test_a_waist_labelled_lower_interface_is_held_where_the_pattern_puts_it(body_sdf, skirts):
    body, sdf = body_sdf
    waist, d_plain, d_held = skirts
    mesh = d_held.mesh
    idx, height = attached_vertices(d_held.pattern, mesh, body, sdf)
    on_waist = np.concatenate([mesh.edge_verts[(n, waist)] for n in d_held.pattern.panels])
    assert set(idx.tolist()) == set(on_waist.tolist())
    assert check_dressed(d_held, body=body).ok and d_held.stats["held"] == len(idx)
    y = d_held.x.numpy()[np.asarray(mesh.x_of_u)[idx.numpy()], 1]
    assert np.abs(y - height.numpy()).max() < 0.01 and abs(y.mean() - height.numpy().mean()) < 3e-3
    # left free, the same skirt's waist settles lower: the hold did the work
    assert _waist_heights(d_plain, d_plain.mesh, waist).mean() < height.numpy().mean() - 0.03


def test_later_drapes_hold_what_the_dressing_held(body_sdf, skirts):
    """held_anchors reads the hold off a drape (the fit's start); settle() keeps it in another fabric."""
    body, sdf = body_sdf
    _, d_plain, d_held = skirts
    anchors = held_anchors(d_held.pattern, d_held.mesh, body, sdf, d_held.x.numpy())
    assert anchors is not None
    assert held_anchors(d_held.pattern, d_held.mesh, body, sdf, d_plain.x.numpy()) is None
    x = settle(d_held.mesh, d_held.x.numpy(), sdf, "silk", settings=SETTINGS, anchors=anchors)
    y = x[np.asarray(d_held.mesh.x_of_u)[anchors[0].numpy()], 1]
    assert np.abs(y - anchors[1].numpy()).max() < 0.01


def test_only_open_edges_are_held(body_sdf):
    body, sdf = body_sdf
    p = make_base_pattern("skirt")
    hem = _edge(p, "hem")
    sewn = p.stitches[0].a
    p.panels[sewn.panel].edges[sewn.edge].label = "lower_interface"  # a seam: it hangs from its panels
    mesh = mesh_pattern(p, edge_length=SETTINGS.edge_length)
    assert attached_vertices(p, mesh, body, sdf) is None
    for pa in p.panels.values():
        pa.edges[hem].label = "strapless_top"
    idx, _ = attached_vertices(p, mesh, body, sdf)
    assert set(idx.tolist()) == set(np.concatenate([mesh.edge_verts[(n, hem)] for n in p.panels]).tolist())


@pytest.mark.parametrize(
    "kw",
    [
        dict(garment="skirt", skirt="circle"),
        dict(garment="skirt", waistband=True, panels=4),
        dict(garment="skirt", skirt="pencil", darts=True),
        dict(garment="pants", darts=True),
        dict(garment="shorts", waistband=True),
        dict(garment="dress", waist_seam=True),
        dict(garment="jumpsuit"),
        dict(garment="tshirt"),
    ],
    ids=lambda kw: "-".join(str(v) for v in kw.values()),
)
def test_a_drafted_lower_garment_hangs_from_its_open_top(body_sdf, kw):
    """A drafted skirt's or trousers' open top (its waist, or its band's top) is held where the
    draft places it, as GarmentCode's simulation holds a lower garment's; a garment hanging from
    its shoulders (a dress's skirt or a jumpsuit's legs sewn to a bodice, a top) holds nothing."""
    from unsew.pattern.design import Design, draft

    body, sdf = body_sdf
    p = draft(Design(**kw))
    mesh = mesh_pattern(p, edge_length=SETTINGS.edge_length)
    got = attached_vertices(p, mesh, body, sdf)
    if kw["garment"] not in ("skirt", "pants", "shorts"):
        assert got is None
        return
    idx, height = got
    top = max(float(pa.to_world(pa.vertices)[:, 1].max()) for pa in p.panels.values())
    sewn = {(s.a.panel, s.a.edge) for s in p.stitches} | {(s.b.panel, s.b.edge) for s in p.stitches}
    tops = [(n, i) for n, pa in p.panels.items() for i in range(len(pa.edges)) if (n, i) not in sewn]
    tops = [k for k in tops if mesh.edge_verts[k].size and _edge_top(p, *k) > top - 0.03]
    assert tops and set(idx.tolist()) == set(np.concatenate([mesh.edge_verts[k] for k in tops]).tolist())
    h = height.numpy()  # where the draft places the top (a circle skirt's waist curve dips)
    assert h.max() <= top + 1e-9 and h.min() > top - 0.1


def _edge_top(p, name, i) -> float:
    """The lowest world height [m] of panel ``name``'s edge ``i`` as placed (its endpoints)."""
    pa = p.panels[name]
    e = pa.edges[i]
    return float(pa.to_world(pa.vertices[[e.start, e.end]])[:, 1].min())
