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
- ``cuffs``: a cuff piece on the sleeves or the trouser legs.
A choice counts as present only where the design's pattern has the piece (``built_choices``):
GarmentCode leaves a lapel out on some necklines although the design names one.
"""

from __future__ import annotations

import yaml

#: pants at most this share of the leg long are shorts (the knee sits near half the leg).
SHORTS_MAX_LENGTH = 0.5
CHOICES = ("sleeves", "waistband", "collar", "cuffs")
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
        },
        "collar_piece": extra,
        "upper": upper,
        "bottom": bottom,
        "wb": wb,
    }


def choices_of_spec(spec: dict) -> dict:
    """The structural choices of a GarmentCode specification dict, read from its panel names
    (GarmentCode's and unsew's programs name the pieces: ``*sleeve*``, ``wb_*`` / ``*band*``,
    ``*collar*`` / ``*hood*`` / ``*lapel*``, ``*cuff*``). {name: bool} for ``CHOICES``."""
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
    }


def built_choices(design_choices: dict, spec: dict) -> dict:
    """The design's choices, each kept only where its specification has the piece: {name: bool}."""
    has = choices_of_spec(spec)
    return {k: bool(design_choices[k] and has[k]) for k in CHOICES}
