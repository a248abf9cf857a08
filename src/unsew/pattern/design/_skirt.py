"""Skirts of N panels (gores), alone (under a waistband or not) or below a bodice.

A cone skirt (A-line, circle) unrolls to an annulus sector of angle ``theta`` [rad]; each of its
N gores is a sector of ``theta / N`` (:func:`unsew.pattern.base.skirt._panel`: edges 0 hem, 1
right side, 2 waist, 3 left side), so the N hems together are ``theta * r_hem`` long. A pencil
gore is a hexagon, straight (or tapered to the cut's ``hem`` girth) from the hem to hip depth and
then narrowing to its top (edges 0 hem, 1 right side, 2 right hip line, 3 top, 4 left hip line, 5
left side), as the library's pencil.

Gore k of N is centred at the angle ``phi_k = -90 + 360 (k + 1/2) / N`` degrees around the body
(0 the front, 90 the body's left side): the seams fall on both sides, half of the gores are in
front (``front``, or ``front_0``, ``front_1``, ... from the body's right to its left) and half at
the back (``back`` or ``back_0``, ... from the body's left to its right), and each gore is laid
flat facing out at ``phi_k`` on an ellipse around the hips. With N = 2 this is the library's
two-panel skirt (:mod:`unsew.pattern.base.skirt`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from unsew.pattern.base._band import BAND_HEIGHT, band_panels, band_stitches
from unsew.pattern.base._build import loop_panel, place, stitch
from unsew.pattern.base.skirt import _panel
from unsew.pattern.design._darts import SKIRT_DART, dart_edge, symmetric_darts
from unsew.errors import InputError
from unsew.pattern.curves import edge_length, sample_edge
from unsew.pattern.model import Panel, Stitch

__all__ = ["SkirtCut", "gore_angles", "skirt_panels"]


@dataclass(frozen=True)
class SkirtCut:
    """What a skirt is cut to (world frame, metres)."""

    style: str  #: ``aline``, ``circle`` (cones of angle ``theta``) or ``pencil``
    panels: int  #: number of gores N (even)
    top: float  #: girth of the skirt's top edge [m]
    hip: float  #: girth at the hips, ease included [m]
    top_y: float  #: world height of the skirt's top [m]
    hip_depth: float  #: the hips below the skirt's top [m]
    length: float  #: from the skirt's top to its hem [m]
    theta: float  #: cone: unrolled angle of the whole skirt [rad]
    axes: tuple  #: (x, z) half axes [m] of the ellipse the gores are laid on
    band: bool  #: under a waistband (the band's lower edge meets the gores' tops)
    hem: float | None = None  #: pencil: the hem's girth [m] (None: the hips')
    darts: bool = False  #: two-panel pencil: two waist darts per panel (:data:`SKIRT_DART`)


def gore_angles(n: int) -> np.ndarray:
    """Centre angles [rad], shape (n,), of the n gores around the body (0 front, pi/2 the left)."""
    return np.radians(-90.0 + 360.0 * (np.arange(n) + 0.5) / n)


def _gore(cut: SkirtCut, name: str) -> tuple[Panel, tuple, list, int, list]:
    """One gore in its own frame, the panel point (2,) [m] that sits at the skirt's top on the
    body, its side seams ``[(right edge, left edge, kind)]``, its top edge (the first of its
    top's pieces when darted) and its darts' stitches."""
    n = cut.panels
    if cut.style == "pencil":
        h, t, L, d = cut.hip / (2 * n), cut.top / (2 * n), cut.length, cut.hip_depth
        e = h if cut.hem is None else cut.hem / (2 * n)  # the hem's half width [m]
        share, at, depth = SKIRT_DART
        dw = share * (h - t) if cut.darts else 0.0  # a dart's width [m], one per half panel
        darts = symmetric_darts(t + dw, dw, depth * d, at) if cut.darts else []
        tc = t + dw if darts else t  # the top's corner, the darts' cloth included [m]
        v = np.array([(-e, 0.0), (e, 0.0), (h, L - d), (tc, L), (-tc, L), (-h, L - d)])
        labels = ["hem", "right_side", "right_hip", "waist", "left_hip", "left_side"]
        p = loop_panel(name, v, None, labels)
        if not darts:
            return p, (0.0, L), [(1, 5, "side"), (2, 4, "hip")], 3, []
        p, st, _ = dart_edge(p, 3, darts, "waist")
        k = 3 * len(darts)
        return p, (0.0, L), [(1, 5 + k, "side"), (2, 4 + k, "hip")], 3, st
    r_w = cut.top / cut.theta
    r_h = r_w + cut.length
    p = _panel(name, r_w, r_h, cut.theta / (2 * n))
    # the waist arc's lowest point at the waist; under a band its mean height at the band's edge
    local = (0.0, float(sample_edge(p, 2, 64)[:, 1].mean())) if cut.band else (0.0, r_h - r_w)
    return p, local, [(1, 3, "side")], 2, []


def _cos_sin(phi: float) -> tuple[float, float]:
    """cos and sin of phi [rad], exactly 0 at multiples of a quarter turn."""
    c, s = float(np.cos(phi)), float(np.sin(phi))
    return (0.0 if abs(c) < 1e-12 else c), (0.0 if abs(s) < 1e-12 else s)


def _names(n: int, prefix: str) -> list[str]:
    if n == 2:
        return [f"{prefix}front", f"{prefix}back"]
    return [f"{prefix}front_{j}" for j in range(n // 2)] + [f"{prefix}back_{j}" for j in range(n // 2)]


def _seam_label(k: int, n: int, kind: str, prefix: str) -> str:
    """Label of the seam after gore k (between gores k and k+1), named by its side of the body."""
    deg = round(360.0 * (k + 1) / n) % 360  # from the right side (-90 deg) on
    where = {180: "left", 0: "right"}.get(deg, f"gores_{k}_{(k + 1) % n}")
    return f"{prefix}{where}_{kind}"


def skirt_panels(cut: SkirtCut, *, prefix: str = "", depth_z: float) -> tuple[dict, list[Stitch], list]:
    """The gores of ``cut`` (and its waistband), placed around the body (the ellipse's front at
    z = ``depth_z`` [m]), their seams, and the (panel, edge) of each gore's top, front gores
    first from the body's right to its left, then the back gores from its left to its right.

    Panel names start with ``prefix``; without a band the tops are left for the caller to sew.
    """
    n = cut.panels
    ax, az = cut.axes
    panels, tops, st = {}, [], []
    seams: list = []
    if cut.darts and (cut.style != "pencil" or n != 2):
        raise InputError("waist darts are cut in a two-panel pencil skirt; set skirt='pencil', panels=2")
    for name, phi in zip(_names(n, prefix), gore_angles(n)):
        p, local, seams, top, dart_st = _gore(cut, name)
        st += dart_st
        c, s = _cos_sin(phi)
        r = 1.0 / np.hypot(s / ax, c / az)  # the ellipse's radius at phi [m]
        R = np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])  # +Z turned to (s, 0, c)
        place(p, R, (r * s, cut.top_y, r * c), local)
        panels[name] = p
        tops.append((name, top))
    names = list(panels)
    for k in range(n):
        for right, left, kind in seams:
            st.append(stitch(names[k], right, names[(k + 1) % n], left, _seam_label(k, n, kind, prefix)))
    if cut.band and cut.darts:
        bands, band_st = _darted_band(cut, panels, depth_z)
        panels.update(bands)
        st += band_st
    elif cut.band:
        bands, band_st = _band(cut, panels, tops, depth_z)
        panels.update(bands)
        st += band_st
    return panels, st, tops


def _band(cut: SkirtCut, panels: dict, tops: list, depth_z: float):
    """Front and back waistbands over the gores' tops, their lower edges cut one piece per gore."""
    half = cut.panels // 2
    top_len = edge_length(panels[tops[0][0]], tops[0][1])
    hw = half * top_len / 2
    cuts = [-hw + j * top_len for j in range(1, half)] or None
    waist_y = cut.top_y + BAND_HEIGHT
    bf, bb = band_panels(hw, waist_y, depth_z, cuts=cuts)
    st = []
    for band, side, gores in ((bf, "front", tops[:half]), (bb, "back", tops[half:])):
        for j, (g, e) in enumerate(gores):
            st.append(stitch(band.name, j, g, e, f"{side}_waist" + (f"_{j}" if half > 1 else "")))
    return {bf.name: bf, bb.name: bb}, st + band_stitches(pieces=half)


def _darted_band(cut: SkirtCut, panels: dict, depth_z: float):
    """Front and back waistbands over a darted two-panel pencil skirt, their lower edges cut in
    three to meet the three pieces of each panel's top (right of the darts, between them, left)."""
    names = list(panels)
    p = panels[names[0]]
    pieces = [3, 6, 9]  # the top's pieces, from the panel's right (+x) to its left
    lengths = [edge_length(p, e) for e in pieces]
    t = 0.5 * sum(lengths)
    bf, bb = band_panels(t, cut.top_y + BAND_HEIGHT, depth_z, cuts=[-t + lengths[2], t - lengths[0]])
    st = []
    for band, pn in ((bf, names[0]), (bb, names[1])):
        # the band's lower pieces left to right (+x) against the panel's top pieces (-x)
        st += [stitch(band.name, k, pn, e, f"{pn}_waist_{k}") for k, e in enumerate(pieces[::-1])]
    return {bf.name: bf, bb.name: bb}, st + band_stitches(pieces=3)
