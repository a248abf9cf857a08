"""The re-dress check's test of whether phase two moved anything (unsew.fit.checks.unmoved)."""

import dataclasses
from types import SimpleNamespace

import numpy as np

from unsew.fit.checks import UNMOVED_TOL, unmoved
from unsew.pattern.base import make_base_pattern
from unsew.pattern.model import Curvature
from unsew.sim.material import get_material


def _start():
    return SimpleNamespace(graded=make_base_pattern("skirt"), material=get_material("cotton"))


def test_a_copy_moved_by_round_off_is_unmoved():
    s = _start()
    p = s.graded.copy()
    for panel in p.panels.values():
        panel.vertices = np.asarray(panel.vertices, dtype=np.float64) + 1e-3 * UNMOVED_TOL
    mat = dataclasses.replace(s.material, h00=s.material.h00 * (1 + 1e-12))
    assert unmoved(p, mat, s)


def test_a_moved_vertex_a_moved_curve_or_another_material_is_moved():
    s = _start()
    name = next(iter(s.graded.panels))
    p = s.graded.copy()
    p.panels[name].vertices = np.asarray(p.panels[name].vertices, dtype=np.float64).copy()
    p.panels[name].vertices[0, 0] += 1e-4  # 0.1 mm
    assert not unmoved(p, s.material, s)

    q = s.graded.copy()  # only a curve's control point moves: the outline does, the vertices not
    edge = q.panels[name].edges[0]
    edge.curvature = Curvature("quadratic", [[0.5, 0.05]]) if edge.curvature is None else Curvature(
        "quadratic", [[0.5, 0.1]])
    assert not unmoved(q, s.material, s)

    assert not unmoved(s.graded.copy(), dataclasses.replace(s.material, bend=s.material.bend * 1.01), s)
    assert not unmoved(s.graded.copy(), get_material("silk"), s)
