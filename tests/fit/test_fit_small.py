"""The whole fit in small mode (coarse mesh, few iterations): a known-truth t-shirt case is made
by draping, fitted from the base t-shirt, and the result folder is complete and better than the
base. The full-size checks are in benchmarks/bench_fit.py and the slow test below."""

import json

import numpy as np
import pytest

from unsew.fit.config import CheckSettings, LossWeights, OptimizerSettings, load_config
from unsew.fit.scene import Scene

#: The solver is pinned (:func:`_cholespy`): the figures below were measured with cholespy, and where
#: CHOLMOD is installed ("auto") round-off grown through the drapes moves them by more than their margins.
#: On CHOLMOD at 71a0347 the proof of phase two read 5.83 / 6.03 / 6.63 -> 6.07 / 5.71 / 5.90 mm
#: (means x0.956, fit's mesh x1.04; cholespy x0.87).
SMALL = {
    "drape.edge_length": 0.04,
    "optimizer.iterations": 3,
    "drape.steps": 8,
    "drape.sew_steps": 60,
    "drape.settle_steps": 20,
    "loss.target_points": 1500,
    "material.start_iteration": 1,
    "material.start": "cotton",
}
FILES = [
    "pattern.json",
    "pattern.svg",
    "pattern.dxf",
    "pattern.pdf",
    "garment.obj",
    "garment_rest.obj",
    "material.json",
    "metrics.json",
    "config.yaml",
    "report.html",
    "pattern_base.json",
    "pattern_graded.json",
]


@pytest.fixture(scope="module", autouse=True)
def _cholespy():
    """Every drape of these tests on cholespy: the "auto" backend sees no CHOLMOD."""
    import unsew.sim.solve

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(unsew.sim.solve, "_HAS_CHOLMOD", False)
        yield


def _fewer_material_steps(monkeypatch):
    """The material choice grades again in one other fabric and searches the stiffness one round."""
    import unsew.fit.material

    monkeypatch.setattr(unsew.fit.material, "REGRADE", 1)
    monkeypatch.setattr(unsew.fit.material, "REFINE_ROUNDS", 1)


@pytest.fixture(scope="module")
def small_case(tmp_path_factory):
    from unsew.fit.demo import make_truth_case

    d = tmp_path_factory.mktemp("case") / "tshirt"
    return make_truth_case(d, settings=load_config(**SMALL).drape)


#: phase two's iterations in the small fit: with 3 the verdict of the re-dress check depended on
#: the machine
PROOF_ITERATIONS = 6


@pytest.fixture(scope="module")
def small_fit(small_case, tmp_path_factory):
    from unsew.fit.run import run_fit
    from unsew.body.case import load_case

    out = tmp_path_factory.mktemp("fit") / "result"
    result, metrics = run_fit(
        load_case(small_case),
        load_config(**{**SMALL, "optimizer.iterations": PROOF_ITERATIONS}),
        out,
        progress=False,
        log=lambda s: None,
    )
    return out, result, metrics


def test_result_folder_is_complete(small_fit):
    out, result, metrics = small_fit
    for name in FILES:
        assert (out / name).is_file(), name
    assert not (out.parent / (out.name + ".partial")).exists()
    saved = json.loads((out / "metrics.json").read_text())
    assert saved["iterations"] == PROOF_ITERATIONS
    assert saved["drape_check"]["ok"] and saved["drape_check"]["inside_pct"] < 0.5
    from unsew.io.garmentcode import load_pattern
    from unsew.metrics.panels import panel_area

    p = load_pattern(out / "pattern.json")
    assert set(p.panels) == set(result.pattern.panels)
    assert "material" in p.unsew and "symmetry" in p.unsew
    base = load_pattern(out / "pattern_base.json")  # the starting points, saved for their pattern errors
    assert set(base.panels) == set(result.base_pattern.panels)
    assert saved["pattern_base"]["area_error_weighted_rel"] >= saved["pattern_base"]["area_error_total_rel"]
    assert saved["pattern_graded"]["unmatched"] == {"estimated": [], "true": []}
    a = saved["area_m2"]  # total panel areas against the target's surface area
    assert set(a) == {"target", "base", "graded", "result"} and min(a.values()) > 0
    assert a["result"] == pytest.approx(sum(panel_area(q) for q in p.panels.values()), rel=1e-6)
    assert a["graded"] == pytest.approx(a["target"], rel=1e-6)  # area: target, grading scaled it there
    seams = saved["seams"]  # stitched edges' length differences, the base's ease left out
    assert set(seams["gap_max_mm"]) == {"base", "graded", "result"}
    assert set(seams["change_from_base_max_mm"]) == {"graded", "result"}
    from unsew.pattern.seams import stitch_length_gaps

    assert seams["gap_max_mm"]["result"] == pytest.approx(1e3 * np.abs(stitch_length_gaps(p)).max(), abs=1e-6)


def test_fit_improves_on_the_base(small_fit):
    _, result, metrics = small_fit
    assert metrics["surface"]["chamfer_mm"] < metrics["surface_base"]["chamfer_mm"]
    assert metrics["pattern"]["area_error_rel_mean"] < metrics["pattern_base"]["area_error_rel_mean"]
    # phase two's loss falls: measured 3.94e-4 -> 3.65e-4 (x0.925) over the three iterations
    # (graded to the target's area, area: target; x0.79 from a start that was not); with the
    # control points and material held (pattern_start past the budget) it rises and min(h) is
    # h[0], so this fails when phase two does nothing
    h = result.history["total"]
    assert min(h) < 0.95 * h[0]


def test_phase_two_is_kept_and_lowers_the_redressed_distance(small_fit):
    """Grading alone is not enough on this case: it is graded in cotton, the truth is jersey, and
    grading cannot change the fabric. Phase two (control points and material, through
    differentiable drapes) must give a pattern that, dressed from scratch, lies closer to the
    target than the graded one, and the re-dress check must keep it: the returned pattern is
    phase two's. Measured with 6 iterations, both patterns dressed from scratch on the re-dress
    check's three meshes: 5.62 / 5.98 / 6.27 -> 5.05 / 5.42 / 5.09 mm, means x0.87; on another
    machine the first mesh gained only 0.2 %, and with the outline on its 1 nm grid
    (decision 041) 5.44 / 6.30 / 6.31 -> 5.58 / 4.85 / 6.02 (one mesh 2.6 % farther, the means
    x0.91): one mesh's drape moves by a few % with its triangles, which is why the check judges
    the mean of three. So the means, x0.95 lower, and two meshes of three lower. With phase two
    held (pattern_start past the budget) the graded pattern is returned and this fails."""
    import numpy as np

    _, result, metrics = small_fit
    rd = metrics["redress"]
    assert rd["meshes"] == 3 and rd["phase_two_kept"]
    assert rd["fit_mean_mm"] < 0.95 * rd["graded_mean_mm"]
    # closer on most of the three meshes
    assert sum(f < g for f, g in zip(rd["fit_mm"], rd["graded_fresh_mm"])) >= 2
    moved = max(
        float(np.abs(result.pattern.panels[n].vertices - p.vertices).max())
        for n, p in result.graded_pattern.panels.items()
    )
    assert moved > 1e-3  # [m]: the returned pattern is not the graded one


#: Known limit (README, "Known limits": phase two can move area between panels): it lowers the
#: drape's distance, not the pattern error, where grading already fits the panels' areas; measured
#: over cases by `python -m benchmarks fit` (area error of the graded and the fitted pattern per
#: garment type) and `python -m benchmarks foreign_fit` (per-panel area errors, graded and final).
#: Strict: an XPASS says the limit is lifted here.
AREA_LIMIT = pytest.mark.xfail(
    strict=True,
    reason="known limit: phase two lowers the drape's distance, not the pattern error, where grading "
    "already fits the areas (mean panel area error 0.98 % graded -> 1.09 % final here); measured by "
    "`python -m benchmarks fit` and `foreign_fit`",
)

#: Known limit: phase two moves corners the truth did not move; measured by
#: `python -m benchmarks phase_two_paths` (corner L2 of the graded and the best iterate).
CORNER_LIMIT = pytest.mark.xfail(
    strict=True,
    reason="known limit: phase two moves corners the truth did not move (rigid corner L2 0.14 -> 0.29 cm "
    "here); measured by `python -m benchmarks phase_two_paths` (corner L2 graded / best)",
)


@AREA_LIMIT
def test_phase_two_lowers_the_pattern_error_below_grading(small_fit):
    """The pattern error itself: the mean panel area error of phase two's pattern at most 0.7x the
    graded pattern's. Not on this t-shirt, whose graded area error is already under 1 %; the
    default suite's proof is on a case grading cannot fit,
    tests/fit/test_phase_two.py::test_phase_two_lowers_the_area_error."""
    _, _, metrics = small_fit
    assert metrics["pattern"]["area_error_rel_mean"] < 0.7 * metrics["pattern_graded"]["area_error_rel_mean"]


@CORNER_LIMIT
def test_phase_two_lowers_the_corner_distance_below_grading(small_fit):
    """The other pattern error: the panels' corners (rigidly aligned) closer to the truth's after
    phase two than after grading. Not on this t-shirt; where it holds, on the hip that grading
    left: tests/fit/test_phase_two.py::test_phase_two_lowers_the_corner_distance_on_the_hip."""
    _, _, metrics = small_fit
    assert metrics["pattern"]["vertex_l2_cm_mean"] < metrics["pattern_graded"]["vertex_l2_cm_mean"]


def test_a_result_off_the_body_is_no_result(small_case, small_fit, tmp_path, monkeypatch):
    """A fit whose drape is judged fallen (here: the small fit's own drape shown to the real check
    1.2 m lower, through the floor) ends in one SimulationError line and leaves neither the result
    folder nor its .partial."""
    import dataclasses

    import numpy as np

    import unsew.fit.run as run_module
    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.errors import SimulationError
    from unsew.sim.checks import check_drape

    _, result, _ = small_fit
    case = load_case(small_case)
    x = np.asarray(result.x) - np.array([0.0, 1.2, 0.0])
    verdict = check_drape(
        x,
        faces=result.mesh.faces,
        uv=result.uv,
        faces_uv=result.mesh.faces_uv,
        body=case.body,
        sdf=BodySDF.build(case.body),
    )
    fallen = dataclasses.replace(result, checks=dataclasses.replace(result.checks, x=x), drape_check=verdict)
    monkeypatch.setattr(run_module, "fit", lambda *a, **k: fallen)
    out = tmp_path / "result"
    with pytest.raises(SimulationError, match="fit failed: fallen"):
        run_module.run_fit(case, load_config(**SMALL), out, progress=False, log=lambda s: None)
    assert not out.exists() and not run_module.partial_dir(out).exists()


#: one phase-two fit asked for several things at once, each checked by its own test: the prior
#: term, the slip speed of phase two's drapes (both set by :func:`_free_constants`), only the
#: bending entry of the material freed from the first iteration; the interrupted and resumed fit
#: is compared with it. No re-dress check: these are phase two's own results
FREE = {
    **SMALL,
    "optimizer.iterations": 2,
    "output.report": False,
    "checks.mesh_spread": 0.0,
    "material.start_iteration": 0,
    "material.fit": "k",
    "checks.redress": False,
}
#: the prior weight (LossWeights.prior) and phase two's slip speed (OptimizerSettings.friction_eps)
#: of the FREE fit
FREE_PRIOR, FREE_FRICTION_EPS = 1.0, 2e-3


def _free_constants(mp):
    """The FREE fit's prior weight and phase two's slip speed, set on ``mp`` (a MonkeyPatch)."""
    mp.setattr(LossWeights, "prior", FREE_PRIOR)
    mp.setattr(OptimizerSettings, "friction_eps", FREE_FRICTION_EPS)


@pytest.fixture(scope="module")
def free_fit(small_case, tmp_path_factory):
    """run_fit with FREE: (FitResult, the friction_eps of each phase-two drape, in order)."""
    import importlib

    from unsew.body.case import load_case
    from unsew.fit.run import run_fit

    optimize = importlib.import_module("unsew.fit.optimize")
    orig, seen = optimize.drape, []

    def spy(*a, **k):  # phase two's drapes are the ones whose rest mesh is a variable
        cloth = a[3] if len(a) > 3 else k.get("cloth")
        if cloth is not None and cloth.uv.requires_grad:
            seen.append(k["settings"].friction_eps)
        return orig(*a, **k)

    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(optimize, "drape", spy)
        _free_constants(mp)
        out = tmp_path_factory.mktemp("free") / "result"
        result, _ = run_fit(
            load_case(small_case), load_config(**FREE), out, progress=False, log=lambda s: None
        )
    return result, seen


def test_resume_continues_from_checkpoint(small_case, free_fit, tmp_path, monkeypatch):
    """An interrupted fit leaves RESULT.partial with a checkpoint; --resume finishes it."""
    from unsew.fit.run import partial_dir, run_fit
    from unsew.body.case import load_case

    out = tmp_path / "r"
    case = load_case(small_case)
    cfg = load_config(**FREE)
    _free_constants(monkeypatch)

    def interrupt(info):
        # stopped after the first iteration's checkpoint, as by Ctrl-C
        if info.iteration == 0:
            raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        run_fit(case, cfg, out, progress=False, log=lambda s: None, callback=interrupt)
    assert not out.exists()
    assert (partial_dir(out) / "checkpoint.pt").is_file()
    seen = []
    result, _ = run_fit(case, cfg, out, resume=True, progress=False, log=seen.append)
    assert any("resuming from iteration 1" in line for line in seen)
    assert out.is_dir() and not partial_dir(out).exists()
    assert len(result.history["total"]) == 2
    # the resumed fit is the fit that was not interrupted
    whole, _ = free_fit
    assert result.history == whole.history and result.best_iteration == whole.best_iteration


def test_result_is_the_best_iterate_and_says_so(small_fit):
    """The returned drape is the lowest-loss iterate; metrics.json says which and whether its
    material was fitted: here the loss fell from the graded start, so the best iterate comes
    after the material was freed, phase two was kept, and its fabric is not the start's."""
    _, result, metrics = small_fit
    h = result.history["total"]
    assert metrics["best_iteration"] == min(range(len(h)), key=h.__getitem__)
    assert (
        metrics["best_iteration"] >= SMALL["material.start_iteration"]
        and metrics["redress"]["phase_two_kept"]
    )
    assert metrics["material_fitted"] and result.material != result.start_material


def test_redress_check_decides_and_returns_what_it_decided(small_fit):
    """Phase two's pattern, kept by the re-dress check on three meshes, is returned dressed from
    scratch, its warm-started drape reported beside it; the graded pattern dressed from scratch is
    the graded drape reported. (The graded pattern returned when phase two found nothing:
    test_redress_check_returns_the_graded_pattern_when_phase_two_found_nothing.)"""
    out, result, metrics = small_fit
    rd = metrics["redress"]
    report = (out / "report.html").read_text()
    assert "re-dress check" in report
    assert rd["meshes"] == 3 and rd["phase_two_kept"]
    assert metrics["drapes"] == {"result": "fresh", "graded": "fresh"}
    assert rd["graded_fresh_mm"][0] == pytest.approx(metrics["surface_graded"]["chamfer_mm"], rel=0.1)
    assert rd["fit_redressed_mm"] == pytest.approx(metrics["surface"]["chamfer_mm"], rel=0.1)
    assert result.x_warm is not None and metrics["surface_warm"]["chamfer_mm"] > 0
    assert "warm-started drape lay" in report


def test_the_result_drape_is_its_pattern_dressed_from_scratch(small_case, small_fit):
    """garment.obj is what dressing the returned pattern in the returned material from scratch
    on the result's mesh gives, whichever pattern the re-dress check returned: not a drape
    warm-started along the optimizer's path, which can lie nearer the target than its pattern
    dresses."""
    from unsew.body.case import load_case
    from unsew.body.sdf import BodySDF
    from unsew.dress import dress
    from unsew.grading.grade import moved_mesh

    _, result, metrics = small_fit
    assert metrics["drapes"]["result"] == "fresh"
    body = load_case(small_case).body
    x = dress(
        result.pattern,
        body,
        sdf=BodySDF.build(body),
        mesh=moved_mesh(result.mesh, result.pattern, result.uv),
        material=result.material,
        settings=load_config(**SMALL).drape,
    ).x.numpy()
    np.testing.assert_allclose(x, result.x, atol=1e-9)


def test_mesh_spread_dresses_the_returned_pattern_on_two_other_meshes(small_fit):
    """metrics.json's mesh_spread: the returned pattern dressed on meshes 4 % finer and coarser,
    each at its own distance from the target, beside the result's own (the re-dress figure of
    whichever pattern was returned); the report says so."""
    import math

    out, result, metrics = small_fit
    ms = json.loads((out / "metrics.json").read_text())["mesh_spread"]
    h = SMALL["drape.edge_length"]
    assert ms["edge_lengths_m"] == pytest.approx([0.96 * h, 1.04 * h])
    rd = metrics["redress"]
    graded = rd["graded_fresh_mm"][0] if rd["meshes"] == 3 else rd["graded_mm"]
    assert ms["result_mm"] == (rd["fit_redressed_mm"] if rd["phase_two_kept"] else graded)
    for v in ms["chamfer_mm"]:
        assert math.isfinite(v) and 0 < v < 100
        assert abs(v - ms["result_mm"]) > 1e-6  # another triangulation, another drape
    assert "mesh spread" in (out / "report.html").read_text()


#: phase two with the pattern and material held: the control points start past the budget
HELD = {
    **SMALL,
    "optimizer.iterations": 2,
    "optimizer.pattern_start": 5,
    "material.fit": [],
    "output.report": False,
}


@pytest.fixture(scope="module")
def held_fit(small_case):
    """fit() with HELD and the default checks (re-dress on three meshes, mesh spread)."""
    from unsew.body.case import load_case
    from unsew.fit.fit import fit

    return fit(load_case(small_case), load_config(**HELD), progress=False, log=lambda s: None)


@pytest.fixture(scope="module")
def held_unchecked(small_case):
    """fit() with HELD, no re-dress check and no mesh spread: what phase two itself returns."""
    from unsew.body.case import load_case
    from unsew.fit.fit import fit

    cfg = load_config(**HELD).replace(checks=CheckSettings(redress=False, mesh_spread=0.0))
    return fit(load_case(small_case), cfg, progress=False, log=lambda s: None)


def test_redress_check_returns_the_graded_pattern_when_phase_two_found_nothing(held_fit, held_unchecked):
    """With the pattern and material held, the re-dress reproduces the graded drape, so the check
    returns the graded pattern, its drape and the start material; without the check the result
    is the warm-started drape the optimizer ended on."""
    import numpy as np

    r = held_fit
    assert r.redress.phase_two_kept is False
    assert r.redress.fit_redressed_mm == pytest.approx(r.redress.graded_mm, abs=1e-6)
    # an unmoved pattern is not judged by drapes of it on other meshes, which round-off can move
    # by tenths of a millimetre (unsew.fit.checks.unmoved): the graded pattern's stand for them
    assert r.redress.meshes == 3 and r.redress.fit_mm[1:] == r.redress.graded_fresh_mm[1:]
    np.testing.assert_array_equal(r.x, r.x_graded)
    np.testing.assert_array_equal(r.uv, r.mesh.uv)  # the rest mesh the graded drape was made on
    assert r.material == r.start_material
    assert r.mesh_spread is not None
    off = held_unchecked
    assert off.redress is None and off.mesh_spread is None
    assert np.abs(off.x - off.x_graded).max() > 1e-6


@pytest.fixture(scope="module")
def held_cold(small_case):
    """fit() with HELD, three iterations, each drape started from the graded drape
    (OptimizerSettings.warm_start False), and no mesh spread: the re-dress check has three
    meshes asked for (the default) but no spread meshes."""
    from unsew.body.case import load_case
    from unsew.fit.fit import fit

    cfg = load_config(**{**HELD, "optimizer.iterations": 3, "checks.mesh_spread": 0.0})
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(OptimizerSettings, "warm_start", False)
        return fit(load_case(small_case), cfg, progress=False, log=lambda s: None)


def test_three_meshes_asked_without_spread_meshes_are_judged_on_one(held_cold):
    """Three re-dress meshes (unsew.fit.checks.REDRESS_MESHES) with mesh_spread 0: no meshes to
    judge on but the fit's, so the re-dress check judges on one, then dresses the returned (graded)
    pattern afresh."""
    one = held_cold
    assert one.redress.meshes == 1 and one.mesh_spread is None
    assert one.drapes == {"result": "fresh", "graded": "fresh"}


def test_material_parameterisation_stays_valid():
    import torch

    from unsew.fit.optimize import material_params
    from unsew.sim.material import check_gamma, get_material

    g0 = get_material("cotton").gamma()
    theta, gamma_of = material_params(g0)
    assert torch.allclose(gamma_of(theta), g0, rtol=1e-12)
    for t in ([5, 9, -5, 3, -8], [-5, -9, 5, -3, 8], [0, 40, 0, 0, 0]):
        g = gamma_of(torch.tensor(t, dtype=torch.float64))
        check_gamma(g)  # positive definite membrane stiffness, non-negative bending


def test_pattern_start_holds_the_control_points(held_unchecked):
    """Before cfg.pattern_start the control points do not move: with it past the budget phase two
    returns the graded pattern unchanged (no re-dress check to return it instead)."""
    import numpy as np

    r = held_unchecked
    assert r.best_iteration >= 0  # phase two's own iterate, not the graded start
    for name, panel in r.graded_pattern.panels.items():
        np.testing.assert_allclose(r.pattern.panels[name].vertices, panel.vertices, atol=1e-12)


def test_prior_term_is_wired_in(free_fit):
    """With a prior weight (LossWeights.prior) the loss carries the pull towards the graded
    pattern: zero at the first iterate (the graded pattern itself), positive once the control
    points moved."""
    r, _ = free_fit
    assert r.history["prior"][0] == 0.0
    assert r.history["prior"][1] > 0.0


def test_material_params_frees_only_the_listed_entries(free_fit):
    """Only "k" in material.fit: the last iterate's bending has moved, its stretch and shear have not."""
    from unsew.sim.material import MATERIALS

    r, _ = free_fit
    g0 = [float(v) for v in MATERIALS[FREE["material.start"]].gamma()]
    g = r.gamma_last
    assert g[:4] == pytest.approx(g0[:4], rel=1e-12)
    assert abs(g[4] / g0[4] - 1) > 1e-3


def test_cold_start_makes_the_drape_a_function_of_the_parameters(held_cold, held_unchecked):
    """OptimizerSettings.warm_start False: every iteration drapes from the graded pattern's
    settled drape, so with the pattern and material held, every iteration's loss is the same;
    warm-started (the default), the cloth keeps moving and the loss changes."""
    cold = held_cold.history["total"]
    warm = held_unchecked.history["total"]
    assert len(cold) == 3 and max(cold) - min(cold) <= 1e-12 * max(cold)
    assert len(warm) == 2 and max(warm) - min(warm) > 1e-6 * max(warm)


#: the material chosen by draping (material.start auto) among three library fabrics, with a
#: stiffness search (shortened by :func:`_fewer_material_steps`)
AUTO = {
    **SMALL,
    "optimizer.iterations": 1,
    "material.fit": [],
    "output.report": False,
    "checks.mesh_spread": 0.0,
    "material.start": "auto",
    "material.candidates": "cotton,denim,jersey",
}


@pytest.fixture(scope="module")
def auto_fit(small_case, tmp_path_factory):
    """run_fit with AUTO and no time limit: (FitResult, metrics)."""
    from unsew.body.case import load_case
    from unsew.fit.run import run_fit

    out = tmp_path_factory.mktemp("auto") / "result"
    cfg = load_config(**AUTO, time_limit=0)
    with pytest.MonkeyPatch.context() as mp:
        _fewer_material_steps(mp)
        return run_fit(load_case(small_case), cfg, out, progress=False, log=lambda s: None)


def test_auto_material_picks_the_true_fabric(auto_fit):
    """material=auto dresses the cotton-graded pattern in each candidate, grades again in the best
    one other than cotton, refines the winner's stiffness by draping, checks the winner by a drape
    from scratch, and starts phase two from the closest: the target is the demo t-shirt in jersey, so jersey
    wins over cotton and denim, and the fit's material is jersey's (density, friction and Poisson ratio; a
    refinement scales only the stiffness)."""
    import math

    from unsew.sim.material import MATERIALS

    r, _ = auto_fit
    # the material check's two drapes from scratch come first, the kept start on top: the choice
    # in jersey dresses no farther than the cotton-graded pattern, so it stands
    checked, table = r.material_choice[:2], r.material_choice[2:]
    assert [row["pattern"].endswith(", dressed from scratch") for row in checked] == [True, True]
    assert checked[0]["material"].startswith("jersey") and checked[1]["material"] == "cotton"
    library = [row for row in table if "(" not in row["material"]]
    refined = [row for row in table if "(" in row["material"]]
    assert library[0]["material"] == "jersey" and table[0]["material"].startswith("jersey")
    assert sorted((row["material"], row["pattern"]) for row in library) == [
        ("cotton", "graded in cotton"),
        ("denim", "graded in cotton"),
        ("jersey", "graded in cotton"),
        ("jersey", "graded in jersey"),
    ]
    # one round: stretch and bending each tried at x0.5, and at x2 unless x0.5 came closer
    assert 2 <= len(refined) <= 4 and all(row["material"].startswith("jersey (stretch x") for row in refined)
    assert all(row["pattern"] == library[0]["pattern"] for row in refined)
    cf = [row["chamfer_mm"] for row in table]
    assert cf == sorted(cf) and cf[0] < cf[-1]
    j = MATERIALS["jersey"]
    assert (r.material.density, r.material.friction) == (j.density, j.friction)
    assert math.isclose(r.material.h01 / r.material.h00, j.h01 / j.h00)
    assert (r.material == j) == (table[0]["material"] == "jersey")


def test_choose_material_ranks_by_the_objective():
    """choose_material keeps every finite candidate, best first, and returns the winner's drape;
    a candidate whose drape is not finite is dropped; none finite is a one-line InputError."""
    import math

    import numpy as np

    from unsew.errors import InputError
    from unsew.fit.material import choose_material
    from unsew.sim.material import MATERIALS

    drapes = {
        MATERIALS[n].density: np.full((4, 3), i, dtype=float)
        for i, n in enumerate(["cotton", "silk", "wool"])
    }
    score = {0.0: 2.0, 1.0: 1.0, 2.0: math.nan}
    mat, x, table = choose_material(
        ["cotton", "silk", "wool"], lambda m, bar: drapes[m.density], lambda x: score[float(x[0, 0])]
    )
    assert mat == MATERIALS["silk"] and float(x[0, 0]) == 1.0
    assert [r["material"] for r in table] == ["silk", "cotton"]
    with pytest.raises(InputError):
        choose_material(["wool"], lambda m, bar: drapes[m.density], lambda x: math.nan)
    # no room after the first fabric (the time limit): the ones draped so far compete
    asked = []
    mat, _, table = choose_material(
        ["cotton", "silk", "wool"],
        lambda m, bar: drapes[m.density],
        lambda x: score[float(x[0, 0])],
        room=lambda s: asked.append(s) or False,
    )
    assert mat == MATERIALS["cotton"] and [r["material"] for r in table] == ["cotton"] and len(asked) == 1


def test_refine_material_walks_towards_the_closest_stiffness():
    """refine_material scales stretch and bending by 1/s and s (s = 2, sqrt 2) and keeps a
    scaling only when the objective falls: on a distance whose minimum is stretch x0.5 and
    bending x1.41 of cotton it lands there, keeps the Poisson ratio, and never returns a
    material worse than its start."""
    import math

    import numpy as np

    from unsew.fit.material import refine_material
    from unsew.sim.material import MATERIALS

    c = MATERIALS["cotton"]

    froms = []

    def dress_in(m, bar, x_from=None):  # the "drape" carries the material's stiffness
        froms.append(x_from)
        return np.array([[m.h00, m.bend, m.h01]])

    def objective(x):
        return abs(math.log(x[0, 0] / (0.5 * c.h00))) + abs(math.log(x[0, 1] / (math.sqrt(2) * c.bend)))

    start = dress_in(c, None)
    mat, x, rows = refine_material(c, "cotton", start, objective(start), dress_in, objective)
    assert mat.h00 == pytest.approx(0.5 * c.h00) and mat.bend == pytest.approx(math.sqrt(2) * c.bend)
    assert mat.h01 / mat.h00 == pytest.approx(c.h01 / c.h00) and mat.density == c.density
    assert float(x[0, 0]) == mat.h00 and objective(x) == pytest.approx(0.0, abs=1e-12)
    assert rows and all(r["material"].startswith("cotton (stretch x") for r in rows)
    assert froms[0] is None and froms[1] is start  # each scaling is draped from the best drape so far
    # a start already at the minimum is kept: every scaling is worse
    mat2, x2, rows2 = refine_material(mat, "m", x, objective(x), dress_in, objective)
    assert mat2 == mat and len(rows2) == 8


def test_refine_material_walks_on_to_a_fabric_far_from_the_library():
    """A target eight times stiffer in bending than the start is reached in the first round: a
    scaling that helps is applied again while it keeps helping (REFINE_REPEAT), and stops at the
    first that does not."""
    import math

    import numpy as np

    from unsew.fit.material import REFINE_REPEAT, refine_material
    from unsew.sim.material import MATERIALS

    assert REFINE_REPEAT >= 2
    c = MATERIALS["cotton"]

    def dress_in(m, bar, x_from=None):
        return np.array([[m.h00, m.bend]])

    def objective(x):
        return abs(math.log(x[0, 0] / c.h00)) + abs(math.log(x[0, 1] / (8.0 * c.bend)))

    start = dress_in(c, None)
    mat, x, rows = refine_material(c, "cotton", start, objective(start), dress_in, objective)
    assert mat.bend == pytest.approx(8.0 * c.bend) and mat.h00 == c.h00
    # round one: stretch /2, x2 (both worse), bending /2 (worse), x2, x4, x8, x16 (worse);
    # round two: stretch and bending by 1/sqrt 2 and sqrt 2, all worse
    assert len(rows) == 7 + 4
    assert "bending x16" in rows[6]["material"] and rows[6]["chamfer_mm"] > objective(x)


def test_fit_friction_eps_reaches_phase_two_drapes(free_fit):
    """OptimizerSettings.friction_eps is the slip speed of phase two's drapes."""
    _, seen = free_fit
    assert seen == [FREE_FRICTION_EPS] * FREE["optimizer.iterations"]


def test_phase_two_stage_loss_step_and_state_dict(small_case, monkeypatch):
    """The optimize stage on its own: loss() returns named terms whose weighted sum is the total;
    step() records them; a PhaseTwo loaded from another's state_dict steps exactly like it."""
    import torch

    from unsew.body.sdf import BodySDF
    from unsew.fit.material import MaterialChoice
    from unsew.fit.optimize import LOSS_TERMS, PhaseTwo
    from unsew.fit.start import base_pattern_for, start
    from unsew.fit.target import Target
    from unsew.body.case import load_case
    from unsew.sim.material import get_material

    case = load_case(small_case)
    cfg = load_config(**{**SMALL, "grading": False})
    monkeypatch.setattr(LossWeights, "prior", 0.5)
    sdf, target = BodySDF.build(case.body), Target.of_case(case)
    s = start(base_pattern_for(case, cfg), Scene(case.body, target, sdf, cfg), get_material("cotton"))
    two = PhaseTwo(MaterialChoice(s), target, sdf, cfg)
    terms, _, x = two.loss()
    w = cfg.loss
    assert tuple(terms.floats()) == LOSS_TERMS and x.shape == (s.mesh.n_x, 3)
    weighted = (
        terms.chamfer
        + w.open * terms.open
        + w.seam * terms.seam
        + w.material * terms.material
        + w.prior * terms.prior
        + w.area * terms.area
        + w.panel_area * terms.panel_area
    )
    assert float(terms.total.detach()) == pytest.approx(float(weighted.detach()), rel=1e-12)
    f = terms.floats()
    assert (
        f["chamfer"] > 0
        and f["open"] > 0
        and f["prior"] == 0.0
        and f["area"] == 0.0
        and f["panel_area"] == 0.0
    )
    info = two.step()
    assert (info.iteration, two.iteration) == (0, 1) and info.terms == {
        k: v[0] for k, v in two.history.items()
    }
    other = PhaseTwo(MaterialChoice(s), target, sdf, cfg)
    other.load_state_dict(two.state_dict())
    assert torch.equal(other.K, two.K) and other.iteration == 1
    two.step()
    other.step()
    assert other.history == two.history and torch.equal(other.K, two.K)


def test_redress_refuses_a_pattern_that_cannot_be_meshed_afresh():
    """Phase two moves the rest mesh's vertices and can squeeze a panel flat while the moved mesh
    still drapes (a waistband 0.9 mm high on a foreign flared skirt): such a pattern is refused
    before dressing and the graded one returned, not crashed on later by the mesh spread."""
    from unsew.pattern.base import make_base_pattern

    pat = make_base_pattern("skirt_band")
    band = pat.panels["waistband_front"]
    v = band.vertices.copy()
    v[:, 1] = v[:, 1].min() + (v[:, 1] - v[:, 1].min()) * 0.02  # 4 cm high -> under 1 mm
    band.vertices = v
    rd, lines = _redress_on_stand_ins(pat)
    assert not rd.phase_two_kept and rd.fit_redressed_mm is None and rd.graded_mm == 7.5
    assert "waistband_front" in rd.refused and "sliver" in rd.refused
    assert "graded pattern is returned" in lines[0]


def test_redress_refuses_a_pattern_its_reader_would_refuse(monkeypatch):
    """A pattern that meshes but whose outline crosses itself at a corner (phase two moved a side
    seam's point past the armhole; written, load_pattern refused it and the benchmark's reader
    crashed) is refused like one that cannot be meshed: the graded pattern is returned. The
    validator stands in for such an outline here."""
    import unsew.fit.checks as checks
    from unsew.errors import PatternError
    from unsew.pattern.base import make_base_pattern

    def crossing(p):
        raise PatternError("panel 'front' outline intersects itself: edge 3 crosses edge 4")

    monkeypatch.setattr(checks, "validate_pattern", crossing)
    meshed = []
    monkeypatch.setattr(checks, "mesh_pattern", lambda *a, **k: meshed.append(1))
    rd, lines = _redress_on_stand_ins(make_base_pattern("tshirt"))
    assert not rd.phase_two_kept and rd.fit_redressed_mm is None and "crosses edge 4" in rd.refused
    assert meshed == [] and "graded pattern is returned" in lines[0]


def test_a_drape_from_scratch_that_fails_its_check_decides_nothing(monkeypatch):
    """A drape from scratch that ends exploded (one edge torn through an armhole) can lie close
    to the target. Phase two's pattern whose fresh drape failed its check is not kept, the graded
    pattern is returned and the log says why; the graded pattern's failed fresh drape and a failed
    drape on another mesh count as failed (None), not by their distance."""
    from types import SimpleNamespace

    import numpy as np

    import unsew.fit.checks as checks
    from unsew.fit.config import FitConfig
    from unsew.fit.progress import Progress
    from unsew.pattern.base import make_base_pattern

    torn = "exploded: an edge is stretched to 5.1 times its pattern length (bound 3)"
    dressed = SimpleNamespace(
        x=SimpleNamespace(numpy=lambda: np.ones((3, 3))), mesh=SimpleNamespace(faces=None)
    )
    monkeypatch.setattr(checks, "dress", lambda *a, **k: dressed)
    monkeypatch.setattr(checks, "moved_mesh", lambda *a: None)
    monkeypatch.setattr(checks, "mesh_pattern", lambda *a, **k: None)
    monkeypatch.setattr(checks, "check_dressed", lambda d, body: SimpleNamespace(ok=False, reason=torn))
    start = SimpleNamespace(x=np.zeros((3, 3)), mesh=SimpleNamespace(faces=None), graded=None, material=None)
    target = SimpleNamespace(distance_mm=lambda x, f: 1.0 if x.any() else 7.5)  # the torn drape lies closer
    lines = []
    rd = checks.redress_check(
        make_base_pattern("tshirt"),
        None,
        None,
        start,
        Scene(None, target, None, FitConfig(), progress=Progress(False), log=lines.append),
    )
    assert not rd.phase_two_kept and rd.fit_redressed_mm is None and rd.failed == torn and rd.refused == ""
    assert rd.graded_mm == 7.5 and "failed (exploded" in lines[0] and "graded pattern is returned" in lines[0]
    assert checks.graded_afresh(start, Scene(None, target, None, FitConfig())) == (
        None,
        None,
    )
    assert checks._dressed_mm(None, None, Scene(None, target, None, FitConfig()), 0.02, "it") is None
    monkeypatch.setattr(checks, "check_dressed", lambda d, body: SimpleNamespace(ok=True, reason=""))
    assert checks._dressed_mm(None, None, Scene(None, target, None, FitConfig()), 0.02, "it") == 1.0
    assert checks.redress_check(
        make_base_pattern("tshirt"),
        None,
        None,
        start,
        Scene(None, target, None, FitConfig(), progress=Progress(False), log=lines.append),
    ).phase_two_kept


def test_report_says_when_phase_two_was_refused():
    from unsew.fit.report import _redress_note

    note = _redress_note(
        {
            "fit_redressed_mm": None,
            "graded_mm": 7.5,
            "phase_two_kept": False,
            "refused": "panel 'waistband_front' has 3.53 cm^2 over a 81.1 cm outline",
        }
    )
    assert "cannot be meshed afresh" in note and "waistband_front" in note and "graded pattern" in note
    kept = _redress_note({"fit_redressed_mm": 6.0, "graded_mm": 7.5, "phase_two_kept": True, "refused": ""})
    assert "6.00 mm" in kept and "phase two's pattern is returned" in kept
    failed = _redress_note(
        {
            "fit_redressed_mm": None,
            "graded_mm": 7.5,
            "phase_two_kept": False,
            "refused": "",
            "failed": "exploded: an edge is stretched to 5.1 times its pattern length (bound 3)",
        }
    )
    assert "dressed from scratch failed (exploded" in failed and "graded pattern" in failed
    three = _redress_note(
        {
            "fit_redressed_mm": 6.0,
            "graded_mm": 7.5,
            "phase_two_kept": False,
            "refused": "",
            "meshes": 3,
            "edge_lengths_m": [0.025, 0.024, 0.026],
            "fit_mm": [6.0, 9.0, None],
            "graded_fresh_mm": [7.0, 7.2, 7.4],
            "fit_mean_mm": None,
            "graded_mean_mm": 7.2,
        }
    )
    assert "three meshes (2.50 / 2.40 / 2.60 cm" in three and "6.00 / 9.00 / failed" in three
    assert "no mean" in three and "graded pattern and its drape are returned" in three


@pytest.fixture(scope="module")
def auto_spent(small_case, tmp_path_factory):
    """run_fit with AUTO, the report, a mesh spread asked for (4 %), and a 600 s time limit on a
    command that began 1000 s ago (a case whose body took that long to load): (folder, FitResult,
    metrics)."""
    import time

    from unsew.body.case import load_case
    from unsew.fit.run import run_fit

    out = tmp_path_factory.mktemp("spent") / "result"
    cfg = load_config(**{**AUTO, "output.report": True, "checks.mesh_spread": 0.04}, time_limit=600)
    started = time.perf_counter() - 1000
    with pytest.MonkeyPatch.context() as mp:
        _fewer_material_steps(mp)
        result, metrics = run_fit(
            load_case(small_case), cfg, out, progress=False, log=lambda s: None, started=started
        )
    return out, result, metrics


def test_the_time_limit_counts_the_time_before_the_fit(auto_spent):
    """A command that began 1000 s ago has spent a 600 s limit before the fit starts: phase two
    makes no iteration and the mesh spread is skipped, and timings_s says how long the load took."""
    _, r, metrics = auto_spent
    assert r.timings["load_s"] >= 1000
    assert r.time_limit["cuts"][-2:] == ["phase two stopped after 0 of 1 iterations", "mesh spread skipped"]
    assert r.iterations == 0 and metrics["iterations"] == 0 and "mesh_spread" not in metrics


def test_a_spent_time_limit_leaves_out_the_optional_work_and_says_so(auto_spent, auto_fit):
    """With the time limit spent before the fit, grading drapes its first pass only, the material
    choice drapes no fabric (the start's cotton kept), phase two makes no iteration, the mesh
    spread is skipped, and the fit
    still ends with a complete result (the graded pattern) whose metrics.json lists each cut;
    without the limit (auto_fit: the same settings, no mesh spread asked) the material choice
    grades again and searches the stiffness, and phase two iterates."""
    import numpy as np

    out, result, metrics = auto_spent
    cuts = json.loads((out / "metrics.json").read_text())["time_limit"]["cuts"]
    assert cuts[0].startswith("grading: passes 2-2 not draped (about ")
    assert cuts[1:] == [
        "material choice: cotton kept (draping the fabrics would overrun)",
        "phase two stopped after 0 of 1 iterations",
        "mesh spread skipped",
    ]
    assert metrics["iterations"] == 0 and "redress" not in metrics
    np.testing.assert_array_equal(result.x, result.x_graded)
    assert (out / "pattern.json").is_file() and metrics["drape_check"]["ok"]
    assert "time limit 600 s (--time-limit): grading: passes 2-2" in (out / "report.html").read_text()
    from unsew.sim.material import MATERIALS

    assert result.material_choice == [] and result.material == MATERIALS["cotton"]  # no fabric draped

    whole, m2 = auto_fit
    assert m2["time_limit"] == {"limit_s": None, "cuts": []}
    assert m2["iterations"] == AUTO["optimizer.iterations"] and "redress" in m2
    assert any(row["pattern"] == "graded in jersey" for row in whole.material_choice)  # graded again
    assert any("(stretch x" in row["material"] for row in whole.material_choice)  # stiffness scaled


def test_redress_on_three_meshes_compares_fresh_drapes_of_both_patterns(held_fit):
    """Three re-dress meshes (unsew.fit.checks.REDRESS_MESHES, the default): with the pattern and
    material held, phase two's pattern is the graded one up to round-off (1e-16 m). On the fit's
    mesh both dress from scratch to the same distance, which is the start drape's (its material
    was named, not settled into); on the spread's two other meshes an unmoved pattern's drapes are
    the graded pattern's (unsew.fit.checks.unmoved), so the means are equal, the graded pattern is
    returned, and the mesh spread is its drapes on those meshes."""
    import numpy as np

    r = held_fit
    rd = r.redress
    h = SMALL["drape.edge_length"]
    assert rd.meshes == 3 and rd.edge_lengths_m == pytest.approx([h, 0.96 * h, 1.04 * h])
    assert rd.fit_mm[0] == pytest.approx(rd.graded_fresh_mm[0], abs=1e-6)
    assert rd.graded_fresh_mm[0] == pytest.approx(rd.graded_mm, abs=1e-6)
    assert len(set(np.round(rd.graded_fresh_mm, 6))) == 3  # three triangulations, three drapes
    assert rd.fit_mean_mm == pytest.approx(rd.graded_mean_mm, abs=1e-6)
    assert not rd.phase_two_kept and not r.material_fitted
    assert r.mesh_spread.chamfer_mm == rd.graded_fresh_mm[1:]
    np.testing.assert_array_equal(r.x, r.x_graded)


@pytest.mark.parametrize(
    "fit_mm, graded_mm, kept, fit_mean",
    [
        ([4.0, 5.0, 6.0], [4.5, 5.5, 6.5], True, 5.0),  # lower on every mesh
        # lower on the fit's mesh only: one drape would keep it
        ([3.0, 7.0, 7.0], [4.0, 5.0, 5.0], False, 17 / 3),
        # phase two's pattern failed a drape the graded one made
        ([4.0, None, 5.0], [5.0, 6.0, 6.0], False, None),
        # a failed graded drape drops that mesh from both means
        ([4.0, 5.0, 5.0], [5.0, None, 6.0], True, 4.5),
    ],
)
def test_redress_on_three_keeps_phase_two_by_the_mean(monkeypatch, fit_mm, graded_mm, kept, fit_mean):
    """The three-mesh verdict from given distances (the drapes replaced)."""
    from types import SimpleNamespace

    import unsew.fit.checks as checks
    from unsew.fit.progress import Progress

    fit_pattern, graded_pattern = object(), object()
    rest = {id(fit_pattern): iter(fit_mm[1:]), id(graded_pattern): iter(graded_mm[1:])}
    monkeypatch.setattr(checks, "_dressed_mm", lambda pattern, *a: next(rest[id(pattern)]))
    monkeypatch.setattr(
        checks, "dress", lambda *a, **k: SimpleNamespace(x=SimpleNamespace(numpy=lambda: None))
    )
    monkeypatch.setattr(checks, "check_dressed", lambda d, body: SimpleNamespace(ok=True, reason=""))
    monkeypatch.setattr(checks, "unmoved", lambda *a: False)  # two patterns, as told
    target = SimpleNamespace(distance_mm=lambda x, faces: graded_mm[0])
    start = SimpleNamespace(graded=graded_pattern, mesh=SimpleNamespace(faces=None), material=None)
    first = checks.RedressCheck(fit_mm[0], 9.0, fit_mm[0] < 9.0)
    check, spread = checks.redress_on_three(
        first,
        fit_pattern,
        None,
        start,
        Scene(None, target, None, load_config(), progress=Progress(False), log=lambda s: None),
    )
    assert check.phase_two_kept is kept and check.fit_mm == fit_mm and check.graded_fresh_mm == graded_mm
    assert check.fit_mean_mm == (pytest.approx(fit_mean) if fit_mean is not None else None)
    assert spread.chamfer_mm == (fit_mm[1:] if kept else graded_mm[1:])


def test_a_start_graded_again_carries_its_own_meshs_held_vertices(monkeypatch):
    """When the material choice keeps a pattern graded again in another fabric, the start takes
    that grading's mesh, drape and held vertices together (indices into the other mesh would hold
    the wrong vertices)."""
    from types import SimpleNamespace

    import numpy as np

    import unsew.fit.material as fm
    from unsew.fit.budget import TimeBudget
    from unsew.fit.start import Start
    from unsew.sim.material import MATERIALS

    mesh_a, mesh_b = SimpleNamespace(faces="a"), SimpleNamespace(faces="b")
    cotton, wool = MATERIALS["cotton"], MATERIALS["wool"]
    first = Start("base", "pa", mesh_a, np.zeros((3, 3)), [], None, None, cotton, anchors="held_a")
    again = Start("base", "pb", mesh_b, np.ones((4, 3)), [], None, None, wool, anchors="held_b")
    monkeypatch.setattr(fm, "start", lambda *a, **k: again)
    scene = SimpleNamespace(
        cfg=SimpleNamespace(grading=True),
        target=SimpleNamespace(distance_mm=lambda x, faces: 1.0 if faces == "b" else 5.0),
        log=lambda m: None,
    )
    table = [{"material": "wool", "chamfer_mm": 3.0}]
    cur, cf = fm._regraded(first, first, table, scene, "tshirt", TimeBudget(0))
    assert cf == 1.0 and cur.mesh is mesh_b and cur.x is again.x and cur.anchors == "held_b"


def test_redress_returns_the_graded_pattern_when_the_fit_cannot_be_dressed(monkeypatch):
    """Phase two's pattern whose drape from scratch diverges (a foreign tee's re-dress check, at
    193 m/s in its settling) leaves the graded pattern as the result, said in one line, instead
    of ending the fit with the simulator's error."""
    import unsew.fit.checks as checks
    from unsew.errors import SimulationError
    from unsew.pattern.base import make_base_pattern

    def bursts(*a, **k):
        raise SimulationError("simulation diverged at step 27: vertex 204 speed 193 m/s (limit 50)")

    monkeypatch.setattr(checks, "dress", bursts)
    monkeypatch.setattr(checks, "moved_mesh", lambda *a: None)
    rd, lines = _redress_on_stand_ins(make_base_pattern("tshirt"))
    assert not rd.phase_two_kept and rd.graded_mm == 7.5 and "diverged" in rd.failed
    assert len(lines) == 1 and "graded pattern is returned" in lines[0]


def _redress_on_stand_ins(pattern):
    """``redress_check`` of ``pattern`` with a stand-in start (one triangle) and target (7.5 mm
    from anything): (its result, the lines it logged)."""
    from types import SimpleNamespace

    from unsew.fit import checks
    from unsew.fit.config import FitConfig
    from unsew.fit.progress import Progress

    start = SimpleNamespace(x=np.zeros((3, 3)), mesh=SimpleNamespace(faces=np.array([[0, 1, 2]])))
    target = SimpleNamespace(distance_mm=lambda x, f: 7.5)
    lines = []
    scene = Scene(None, target, None, FitConfig(), progress=Progress(False), log=lines.append)
    return checks.redress_check(pattern, None, None, start, scene), lines
