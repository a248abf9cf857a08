"""Checks the commands make before any long work: a job whose inputs cannot give a sensible
result is refused with one line (:class:`~unsew.errors.InputError`) instead of running for
minutes and writing a huge or meaningless output.

The limits are deliberately loose (a factor of several beyond any garment the base patterns
make); each message says which option overrides or fixes it.
"""

from __future__ import annotations

import numpy as np

from unsew.errors import InputError

__all__ = [
    "MAX_TRIANGLES",
    "estimate_triangles",
    "check_triangle_budget",
    "check_pattern_scale",
]

#: Default refusal threshold of the estimated triangle count of a sewn pattern mesh. The base
#: dress at the finest accepted edge length (0.005 m) makes about 180,000.
MAX_TRIANGLES = 250_000

#: Triangles per (panel area / edge length^2) of the panel mesher: measured on the base tshirt,
#: dress and pants at 0.01 and 0.02 m edges (3.5-3.6); the estimate errs slightly high.
_TRIANGLES_PER_AREA = 3.6

#: A pattern's total panel area against its wearer's surface area: the base patterns span
#: 0.27 (shorts) to 0.79 (dress) of the default body's 1.56 m^2; beyond these factors it cannot
#: be the body's garment.
_AREA_RATIO_RANGE = (0.02, 4.0)


def _pattern_area(pattern) -> float:
    """Total panel area [m^2] of a pattern (absolute signed areas of the outlines)."""
    from unsew.pattern.validate import signed_area

    return float(sum(abs(signed_area(p)) for p in pattern.panels.values()))


def estimate_triangles(pattern, edge_length: float) -> int:
    """Estimated triangle count of ``mesh_pattern(pattern, edge_length=edge_length)``.

    Args:
        pattern: a :class:`~unsew.pattern.model.Pattern` (lengths in metres).
        edge_length: target edge length [m].
    """
    return int(round(_TRIANGLES_PER_AREA * _pattern_area(pattern) / float(edge_length) ** 2))


def check_triangle_budget(
    pattern, edge_length: float, *, limit: int = MAX_TRIANGLES, override: str | None = "--max-triangles"
) -> int:
    """Refuse a pattern whose mesh at ``edge_length`` [m] would exceed ``limit`` triangles.

    Returns the estimate. The message names the panel area so a pattern in the wrong units
    (panels 100x too large) is recognised as such, and ``override`` (the option that raises
    the limit, if the command has one).
    """
    n = estimate_triangles(pattern, edge_length)
    if n > limit:
        area = _pattern_area(pattern)
        raise InputError(
            f"pattern {pattern.name!r} has {area:.3g} m^2 of panels: at edge length {edge_length:g} m its "
            f"mesh would have about {n:,} triangles (limit {limit:,}): check the pattern's units_in_meter or "
            "use a larger --edge-length" + (f", or raise {override}" if override else "")
        )
    return n


def _body_area(body) -> float:
    v = np.asarray(body.verts, dtype=np.float64)
    f = np.asarray(body.faces, dtype=np.int64)
    e1, e2 = v[f[:, 1]] - v[f[:, 0]], v[f[:, 2]] - v[f[:, 0]]
    return float(0.5 * np.linalg.norm(np.cross(e1, e2), axis=1).sum())


def check_pattern_scale(pattern, body) -> None:
    """Refuse a pattern whose panels are far too large or small for ``body``: total panel area
    outside 2 % - 400 % of the body's surface area (a wrong ``units_in_meter``, a pattern drawn
    for a doll or a building)."""
    area, body_area = _pattern_area(pattern), _body_area(body)
    if body_area <= 0:
        return
    ratio = area / body_area
    lo, hi = _AREA_RATIO_RANGE
    if not (lo <= ratio <= hi):
        size = "large" if ratio > hi else "small"
        raise InputError(
            f"pattern {pattern.name!r} is far too {size} for the body: {area:.3g} m^2 of panels against "
            f"{body_area:.3g} m^2 of body surface ({ratio:.3g}x; a garment is {lo:g}x-{hi:g}x); "
            "check the pattern's units_in_meter"
        )
