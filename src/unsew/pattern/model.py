"""The sewing-pattern model (paper 3.2): panels, edges with curves, stitches.

Units: metres inside unsew. Panel vertices are 2D positions in the panel's own frame [m];
each panel has a 3D placement (translation [m], rotation as XYZ Euler angles [degrees],
GarmentCode's convention: a 2D point p maps to ``R @ (p_x, p_y, 0) + translation``).

A panel's outline is a closed counter-clockwise loop of edges: ``edges[i].end ==
edges[(i+1) % n].start`` and the signed area is positive. Edge curvature follows
GarmentCode's *relative* coordinates: a control point ``(s, t)`` of the edge from ``a`` to
``b`` sits at ``a + s*(b-a) + t*perp(b-a)`` with ``perp(x, y) = (-y, x)`` (a quarter turn
counter-clockwise). A circular arc is stored as ``(radius [m], large_arc, right)``:
the arc through ``a`` and ``b`` of that radius, the larger of the two arcs if ``large_arc``,
bulging to the right of ``a -> b`` if ``right``.

A stitch pairs two panel edges; by convention side ``a`` runs against side ``b`` (the
start of ``a`` is sewn to the end of ``b``), which is how two counter-clockwise panels facing
each other meet. Curve geometry (sampling, lengths) is in :mod:`unsew.pattern.curves`.
"""

from __future__ import annotations

import copy
from dataclasses import dataclass, field
from typing import Literal

import numpy as np

__all__ = ["Curvature", "Edge", "Panel", "StitchSide", "Stitch", "Pattern"]

CurveKind = Literal["quadratic", "cubic", "circle"]


@dataclass
class Curvature:
    """Curvature of one edge, in GarmentCode's relative convention (see module docstring).

    ``quadratic``: ``params = [[s, t]]`` (one control point, relative).
    ``cubic``: ``params = [[s1, t1], [s2, t2]]`` (two control points, relative).
    ``circle``: ``params = [radius_m, large_arc, right]`` (radius in metres; two bools).
    """

    kind: CurveKind
    params: list

    def copy(self) -> "Curvature":
        return Curvature(self.kind, copy.deepcopy(self.params))


@dataclass
class Edge:
    """One edge of a panel outline, from vertex ``start`` to vertex ``end`` (panel indices)."""

    start: int
    end: int
    curvature: Curvature | None = None
    label: str = ""


@dataclass
class Panel:
    """A pattern piece.

    vertices: 2D corner/join positions [m], shape (N, 2), float64.
    edges: closed counter-clockwise loop over the vertices.
    translation: 3D placement [m], shape (3,). rotation: XYZ Euler angles [deg], shape (3,).
    """

    name: str
    vertices: np.ndarray
    edges: list[Edge]
    translation: np.ndarray = field(default_factory=lambda: np.zeros(3))
    rotation: np.ndarray = field(default_factory=lambda: np.zeros(3))
    label: str = ""

    def __post_init__(self) -> None:
        self.vertices = np.asarray(self.vertices, dtype=np.float64).reshape(-1, 2)
        self.translation = np.asarray(self.translation, dtype=np.float64).reshape(3)
        self.rotation = np.asarray(self.rotation, dtype=np.float64).reshape(3)

    def copy(self) -> "Panel":
        return Panel(
            self.name,
            self.vertices.copy(),
            [Edge(e.start, e.end, e.curvature.copy() if e.curvature else None, e.label) for e in self.edges],
            self.translation.copy(),
            self.rotation.copy(),
            self.label,
        )


@dataclass(frozen=True)
class StitchSide:
    """One side of a stitch: edge number ``edge`` of panel ``panel``."""

    panel: str
    edge: int


@dataclass
class Stitch:
    """Two panel edges sewn together; ``a.start`` meets ``b.end`` (see module docstring)."""

    a: StitchSide
    b: StitchSide
    label: str = ""


@dataclass
class Pattern:
    """A sewing pattern: named panels, stitches, and what GarmentCode or unsew keep beside them.

    properties: GarmentCode's ``properties`` block, kept for lossless round trips.
    unsew: unsew's own additions (control points, symmetry, material), written under the
    ``"unsew"`` key of the JSON so GarmentCode readers ignore it.
    """

    name: str
    panels: dict[str, Panel]
    stitches: list[Stitch] = field(default_factory=list)
    panel_order: list[str] = field(default_factory=list)
    properties: dict = field(default_factory=dict)
    unsew: dict = field(default_factory=dict)
    extra: dict = field(default_factory=dict)  # unknown top-level keys, written back unchanged

    def __post_init__(self) -> None:
        if not self.panel_order:
            self.panel_order = list(self.panels)

    def ordered_panels(self) -> list[Panel]:
        """Panels in ``panel_order`` (the order meshing and control points use)."""
        return [self.panels[n] for n in self.panel_order]

    def copy(self) -> "Pattern":
        return Pattern(
            self.name,
            {k: p.copy() for k, p in self.panels.items()},
            [Stitch(s.a, s.b, s.label) for s in self.stitches],
            list(self.panel_order),
            copy.deepcopy(self.properties),
            copy.deepcopy(self.unsew),
            copy.deepcopy(self.extra),
        )
