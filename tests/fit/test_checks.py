"""The re-dress check: whether phase two moved anything (unsew.fit.checks.unmoved), and which pattern
its drapes on three meshes keep (kept_on_meshes)."""

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

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
    edge.curvature = (
        Curvature("quadratic", [[0.5, 0.05]])
        if edge.curvature is None
        else Curvature("quadratic", [[0.5, 0.1]])
    )
    assert not unmoved(q, s.material, s)

    assert not unmoved(s.graded.copy(), dataclasses.replace(s.material, bend=s.material.bend * 1.01), s)
    assert not unmoved(s.graded.copy(), get_material("silk"), s)


def test_on_three_meshes_the_pattern_that_can_be_dressed_is_kept():
    """Measured on the tall thin sleeveless shift (at 6ff367a): phase two's pattern dressed from
    scratch at 16.32 mm on the fit's mesh and failed on the other two, the graded one failed on
    all three; returning the graded pattern made the fit fail at its final drape. The pattern
    whose drapes fail on fewer meshes is kept; otherwise the means decide, as before."""
    from unsew.fit.checks import REDRESS_MARGIN_MM, kept_on_meshes

    kept, fit_mean, graded_mean, why = kept_on_meshes([16.32, None, None], [None, None, None])
    assert kept and fit_mean is None and graded_mean is None and "failed on 3 of 3" in why
    assert kept_on_meshes([6.0, None, 6.1], [7.0, None, None])[0]  # fewer failures, whatever the pairs say
    assert not kept_on_meshes([6.0, None, None], [7.0, 7.1, None])[0]  # more failures: the graded one
    # as many failures: phase two's must succeed wherever the graded one did, and be closer there
    assert not kept_on_meshes([6.0, None, 6.0], [7.0, 7.0, None])[0]
    kept, fit_mean, graded_mean, why = kept_on_meshes([6.0, 6.2, None], [7.0, 7.2, None])
    assert kept and fit_mean == pytest.approx(6.1) and graded_mean == pytest.approx(7.1) and why == ""
    assert not kept_on_meshes([7.0, 7.0, 7.0], [7.0 + 0.5 * REDRESS_MARGIN_MM] * 3)[0]
