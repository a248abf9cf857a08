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
