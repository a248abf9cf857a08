"""GarmentCode's sample specifications (not made by unsew) draped the way `unsew drape` does:
on the body, not fallen, not exploded, outside it. Small mode in the default suite (the shirt at
5 cm edges); every sample on the default body, and the samples and base patterns on a T-pose
and a moved-limb anny body, as slow tests."""

import warnings
from pathlib import Path

import numpy as np
import pytest

from unsew.body.body import body_from_npz, default_body
from unsew.body.sdf import BodySDF
from unsew.dress import DRESS_SETTINGS, dress
from unsew.io.garmentcode import load_pattern
from unsew.sim.checks import check_dressed

ROOT = Path(__file__).resolve().parents[2]
BENCH_DATA = ROOT / "benchmarks" / "data"
SAMPLES = ["shirt_mean", "dress_pencil", "hoody_mean", "js_mean_all"]


def _foreign() -> Path:
    """shared/foreign/patterns beside the repository (../shared from its root in CI)."""
    for up in ROOT.parents:
        d = up / "shared" / "foreign" / "patterns"
        if d.is_dir():
            return d
    pytest.skip("GarmentCode samples not found at ../shared/foreign/patterns beside the repository")


def _sample(name):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # GarmentCode draws backs clockwise: mirrored, with a warning
        return load_pattern(_foreign() / f"{name}_specification.json")


def _check_on_body(name, pattern, body, sdf, *, edge_length, **kw):
    d = dress(pattern, body, sdf=sdf, settings=DRESS_SETTINGS.replace(edge_length=edge_length, **kw))
    v = check_dressed(d, body=body)
    assert v.ok, f"{name}: {v.reason}"
    assert v.inside_pct < 0.5, f"{name}: {v.inside_pct:.2f} % inside the body"
    return d, v


@pytest.fixture(scope="module")
def default_sdf():
    b = default_body()
    return b, BodySDF.build(b)


def test_shirt_small_hangs_from_the_shoulders(default_sdf):
    """GarmentCode's sample shirt (8 panels, backs and right halves drawn clockwise, sleeves in
    front/back halves, no seam labels) hangs from the shoulders with its sleeves on the arms;
    before, it ended at y 0.22-0.53 m."""
    body, sdf = default_sdf
    sk = body.skeleton
    d, v = _check_on_body(
        "shirt", _sample("shirt_mean"), body, sdf, edge_length=0.05, sew_steps=40, settle_steps=10
    )
    assert v.y_max > sk.position("left_shoulder")[1] and v.y_min > sk.position("pelvis")[1]
    x = d.x.numpy()
    names = d.mesh.panel_names
    part = d.mesh.uv_panel
    for side, sgn in (("left", 1.0), ("right", -1.0)):
        sleeve = np.isin(part, [names.index(f"{side}_sleeve_f"), names.index(f"{side}_sleeve_b")])
        c = x[np.unique(d.mesh.x_of_u[sleeve])].mean(axis=0)
        assert sgn * c[0] > abs(sk.position(f"{side}_shoulder")[0]), f"{side} sleeve not on its arm: {c}"


@pytest.mark.slow
@pytest.mark.parametrize("name", SAMPLES)
def test_samples_on_the_default_body(default_sdf, name):
    body, sdf = default_sdf
    _check_on_body(name, _sample(name), body, sdf, edge_length=0.025)


#: Known limit: the jumpsuit is dressed with no code for its kind; on its own body its legs' crotch
#: seam is already the most stretched (1.50, docs/true_patterns.md, `python -m benchmarks
#: true_patterns`), and on pose_step an edge at the moved leg tears. Strict: an XPASS says it drapes.
_JUMPSUIT_STEP = pytest.mark.xfail(
    strict=True,
    reason="known limit: the 12-panel jumpsuit on pose_step, one edge at the moved leg 3.3x its length "
    "(its crotch seam at 1.50 already on its own body: `python -m benchmarks true_patterns`); on the "
    "T-pose body it drapes, its shoulder line over the raised arms' roots",
)


@pytest.mark.slow
@pytest.mark.parametrize(
    "name, body_name",
    [
        pytest.param(n, b, marks=_JUMPSUIT_STEP) if (n, b) == ("js_mean_all", "pose_step") else (n, b)
        for b in ("tpose", "pose_step")
        for n in SAMPLES + ["base_tshirt", "base_dress", "base_pants", "base_shorts", "base_skirt"]
    ],
)
def test_on_posed_bodies(name, body_name):
    path = BENCH_DATA / f"body_{body_name}.npz"
    body = body_from_npz(path)
    if name.startswith("base_"):
        from unsew.io.garmentcode import pattern_from_dict, pattern_to_dict
        from unsew.pattern.base import make_base_pattern

        # through GarmentCode JSON (cm), as a foreign pattern arrives
        pattern = pattern_from_dict(pattern_to_dict(make_base_pattern(name[5:])), name=name[5:])
    else:
        pattern = _sample(name)
    _check_on_body(f"{name} on {body_name}", pattern, body, BodySDF.build(body), edge_length=0.025)


def test_loose_tee_that_tears_without_met_seams_is_dressed_again_with_them():
    """The foreign benchmark's loose long-sleeved tee (its true pattern) on the anny default
    (A-pose) body: started with seam copies apart (the A-pose default) a sleeve edge tore to 3.6x
    its length on the meshes before decision 041; dress() dresses such a drape again with the
    copies met at their midpoint, which holds. Whichever start tears, the drape returned is
    sound (test_dress_guide_fallback.py drives the retry itself)."""
    pytest.importorskip("anny", reason="the case's wearer is an anny body (extra unsew[anny])")
    from unsew.body.case import load_case

    case = load_case(ROOT / "benchmarks" / "foreign" / "cases" / "tee_loose_long__default")
    d = dress(case.pattern_gt, case.body, settings=DRESS_SETTINGS)
    v = check_dressed(d, body=case.body)
    assert v.ok and v.inside_pct < 0.5, v.reason
