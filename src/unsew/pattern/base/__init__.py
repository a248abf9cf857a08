"""Base sewing patterns (paper 3.2): our own parametric generators sized from body measurements.

``make_base_pattern(name, measurements=None) -> Pattern`` for a garment type (``tshirt``,
``dress``, ``pants``, ``shorts``, ``skirt``: its first, default base) or one of the library's
variants of a type (:data:`BASES`, :func:`bases_for`): tees with long sleeves or none, a
sleeveless dress, straight (unwaisted) dresses, trousers, shorts and skirts under a waistband, a half-circle
skirt, a pencil skirt, a darted A-line. Panels are placed in 3D around the body (world frame: metres, Y up,
facing +Z, body's left at +X; see :mod:`unsew.pattern.base._frame`).
"""

from __future__ import annotations

import importlib

from unsew.errors import InputError

__all__ = ["make_base_pattern", "GARMENTS", "BASES", "bases_for", "garment_of"]

#: Base name -> (garment type, module, function). The first base of each type is its default.
_MAKERS = {
    "tshirt": ("tshirt", "tshirt", "make_tshirt"),
    "tshirt_long": ("tshirt", "tshirt", "make_tshirt_long"),
    "tshirt_sleeveless": ("tshirt", "tshirt", "make_tshirt_sleeveless"),
    "dress": ("dress", "dress", "make_dress"),
    "dress_sleeveless": ("dress", "dress", "make_dress_sleeveless"),
    "dress_straight": ("dress", "dress", "make_dress_straight"),
    "dress_straight_sleeveless": ("dress", "dress", "make_dress_straight_sleeveless"),
    "pants": ("pants", "pants", "make_pants"),
    "pants_band": ("pants", "pants", "make_pants_band"),
    "shorts": ("shorts", "pants", "make_shorts"),
    "shorts_band": ("shorts", "pants", "make_shorts_band"),
    "skirt": ("skirt", "skirt", "make_skirt"),
    "skirt_band": ("skirt", "skirt", "make_skirt_band"),
    "skirt_circle": ("skirt", "skirt", "make_skirt_circle"),
    "skirt_pencil": ("skirt", "skirt", "make_skirt_pencil"),
    "skirt_darts": ("skirt", "skirt", "make_skirt_darts"),
}
#: The garment types (each is also the name of its default base).
GARMENTS = ["tshirt", "dress", "pants", "shorts", "skirt"]
#: Every base of the library, default bases first within each type.
BASES = list(_MAKERS)


def bases_for(garment: str) -> list[str]:
    """The library's base names of garment type ``garment``, its default first."""
    if garment not in GARMENTS:
        raise InputError(f"unknown garment {garment!r}; choose one of {', '.join(GARMENTS)}")
    return [n for n, (g, _, _) in _MAKERS.items() if g == garment]


def garment_of(name: str) -> str:
    """The garment type of base ``name`` (a type is its own)."""
    if name not in _MAKERS:
        raise InputError(f"unknown base pattern {name!r}; choose one of {', '.join(BASES)}")
    return _MAKERS[name][0]


#: The bases whose side seam curves in at the waist: ``waist_point`` makes that waist a vertex.
WAISTED = ("dress", "dress_sleeveless")


def make_base_pattern(garment: str, measurements=None, *, waist_point: bool = False, necklines=None):
    """The base :class:`~unsew.pattern.model.Pattern` ``garment`` (a garment type or a base name
    of :data:`BASES`) sized to ``measurements`` (a
    :class:`~unsew.pattern.measurements.Measurements`; default: the default body).
    waist_point: a :data:`WAISTED` base's side seam as two straight edges meeting at the waist, a
    vertex that grading can move (:mod:`unsew.grading.profile`); other bases are unchanged.
    necklines: a top's or dress's front and back neckline shapes
    (:data:`unsew.pattern.base.tshirt.NECKLINES`; None: round); ignored by other garments."""
    if garment not in _MAKERS:
        raise InputError(f"unknown garment {garment!r}; choose one of {', '.join(BASES)}")
    g, mod, fn = _MAKERS[garment]
    module = importlib.import_module(f"unsew.pattern.base.{mod}")
    kw = {}
    if waist_point and garment in WAISTED:
        kw["waist_point"] = True
    if necklines is not None and g in ("tshirt", "dress"):
        kw["necklines"] = tuple(necklines)
    return getattr(module, fn)(measurements, **kw)
