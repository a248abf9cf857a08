"""The fit's stages (unsew.fit.stages) and the FitResult made of their results, on stand-in
results: no drape is made."""

import dataclasses
from types import SimpleNamespace

import numpy as np
import pytest

from unsew.fit.budget import TimeBudget
from unsew.fit.checks import RedressCheck
from unsew.fit.config import load_config
from unsew.fit.fit import FitResult
from unsew.fit.scene import FitContext, Scene
from unsew.fit.stages import ChecksResult, PhaseOneResult, PhaseTwoResult, redress_stage, spread_stage


def _phase_two(best_iteration: int, *, material_on: bool = False) -> PhaseTwoResult:
    start = SimpleNamespace(
        mesh=SimpleNamespace(faces=np.array([[0, 1, 2]])), x=np.zeros((3, 3)), dress_s=2.0, graded="graded"
    )
    return PhaseTwoResult(
        start=start,
        pattern="phase two's pattern",
        uv=np.zeros((3, 2)),
        x=np.ones((3, 3)),
        material="phase two's material",
        best_iteration=best_iteration,
        best_material_on=material_on,
        history={"total": [1.0, 0.5]},
        converged=False,
        params=None,
        gamma_last=[1.0] * 5,
        rest={"steps": 0},
        material_start_iteration=0 if material_on else None,
    )


def _ctx(budget: TimeBudget, **cfg) -> FitContext:
    target = SimpleNamespace(distance_mm=lambda x, faces: 5.0)
    return FitContext(None, target, None, load_config(**cfg), log=lambda s: None, budget=budget)


def test_the_context_is_a_scene_that_cannot_change():
    ctx = _ctx(TimeBudget(0))
    assert isinstance(ctx, Scene)
    with pytest.raises(dataclasses.FrozenInstanceError):
        ctx.budget = TimeBudget(10)


def test_phase_two_that_never_beat_its_start_is_returned_unchecked():
    """No iterate lower than the start: nothing for the re-dress check to judge; the result is
    phase two's start as phase two drapes it, and says so."""
    r = redress_stage(_ctx(TimeBudget(0)), _phase_two(-1))
    assert r.redress is None and r.pattern == "phase two's pattern"
    assert r.drapes == {"result": "graded start", "graded": "graded start"}
    np.testing.assert_array_equal(r.x_graded, np.zeros((3, 3)))


def test_a_mesh_spread_that_would_overrun_the_limit_is_skipped_and_listed():
    clock = SimpleNamespace(t=0.0)
    budget = TimeBudget(10.0, clock=lambda: clock.t, log=lambda s: None)
    r = redress_stage(_ctx(budget, **{"checks.redress": False}), _phase_two(3))
    assert r.drapes["result"] == "phase two"
    checked = spread_stage(_ctx(budget, **{"checks.mesh_spread": 0.25}), dataclasses.replace(r, drape_s=6.0))
    assert checked.spread is None
    assert budget.as_dict()["cuts"] == ["mesh spread skipped"]


def test_a_material_the_redress_check_turned_down_is_not_reported_fitted():
    two = _phase_two(3, material_on=True)
    one = PhaseOneResult(SimpleNamespace(start=two.start, table=[]))
    checks = ChecksResult("p", two.uv, two.x, "m", two.start.mesh, two.x, {}, 1.0)
    kept = RedressCheck(1.0, 2.0, True)
    refused = RedressCheck(3.0, 2.0, False)
    assert FitResult(one, two, checks).material_fitted
    assert FitResult(one, two, dataclasses.replace(checks, redress=kept)).material_fitted
    result = FitResult(one, two, dataclasses.replace(checks, redress=refused))
    assert not result.material_fitted and result.redress is refused and result.iterations == 2
    with pytest.raises(dataclasses.FrozenInstanceError):
        result.x = np.zeros((3, 3))
