"""Fuzz the command line with damaged inputs: every one must end in one ``unsew: error:`` line
and exit status 2 (an :class:`~unsew.errors.InputError`), never a traceback, never exit 0.

Meshes, patterns, skeletons, configs and case folders are generated from valid ones by one
damage each and fed to the real CLI in-process (``unsew.cli.main``). ``unsew fit`` is stopped
just before the fit itself (``run_fit`` is replaced by a guard that fails the test), so an
input that slips through the checks is reported at once instead of running for minutes.
"""

from __future__ import annotations

import copy
import json
from pathlib import Path

import numpy as np
import pytest
import trimesh

from unsew.cli import main
from unsew.errors import InputError
from unsew.io.mesh import write_obj

# ---------------------------------------------------------------------------- valid inputs


def _tube():
    """A sleeveless tube around the default body's chest: verts (V, 3) [m], faces (F, 3)."""
    m = trimesh.creation.cylinder(radius=0.17, height=0.4, sections=24)
    keep = np.abs(m.face_normals[:, 2]) < 0.5
    return m.vertices[:, [0, 2, 1]] + [0.0, 1.15, 0.0], m.faces[keep]


@pytest.fixture(scope="module")
def valid(tmp_path_factory):
    """Files every damage starts from: a tube target, the default body and its skeleton as
    files, a base tshirt pattern (GarmentCode JSON)."""
    from unsew.body.body import default_body
    from unsew.body.skeleton import save_skeleton
    from unsew.io.garmentcode import save_pattern
    from unsew.pattern.base import make_base_pattern

    d = tmp_path_factory.mktemp("valid")
    v, f = _tube()
    write_obj(d / "target.obj", v, f)
    body = default_body()
    write_obj(d / "body.obj", body.verts, body.faces)
    save_skeleton(body.skeleton, d / "skeleton.json")
    save_pattern(make_base_pattern("tshirt"), d / "pattern.json")
    return d


def _case(
    root: Path,
    valid: Path,
    *,
    target: str | None = None,
    meta: dict | str | None = None,
    body: bool = False,
    skeleton: str | None = None,
) -> Path:
    """A case folder: the valid tube target and a default-body meta.json unless replaced."""
    d = root / "case"
    d.mkdir()
    (d / "target.obj").write_text(target if target is not None else (valid / "target.obj").read_text())
    if meta is None:
        meta = {"garment": "tshirt", "body": "default", "units": "m"}
    (d / "meta.json").write_text(meta if isinstance(meta, str) else json.dumps(meta))
    if body:
        (d / "body.obj").write_text((valid / "body.obj").read_text())
        (d / "skeleton.json").write_text(
            skeleton if skeleton is not None else (valid / "skeleton.json").read_text()
        )
    return d


def _obj(v, f) -> str:
    lines = [f"v {x} {y} {z}" for x, y, z in np.asarray(v, dtype=float)]
    lines += ["f " + " ".join(str(int(i) + 1) for i in face) for face in f]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------------- damages
# Each maker takes (tmp, valid) and returns the argv of one command on one damaged input.


def _fit(d: Path, tmp: Path, *extra: str) -> list[str]:
    return ["fit", str(d), "--out", str(tmp / "result"), "--no-progress", *extra]


def _mesh_case(text_of):
    """A maker: fit a case whose target.obj is ``text_of(verts, faces)``."""

    def make(tmp, valid):
        v, f = _tube()
        return _fit(_case(tmp, valid, target=text_of(v, f)), tmp)

    return make


def _nan_vertex(v, f):
    v = v.copy()
    v[f[0, 0], 1] = np.nan  # a vertex a face uses (OBJ readers drop unreferenced ones)
    return _obj(v, f)


def _inf_vertex(v, f):
    v = v.copy()
    v[f[5, 1], 0] = np.inf
    return _obj(v, f)


def _only_segments(v, f):  # "faces" of two vertices: no triangle at all
    return _obj(v, []) + "".join(f"f {a + 1} {b + 1}\n" for a, b, _ in f)


MESHES = {
    "mesh_empty": _mesh_case(lambda v, f: ""),
    "mesh_whitespace": _mesh_case(lambda v, f: "\n \n# nothing here\n"),
    "mesh_nan_vertex": _mesh_case(_nan_vertex),
    "mesh_inf_vertex": _mesh_case(_inf_vertex),
    "mesh_index_out_of_range": _mesh_case(lambda v, f: _obj(v, f) + f"f 1 2 {len(v) + 50}\n"),
    "mesh_no_faces": _mesh_case(lambda v, f: _obj(v, [])),
    "mesh_segments_only": _mesh_case(_only_segments),
    "mesh_binary_garbage": _mesh_case(
        lambda v, f: bytes(np.random.default_rng(0).integers(0, 256, 4000, dtype=np.uint8)).decode("latin-1")
    ),
    "mesh_in_centimetres": _mesh_case(lambda v, f: _obj(v * 100.0, f)),
    "mesh_in_millimetres_declared_metres": _mesh_case(lambda v, f: _obj(v * 1000.0, f)),
    "mesh_z_up": _mesh_case(lambda v, f: _obj(v[:, [0, 2, 1]] * [1, -1, 1], f)),
    "mesh_all_degenerate": _mesh_case(lambda v, f: _obj(np.repeat(v[:1], len(v), 0), f)),
    "mesh_closed_sphere": _mesh_case(
        lambda v, f: _obj(
            trimesh.creation.icosphere(2, 0.2).vertices + [0, 1.1, 0],
            trimesh.creation.icosphere(2, 0.2).faces,
        )
    ),
    "mesh_far_from_body": _mesh_case(lambda v, f: _obj(v + [0.0, 0.0, 0.5], f)),
}

# --- patterns: `unsew pattern export` and `unsew drape` on a damaged GarmentCode JSON


def _pattern_case(damage, command="export"):
    def make(tmp, valid):
        spec = json.loads((valid / "pattern.json").read_text())
        out = damage(copy.deepcopy(spec))
        p = tmp / "pattern.json"
        p.write_text(out if isinstance(out, str) else json.dumps(out))
        if command == "export":
            return ["pattern", "export", str(p), "--svg", str(tmp / "p.svg")]
        if command == "mesh":
            return ["pattern", "mesh", str(p), "--out", str(tmp / "p.obj")]
        if command == "fine mesh":
            return ["pattern", "mesh", str(p), "--out", str(tmp / "p.obj"), "--edge-length", "0.005"]
        return ["drape", str(p), "--out", str(tmp / "g.obj"), "--no-progress"]

    return make


def _panel(spec, name="front"):
    return spec["pattern"]["panels"][name]


def _open_loop(s):
    _panel(s)["edges"][-1]["endpoints"][1] = _panel(s)["edges"][-1]["endpoints"][0]
    return s


def _missing_stitch_target(s):
    s["pattern"]["stitches"][0][1]["panel"] = "no_such_panel"
    return s


def _stitch_edge_out_of_range(s):
    s["pattern"]["stitches"][0][0]["edge"] = 99
    return s


def _self_intersecting(s):  # swap two corners: a bow tie
    v = _panel(s)["vertices"]
    v[0], v[1] = v[1], v[0]
    v[0], v[2] = v[2], v[0]
    return s


def _zero_area(s):  # every corner on one straight line, every edge straight
    p = _panel(s)
    p["vertices"] = [[0.0, 10.0 * i] for i in range(len(p["vertices"]))]
    for e in p["edges"]:
        e.pop("curvature", None)
    return s


def _spike(s):  # corners on one line, curved edges kept: a sliver that folds back on itself
    p = _panel(s)
    p["vertices"] = [[0.0, float(i)] for i in range(len(p["vertices"]))]
    return s


def _units(value):
    def damage(s):
        s["properties"]["units_in_meter"] = value
        return s

    return damage


def _nan_pattern_vertex(s):
    return json.dumps(s).replace(json.dumps(_panel(s)["vertices"][0]), "[NaN, 0.0]", 1)


def _edge_vertex_out_of_range(s):
    _panel(s)["edges"][0]["endpoints"][1] = 999
    return s


PATTERNS = {
    "pattern_not_json": _pattern_case(lambda s: '{"pattern": [1, 2'),
    "pattern_no_panels": _pattern_case(
        lambda s: {"pattern": {"panels": {}, "stitches": []}, "properties": s["properties"]}
    ),
    "pattern_is_a_list": _pattern_case(lambda s: [s]),
    "pattern_open_loop": _pattern_case(_open_loop),
    "pattern_missing_stitch_target": _pattern_case(_missing_stitch_target),
    "pattern_stitch_edge_out_of_range": _pattern_case(_stitch_edge_out_of_range),
    "pattern_self_intersecting_panel": _pattern_case(_self_intersecting, "mesh"),
    "pattern_zero_area_panel": _pattern_case(_zero_area, "mesh"),
    "pattern_spike_panel": _pattern_case(_spike, "fine mesh"),  # crashed Triangle (segfault)
    "pattern_units_zero": _pattern_case(_units(0)),
    "pattern_units_negative": _pattern_case(_units(-100)),
    "pattern_units_text": _pattern_case(_units("cm")),
    "pattern_units_absurd_large": _pattern_case(_units(1), "mesh"),
    "pattern_units_absurd_for_body": _pattern_case(_units(10), "drape"),
    "pattern_units_absurd_small": _pattern_case(_units(1e6), "drape"),
    "pattern_nan_vertex": _pattern_case(_nan_pattern_vertex),
    "pattern_edge_vertex_out_of_range": _pattern_case(_edge_vertex_out_of_range),
}

# --- skeletons: `unsew body measure BODY_DIR` on a body folder with a damaged skeleton.json


def _skeleton_case(damage):
    def make(tmp, valid):
        d = tmp / "body"
        d.mkdir()
        (d / "body.obj").write_text((valid / "body.obj").read_text())
        sk = json.loads((valid / "skeleton.json").read_text())
        out = damage(copy.deepcopy(sk))
        (d / "skeleton.json").write_text(out if isinstance(out, str) else json.dumps(out))
        return ["body", "measure", str(d)]

    return make


def _joint(sk, name):
    return next(j for j in sk["joints"] if j["name"] == name)


def _drop_joint(name):
    def damage(sk):
        sk["joints"] = [j for j in sk["joints"] if j["name"] != name]
        for j in sk["joints"]:
            if j["parent"] == name:
                j["parent"] = "pelvis"
        return sk

    return damage


def _cycle(sk):
    _joint(sk, "pelvis")["parent"] = "chest"
    return sk


def _nan_joint(sk):
    return json.dumps(sk).replace(json.dumps(_joint(sk, "left_elbow")["position"]), "[NaN, 1.0, 0.0]", 1)


def _unknown_parent(sk):
    _joint(sk, "left_knee")["parent"] = "tail"
    return sk


def _duplicate_joint(sk):
    sk["joints"].append(dict(_joint(sk, "neck")))
    return sk


def _bad_part(sk):
    _joint(sk, "left_wrist")["part"] = "wing"
    return sk


def _short_position(sk):
    _joint(sk, "head")["position"] = [0.0, 1.6]
    return sk


def _reparent(name, parent):
    def damage(sk):
        _joint(sk, name)["parent"] = parent
        return sk

    return damage


def _moved(names, dy):
    def damage(sk):
        for n in names:
            _joint(sk, n)["position"][1] += dy
        return sk

    return damage


SKELETONS = {
    "skeleton_knee_under_elbow": _skeleton_case(_reparent("left_knee", "left_elbow")),
    "skeleton_chest_under_hip": _skeleton_case(_reparent("chest", "left_hip")),
    "skeleton_shoulder_under_head": _skeleton_case(_reparent("right_shoulder", "head")),
    "skeleton_chest_above_neck": _skeleton_case(_moved(["chest"], 0.3)),
    "skeleton_hips_at_the_waist": _skeleton_case(_moved(["left_hip", "right_hip"], 0.15)),
    "skeleton_not_json": _skeleton_case(lambda sk: "joints: [pelvis"),
    "skeleton_no_joints": _skeleton_case(lambda sk: {"units": "m", "joints": []}),
    "skeleton_missing_left_knee": _skeleton_case(_drop_joint("left_knee")),
    "skeleton_missing_head": _skeleton_case(_drop_joint("head")),
    "skeleton_cycle": _skeleton_case(_cycle),
    "skeleton_nan_joint": _skeleton_case(_nan_joint),
    "skeleton_unknown_parent": _skeleton_case(_unknown_parent),
    "skeleton_duplicate_joint": _skeleton_case(_duplicate_joint),
    "skeleton_unknown_part": _skeleton_case(_bad_part),
    "skeleton_two_coordinates": _skeleton_case(_short_position),
    "skeleton_in_centimetres_declared_metres": _skeleton_case(
        lambda sk: {
            **sk,
            "joints": [{**j, "position": [100 * x for x in j["position"]]} for j in sk["joints"]],
        }
    ),
}

# --- configs: `unsew fit CASE --config bad.yaml` (the config is read before the case)


def _config_case(text):
    def make(tmp, valid):
        c = tmp / "fit.yaml"
        c.write_text(text)
        return _fit(_case(tmp, valid), tmp, "--config", str(c))

    return make


CONFIGS = {
    "config_not_yaml": _config_case("optimizer:\n  iterations: [1, 2\n"),
    "config_a_list": _config_case("- iterations\n- 10\n"),
    "config_unknown_key": _config_case("iterashuns: 10\n"),
    "config_old_key": _config_case("iterations: 10\n"),
    "config_wrong_type_int": _config_case("optimizer:\n  iterations: many\n"),
    "config_wrong_type_bool": _config_case("grading: 3\n"),
    "config_fractional_iterations": _config_case("optimizer:\n  iterations: 2.5\n"),
    "config_negative_iterations": _config_case("optimizer:\n  iterations: -5\n"),
    "config_negative_edge_length": _config_case("drape:\n  edge_length: -0.02\n"),
    "config_huge_edge_length": _config_case("drape:\n  edge_length: 3.0\n"),
    "config_nan_edge_length": _config_case("drape:\n  edge_length: .nan\n"),
    "config_unknown_material": _config_case("material:\n  start: unobtainium\n"),
    "config_zero_steps": _config_case("drape:\n  steps: 0\n"),
}

# --- case folders


def _case_maker(build):
    def make(tmp, valid):
        return _fit(build(tmp, valid), tmp)

    return make


def _no_meta(tmp, valid):
    d = _case(tmp, valid)
    (d / "meta.json").unlink()
    return d


def _no_target(tmp, valid):
    d = _case(tmp, valid)
    (d / "target.obj").unlink()
    return d


def _unriggable_body(tmp, valid):
    """A closed body mesh without skeleton.json that is no standing person (a 0.6 m ball): it
    cannot be rigged."""
    d = _case(tmp, valid, body=True)
    (d / "skeleton.json").unlink()
    ball = trimesh.creation.icosphere(subdivisions=3, radius=0.3)
    write_obj(d / "body.obj", ball.vertices + [0.0, 1.0, 0.0], ball.faces)
    return d


CASES = {
    "case_missing_folder": lambda tmp, valid: _fit(tmp / "nowhere", tmp),
    "case_folder_is_a_file": lambda tmp, valid: _fit(Path(str(_case(tmp, valid) / "meta.json")), tmp),
    "case_no_meta": _case_maker(_no_meta),
    "case_meta_not_json": _case_maker(lambda tmp, valid: _case(tmp, valid, meta="{garment: tshirt")),
    "case_meta_a_list": _case_maker(lambda tmp, valid: _case(tmp, valid, meta="[1, 2]")),
    "case_unknown_garment": _case_maker(
        lambda tmp, valid: _case(tmp, valid, meta={"garment": "poncho", "body": "default"})
    ),
    "case_unknown_units": _case_maker(
        lambda tmp, valid: _case(
            tmp, valid, meta={"garment": "tshirt", "body": "default", "units": "furlong"}
        )
    ),
    "case_bad_up_axis": _case_maker(
        lambda tmp, valid: _case(tmp, valid, meta={"garment": "tshirt", "body": "default", "up": "w"})
    ),
    "case_up_equals_front": _case_maker(
        lambda tmp, valid: _case(
            tmp, valid, meta={"garment": "tshirt", "body": "default", "up": "z", "front": "z"}
        )
    ),
    "case_no_target": _case_maker(_no_target),
    "case_no_body": _case_maker(lambda tmp, valid: _case(tmp, valid, meta={"garment": "tshirt"})),
    "case_unknown_body_model": _case_maker(
        lambda tmp, valid: _case(tmp, valid, meta={"garment": "tshirt", "body": {"model": "smurf"}})
    ),
    "case_unriggable_body_without_skeleton": _case_maker(_unriggable_body),
    "case_body_with_cyclic_skeleton": _case_maker(
        lambda tmp, valid: _case(
            tmp,
            valid,
            body=True,
            skeleton=json.dumps(_cycle(json.loads((valid / "skeleton.json").read_text()))),
        )
    ),
    "case_bad_pattern_gt": lambda tmp, valid: _fit(
        _write(_case(tmp, valid) / "pattern_gt.json", "{}").parent, tmp
    ),
    "case_base_pattern_missing": lambda tmp, valid: _fit(
        _case(tmp, valid), tmp, "--base", str(tmp / "nope.json")
    ),
}


def _write(p: Path, text: str) -> Path:
    p.write_text(text)
    return p


ALL = {**MESHES, **PATTERNS, **SKELETONS, **CONFIGS, **CASES}


def test_enough_damages():
    assert len(ALL) >= 30
    assert all(len(group) >= 5 for group in (MESHES, PATTERNS, SKELETONS, CONFIGS, CASES))


@pytest.fixture
def no_fit(monkeypatch):
    """Replace the fit itself: an input that reaches it slipped through every check."""

    def accepted(*args, **kwargs):
        raise AssertionError("the damaged input was accepted: the fit started")

    monkeypatch.setattr("unsew.fit.run.run_fit", accepted)


@pytest.mark.parametrize("name", sorted(ALL))
def test_damaged_input_is_one_line_and_exit_2(name, tmp_path, valid, no_fit, capsys, monkeypatch):
    raised: list[BaseException] = []
    import unsew.cli

    real = unsew.cli._one_line
    monkeypatch.setattr(unsew.cli, "_one_line", lambda exc: (raised.append(exc), real(exc))[1])
    argv = ALL[name](tmp_path, valid)
    capsys.readouterr()
    code = main(argv)
    out, err = capsys.readouterr()
    lines = [ln for ln in err.strip().splitlines() if not ln.startswith("unsew: warning: ")]
    assert code == 2, f"{name}: exit {code}; stderr: {err!r}"
    assert len(lines) == 1 and lines[0].startswith("unsew: error: "), f"{name}: {err!r}"
    assert "Traceback" not in err + out
    assert raised and isinstance(raised[-1], InputError), (
        f"{name}: {type(raised[-1]).__name__ if raised else None}"
    )
    # nothing that looks like a result
    assert not any(p.name in ("result", "p.svg", "p.obj", "g.obj") for p in tmp_path.iterdir())


# ---------------------------------------------------------------------------- other conventions
# skeleton.json files as other rigs write them (tests/skeleton_conventions.py): accepted, and the
# body measures as with its own skeleton


@pytest.mark.parametrize("seed", [1, 4, 7])  # together: every convention of combined()
def test_skeletons_of_other_conventions_measure_the_body(seed, tmp_path, valid, capsys):
    """Limb-labelled parts, SMPL-style joint placements, extra joints with other names, random
    or no labels, shuffled joints, centimetres, combined at random: ``unsew body measure``
    accepts each and reads bust, waist and hip within 2.5 cm of the body's reading with its own
    skinning weights."""
    from skeleton_conventions import combined

    from unsew.body.body import default_body
    from unsew.body.measure import measure_body

    ref = measure_body(default_body()).as_dict()
    d = tmp_path / "body"
    d.mkdir()
    (d / "body.obj").write_text((valid / "body.obj").read_text())
    own = json.loads((valid / "skeleton.json").read_text())
    (d / "skeleton.json").write_text(json.dumps(combined(own, seed)))
    code = main(["body", "measure", str(d), "--json"])
    out, err = capsys.readouterr()
    assert code == 0, err
    got = json.loads(out)
    for k in ("bust", "waist", "hip"):
        assert abs(got[k] - ref[k]) <= 0.025, f"{k}: {got[k]} vs {ref[k]} m"
