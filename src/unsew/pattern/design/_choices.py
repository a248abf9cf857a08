"""The choices of a design: :class:`Design`, the discrete options (:data:`CHOICES`), the candidates
of a garment type (:func:`design_space`) and the design of each library base (:func:`design_of_base`)."""

from __future__ import annotations

import itertools
from dataclasses import asdict, dataclass, fields, replace

from unsew.errors import InputError
from unsew.pattern.design._collar import TURTLE_HEIGHT

__all__ = [
    "Design",
    "CHOICES",
    "GARMENTS",
    "CIRCLE_FRACTIONS",
    "LENGTHS",
    "STRAPLESS_DROP",
    "TOP_DROP_RANGE",
    "design_space",
    "design_of_base",
    "design_name",
]

#: Garment types a design drafts.
GARMENTS = ("tshirt", "dress", "pants", "shorts", "skirt", "jumpsuit")
#: Discrete choices: field of :class:`Design` -> its options.
CHOICES = {
    "garment": GARMENTS,
    "sleeves": ("none", "short", "long"),
    "sleeve_pieces": (1, 2),
    "cuffs": (False, True),
    "neckline_front": ("round", "v", "square", "boat"),
    "neckline_back": ("round", "v", "square", "boat"),
    "waist_seam": (False, True),
    "fitted": (True, False),
    "skirt": ("aline", "pencil", "circle", "darted"),
    "panels": (2, 4, 6, 8),
    "waistband": (False, True),
    "darts": (False, True),
    "leg": ("full", "knee", "shorts"),
    "leg_cuffs": (False, True),
    "collar": ("none", "hood", "turtle"),
}
#: Named hem positions a design's ``length`` may give (see :func:`unsew.pattern.design.length_to`).
LENGTHS = ("hip", "mini", "knee", "midi", "ankle")
#: Circle fractions :func:`design_space` samples for circle skirts (the field is continuous).
CIRCLE_FRACTIONS = (0.25, 0.5, 0.75, 1.0)

#: Garments with a top (front and back from the neck down, sleeves, necklines).
TOPS = ("tshirt", "dress", "jumpsuit")
#: A strapless top's edge below the armpits [m], where none is read, and the range it may take [m].
STRAPLESS_DROP = 0.03
TOP_DROP_RANGE = (-0.15, 0.3)
#: How far above the natural waist a top's hem may lie [m] (a crop top; a fitted bodice ends at
#: the waist); every other garment's hem lies at least :data:`MIN_LENGTH` below it [m].
TOP_LENGTH_MIN = -0.15
MIN_LENGTH = 0.05
#: Garments with trouser legs, and each one's default leg length.
LEGGED = {"pants": "full", "shorts": "shorts", "jumpsuit": "full"}


@dataclass(frozen=True)
class Design:
    """A garment's structural choices and the few measures not read off the body.

    Fields that do not apply to the garment type are ignored (a skirt's ``sleeves``); the body's
    girths and lengths come from :class:`~unsew.pattern.measurements.Measurements` at drafting.

    garment: one of :data:`GARMENTS`. A ``dress`` is one piece from neck to hem
    (``waist_seam=False``) or a bodice and a skirt sewn at the natural waist; a ``jumpsuit`` is a
    bodice and trousers sewn at the natural waist; ``shorts`` are trousers of leg ``"shorts"``.
    """

    garment: str = "tshirt"
    #: tops and bodices: ``none``, ``short`` or ``long`` (tapering to the wrist)
    sleeves: str = "short"
    #: 1: one panel per arm, sewn to itself under the arm; 2: front and back halves joined by a
    #: straight seam along the top of the arm
    sleeve_pieces: int = 1
    #: a cuff (a band CUFF_HEIGHT high) at each sleeve's hem, the sleeve that much shorter
    cuffs: bool = False
    #: front and back necklines: ``round``, ``v``, ``square`` or ``boat`` (a boat neck widens the
    #: neck opening of both front and back, whose shoulder seams meet)
    neckline_front: str = "round"
    neckline_back: str = "round"
    #: dress: a bodice and a skirt sewn at the natural waist (else one piece, neck to hem)
    waist_seam: bool = False
    #: one-piece dress: its side seam curved in at the waist (else straight, a shift dress)
    fitted: bool = True
    #: skirts and a waist-seamed dress's skirt: ``aline`` (a cone), ``pencil`` (straight below the
    #: hips), ``circle`` (a cone of ``circle_fraction`` of a full circle), ``darted`` (an A-line
    #: shaped by darts: two panels under a waistband, a skirt only)
    skirt: str = "aline"
    #: circle skirt: the unrolled cone's angle as a fraction of a full turn [-], (0.1, 1]
    circle_fraction: float = 0.5
    #: A-line: the cone's unrolled angle beyond what the hips need [rad]
    aline_flare: float = 0.35
    #: skirts: number of panels (gores), even, 2-16; seams at the sides, half of them in front
    panels: int = 2
    #: skirts and trousers: under a front and a back waistband; a dress cut at the waist
    #: (``waist_seam``) or a jumpsuit: a band between the bodice and the skirt or trousers
    waistband: bool = False
    #: waist darts (V notches sewn shut): a top's front and back at the hem (for a hem at the
    #: waist), a waist-seamed dress's bodice under a waistband, a two-panel pencil skirt's top
    darts: bool = False
    #: trousers and jumpsuits: ``full``, ``knee`` or ``shorts`` (None: the garment's own, set at
    #: construction: ``shorts`` for shorts, else ``full``)
    leg: str | None = None
    #: trousers and jumpsuits: a cuff (a band CUFF_HEIGHT high, front and back) at each leg's
    #: hem, the leg that much shorter
    leg_cuffs: bool = False
    #: hem below the natural waist [m] (a top's may lie above it, down to :data:`TOP_LENGTH_MIN`),
    #: or where on the body it falls, one of :data:`LENGTHS` (``"knee"``: measured on the body
    #: drafted for, :func:`~unsew.pattern.design.length_to`); None: the garment's own (a tee at
    #: the hips, a skirt at the knee, a dress at mid-calf or the knee, trousers by ``leg``)
    length: float | str | None = None
    #: one-piece dress: the hem's width beyond the hips per side seam [m]; trousers: the hem's
    #: half width added per leg panel [m] (None: the garment's own: 0.18 / 0.03 / 0)
    hem_flare: float | None = None
    #: the hem's girth [m]: each trouser leg's opening, a pencil skirt's, a one-piece dress's or a
    #: top's hem (it replaces ``hem_flare`` there); None: the garment's own
    hem_girth: float | None = None
    #: added to the bust, waist and hip girths the garment is cut to [m] (a looser fit)
    ease: float = 0.0
    #: tops: ``none``, ``hood`` (two side panels sewn together over the head, sized to the head)
    #: or ``turtle`` (a standing band, front and back); sewn to round necklines
    collar: str = "none"
    #: a turtle collar's height above the neckline [m]
    collar_height: float = TURTLE_HEIGHT
    #: tops: no shoulders, armholes nor neckline; front and back end in one straight edge round
    #: the chest (``strapless_top``, held at its height when dressed), ``top_drop`` below the armpits
    strapless: bool = False
    #: a strapless top's edge below the armpits (the underarm point a sleeved top is cut to) [m]
    top_drop: float = STRAPLESS_DROP

    def __post_init__(self) -> None:
        names = ("garment", "sleeves", "sleeve_pieces", "neckline_front", "neckline_back", "skirt", "collar")
        for name in names:
            _check_choice(name, getattr(self, name))
        if self.collar != "none" and (self.neckline_front, self.neckline_back) != ("round", "round"):
            raise InputError(
                f"a {self.collar} is sewn to round necklines; set neckline_front and neckline_back to 'round'"
            )
        _check_range("collar_height", self.collar_height, 0.02, 0.25)
        _check_strapless(self)
        if self.leg is not None:
            _check_choice("leg", self.leg)
        if self.leg is None and self.garment in LEGGED:  # the garment's own leg, named
            object.__setattr__(self, "leg", LEGGED[self.garment])
        if self.garment == "shorts" and self.leg not in (None, "shorts"):
            raise InputError(
                f"shorts have leg 'shorts', not {self.leg!r}; use garment 'pants' for other legs"
            )
        if not (isinstance(self.panels, int) and 2 <= self.panels <= 16 and self.panels % 2 == 0):
            raise InputError(f"a skirt has an even number of panels from 2 to 16, not {self.panels!r}")
        _check_range("circle_fraction", self.circle_fraction, 0.1, 1.0)
        _check_range("aline_flare", self.aline_flare, 0.0, 2.0)
        _check_range("ease", self.ease, -0.05, 0.4)
        if isinstance(self.length, str):
            if self.length not in LENGTHS:
                raise InputError(
                    f"design length must be metres or one of {list(LENGTHS)}, not {self.length!r}"
                )
        elif self.length is not None:
            lo = TOP_LENGTH_MIN if self.garment == "tshirt" else MIN_LENGTH
            _check_range("length", self.length, lo, 1.6)
        if self.hem_flare is not None:
            _check_range("hem_flare", self.hem_flare, 0.0, 0.6)
        if self.hem_girth is not None:
            _check_range("hem_girth", self.hem_girth, 0.2, 4.0)

    def replace(self, **changes) -> "Design":
        """A copy with ``changes`` (field name -> value)."""
        return replace(self, **changes)

    def as_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def from_dict(cls, d: dict) -> "Design":
        """From a mapping of field names (a YAML or JSON file); unknown keys raise InputError."""
        unknown = set(d) - {f.name for f in fields(cls)}
        if unknown:
            raise InputError(
                f"unknown design field(s) {sorted(unknown)}; known: {[f.name for f in fields(cls)]}"
            )
        return cls(**d)


def _check_strapless(d: Design) -> None:
    """A strapless design is a top without sleeves, collar or neckline shapes."""
    _check_range("top_drop", d.top_drop, *TOP_DROP_RANGE)
    if not d.strapless:
        return
    if d.garment not in TOPS:
        raise InputError(f"a {d.garment} has no top to be strapless; strapless is for {', '.join(TOPS)}")
    if d.sleeves != "none" or d.collar != "none":
        raise InputError("a strapless top has no sleeves nor collar; set sleeves='none', collar='none'")
    if (d.neckline_front, d.neckline_back) != ("round", "round"):
        raise InputError("a strapless top has no neckline; leave neckline_front and neckline_back 'round'")


def _check_choice(name: str, value) -> None:
    if value not in CHOICES[name] or type(value) is not type(CHOICES[name][0]):
        raise InputError(f"design {name} must be one of {list(CHOICES[name])}, not {value!r}")


def _check_range(name: str, value, lo: float, hi: float) -> None:
    if not isinstance(value, (int, float)) or not (lo <= float(value) <= hi):
        raise InputError(f"design {name} must be a number in [{lo:g}, {hi:g}], not {value!r}")


#: Base name -> the fields of its design (the rest at their defaults).
_BASES = {
    "tshirt": {},
    "tshirt_long": {"sleeves": "long"},
    "tshirt_sleeveless": {"sleeves": "none"},
    "dress": {"garment": "dress"},
    "dress_sleeveless": {"garment": "dress", "sleeves": "none"},
    "dress_straight": {"garment": "dress", "fitted": False},
    "dress_straight_sleeveless": {"garment": "dress", "fitted": False, "sleeves": "none"},
    "pants": {"garment": "pants"},
    "pants_band": {"garment": "pants", "waistband": True},
    "shorts": {"garment": "shorts"},
    "shorts_band": {"garment": "shorts", "waistband": True},
    "skirt": {"garment": "skirt"},
    "skirt_band": {"garment": "skirt", "waistband": True},
    "skirt_circle": {"garment": "skirt", "skirt": "circle", "waistband": True},
    "skirt_pencil": {"garment": "skirt", "skirt": "pencil", "waistband": True},
    "skirt_darts": {"garment": "skirt", "skirt": "darted", "waistband": True},
}


def design_of_base(name: str) -> Design:
    """The design whose :func:`~unsew.pattern.design.draft` is the library base ``name``
    (:data:`unsew.pattern.base.BASES`) for any measurements."""
    if name not in _BASES:
        raise InputError(f"unknown base pattern {name!r}; choose one of {', '.join(_BASES)}")
    return Design(**_BASES[name])


def _top_choices() -> list[dict]:
    """Every sleeve, cuff and neckline combination of a top (no cuffs or pieces without sleeves),
    each collar on round necklines, and the strapless top."""
    out = []
    for sleeves in CHOICES["sleeves"]:
        pieces = (1,) if sleeves == "none" else CHOICES["sleeve_pieces"]
        cuffs = (False,) if sleeves == "none" else CHOICES["cuffs"]
        for p, c, nf, nb in itertools.product(
            pieces, cuffs, CHOICES["neckline_front"], CHOICES["neckline_back"]
        ):
            out.append(dict(sleeves=sleeves, sleeve_pieces=p, cuffs=c, neckline_front=nf, neckline_back=nb))
        for p, c, collar in itertools.product(pieces, cuffs, CHOICES["collar"][1:]):  # on round necklines
            out.append(dict(sleeves=sleeves, sleeve_pieces=p, cuffs=c, collar=collar))
    return out + [dict(sleeves="none", strapless=True)]


def _skirt_choices(*, band: bool) -> list[dict]:
    """Every skirt style, circle fraction, panel count (and waistband when ``band``)."""
    out = []
    bands = CHOICES["waistband"] if band else (False,)
    for style, n, wb in itertools.product(("aline", "pencil", "circle"), CHOICES["panels"], bands):
        for frac in CIRCLE_FRACTIONS if style == "circle" else (0.5,):
            out.append(dict(skirt=style, panels=n, waistband=wb, circle_fraction=frac))
    if band:
        out.append(dict(skirt="darted", panels=2, waistband=True))
    return out


def design_space(garment: str) -> list[Design]:
    """Every design of garment type ``garment`` over :data:`CHOICES` (circle fractions from
    :data:`CIRCLE_FRACTIONS`), continuous measures at their defaults: the candidates a fit can
    enumerate. Fields that do not apply to the garment stay at their defaults."""
    if garment not in GARMENTS:
        raise InputError(f"unknown garment {garment!r}; choose one of {', '.join(GARMENTS)}")
    if garment == "tshirt":
        return [Design(**t) for t in _top_choices()]
    if garment == "skirt":
        return [Design(garment="skirt", **s) for s in _skirt_choices(band=True)]
    if garment in ("pants", "shorts"):
        legs = CHOICES["leg"] if garment == "pants" else ("shorts",)
        return [
            Design(garment=garment, leg=g, waistband=b, leg_cuffs=c)
            for g, b, c in itertools.product(legs, CHOICES["waistband"], CHOICES["leg_cuffs"])
        ]
    if garment == "jumpsuit":
        return [Design(garment="jumpsuit", leg=g, **t) for g in CHOICES["leg"] for t in _top_choices()]
    lowers = [dict(waist_seam=False, fitted=f) for f in CHOICES["fitted"]]
    lowers += [dict(waist_seam=True, **s) for s in _skirt_choices(band=False)]
    return [Design(garment="dress", **lo, **t) for lo in lowers for t in _top_choices()]


def _top_parts(d: Design) -> list[str]:
    """A top's part of its design's name: sleeves (2: in two pieces), cuffs, necklines, a collar;
    ``strapless`` alone for a strapless top."""
    if d.strapless:
        return ["strapless"]
    sleeved = d.sleeves != "none"
    parts = [d.sleeves + ("2" if sleeved and d.sleeve_pieces == 2 else "")]
    if d.cuffs and sleeved:
        parts.append("cuffs")
    return parts + [d.neckline_front, d.neckline_back] + ([d.collar] if d.collar != "none" else [])


def _measure_parts(d: Design, parts: list[str]) -> list[str]:
    """The measures' part of a design's name: those set away from their defaults."""
    out = []
    if d.aline_flare != Design.aline_flare and any(q.startswith("alinex") for q in parts):
        out.append(f"flare{d.aline_flare:g}")
    if isinstance(d.length, str):
        out.append(d.length)
    for f in ("length", "hem_flare", "hem_girth"):
        if isinstance(getattr(d, f), (int, float)):
            out.append(f"{f}{getattr(d, f):g}")
    if d.ease:
        out.append(f"ease{d.ease:g}")
    if d.collar == "turtle" and d.collar_height != Design.collar_height:
        out.append(f"collar{d.collar_height:g}")
    if d.strapless and d.top_drop != Design.top_drop:
        out.append(f"drop{d.top_drop:g}")
    return out


def design_name(d: Design) -> str:
    """A short name of ``d``: the library base's name when ``d`` is a base's design, else the
    garment and its choices joined by ``-`` (e.g. ``dress-seam-circle0.75x4-long2-cuffs-square-round``,
    ``tshirt-long-round-round-hood``)."""
    for base, kw in _BASES.items():
        if Design(**kw) == d:
            return base
    parts = [d.garment]
    if d.garment == "dress":
        parts.append("seam" if d.waist_seam else ("fitted" if d.fitted else "straight"))
    if d.garment == "skirt" or (d.garment == "dress" and d.waist_seam):
        frac = f"{d.circle_fraction:g}" if d.skirt == "circle" else ""
        parts.append(f"{d.skirt}{frac}x{d.panels}")
    if d.garment in LEGGED:
        parts.append(d.leg + ("-legcuffs" if d.leg_cuffs else ""))
    banded = d.garment in ("skirt", "pants", "shorts", "jumpsuit") or (d.garment == "dress" and d.waist_seam)
    if banded and d.waistband:
        parts.append("band")
    if d.darts:
        parts.append("darts")
    if d.garment in TOPS:
        parts += _top_parts(d)
    return "-".join(parts + _measure_parts(d, parts))
