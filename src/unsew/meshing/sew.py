"""Panel meshes and the sewn garment mesh (paper 3.2, "Parameterization" and "Sewn garment shape").

``mesh_pattern`` samples every panel edge at a target edge length, giving the two sides of each
stitch the same number of segments, triangulates every panel (:mod:`unsew.meshing.triangulate`),
and merges stitched vertices into the sewn mesh X. The 2D rest mesh U keeps one vertex per panel
corner/sample; the map X <- U (``x_of_u``) is one-to-many on seams and one-to-one elsewhere.

Stitch convention (:mod:`unsew.pattern.model`): side ``a`` runs against side ``b``, so the k-th
sample of ``a`` (from its start) is sewn to the k-th sample of ``b`` counted from its end.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field

import numpy as np

from unsew.errors import InputError, PatternError
from unsew.meshing.triangulate import signed_areas, triangle_min_angles, triangulate_polygon
from unsew.pattern.curves import edge_length as _edge_length
from unsew.pattern.curves import sample_edge
from unsew.pattern.model import Pattern, euler_xyz_to_matrix

__all__ = ["GarmentMesh", "mesh_pattern", "write_rest_obj", "EDGE_LENGTH_RANGE"]

#: Accepted target edge lengths [m] (smaller is too slow to simulate, larger too coarse to drape).
EDGE_LENGTH_RANGE = (0.005, 0.1)


@dataclass
class GarmentMesh:
    """The 2D rest mesh U of all panels and the sewn 3D topology X (docs/ARCHITECTURE.md).

    uv: 2D rest positions [m], (Nu, 2) float64, each panel in its own frame.
    uv_panel: panel index (into ``panel_names``) of each uv vertex, (Nu,) int64.
    faces_uv: triangles into ``uv``, (F, 3) int64, counter-clockwise in 2D.
    x_of_u: sewn vertex of each uv vertex, (Nu,) int64, values in [0, n_x).
    faces: the same triangles into the sewn vertices, (F, 3) int64 (= x_of_u[faces_uv]).
    n_x: number of sewn vertices.
    panel_names: panel names, = pattern.panel_order.
    edge_verts: (panel name, edge index) -> uv indices along that edge, (k,) int64, start to end,
        corners included.
    seam_pairs: uv index pairs sewn together, (S, 2) int64 (side a, side b).
    uv_placed3d: flat panels placed in 3D by their translation/rotation [m], (Nu, 3) float64:
        ``R @ (u, v, 0) + t`` with R from :func:`unsew.pattern.model.euler_xyz_to_matrix`
        (GarmentCode's XYZ Euler convention as its mesh generator applies it, ``R = Rz Ry Rx``).
    panel_offsets: first uv index of each panel and Nu at the end, (P+1,) int64; a panel's
        boundary vertices come first, in outline order, then its interior vertices.
    n_boundary: number of boundary (outline) vertices of each panel, (P,) int64.
    edge_length: target edge length used [m].
    """

    uv: np.ndarray
    uv_panel: np.ndarray
    faces_uv: np.ndarray
    x_of_u: np.ndarray
    faces: np.ndarray
    n_x: int
    panel_names: list[str]
    edge_verts: dict
    seam_pairs: np.ndarray
    uv_placed3d: np.ndarray
    panel_offsets: np.ndarray = field(default_factory=lambda: np.zeros(1, dtype=np.int64))
    n_boundary: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=np.int64))
    edge_length: float = 0.02
    #: panel name -> "mirror" (half triangulated and mirrored), "pair:<source>" (the source's
    #: triangulation moved onto it) or "own" (triangulated on its own); see mesh_pattern.
    panel_symmetry: dict = field(default_factory=dict)

    @property
    def n_uv(self) -> int:
        """Number of 2D rest vertices Nu."""
        return int(len(self.uv))

    def boundary_loop(self, p: int) -> np.ndarray:
        """uv indices (k,) int64 of panel ``p``'s outline, counter-clockwise, starting at the start
        of its edge 0."""
        o = int(self.panel_offsets[p])
        return np.arange(o, o + int(self.n_boundary[p]), dtype=np.int64)

    def interior(self, p: int) -> np.ndarray:
        """uv indices (k,) int64 of panel ``p``'s interior (non-outline) vertices."""
        return np.arange(
            int(self.panel_offsets[p]) + int(self.n_boundary[p]),
            int(self.panel_offsets[p + 1]),
            dtype=np.int64,
        )

    def min_angle(self) -> float:
        """Smallest triangle angle [deg] over the whole 2D mesh."""
        return float(triangle_min_angles(self.uv, self.faces_uv).min())

    def quality(self) -> dict:
        """Mesh figures: vertices (uv and sewn), triangles, min angle [deg], smallest signed area
        [m^2], count of non-counter-clockwise or degenerate triangles."""
        area = signed_areas(self.uv, self.faces_uv)
        return {
            "uv_vertices": self.n_uv,
            "sewn_vertices": int(self.n_x),
            "triangles": int(len(self.faces_uv)),
            "min_angle_deg": self.min_angle(),
            "min_area_m2": float(area.min()),
            "bad_triangles": int((area <= 1e-14).sum()),
        }


class _UnionFind:
    def __init__(self, n: int) -> None:
        self.parent = np.arange(n)

    def find(self, i: int) -> int:
        p = self.parent
        root = i
        while p[root] != root:
            root = p[root]
        while p[i] != root:
            p[i], i = root, p[i]
        return int(root)

    def union(self, i: int, j: int) -> None:
        ri, rj = self.find(i), self.find(j)
        if ri != rj:
            self.parent[max(ri, rj)] = min(ri, rj)


def _segments_per_edge(pattern: Pattern, edge_length: float, even: frozenset = frozenset()) -> dict:
    """Number of segments of every (panel, edge); both sides of a stitch (and chains of stitches)
    get the largest count any of them asks for, made even when the chain holds a key of ``even``
    (an edge crossed by its panel's mirror axis, which needs a sample at its midpoint)."""
    keys = [(name, i) for name in pattern.panel_order for i in range(len(pattern.panels[name].edges))]
    index = {k: j for j, k in enumerate(keys)}
    n = np.array(
        [max(1, math.ceil(_edge_length(pattern.panels[k[0]], k[1]) / edge_length - 1e-9)) for k in keys],
        dtype=np.int64,
    )
    uf = _UnionFind(len(keys))
    for s in pattern.stitches:
        for side in (s.a, s.b):
            if (side.panel, side.edge) not in index:
                raise PatternError(
                    f"stitch {s.label or ''} refers to panel {side.panel!r} edge {side.edge}, which does not "
                    "exist; fix the stitch or add the panel"
                )
        uf.union(index[(s.a.panel, s.a.edge)], index[(s.b.panel, s.b.edge)])
    roots = np.array([uf.find(j) for j in range(len(keys))])
    best = np.zeros(len(keys), dtype=np.int64)
    np.maximum.at(best, roots, n)
    for k in even:
        r = roots[index[k]]
        best[r] += best[r] % 2
    return {k: int(best[roots[j]]) for j, k in enumerate(keys)}


def mesh_pattern(
    pattern: Pattern, *, edge_length: float = 0.02, min_angle: float = 20.0, symmetric: bool = False
) -> GarmentMesh:
    """Triangulate every panel and sew the panels into one garment mesh.

    pattern: the sewing pattern (panels closed, counter-clockwise; see unsew.pattern.validate).
    edge_length: target edge length h [m], in [0.005, 0.1]. Each edge gets
        n = max(1, ceil(length / h)) segments of equal arc length (stitched sides share n).
    min_angle: triangle quality bound [deg] (interior triangles; a sharper outline corner keeps
        its own angle).
    symmetric: mesh symmetric panels symmetrically (:mod:`unsew.meshing.symmetric`): a panel
        with a mirror axis (Algorithm 1) is triangulated on one half and mirrored, the second
        panel of a pair gets the first one's triangulation; an edge crossed by a mirror axis
        gets an even number of segments. Panels whose sampled outline is not symmetric are
        triangulated on their own. ``GarmentMesh.panel_symmetry`` says what each panel got.
        Off by default: measured with bench_grading (3 cm) on the exactly symmetric default
        body, symmetric meshes made the drape exactly symmetric but not more repeatable from
        one mesh to another (t-shirt: 7-8 mm between 2.9/3.0/3.1 cm meshes against 4.5-5.7),
        and grading came out worse (Chamfer ratio t-shirt 0.75 against 0.26, skirt 1.01
        against 0.58).

    Returns a :class:`GarmentMesh` (shapes in its docstring).
    """
    lo, hi = EDGE_LENGTH_RANGE
    if not (lo <= float(edge_length) <= hi):
        raise InputError(
            f"edge length {edge_length:g} m is outside {lo:g}-{hi:g} m; pass e.g. --edge-length 0.02"
        )
    if not (0.0 <= float(min_angle) <= 33.0):
        raise InputError(f"minimum angle {min_angle:g} deg is outside 0-33 deg (Triangle's guaranteed range)")
    if not pattern.panel_order:
        raise PatternError("the pattern has no panels; add at least one panel")
    sym = _symmetry_of(pattern) if symmetric else None
    mirrors = {mi.panel: mi for mi in sym.mirrors} if sym is not None else {}
    pair_of = {pr.target: pr for pr in sym.pairs} if sym is not None else {}
    nseg = _segments_per_edge(
        pattern, edge_length, _axis_edges(pattern, _axes(sym) if sym is not None else {})
    )
    outlines, starts_of = _sample_outlines(pattern, nseg)
    meshed, how = _mesh_panels(pattern, outlines, mirrors, pair_of, edge_length, min_angle)
    rest = _join_panels(pattern, meshed, outlines, starts_of, nseg)
    seam_pairs = _seam_pairs(pattern, rest["edge_verts"])
    x_of_u = _sewn_index(seam_pairs, len(rest["uv"]))
    return GarmentMesh(
        uv=rest["uv"],
        uv_panel=rest["uv_panel"],
        faces_uv=rest["faces_uv"],
        x_of_u=x_of_u,
        faces=x_of_u[rest["faces_uv"]],
        n_x=int(x_of_u.max()) + 1,
        panel_names=list(pattern.panel_order),
        edge_verts=rest["edge_verts"],
        seam_pairs=seam_pairs,
        uv_placed3d=rest["uv_placed3d"],
        panel_offsets=rest["panel_offsets"],
        n_boundary=rest["n_boundary"],
        edge_length=float(edge_length),
        panel_symmetry=how,
    )


def _sample_outlines(pattern: Pattern, nseg: dict) -> tuple[dict, dict]:
    """Each panel's outline sampled with ``nseg[(panel, edge)]`` segments per edge.

    Returns (panel name -> outline (m, 2) [m], closed loop without its last point repeated;
    panel name -> index in that outline of each edge's first sample)."""
    outlines, starts_of = {}, {}
    for name in pattern.panel_order:
        panel = pattern.panels[name]
        parts, starts = [], []
        m = 0
        for i in range(len(panel.edges)):
            pts = sample_edge(panel, i, nseg[(name, i)])[:-1]
            starts.append(m)
            parts.append(pts)
            m += len(pts)
        outlines[name], starts_of[name] = np.concatenate(parts, axis=0), starts
    return outlines, starts_of


def _join_panels(pattern: Pattern, meshed: dict, outlines: dict, starts_of: dict, nseg: dict) -> dict:
    """The panel meshes ``meshed`` (name -> (verts (n, 2) [m], tris (t, 3))) one after another
    in ``panel_order``: the rest mesh U before sewing.

    Returns a dict of :class:`GarmentMesh` fields: ``uv`` (Nu, 2) [m], ``uv_panel`` (Nu,),
    ``faces_uv`` (F, 3) int64, ``uv_placed3d`` (Nu, 3) [m] (each panel at its 3D placement),
    ``panel_offsets`` (P + 1,), ``n_boundary`` (P,) and ``edge_verts`` ((panel, edge) -> uv
    indices of its samples, both ends included)."""
    uvs, panels_of, tris_all, placed = [], [], [], []
    edge_verts: dict = {}
    offsets = [0]
    n_boundary = []
    for p, name in enumerate(pattern.panel_order):
        panel = pattern.panels[name]
        starts, m = starts_of[name], len(outlines[name])
        verts, tris = meshed[name]
        o = offsets[-1]
        for i in range(len(panel.edges)):
            k = nseg[(name, i)]
            edge_verts[(name, i)] = o + (starts[i] + np.arange(k + 1)) % m
        uvs.append(verts)
        panels_of.append(np.full(len(verts), p, dtype=np.int64))
        tris_all.append(tris + o)
        r = euler_xyz_to_matrix(panel.rotation)  # GarmentCode's convention, R = Rz Ry Rx
        placed.append(np.c_[verts, np.zeros(len(verts))] @ r.T + panel.translation)
        n_boundary.append(m)
        offsets.append(o + len(verts))
    return {
        "uv": np.concatenate(uvs, axis=0),
        "uv_panel": np.concatenate(panels_of),
        "faces_uv": np.concatenate(tris_all, axis=0).astype(np.int64),
        "uv_placed3d": np.concatenate(placed, axis=0),
        "panel_offsets": np.asarray(offsets, dtype=np.int64),
        "n_boundary": np.asarray(n_boundary, dtype=np.int64),
        "edge_verts": edge_verts,
    }


def _seam_pairs(pattern: Pattern, edge_verts: dict) -> np.ndarray:
    """(S, 2) int64 uv vertex pairs sewn together: side ``a``'s k-th sample against side
    ``b``'s k-th from its end, stitch by stitch."""
    pairs = []
    for s in pattern.stitches:
        ea = edge_verts[(s.a.panel, s.a.edge)]
        eb = edge_verts[(s.b.panel, s.b.edge)]
        pairs.append(np.stack([ea, eb[::-1]], axis=1))
    return np.concatenate(pairs, axis=0).astype(np.int64) if pairs else np.zeros((0, 2), dtype=np.int64)


def _sewn_index(seam_pairs: np.ndarray, n_uv: int) -> np.ndarray:
    """x_of_u (Nu,) int64: the sewn vertex of each of the ``n_uv`` uv vertices, seam pairs
    merged, numbered in the order of their first uv vertex."""
    uf = _UnionFind(n_uv)
    for i, j in seam_pairs:
        uf.union(int(i), int(j))
    roots = np.array([uf.find(i) for i in range(n_uv)], dtype=np.int64)
    _, x_of_u = np.unique(roots, return_inverse=True)  # roots are min indices: X keeps U's order
    return x_of_u.astype(np.int64)


def _symmetry_of(pattern: Pattern):
    """Algorithm 1 on the pattern, or None when it cannot run (a pattern it does not handle is
    meshed without symmetry rather than refused)."""
    from unsew.pattern.symmetry import detect_symmetry

    try:
        return detect_symmetry(pattern)
    except Exception:  # noqa: BLE001 - symmetry is an optimisation of the mesh, never required
        return None


def _axes(sym) -> dict:
    """panel -> (point, direction) of its mirror axis [m]: the detected ones, and for the second
    panel of a pair whose first panel has one, that axis moved by the pair's rigid motion."""
    axes = {mi.panel: (np.asarray(mi.point), np.asarray(mi.direction)) for mi in sym.mirrors}
    names = list(sym.panel_names)

    def centre(n):
        p = names.index(n)
        return sym.c0[int(sym.offsets[p]) : int(sym.offsets[p + 1])].mean(axis=0)

    for pr in sym.pairs:
        if pr.source in axes and pr.target not in axes:
            point, direction = axes[pr.source]
            M = np.asarray(pr.matrix)
            axes[pr.target] = (M @ (point - centre(pr.source)) + centre(pr.target), M @ direction)
    return axes


def _axis_edges(pattern: Pattern, axes: dict) -> frozenset:
    """(panel, edge) keys of edges that their panel's mirror axis maps onto themselves."""
    from unsew.meshing.symmetric import reflect

    keys = set()
    for name, (point, direction) in axes.items():
        panel = pattern.panels[name]
        for i in range(len(panel.edges)):
            pts = sample_edge(panel, i, 8)
            scale = max(float(np.linalg.norm(pts[-1] - pts[0])), 1e-9)
            if np.abs(reflect(pts, point, direction) - pts[::-1]).max() < 1e-6 * scale:
                keys.add((name, i))
    return frozenset(keys)


def _mesh_panels(pattern, outlines, mirrors, pair_of, edge_length, min_angle):
    """Triangulate every panel: {name: (verts, tris)} and {name: "mirror" | "pair:<source>" | "own"}."""
    from unsew.meshing.symmetric import transport_mesh, triangulate_mirrored

    meshed, how = {}, {}
    order = [n for n in pattern.panel_order if n not in pair_of] + [
        n for n in pattern.panel_order if n in pair_of
    ]
    for name in order:
        out = outlines[name]
        res = None
        pr = pair_of.get(name)
        if pr is not None and pr.source in meshed:
            sv, st = meshed[pr.source]
            res = transport_mesh(
                outlines[pr.source], sv, st, out, mirrored=pr.mirrored, edge_length=edge_length
            )
            if res is not None:
                how[name] = f"pair:{pr.source}"
        if res is None and name in mirrors:
            mi = mirrors[name]
            res = triangulate_mirrored(
                out, mi.point, mi.direction, edge_length=edge_length, min_angle=min_angle, name=name
            )
            if res is not None:
                how[name] = "mirror"
        if res is None:
            res = triangulate_polygon(out, edge_length=edge_length, min_angle=min_angle, name=name)
            how[name] = "own"
        meshed[name] = res
    return meshed, how


def write_rest_obj(mesh: GarmentMesh, path: str | os.PathLike) -> None:
    """Write the flat panels as an OBJ [m]: vertices = ``uv_placed3d`` (Nu, 3), texture
    coordinates = the pattern's 2D coordinates ``uv`` [m], faces ``faces_uv``. Atomic (written to
    a temporary name in the same folder, then renamed) through :func:`unsew.io.mesh.write_obj`."""
    from unsew.io.mesh import write_obj

    write_obj(
        path,
        mesh.uv_placed3d,
        mesh.faces_uv,
        uv=mesh.uv,
        faces_uv=mesh.faces_uv,
        header="unsew rest mesh: flat panels placed in 3D; vt = pattern coordinates [m]",
    )
