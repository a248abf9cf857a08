"""Small hand-built patterns for the meshing, control-point, symmetry and parameter tests."""

from __future__ import annotations

import numpy as np

from unsew.pattern.model import Curvature, Edge, Panel, Pattern, Stitch, StitchSide

__all__ = ["loop_edges", "two_squares", "curved_panel", "pentagon", "mini_shirt", "nonconvex_panel"]


def loop_edges(n: int, curv: dict | None = None) -> list[Edge]:
    """Edges i -> i+1 closing the loop of n vertices; curv maps edge index to a Curvature."""
    curv = curv or {}
    return [Edge(i, (i + 1) % n, curv.get(i)) for i in range(n)]


def two_squares(side: float = 0.3) -> Pattern:
    """Two squares side by side, the right edge of A sewn to the left edge of B."""
    sq = np.array([[0, 0], [side, 0], [side, side], [0, side]], float)
    a = Panel("A", sq, loop_edges(4), translation=[0, 0, 0.1])
    b = Panel("B", sq, loop_edges(4), translation=[side, 0, 0.1])
    # A's edge 1 runs (s,0)->(s,s); B's edge 3 runs (0,s)->(0,0): a.start meets b.end.
    return Pattern("two_squares", {"A": a, "B": b}, [Stitch(StitchSide("A", 1), StitchSide("B", 3), "mid")])


def curved_panel() -> Pattern:
    """One panel with a quadratic edge and a circular-arc edge (both bulging outwards)."""
    v = np.array([[0, 0], [0.4, 0], [0.4, 0.3], [0, 0.3]], float)
    curv = {0: Curvature("quadratic", [[0.5, -0.15]]), 2: Curvature("circle", [0.3, False, True])}
    return Pattern("curved", {"P": Panel("P", v, loop_edges(4, curv))})


def pentagon() -> Pattern:
    """A house-shaped pentagon, mirror-symmetric about x = 0.2 (apex on the axis)."""
    v = np.array([[0, 0], [0.4, 0], [0.4, 0.3], [0.2, 0.45], [0, 0.3]], float)
    return Pattern("pentagon", {"H": Panel("H", v, loop_edges(5))})


def nonconvex_panel() -> Pattern:
    """An L-shaped (non-convex) panel with a curved edge."""
    v = np.array([[0, 0], [0.5, 0], [0.5, 0.2], [0.2, 0.2], [0.2, 0.5], [0, 0.5]], float)
    return Pattern("ell", {"L": Panel("L", v, loop_edges(6, {3: Curvature("quadratic", [[0.5, 0.1]])}))})


def mini_shirt() -> Pattern:
    """A toy shirt: front and back (mirror-symmetric torso outlines with a curved neckline) and two
    mirror-image sleeves, sewn at the sides, shoulders and armholes."""
    torso = np.array(
        [
            [-0.25, 0.0],
            [0.25, 0.0],
            [0.25, 0.4],
            [0.3, 0.55],
            [0.08, 0.6],
            [-0.08, 0.6],
            [-0.3, 0.55],
            [-0.25, 0.4],
        ],
        float,
    )
    neck = {4: Curvature("quadratic", [[0.5, -0.2]])}
    front = Panel("front", torso, loop_edges(8, neck), translation=[0, 1.0, 0.15])
    back = Panel(
        "back",
        torso.copy(),
        loop_edges(8, {4: Curvature("quadratic", [[0.5, -0.05]])}),
        translation=[0, 1.0, -0.15],
        rotation=[0, 180, 0],
    )
    # Left sleeve: a trapezoid; the right sleeve is its mirror image (x -> -x), re-ordered CCW.
    sl = np.array([[0.0, 0.0], [0.2, 0.03], [0.2, 0.17], [0.0, 0.2]], float)
    sr = sl * [-1, 1]
    sr = sr[[1, 0, 3, 2]]  # mirror reverses orientation: reorder to CCW
    left = Panel("lsleeve", sl, loop_edges(4), translation=[0.3, 1.4, 0.0])
    right = Panel("rsleeve", sr, loop_edges(4), translation=[-0.3, 1.4, 0.0])
    st = [
        Stitch(StitchSide("front", 1), StitchSide("back", 7), "right_side"),
        Stitch(StitchSide("front", 7), StitchSide("back", 1), "left_side"),
        Stitch(StitchSide("front", 3), StitchSide("back", 5), "shoulder_l"),
        Stitch(StitchSide("front", 5), StitchSide("back", 3), "shoulder_r"),
        Stitch(StitchSide("lsleeve", 0), StitchSide("lsleeve", 2), "l_under"),
        Stitch(StitchSide("rsleeve", 0), StitchSide("rsleeve", 2), "r_under"),
    ]
    return Pattern("mini_shirt", {"front": front, "back": back, "lsleeve": left, "rsleeve": right}, st)
