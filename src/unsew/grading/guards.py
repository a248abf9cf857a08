"""Bounds on a grading edit that keep every panel valid and a waist above the hips.

Linear grading moves an open curve by the offset measured between two drapes; nothing in that
offset knows how much panel there is to move into, nor where the body holds a waist up. Two
failures seen on garments unsew did not make (the foreign benchmark):

- the sleeved base dress graded towards a sleeveless target: each cuff was asked 26 cm up a
  sleeve whose side seams are shorter than that, and the sleeve became a zero-width spike that
  meshing refuses;
- a waist widened or lowered past the body's hips hangs from nothing and the garment slides down.

So, per edit (:func:`bounded_extensions`, :func:`bounded_girth`, :func:`bounded_waist`):

- *length*: a curve moved inwards (towards its panel's middle) keeps at least
  :data:`MIN_KEEP_LENGTH` between it and the nearest other control point of its panel, measured
  along the move (all of it when the panel already has less); one contour's curves move together
  by the most any of them allows, so a hem stays one line across its panels;
- *width*: a curve narrowed keeps at least :data:`MIN_KEEP_WIDTH` of its 2D length;
- *waist*: the top opening of a garment hanging from the waist (its centre nearer the hip joints
  than the shoulders) is moved down no lower than :data:`WAIST_ABOVE_HIP` above the hip joints,
  and widened to no more than the body's hip girth less :data:`WAIST_HIP_EASE` (a waist already
  wider is not widened; grading never narrows it for this bound, since a loop measured on a
  crumpled drape reads longer than the opening is);
- *band*: a waistband's top is lengthened to no more than the target's top loop
  (:func:`bounded_band`): a band drapes stretched or at rest, never gathered shorter than its cloth.

What is cut is reported as a warning on the contour's row of the grading table.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.errors import UnsewError
from unsew.grading.edit import edit_directions
from unsew.pattern.curves import edge_length

__all__ = [
    "MIN_KEEP_LENGTH",
    "MIN_KEEP_WIDTH",
    "WAIST_ABOVE_HIP",
    "WAIST_HIP_EASE",
    "WaistBound",
    "waist_bound",
    "room_inward",
    "bounded_extensions",
    "bounded_girth",
    "bounded_waist",
    "bounded_band",
]

#: Length [m] an inward move leaves between a curve and the rest of its panel (a sleeve keeps
#: at least this much of its side seams).
MIN_KEEP_LENGTH = 0.03
#: Length [m] a narrowed open curve keeps in 2D (a cuff or hem never closes up).
MIN_KEEP_WIDTH = 0.03
#: Height [m] above the hip joints below which grading does not move a waist.
WAIST_ABOVE_HIP = 0.03
#: A waist opening stays at least this much [m] smaller than the body's hip girth.
WAIST_HIP_EASE = 0.02


@dataclass(frozen=True)
class WaistBound:
    """Where the body holds a waist up: hip joints' mean height ``hip_height`` [m] (world y),
    shoulder joints' mean height ``shoulder_height`` [m], and the hip girth [m] (None when it
    could not be measured)."""

    hip_height: float
    shoulder_height: float
    hip_girth: float | None

    def holds(self, centre_y: float) -> bool:
        """Whether a top opening whose centre is at height ``centre_y`` [m] is a waist (nearer
        the hip joints than the shoulders)."""
        return abs(centre_y - self.hip_height) < abs(centre_y - self.shoulder_height)


def waist_bound(body) -> WaistBound | None:
    """The :class:`WaistBound` of a body (:class:`~unsew.body.body.Body` with a skeleton), or None
    when its skeleton lacks hip or shoulder joints."""
    sk = body.skeleton
    names = ("left_hip", "right_hip", "left_shoulder", "right_shoulder")
    if sk is None or any(n not in sk for n in names):
        return None
    hip_y = 0.5 * float(sk.position("left_hip")[1] + sk.position("right_hip")[1])
    sh_y = 0.5 * float(sk.position("left_shoulder")[1] + sk.position("right_shoulder")[1])
    try:
        from unsew.body.measure import measure_body

        girth = float(measure_body(body).hip)
    except (UnsewError, ValueError, IndexError):  # a body the tape cannot read: bound the height only
        girth = None
    return WaistBound(hip_y, sh_y, girth)


def room_inward(pattern, positions: np.ndarray, curve, controls) -> tuple[float, np.ndarray]:
    """How far [m] an open curve can move inwards before it reaches the nearest other control
    point of its panel, measured along its move direction, and that direction (2,) (unit).

    pattern, positions (Nc, 2) float64 [m], curve (:class:`~unsew.grading.curves.OpenCurve`),
    controls: as :func:`unsew.grading.edit.edit_directions`. ``inf`` when the panel has no other
    control point or the curve has none.
    """
    d, _, _ = edit_directions(pattern, positions, curve, controls)
    own = set(int(g) for g in curve.controls)
    others = [int(g) for g in controls.of_panel(curve.panel_index) if int(g) not in own]
    if not others or not own or not np.any(d):
        return float("inf"), d
    inner = float(min(positions[g] @ d for g in own))
    outer_rest = float(max(positions[g] @ d for g in others))
    return max(inner - outer_rest, 0.0), d


def bounded_extensions(pattern, positions: np.ndarray, items, exts: dict, controls) -> tuple[dict, dict]:
    """``exts`` (target index -> extension [m], negative inwards) with every inward move cut to
    the room its curves have (:func:`room_inward` less :data:`MIN_KEEP_LENGTH`, shared by the
    inward-moving curves of one panel), and the notes: target index -> warning."""
    inward_per_panel: dict[int, int] = {}
    for it in items:
        if exts.get(it.match.target, 0.0) < 0:
            for c in it.curves:
                inward_per_panel[c.panel_index] = inward_per_panel.get(c.panel_index, 0) + 1
    out, notes = dict(exts), {}
    for it in items:
        t = it.match.target
        e = out.get(t, 0.0)
        if e >= 0 or not it.curves:
            continue
        allowed = min(
            (
                max(room_inward(pattern, positions, c, controls)[0] - MIN_KEEP_LENGTH, 0.0)
                / inward_per_panel[c.panel_index]
            )
            for c in it.curves
        )
        if -e > allowed:
            out[t] = -allowed
            notes[t] = (
                f"move cut from {e * 100:+.1f} to {-allowed * 100:+.1f} cm: the panel keeps "
                f"{MIN_KEEP_LENGTH * 100:.0f} cm beyond the curve"
            )
    return out, notes


def bounded_girth(pattern, curve, girth_change: float) -> tuple[float, str]:
    """A curve's change of length [m] with a narrowing cut so it keeps :data:`MIN_KEEP_WIDTH` of
    its 2D length (all of it when shorter already), and a warning ("" when nothing was cut)."""
    length = sum(edge_length(pattern.panels[curve.panel], e) for e in curve.edges)
    floor = -max(length - MIN_KEEP_WIDTH, 0.0)
    if girth_change >= floor:
        return girth_change, ""
    return floor, (
        f"{curve.panel}: narrowing cut from {girth_change * 100:+.1f} to {floor * 100:+.1f} cm: "
        f"the curve keeps {MIN_KEEP_WIDTH * 100:.0f} cm"
    )


def bounded_waist(
    bound: WaistBound | None, centre_y: float, extension: float, girth: float, girth_change: float
) -> tuple[float, float, list]:
    """The top opening's (extension [m], girth change [m]) bounded by the body, and warnings.

    bound: the body's :class:`WaistBound` (None: no bound). centre_y: the opening's centre height
    on the drape [m]. extension: its wanted move (negative: down). girth: its girth on the drape
    [m]; girth_change: the wanted change [m] (only a widening is bounded). Only a top opening
    that is a waist (:meth:`WaistBound.holds`) is bounded.
    """
    if bound is None or not bound.holds(centre_y):
        return extension, girth_change, []
    notes = []
    lowest = -max(centre_y - (bound.hip_height + WAIST_ABOVE_HIP), 0.0)
    if extension < lowest:
        notes.append(
            f"waist move cut from {extension * 100:+.1f} to {lowest * 100:+.1f} cm: it stays "
            f"{WAIST_ABOVE_HIP * 100:.0f} cm above the hip joints"
        )
        extension = lowest
    if bound.hip_girth is not None and girth_change > 0:  # a widening only: never narrowed here
        most = max(bound.hip_girth - WAIST_HIP_EASE - girth, 0.0)
        if girth_change > most:
            notes.append(
                f"waist widening cut from {girth_change * 100:+.1f} to {most * 100:+.1f} cm: the "
                f"opening stays {WAIST_HIP_EASE * 100:.0f} cm under the hip girth "
                f"{bound.hip_girth * 100:.1f} cm"
            )
            girth_change = most
    return extension, girth_change, notes


def bounded_band(rest: float, target_length: float, girth_change: float) -> tuple[float, str]:
    """A waistband top's change of length [m] cut so that its cloth edge is no longer than the
    target's top loop, and a warning ("" when nothing was cut).

    rest: the rest length [m] of the band's top edges (the cloth the loop is made of).
    target_length: the target's top loop [m]. girth_change: the wanted change [m] (the target's
    loop minus the drape's).

    A band is a stiff strip held by the body: its top edge drapes at rest or stretched, never
    gathered shorter than its cloth (true of every banded foreign target). Graded by the drapes' difference
    alone, a band whose own drape gathered it would come out longer than the target's loop and slide down.
    """
    if not rest > 0 or rest + girth_change <= target_length:
        return girth_change, ""
    most = target_length - rest
    return most, (
        f"band length change cut from {girth_change * 100:+.1f} to {most * 100:+.1f} cm: its top stays no "
        f"longer than the target's loop ({target_length * 100:.1f} cm)"
    )
