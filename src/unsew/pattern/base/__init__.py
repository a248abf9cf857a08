"""Base sewing patterns (paper 3.2): our own parametric generators sized from body measurements.

``make_base_pattern(garment, measurements=None) -> Pattern`` for ``tshirt``, ``dress``,
``pants``, ``shorts`` and ``skirt``. Panels are placed in 3D around the body (world frame:
metres, Y up, facing +Z, body's left at +X; see :mod:`unsew.pattern.base._frame`).
"""

from __future__ import annotations

import importlib

from unsew.errors import InputError

__all__ = ["make_base_pattern", "GARMENTS"]

#: Garment name -> (module, function).
_MAKERS = {
    "tshirt": ("tshirt", "make_tshirt"),
    "dress": ("dress", "make_dress"),
    "pants": ("pants", "make_pants"),
    "shorts": ("pants", "make_shorts"),
    "skirt": ("skirt", "make_skirt"),
}
GARMENTS = list(_MAKERS)


def make_base_pattern(garment: str, measurements=None):
    """The base :class:`~unsew.pattern.model.Pattern` of ``garment`` sized to ``measurements``
    (a :class:`~unsew.pattern.measurements.Measurements`; default: the default body)."""
    if garment not in _MAKERS:
        raise InputError(f"unknown garment {garment!r}; choose one of {', '.join(GARMENTS)}")
    mod, fn = _MAKERS[garment]
    module = importlib.import_module(f"unsew.pattern.base.{mod}")
    return getattr(module, fn)(measurements)
