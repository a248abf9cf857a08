"""Repair of damaged garment meshes on load: what is safe is cleaned and counted, what is not is
refused with one line saying what and where.

Cleaned (the surface does not change):

- duplicate vertices (same position to within ``MERGE_TOL``) merged into the first one;
- degenerate faces (a repeated corner, or area below ``DEGENERATE_REL`` times the median) removed;
- duplicate faces (same three vertices, either orientation) removed, the first kept;
- unreferenced vertices removed.

Repaired where safe:

- fins: small pieces (each under ``SMALL_PIECE`` of the faces and of the area) hanging on a
  non-manifold edge (an edge with three or more faces) are cut off. The pieces are found as
  components of the faces connected through manifold edges only.
- floating debris: components under ``SMALL_PIECE`` of the area are removed.
- seams left open: where the pieces of a garment meet with their seam vertices unmerged but
  within ``SEAM_WELD`` of each other (other simulators' exports keep each panel's vertices), each
  boundary vertex is merged with its mutual nearest boundary vertex of another piece, and one
  left over (the two sides sampled otherwise) is sewn into the edge of the other piece it lies
  on; without it every seam would read as an opening. A weld that would make an edge branch is
  not made.

Refused (:class:`unsew.errors.InputError`):

- non-manifold edges left after that (the garment itself branches);
- surfaces farther than ``SEPARATE_GAP`` apart: several garments in one file. Pieces closer than
  that (panels of one garment whose seam vertices were not merged) are kept.

Vertex and face order are kept (the first of duplicates survives; faces split by a weld go
last), so a damaged copy of a clean mesh is cleaned back to exactly the clean mesh.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field

import numpy as np

from unsew.errors import InputError
from unsew.geometry import topology
from unsew.geometry.distance import MeshQuery

__all__ = [
    "MeshRepair",
    "repair_garment",
    "MERGE_TOL",
    "DEGENERATE_REL",
    "SMALL_PIECE",
    "SEPARATE_GAP",
    "SEAM_WELD",
    "triangle_areas",
]

#: vertices closer than this are one vertex [m]
MERGE_TOL = 1e-7
#: a face with area below this fraction of the median face area is degenerate [-]
DEGENERATE_REL = 1e-8
#: a piece with less than this fraction of the faces and of the area is a fin or debris [-]
SMALL_PIECE = 0.01
#: surfaces farther apart than this are separate garments [m]
SEPARATE_GAP = 0.05
#: boundary vertices of two pieces closer than this are one seam's, welded [m]
SEAM_WELD = 0.002


@dataclass
class MeshRepair:
    """What :func:`repair_garment` changed, as counts (all 0 for a clean mesh)."""

    merged_vertices: int = 0  # duplicate vertices merged into another
    degenerate_faces: int = 0  # faces with a repeated corner or zero area removed
    duplicate_faces: int = 0  # repeated faces removed
    unreferenced_vertices: int = 0  # vertices in no face removed
    fin_faces: int = 0  # faces of small pieces cut off non-manifold edges
    debris_faces: int = 0  # faces of small disconnected pieces removed
    welded_vertices: int = 0  # seam vertices of one piece merged into another's
    components: int = 1  # surfaces kept (pieces of one garment closer than SEPARATE_GAP)
    notes: list = field(default_factory=list)  # one phrase per repair, with where

    @property
    def changed(self) -> bool:
        """True when the mesh was changed."""
        return bool(self.notes)

    def summary(self) -> str:
        """One line: the repairs, or "clean"."""
        return "; ".join(self.notes) if self.notes else "clean"

    def as_dict(self) -> dict:
        """JSON-ready dict of the counts and notes."""
        return asdict(self)


def _where(p: np.ndarray) -> str:
    return "(" + ", ".join(f"{c:.3f}" for c in p) + ") m"


def triangle_areas(v: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Area [m^2] of every triangle, (F,) float64, of vertices ``v`` (V, 3) [m] and faces ``f``
    (F, 3) int."""
    t = np.asarray(v, dtype=np.float64)[np.asarray(f)]
    return 0.5 * np.linalg.norm(np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]), axis=1)


def _merge_vertices(v: np.ndarray, f: np.ndarray) -> tuple[np.ndarray, int]:
    """Faces re-indexed onto the first of each group of coincident vertices; merged count."""
    key = np.round(v / MERGE_TOL).astype(np.int64)
    _, first, inv = np.unique(key, axis=0, return_index=True, return_inverse=True)
    target = first[inv.reshape(-1)]  # (V,) the first vertex at the same position
    return target[f], int(len(v) - len(first))


def _manifold_components(f: np.ndarray) -> tuple[int, np.ndarray, np.ndarray]:
    """Components of faces joined through edges with exactly two faces; also the per-edge count
    and the non-manifold mask per half-edge."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import connected_components

    edges, inv, cnt = topology.unique_edges(f)
    ok = cnt[inv] == 2  # (3F,) half-edges on manifold interior edges
    F = len(f)
    fid = np.repeat(np.arange(F), 3)
    g = sp.coo_matrix((np.ones(int(ok.sum()), bool), (fid[ok], F + inv[ok])), shape=(F + len(edges),) * 2)
    _, lab = connected_components(g, directed=False)
    n, lab = np.unique(lab[:F], return_inverse=True)
    return len(n), lab.reshape(-1), cnt[inv] > 2


def repair_garment(verts, faces, *, what: str = "target") -> tuple[np.ndarray, np.ndarray, MeshRepair]:
    """Clean and check a garment mesh (module docstring).

    verts: (V, 3) float64 [m]; faces: (F, 3) int. what: the mesh's name in messages.
    Returns (verts (V', 3) float64 [m], faces (F', 3) int64, :class:`MeshRepair`).
    Raises InputError for branching (non-manifold) surfaces, several garments, or nothing left.
    """
    v, f = _check_arrays(verts, faces, what)
    rep = MeshRepair()
    used0 = np.zeros(len(v), bool)
    used0[f.ravel()] = True
    rep.unreferenced_vertices = int((~used0).sum())
    f, rep.merged_vertices = _merge_vertices(v, f)
    f = _drop_bad_faces(v, f, rep, what)
    area = triangle_areas(v, f)
    f, area = _cut_fins(v, f, area, rep, what)
    f = _weld_seams(v, f, rep)
    if rep.welded_vertices:
        area = triangle_areas(v, f)
    f, rep.components = _drop_debris(v, f, area, rep, what)

    # compact vertices, keeping their order
    used = np.zeros(len(v), bool)
    used[f.ravel()] = True
    remap = np.cumsum(used) - 1
    v, f = v[used], remap[f]
    counted = [
        (rep.merged_vertices, "merged {} duplicate vertices"),
        (rep.degenerate_faces, "removed {} degenerate faces"),
        (rep.duplicate_faces, "removed {} duplicate faces"),
        (rep.unreferenced_vertices, "removed {} unreferenced vertices"),
    ]
    rep.notes = [fmt.format(k) for k, fmt in counted if k] + rep.notes
    return np.ascontiguousarray(v), np.ascontiguousarray(f, dtype=np.int64), rep


def _check_arrays(verts, faces, what: str) -> tuple[np.ndarray, np.ndarray]:
    """(V, 3) float64 vertices and (F, 3) int64 faces, or InputError for non-finite or missing ones."""
    v = np.asarray(verts, dtype=np.float64)
    f = np.asarray(faces, dtype=np.int64).reshape(-1, 3)
    if v.ndim != 2 or v.shape[1] != 3 or not np.isfinite(v).all():
        raise InputError(f"{what} needs finite vertex coordinates of shape (V, 3), got shape {v.shape}")
    if len(f) == 0 or f.min() < 0 or f.max() >= len(v):
        raise InputError(f"{what} has no triangles or faces indexing missing vertices (0..{len(v) - 1})")
    return v, f


def _drop_bad_faces(v: np.ndarray, f: np.ndarray, rep: MeshRepair, what: str) -> np.ndarray:
    """Faces without degenerate (repeated vertex or area below DEGENERATE_REL of the median) and
    duplicate triangles, counted in ``rep``; InputError when none is left."""
    area = triangle_areas(v, f)
    med = float(np.median(area)) if len(area) else 0.0
    bad = (f[:, 0] == f[:, 1]) | (f[:, 1] == f[:, 2]) | (f[:, 2] == f[:, 0]) | (area <= DEGENERATE_REL * med)
    rep.degenerate_faces = int(bad.sum())
    keep = ~bad
    key = np.sort(f, axis=1)
    _, first = np.unique(key[keep], axis=0, return_index=True)
    dup = np.ones(len(f), bool)
    dup[np.flatnonzero(keep)[first]] = False
    dup &= keep
    rep.duplicate_faces = int(dup.sum())
    keep &= ~dup
    f = f[keep]
    if len(f) == 0:
        raise InputError(f"{what} has no triangles with area after removing degenerate ones")
    return f


def _cut_fins(v, f, area, rep: MeshRepair, what: str) -> tuple[np.ndarray, np.ndarray]:
    """Faces (and their areas [m^2]) without fins, small pieces hanging on non-manifold edges;
    InputError when non-manifold edges remain."""
    total = float(area.sum())
    _, inv, cnt = topology.unique_edges(f)
    if not (cnt > 2).any():
        return f, area
    n, lab, nm_half = _manifold_components(f)
    n_faces = np.bincount(lab, minlength=n)
    a_comp = np.bincount(lab, weights=area, minlength=n)
    on_nm = np.bincount(lab, weights=nm_half.reshape(-1, 3).any(1), minlength=n) > 0
    small = (n_faces < SMALL_PIECE * len(f)) & (a_comp < SMALL_PIECE * total) & on_nm
    if small.any():
        cut = small[lab]
        rep.fin_faces = int(cut.sum())
        where = _where(v[f[cut]].reshape(-1, 3).mean(0))
        rep.notes.append(f"cut off {int(small.sum())} fin(s) of {rep.fin_faces} face(s) near {where}")
        f = f[~cut]
        area = area[~cut]
    _, inv, cnt = topology.unique_edges(f)
    if (cnt > 2).any():
        e = topology.half_edges(f)[np.argmax(cnt[inv] > 2)]
        raise InputError(
            f"{what} has {int((cnt > 2).sum())} non-manifold edges (3+ triangles on one edge), e.g. at "
            f"{_where(v[e].mean(0))}; the surface branches there: remove the extra faces (e.g. MeshLab "
            "'Select non-manifold edges' then delete) and retry"
        )
    return f, area


def _weld_seams(v: np.ndarray, f: np.ndarray, rep: MeshRepair) -> np.ndarray:
    """Faces with the open seams between pieces welded (module docstring), counted in ``rep``:
    boundary vertices merged with their mutual nearest on another piece, then the ones left (the
    two sides sampled otherwise) inserted into the boundary edge of another piece they lie on."""
    from scipy.spatial import cKDTree

    n, lab = topology.components(f, len(v))
    if n < 2:
        return f
    piece = np.full(len(v), -1)
    piece[f.ravel()] = np.repeat(lab, 3)
    bv = np.unique(topology.boundary_edges(f))
    pairs = cKDTree(v[bv]).query_pairs(SEAM_WELD, output_type="ndarray")
    pairs = pairs[piece[bv[pairs[:, 0]]] != piece[bv[pairs[:, 1]]]]
    if len(pairs) == 0:
        return f
    d = np.linalg.norm(v[bv[pairs[:, 0]]] - v[bv[pairs[:, 1]]], axis=1)
    nearest = np.full(len(bv), -1)
    best = np.full(len(bv), np.inf)
    for (i, j), dij in zip(pairs, d):  # each boundary vertex's nearest on another piece
        for a, b in ((i, j), (j, i)):
            if dij < best[a]:
                best[a], nearest[a] = dij, b
    mutual = [(i, j) for i, j in enumerate(nearest) if j > i and nearest[j] == i]
    remap = np.arange(len(v))
    for i, j in mutual:
        remap[bv[j]] = bv[i]
    welded, face_piece = remap[f], lab
    for _ in range(3):  # a face with two cut edges has its second cut on the next pass
        welded, face_piece, cut = _zip_t_junctions(v, welded, face_piece, piece)
        if not cut:
            break
    _, _, cnt = topology.unique_edges(welded)
    if (cnt > 2).any():  # the pieces overlap rather than meet: left as they are, and said
        rep.notes.append(f"left {len(mutual)} seam vertices open: welding them would make edges branch")
        return f
    inserted = len(welded) - len(f)  # each vertex sewn into an edge adds one face
    rep.welded_vertices = len(mutual) + inserted
    rep.notes.append(
        f"welded {len(mutual) + inserted} seam vertices left open between pieces "
        f"(within {SEAM_WELD * 1000:g} mm)"
        + (f", {inserted} of them sewn into the other side's edges" if inserted else "")
    )
    return welded


def _zip_t_junctions(v: np.ndarray, f: np.ndarray, face_piece: np.ndarray, piece: np.ndarray):
    """Faces with each boundary vertex that lies within SEAM_WELD of a boundary edge of another
    piece (inside the edge, not at its ends; the nearest such edge, of a piece the vertex is not
    already welded to) inserted into that edge: the edge's face is split into a fan through the
    inserted vertices, in order along the edge, so both sides of a seam sampled differently share
    their edges. face_piece: (F,) the piece of each face; piece: (V,) each vertex's piece.
    Returns (faces, their pieces, whether any edge was cut); a face with two cut edges is cut
    along its first only (the caller runs it again for the second)."""
    from scipy.spatial import cKDTree

    he = topology.half_edges(f)
    _, inv, cnt = topology.unique_edges(f)
    bidx = np.flatnonzero(cnt[inv] == 1)
    if len(bidx) == 0:
        return f, face_piece, False
    bverts = np.unique(he[bidx])
    on_boundary = np.zeros(len(v), bool)
    on_boundary[bverts] = True
    near = on_boundary[f].any(1)
    # (vertex, piece) for every piece a boundary vertex is a corner of: a vertex already in a
    # piece's faces (welded to it) is never sewn into that piece's edges
    member = set(zip(f[near].ravel().tolist(), np.repeat(face_piece[near], 3).tolist()))
    tree = cKDTree(v[bverts])
    best: dict[int, tuple] = {}  # vertex -> (distance, half-edge, t): the nearest edge it lies on
    for h in bidx:
        a, b = he[h]
        fa = h // 3
        ab = v[b] - v[a]
        length = float(np.linalg.norm(ab))
        if length == 0.0:
            continue
        for k in tree.query_ball_point(0.5 * (v[a] + v[b]), 0.5 * length + SEAM_WELD):
            m = int(bverts[k])
            if m in (a, b) or piece[m] == face_piece[fa] or (m, int(face_piece[fa])) in member:
                continue
            t = float(np.dot(v[m] - v[a], ab) / length**2)
            dist = float(np.linalg.norm(v[a] + t * ab - v[m]))
            if 0.01 < t < 0.99 and dist <= SEAM_WELD and dist < best.get(m, (np.inf,))[0]:
                best[m] = (dist, int(h), t)
    cuts: dict[int, list] = {}
    for m, (_, h, t) in best.items():
        cuts.setdefault(h, []).append((t, m))
    if not cuts:
        return f, face_piece, False
    keep = np.ones(len(f), bool)
    new, new_piece = [], []
    for h, ms in cuts.items():
        fa, k = divmod(h, 3)
        a, b, c = f[fa, k], f[fa, (k + 1) % 3], f[fa, (k + 2) % 3]
        chain = [a] + [m for _, m in sorted(ms)] + [b]
        if not keep[fa]:
            continue  # a face with two cut edges keeps its first cut only
        keep[fa] = False
        new += [[chain[i], chain[i + 1], c] for i in range(len(chain) - 1)]
        new_piece += [face_piece[fa]] * (len(chain) - 1)
    faces = np.concatenate([f[keep], np.asarray(new, dtype=f.dtype).reshape(-1, 3)])
    return faces, np.concatenate([face_piece[keep], np.asarray(new_piece, dtype=face_piece.dtype)]), True


def _drop_debris(v, f, area, rep: MeshRepair, what: str) -> tuple[np.ndarray, int]:
    """Faces without small loose pieces (debris) and the number of pieces left; InputError for
    several garments apart (:func:`_check_separate`)."""
    n, lab = topology.components(f, len(v))
    if n > 1:
        a_comp = np.bincount(lab, weights=area, minlength=n)
        n_faces = np.bincount(lab, minlength=n)
        small = (a_comp < SMALL_PIECE * a_comp.sum()) & (n_faces < SMALL_PIECE * len(f))
        if small.any() and not small.all():
            cut = small[lab]
            rep.debris_faces = int(cut.sum())
            rep.notes.append(
                f"removed {int(small.sum())} small loose piece(s) of {rep.debris_faces} face(s) near "
                f"{_where(v[f[cut]].reshape(-1, 3).mean(0))}"
            )
            f, lab = f[~cut], lab[~cut]
            big = np.flatnonzero(~small)
            lab = np.searchsorted(big, lab)
            n = len(big)
        if n > 1:
            _check_separate(v, f, lab, n, what)
    return f, int(n)


def _check_separate(v, f, lab, n, what) -> None:
    """Raise InputError when a piece lies farther than SEPARATE_GAP from every other piece."""
    area = triangle_areas(v, f)
    a_comp = np.bincount(lab, weights=area, minlength=n)
    for c in range(n):
        mine = f[lab == c]
        others = f[lab != c]
        gap = float(MeshQuery(v, others).distance(v[np.unique(mine)]).min())
        if gap > SEPARATE_GAP:
            centre = v[np.unique(mine)].mean(0)
            raise InputError(
                f"{what} has {n} separate surfaces (areas "
                + ", ".join(f"{a:.3f}" for a in sorted(a_comp, reverse=True))
                + f" m^2); the one near {_where(centre)} is {gap * 100:.0f} cm from the rest: give one "
                "garment per case"
            )
