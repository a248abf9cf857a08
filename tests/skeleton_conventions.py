"""skeleton.json files of other rigs' conventions, made from one of ours (a mapping as
``Skeleton.to_dict`` writes it, metres): each function returns a new mapping.

The limb-labelled and SMPL-style ones are the benchmark's (benchmarks/bench_body_measure.py).
"""

from __future__ import annotations

import copy
import random

from benchmarks_loader import load_benchmark

from unsew.body.skeleton import PARTS

_bench = load_benchmark("bench_body_measure")
limb_labelled = _bench.limb_labelled
smpl_style = _bench.smpl_style


def _joint(d: dict, name: str) -> dict:
    return next(j for j in d["joints"] if j["name"] == name)


def no_parts(d: dict) -> dict:
    """No ``part`` key on any joint."""
    out = copy.deepcopy(d)
    for j in out["joints"]:
        j.pop("part", None)
    return out


def random_parts(d: dict, *, seed: int = 0) -> dict:
    """Every joint labelled with a part drawn at random."""
    out = copy.deepcopy(d)
    rng = random.Random(seed)
    for j in out["joints"]:
        j["part"] = rng.choice(PARTS)
    return out


def _insert(d: dict, name: str, parent: str, child: str, t: float, part: str) -> None:
    """A joint ``t`` of the way from ``parent`` to ``child``, made ``child``'s parent."""
    a, b = _joint(d, parent)["position"], _joint(d, child)["position"]
    d["joints"].append(
        {"name": name, "parent": parent, "part": part, "position": [x + t * (y - x) for x, y in zip(a, b)]}
    )
    _joint(d, child)["parent"] = name


def extra_joints(d: dict) -> dict:
    """Joints of other rigs added: a floor root under the pelvis, twist joints halfway along
    each upper arm and thigh (labelled torso, as a careless exporter may), a second spine joint,
    and finger and toe ends with other rigs' names."""
    out = copy.deepcopy(d)
    pel = _joint(out, "pelvis")
    out["joints"].append(
        {
            "name": "Root",
            "parent": None,
            "part": "torso",
            "position": [pel["position"][0], 0.0, pel["position"][2]],
        }
    )
    pel["parent"] = "Root"
    _insert(out, "spine_mid", "spine", "chest", 0.5, "torso")
    for side, s in (("left", "L"), ("right", "R")):
        _insert(out, f"{side}_upperarm_twist", f"{side}_shoulder", f"{side}_elbow", 0.5, "torso")
        _insert(out, f"{side}_thigh_twist", f"{side}_hip", f"{side}_knee", 0.5, "torso")
        w = _joint(out, f"{side}_wrist")["position"]
        out["joints"].append(
            {
                "name": f"mixamorig:{s}HandIndex4",
                "parent": f"{side}_wrist",
                "part": "torso",
                "position": [w[0] + (0.08 if side == "left" else -0.08), w[1] - 0.05, w[2]],
            }
        )
    return out


def shuffled(d: dict, *, seed: int = 0) -> dict:
    """The joints listed in another order."""
    out = copy.deepcopy(d)
    random.Random(seed).shuffle(out["joints"])
    return out


def in_cm(d: dict) -> dict:
    """Positions in centimetres, said by ``"units": "cm"``."""
    out = copy.deepcopy(d)
    out["units"] = "cm"
    for j in out["joints"]:
        j["position"] = [100.0 * x for x in j["position"]]
    return out


CONVENTIONS = {
    "limb_labelled": limb_labelled,
    "no_parts": no_parts,
    "random_parts": random_parts,
    "smpl_style": smpl_style,
    "extra_joints": extra_joints,
    "shuffled": shuffled,
    "in_cm": in_cm,
}


def combined(d: dict, seed: int) -> dict:
    """A random chain of conventions (SMPL-style placements first, which rebuild the joints,
    centimetres last), joints shuffled."""
    rng = random.Random(seed)
    out = smpl_style(d, seed=seed) if rng.random() < 0.5 else copy.deepcopy(d)
    for f in (limb_labelled, no_parts, extra_joints):
        if rng.random() < 0.5:
            out = f(out)
    if rng.random() < 0.5:
        out = random_parts(out, seed=seed)
    out = shuffled(out, seed=seed)
    return in_cm(out) if rng.random() < 0.5 else out
