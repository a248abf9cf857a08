"""The truth of a GarmentCode design, read from its ``design_params.yaml``, and the same structural
choices read from any GarmentCode specification JSON (so a recovered pattern can be scored).

Garment type (unsew's names where unsew has one):
- upper only -> ``tshirt``; upper + a skirt -> ``dress``; upper + pants -> ``jumpsuit``;
- pants alone -> ``shorts`` when ``pants.length`` (GarmentCode's share of the leg, 0.2-0.9) is
  at most ``SHORTS_MAX_LENGTH``, else ``pants``; any skirt alone -> ``skirt``.
``jumpsuit`` (and any design with a collar piece: ``hood``, ``lapel``, ``turtle``) is a type or a
part unsew has no base for: such cases stay in and count as misses.

Structural choices (each True/False, compared one by one):
- ``sleeves``: the upper has sleeves (``sleeve.sleeveless`` false; either side when asymmetric);
- ``waistband``: a waistband piece (``meta.wb`` set);
- ``collar``: a collar piece (``collar.component.style`` set: Turtle, SimpleLapel, Hood2Panels);
- ``cuffs``: a cuff piece on the sleeves or the trouser legs;
- ``strapless``: no cloth over either shoulder (a ``FittedShirt`` with ``shirt.strapless``, on
  both sides when asymmetric); in a specification, an edge labelled ``strapless_top``.
A choice counts as present only where the design's pattern has the piece (``built_choices``):
GarmentCode leaves a lapel out on some necklines although the design names one.
"""

from __future__ import annotations

import numpy as np
import yaml

#: pants at most this share of the leg long are shorts (the knee sits near half the leg).
SHORTS_MAX_LENGTH = 0.5
CHOICES = ("sleeves", "waistband", "collar", "cuffs", "strapless")
SKIRTS = (
    "SkirtCircle",
    "AsymmSkirtCircle",
    "GodetSkirt",
    "Skirt2",
    "SkirtManyPanels",
    "PencilSkirt",
    "SkirtLevels",
)


def _values(tree: dict, prefix: str = "") -> dict:
    """Flatten GarmentCode's design tree {group: {param: {"v": value, ...}}} to {"group.param": value}."""
    out = {}
    for k, v in tree.items():
        if isinstance(v, dict) and "v" in v:
            out[prefix + k] = v["v"]
        elif isinstance(v, dict):
            out.update(_values(v, prefix + k + "."))
    return out


def truth_of_design(design_yaml_text: str) -> dict:
    """{"type": str, "choices": {name: bool}, "upper", "bottom", "wb": GarmentCode's meta values}
    of a design_params.yaml text."""
    d = _values(yaml.safe_load(design_yaml_text)["design"])
    upper, bottom, wb = d.get("meta.upper"), d.get("meta.bottom"), d.get("meta.wb")
    if upper and bottom == "Pants":
        typ = "jumpsuit"
    elif upper and bottom:
        typ = "dress"
    elif upper:
        typ = "tshirt"
    elif bottom == "Pants":
        typ = "shorts" if float(d.get("pants.length", 1.0)) <= SHORTS_MAX_LENGTH else "pants"
    elif bottom in SKIRTS:
        typ = "skirt"
    else:  # pragma: no cover - GarmentCode's sampler never makes an empty design
        typ = "none"
    asym = bool(upper) and bool(d.get("left.enable_asym"))
    sleeves = bool(upper) and (
        not d.get("sleeve.sleeveless") or (asym and not d.get("left.sleeve.sleeveless"))
    )
    cuff_sleeve = sleeves and d.get("sleeve.cuff.type") is not None
    cuff_pants = bottom == "Pants" and d.get("pants.cuff.type") is not None
    strapless = (
        upper == "FittedShirt"
        and bool(d.get("shirt.strapless"))
        and (not asym or d.get("left.shirt.strapless"))
    )
    collar = bool(upper) and d.get("collar.component.style") is not None
    extra = (
        {"Hood2Panels": "hood", "SimpleLapel": "lapel", "Turtle": "turtle"}.get(
            d.get("collar.component.style")
        )
        if collar
        else None
    )
    return {
        "type": typ,
        "choices": {
            "sleeves": bool(sleeves),
            "waistband": wb is not None,
            "collar": bool(collar),
            "cuffs": bool(cuff_sleeve or cuff_pants),
            "strapless": bool(strapless),
        },
        "collar_piece": extra,
        "upper": upper,
        "bottom": bottom,
        "wb": wb,
    }


def choices_of_spec(spec: dict) -> dict:
    """The structural choices of a GarmentCode specification dict, read from its panel names
    (GarmentCode's and unsew's programs name the pieces: ``*sleeve*``, ``wb_*`` / ``*band*``,
    ``*collar*`` / ``*hood*`` / ``*lapel*``, ``*cuff*``) and edge labels (both label a strapless
    bodice's top ``strapless_top``). {name: bool} for ``CHOICES``."""
    names = [n.lower() for n in spec["pattern"]["panels"]]

    def has(*keys):
        return any(any(k in n for k in keys) for n in names)

    return {
        "sleeves": has("sleeve"),
        "waistband": any(
            n.startswith("wb") or "waistband" in n or n.endswith("_band") or "waist_band" in n for n in names
        ),
        "collar": has("collar", "hood", "lapel", "turtle"),
        "cuffs": has("cuff"),
        "strapless": any(
            e.get("label") == "strapless_top"
            for p in spec["pattern"]["panels"].values()
            for e in p.get("edges", ())
        ),
    }


def built_choices(design_choices: dict, spec: dict) -> dict:
    """The design's choices, each kept only where its specification has the piece: {name: bool}."""
    has = choices_of_spec(spec)
    return {k: bool(design_choices[k] and has[k]) for k in CHOICES}


# ---- the design's structural choices as classes (what a reading off the 3D shape is scored on) ----

#: Sleeve length (GarmentCode's ``sleeve.length``, a share of the arm from the armhole) at most
#: this is a short sleeve (it ends above the elbow, about half the arm), longer a long one.
SHORT_SLEEVE_MAX = 0.5
#: GarmentCode's neckline halves by the shape a reading can tell: a square (two corners, a flat
#: bottom), a V (one corner at the bottom: the two halves meet at an angle under
#: :data:`V_CORNER_DEG`, measured as :func:`neck_corner_deg` does) and round (the rest).
SQUARE_NECKS = ("SquareNeckHalf", "TrapezoidNeckHalf")
V_CORNER_DEG = 115.0
#: ... the corner's arms, as a share of the neckline's width.
V_ARM = 0.35
#: Hem depth below the hip line as a share of the leg (hip line to floor): up to the first value a
#: hem is "above knee", up to the second "knee", beyond "below knee" (the knee sits near 0.45).
LENGTH_EDGES = (0.33, 0.55)
LENGTH_CLASSES = ("above knee", "knee", "below knee")
#: Hem girth over hip girth: below the first value a skirt is "pencil", below the second
#: "a-line", beyond "flared" (a circle, a godet or tiered skirt).
FLARE_EDGES = (1.2, 1.7)
SKIRT_KINDS = ("pencil", "a-line", "flared")
#: Body measurements [cm] used when a design's own body is not known (GarmentCode's mean_all).
MEAN_BODY = {
    "waist": 84.3,
    "hips": 103.5,
    "hips_line": 23.5,
    "leg_length": 85.3,
    "neck_w": 18.0,
    "shoulder_w": 36.0,
    "bust_line": 26.0,
}


def length_class(share: float | None) -> str | None:
    """The hem's length class (:data:`LENGTH_CLASSES`) of a hem ``share`` of the leg below the
    hip line (None: no hem)."""
    if share is None:
        return None
    return LENGTH_CLASSES[int(share > LENGTH_EDGES[0]) + int(share > LENGTH_EDGES[1])]


def skirt_class(flare: float | None) -> str | None:
    """The skirt kind (:data:`SKIRT_KINDS`) of a hem girth / hip girth ratio ``flare``."""
    if flare is None:
        return None
    return SKIRT_KINDS[int(flare >= FLARE_EDGES[0]) + int(flare >= FLARE_EDGES[1])]


def _hem_share(d: dict, bottom: str, body: dict) -> float | None:
    """The hem's depth below the hip line as a share of the leg, from GarmentCode's length rules
    (skirt_paneled.py, pants.py, skirt_levels.py): every length runs from the hip line, and a
    waistband (bands.py: ``waistband.width`` of the hip line's depth) moves the bottom down by its
    width (meta_garment.py stacks the bottom under it)."""
    wb = (
        float(d.get("waistband.width", 0.0)) * body["hips_line"] / body["leg_length"]
        if d.get("meta.wb")
        else 0.0
    )
    return wb + _length_share(d, bottom)


def _length_share(d: dict, bottom: str) -> float:
    """GarmentCode's length parameter of the bottom ``bottom`` (a share of the leg)."""
    if bottom == "Pants":
        return float(d["pants.length"])
    if bottom == "PencilSkirt" or (bottom == "GodetSkirt" and d.get("godet-skirt.base") == "PencilSkirt"):
        return float(d["pencil-skirt.length"])
    if bottom in ("Skirt2", "GodetSkirt"):
        return float(d["skirt.length"])
    if bottom == "SkirtLevels":
        return float(d["levels-skirt.length"])
    return float(d["flare-skirt.length"])  # SkirtCircle, AsymmSkirtCircle, SkirtManyPanels


def _hem_flare(d: dict, bottom: str, body: dict) -> float | None:
    """The skirt's hem girth over the hip girth from GarmentCode's panel rules (None for pants)."""
    waist, hips = body["waist"], body["hips"]
    length = body["hips_line"] + max(_length_share(d, bottom), 0.0) * body["leg_length"]  # [cm]
    base = bottom
    if bottom == "GodetSkirt":
        base = d.get("godet-skirt.base", "PencilSkirt")
    elif bottom == "SkirtLevels":
        base = d.get("levels-skirt.level", "Skirt2")
    if base == "Pants":
        return None
    if base == "PencilSkirt":
        ratio = float(d.get("pencil-skirt.flare", 1.0))
    elif base == "Skirt2":
        ratio = (waist * float(d.get("skirt.ruffle", 1.0)) + 4 * float(d.get("skirt.flare", 0))) / hips
    else:  # circle-like: the waist plus suns x 2 pi x length
        suns = float(d.get("flare-skirt.suns", 1.0))
        ratio = (waist + suns * 2 * 3.141592653589793 * length) / hips
    if bottom == "GodetSkirt":
        ratio += float(d.get("godet-skirt.num_inserts", 0)) * float(d.get("godet-skirt.insert_w", 0)) / hips
    elif bottom == "SkirtLevels":
        ratio = max(ratio, 1.0) * float(d.get("levels-skirt.level_ruffle", 1.0))
    return ratio


def _neck_half_points(kind: str, depth: float, width: float, d: dict, half: str) -> np.ndarray:
    """(k, 2) points [cm] of one neckline half as collars.py draws it: from the shoulder point
    (0, 0) to the centre's bottom (width / 2, -depth)."""
    from judge import edge_points

    a, b = np.zeros(2), np.array([width / 2, -depth])
    flip = bool(d.get(f"collar.{half}_flip_curve"))
    if kind == "VNeckHalf":
        return np.stack([a, b])
    if kind == "CurvyNeckHalf":
        sign = -1 if flip else 1
        return edge_points(a, b, {"type": "cubic", "params": [[0.4, sign * 0.3], [0.8, -sign * 0.3]]}, True)
    if kind == "Bezier2NeckHalf":
        sign = 1 if flip else -1
        cp = [
            float(d.get(f"collar.{half}_bezier_x", 0.5)),
            sign * float(d.get(f"collar.{half}_bezier_y", 0.3)),
        ]
        return edge_points(a, b, {"type": "quadratic", "params": [cp]}, True)
    if kind == "CircleArcNeckHalf":
        angle = np.deg2rad(float(d.get(f"collar.{half}c_angle", 90)))
        r = float(np.linalg.norm(b - a)) / (2 * np.sin(angle / 2))
        return edge_points(a, b, {"type": "circle", "params": [r, angle > np.pi, not flip]}, True)
    raise ValueError(f"no drawing for neckline {kind!r}")


def neck_corner_deg(half: np.ndarray) -> float:
    """The angle [deg] at the bottom of the neckline made of ``half`` (k, 2) (shoulder point to the
    centre's bottom, the centre at the end) and its mirror image: between the points
    :data:`V_ARM` of the neckline's width along it either way from its lowest point (180: round)."""
    full = np.concatenate([half, (half[::-1] * [-1, 1] + [2 * half[-1, 0], 0])[1:]])
    seg = np.linalg.norm(np.diff(full, axis=0), axis=1)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    i0 = int(np.argmin(full[:, 1] + 1e-9 * np.abs(full[:, 0] - half[-1, 0])))
    arm = V_ARM * float(np.ptp(full[:, 0]))
    pa = np.array([np.interp(s[i0] - arm, s, full[:, k]) for k in range(2)]) - full[i0]
    pb = np.array([np.interp(s[i0] + arm, s, full[:, k]) for k in range(2)]) - full[i0]
    cos = float(pa @ pb / max(np.linalg.norm(pa) * np.linalg.norm(pb), 1e-12))
    return float(np.degrees(np.arccos(np.clip(cos, -1.0, 1.0))))


def _neck(d: dict, half: str, body: dict) -> str:
    """A top's front (``"f"``) or back (``"b"``) neckline kind, "square", "v" or "round", drawn
    as bodice.py and collars.py size it on ``body`` (the width between the neck's and the
    shoulders' widths, the depth a share of the bust line's); "none" for a strapless fitted top."""
    if d.get("meta.upper") == "FittedShirt" and d.get("shirt.strapless"):
        return "none"
    kind = d.get(f"collar.{half}_collar")
    if kind in SQUARE_NECKS:
        return "square"
    if kind not in ("VNeckHalf", "CurvyNeckHalf", "Bezier2NeckHalf", "CircleArcNeckHalf"):
        return "round"  # CircleNeckHalf: a circle's arc, round by its making
    w = float(d.get("collar.width", 0.2))
    width = (
        body["neck_w"] + w * (body["shoulder_w"] - 4 - body["neck_w"]) if w >= 0 else (1 + w) * body["neck_w"]
    )
    depth = max(float(d.get(f"collar.{half}c_depth", 0.4)) * body["bust_line"], 1.0)
    return "v" if neck_corner_deg(_neck_half_points(kind, depth, width, d, half)) < V_CORNER_DEG else "round"


def design_of(design_yaml_text: str, *, spec: dict | None = None, body: dict | None = None) -> dict:
    """The design's structural choices as classes, each None where the design has no such part:
    {"sleeves": "none"|"short"|"long", "neck_front", "neck_back": "v"|"square"|"round"|"none",
    "collar": "none"|"hood"|"lapel"|"turtle", "cuffs", "waistband": bool, "skirt": SKIRT_KINDS,
    "length": LENGTH_CLASSES, and the numbers they come from: "sleeve_share", "hem_share",
    "hem_flare"}. ``spec``: the design's specification dict, to keep a piece only where the pattern
    has it (:func:`built_choices`); ``body``: its body's measurements [cm] (:data:`MEAN_BODY`'s keys).
    The necklines are None under a collar piece (a hood, a lapel, a turtle collar is sewn onto the
    neckline: no opening shows its shape). The length is None under a loose top (GarmentCode's
    ``Shirt``): its bottom hangs from the shirt's hem, whose height its own length sets."""
    d = _values(yaml.safe_load(design_yaml_text)["design"])
    t = truth_of_design(design_yaml_text)
    ch = built_choices(t["choices"], spec) if spec is not None else t["choices"]
    body = {**MEAN_BODY, **(body or {})}
    upper, bottom = t["upper"], t["bottom"]
    share = float(d.get("sleeve.length", 1.0)) if ch["sleeves"] else None
    hem = _hem_share(d, bottom, body) if bottom and upper != "Shirt" else None
    flare = _hem_flare(d, bottom, body) if bottom and bottom != "Pants" else None
    return {
        "sleeves": None if not upper else ("none" if share is None else _sleeve_class(share)),
        "neck_front": _neck(d, "f", body) if upper and not ch["collar"] else None,
        "neck_back": _neck(d, "b", body) if upper and not ch["collar"] else None,
        "collar": None if not upper else (t["collar_piece"] if ch["collar"] else "none"),
        "cuffs": ch["cuffs"],
        "waistband": ch["waistband"],
        "skirt": skirt_class(flare),
        "length": length_class(hem),
        "sleeve_share": share,
        "hem_share": hem,
        "hem_flare": flare,
    }


def _sleeve_class(share: float) -> str:
    return "short" if share <= SHORT_SLEEVE_MAX else "long"


def body_measurements(yaml_text: str) -> dict:
    """{"waist", "hips", "hips_line", "leg_length"} [cm] of a GarmentCode body .yaml
    (``_leg_length`` as GarmentCode's body_params.py computes it)."""
    b = yaml.safe_load(yaml_text)["body"]
    leg = b["height"] - b["head_l"] - b["waist_line"] - b["hips_line"]
    return {"waist": b["waist"], "hips": b["hips"], "hips_line": b["hips_line"], "leg_length": leg}
