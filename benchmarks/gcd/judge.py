"""The GarmentCode benchmark's judge: its own geometry, sharing nothing with unsew.metrics.

- ``chamfer_mm``: symmetric Chamfer distance between two triangle surfaces [mm]: ``n`` points
  sampled uniformly by area on each (fixed seed), each one's exact distance to the other surface
  (trimesh); the mean of the two directions' mean distances.
- ``panels_of_spec``: a GarmentCode specification's panels as outlines (edges discretized:
  straight, quadratic and cubic Bezier with relative or absolute control points, circle arcs as
  GarmentCode's SVG arcs) [m], with each panel's area and 3D centroid from its own placement.
- ``merge_invisible``: panels joined by a seam the 3D shape cannot show are merged into one. A
  seam (the stitches of one run between two panels) hides where each of its stitched edge pairs
  is straight and of equal length (within ``MERGE_LENGTH_TOL``) and the two panels joined along
  it lie flat: at the seam's two ends the outline runs on without a corner (the panels' turning
  angles add up to half a turn within ``MERGE_ANGLE_TOL``), where the seam goes on from one
  stitch into the next the turning angles cancel; a seam between mirror halves that keep their
  grain when joined (a centre-front or centre-back seam, what cutting on a fold makes) hides
  whatever corner the outline makes at its ends (a V-neck's point), the outline their union's
  where their curves run a few mm past the seam's line. The rule reads the seam's two panels alone,
  not what else either is sewn to (a waistband, a cuff) nor the order of the stitches. Pieces
  then grow panel by panel, glued by a rigid 2D motion without overlap, each glue the one that
  closes the most other hidden seams with it. A centre-front seam between mirror halves (a fold
  in the other pattern) and a straight seam between sleeve halves are such seams.
- ``compare_patterns``: which true piece each recovered piece stands for is read where both
  garments drape (``drape_shares``): each point of the recovered drape counts, by its share of
  the drape's area, for the true panel whose draped cloth lies nearest, if that lies within
  ``CORRESPOND_GATE`` (else for none: cloth where the true garment has none). A recovered piece's
  pattern area is shared out in those proportions among the true pieces that take at least
  ``SHARE_MIN`` of it (the one taking most at least). Per true piece the relative surface-area
  error |A_given - A_true| / A_true (1 for a true piece given nothing: a waistband the recovered
  pattern lacks is not stood in for by a sleeve) and the turning-function distance (Arkin et al.
  1991: outlines scaled to unit perimeter, L2 over arc length of the tangent angle, minimized over
  the start point and a rotation) [rad] to the recovered piece giving it most area, where that
  piece gives at least half of it; both averaged over the true pieces (the turning distance over
  those it is measured on). A recovered piece cut where the true pattern has two (a trouser leg
  in one piece) gives each its share: the area error counts the cloth, the piece count and the
  turning distance the cut. Without drapes (a draft in ``gcd starts``) the pieces are
  matched one to one by a Hungarian assignment on the distance of their 3D centroids [m] as the
  panels are placed plus their relative area difference, a true piece left unmatched counting 1.
"""

from __future__ import annotations

import numpy as np

MERGE_LENGTH_TOL = 0.02  #: relative length difference of two straight stitched edges
MERGE_ANGLE_TOL = np.radians(15.0)  #: how far from half a turn the two corners at a seam end may add up
FOLD_TOL = 0.005  #: [m] how far a mirror half may lie from the other half mirrored across their seam
OVERLAP_TOL = 0.01  #: [m] how far two glued panels may reach past their seam's line into each other
CURVE_POINTS = 24  #: points per curved edge
TURNING_SAMPLES = 200  #: arc-length samples of an outline for the turning function
CORRESPOND_GATE = 0.05  #: [m] farthest a recovered drape's point may lie from the true cloth and count for it
SHARE_MIN = 0.25  #: the least share of a recovered piece's area that a true piece takes from it


# ------------------------------------------------------------------ surfaces


def sample_surface(v: np.ndarray, f: np.ndarray, n: int, seed: int = 0) -> np.ndarray:
    """(n, 3) float64 points uniform by area on the triangles f (F, 3) of v (V, 3) [m]."""
    v, f = np.asarray(v, np.float64), np.asarray(f, np.int64)
    a, b, c = v[f[:, 0]], v[f[:, 1]], v[f[:, 2]]
    area = 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1)
    rng = np.random.default_rng(seed)
    t = rng.choice(len(f), size=n, p=area / area.sum())
    r1, r2 = rng.random(n), rng.random(n)
    s = np.sqrt(r1)
    return (1 - s)[:, None] * a[t] + (s * (1 - r2))[:, None] * b[t] + (s * r2)[:, None] * c[t]


def chamfer_mm(va, fa, vb, fb, *, n: int = 10000, seed: int = 0) -> dict:
    """Symmetric Chamfer between surfaces A and B (vertices [m], faces): {"chamfer_mm": mean of
    the two directions' mean distances, "a_to_b_mm", "b_to_a_mm", "p95_mm"} [mm]. Each
    direction: ``n`` points sampled on one surface, their exact distance to the other surface
    (trimesh's closest point, candidates from an r-tree)."""
    import trimesh

    A = trimesh.Trimesh(np.asarray(va, np.float64), np.asarray(fa, np.int64), process=False)
    B = trimesh.Trimesh(np.asarray(vb, np.float64), np.asarray(fb, np.int64), process=False)
    pa, pb = sample_surface(va, fa, n, seed), sample_surface(vb, fb, n, seed + 1)
    dab = trimesh.proximity.closest_point(B, pa)[1]
    dba = trimesh.proximity.closest_point(A, pb)[1]
    return {
        "chamfer_mm": 500.0 * (dab.mean() + dba.mean()),
        "a_to_b_mm": 1000.0 * dab.mean(),
        "b_to_a_mm": 1000.0 * dba.mean(),
        "p95_mm": 1000.0 * float(np.percentile(np.r_[dab, dba], 95)),
    }


# ------------------------------------------------------------------ pattern outlines


def _rel_to_abs(start, end, p):
    e = end - start
    return start + p[0] * e + p[1] * np.array([-e[1], e[0]])


def edge_points(start, end, curvature, relative: bool) -> np.ndarray:
    """(k, 2) points of one GarmentCode edge from start to end (inclusive), same units."""
    start, end = np.asarray(start, np.float64), np.asarray(end, np.float64)
    if not curvature:
        return np.stack([start, end])
    if isinstance(curvature, list):  # old format: one quadratic control point
        curvature = {"type": "quadratic", "params": [curvature]}
    typ, par = curvature["type"], curvature["params"]
    t = np.linspace(0.0, 1.0, CURVE_POINTS)[:, None]
    if typ in ("quadratic", "cubic"):
        cps = [_rel_to_abs(start, end, p) if relative else np.asarray(p, np.float64) for p in par]
        if typ == "quadratic":
            c = cps[0]
            return (1 - t) ** 2 * start + 2 * (1 - t) * t * c + t**2 * end
        c1, c2 = cps[0], cps[1]
        return (1 - t) ** 3 * start + 3 * (1 - t) ** 2 * t * c1 + 3 * (1 - t) * t**2 * c2 + t**3 * end
    if typ == "circle":  # GarmentCode: svgpathtools.Arc(start, r, 0, large_arc, sweep=right, end)
        import svgpathtools

        r, large, right = float(par[0]), bool(par[1]), bool(par[2])
        arc = svgpathtools.Arc(complex(*start), complex(r, r), 0.0, large, right, complex(*end))
        z = np.array([arc.point(float(s)) for s in t[:, 0]])
        pts = np.stack([z.real, z.imag], axis=1)
        pts[0], pts[-1] = start, end
        return pts
    raise ValueError(f"unknown edge curvature type {typ!r}")


def _rotation(angles_deg) -> np.ndarray:
    from scipy.spatial.transform import Rotation

    return Rotation.from_euler("xyz", np.asarray(angles_deg, np.float64), degrees=True).as_matrix()


def _area_centroid(loop: np.ndarray):
    x, y = loop[:, 0], loop[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cr = x * yn - xn * y
    a = 0.5 * cr.sum()
    if abs(a) < 1e-15:
        return 0.0, loop.mean(axis=0)
    return a, np.array([((x + xn) * cr).sum(), ((y + yn) * cr).sum()]) / (6.0 * a)


class Piece:
    """A (possibly merged) panel: edges as point lists [m] in one 2D frame, counter-clockwise."""

    def __init__(self, names, edges, area, centroid3d):
        self.names = names  # panel names merged into this piece
        self.edges = edges  # list of dicts: key (panel, edge index), pts (k, 2), straight
        self.area = area  # [m^2]
        self.centroid3d = centroid3d  # (3,) [m], area-weighted over the merged panels

    def loop(self) -> np.ndarray:
        """The outline (N, 2) [m]; where glued panels overlap across their seam, their union's."""
        return _without_lenses(np.concatenate([e["pts"][:-1] for e in self.edges]))


def panels_of_spec(spec: dict) -> dict:
    """{panel name: Piece} of a GarmentCode specification dict (lengths in m)."""
    props = spec.get("properties", {})
    scale = float(props.get("units_in_meter", 100))
    relative = props.get("curvature_coords", "relative") == "relative"
    out = {}
    for name, pd in spec["pattern"]["panels"].items():
        V = np.asarray(pd["vertices"], np.float64)
        edges = []
        for k, ed in enumerate(pd["edges"]):
            i, j = ed["endpoints"]
            pts = edge_points(V[i], V[j], ed.get("curvature"), relative) / scale
            edges.append({"key": (name, k), "pts": pts, "straight": not ed.get("curvature")})
        loop = np.concatenate([e["pts"][:-1] for e in edges])
        a, c = _area_centroid(loop)
        if a < 0:  # clockwise in the file: reverse the loop (each edge and their order)
            edges = [dict(e, pts=e["pts"][::-1].copy()) for e in reversed(edges)]
            a = -a
        c3 = (
            _rotation(pd.get("rotation", [0, 0, 0])) @ np.r_[c, 0.0]
            + np.asarray(pd.get("translation", [0, 0, 0]), np.float64) / scale
        )
        out[name] = Piece([name], edges, a, c3)
    return out


def _turn(d_in, d_out) -> float:
    """Signed angle [rad] from direction d_in to d_out (left turns positive)."""
    return float(np.arctan2(d_in[0] * d_out[1] - d_in[1] * d_out[0], d_in @ d_out))


def _dir(p, q):
    d = q - p
    return d / max(np.linalg.norm(d), 1e-15)


def _seam_key(st) -> frozenset:
    """The two (panel, edge index) keys of a stitch, unordered."""
    return frozenset(((st[0]["panel"], st[0]["edge"]), (st[1]["panel"], st[1]["edge"])))


def _stitch_flat(A: Piece, ia: int, B: Piece, ib: int, stitched: set):
    """(flat, links) of the stitch of panel A's edge ia to panel B's edge ib, read from the two
    panels' own outlines alone (A, B: single panels, not merged pieces). ``flat``: both edges are
    straight and of equal length (``MERGE_LENGTH_TOL``) and the two panels joined along them lie
    flat across both ends: at an end where the edges next to the stitch on either side are stitched
    to each other too (``stitched``: frozensets of two (panel, edge) keys; the seam goes on) the
    two panels' turning angles cancel, at any other end they add up to half a turn (the outline
    runs on without a corner), each within ``MERGE_ANGLE_TOL``. ``links``: the stitches (frozensets)
    the seam goes on into."""
    ea, eb = A.edges[ia], B.edges[ib]
    na, nb = len(A.edges), len(B.edges)
    a_prev, a_next = A.edges[(ia - 1) % na], A.edges[(ia + 1) % na]
    b_prev, b_next = B.edges[(ib - 1) % nb], B.edges[(ib + 1) % nb]
    # B's edge runs against A's: A's end meets B's start, A's start meets B's end; per end the
    # edge into it and out of it on A and on B, and the two edges the seam would go on along
    ends = (
        (ea, a_next, b_prev, eb, (a_next, b_prev)),
        (a_prev, ea, eb, b_next, (a_prev, b_next)),
    )
    la = np.linalg.norm(ea["pts"][-1] - ea["pts"][0])
    lb = np.linalg.norm(eb["pts"][-1] - eb["pts"][0])
    flat = ea["straight"] and eb["straight"] and abs(la - lb) <= MERGE_LENGTH_TOL * max(la, lb)
    fold = flat and _fold(A, ia, B, ib)
    links = []
    for a_in, a_out, b_in, b_out, (a_on, b_on) in ends:
        on = frozenset((a_on["key"], b_on["key"]))
        inner = on in stitched
        if inner:
            links.append(on)
        turns = _turn(_dir(*a_in["pts"][-2:]), _dir(*a_out["pts"][:2])) + _turn(
            _dir(*b_in["pts"][-2:]), _dir(*b_out["pts"][:2])
        )
        # the outline may turn at the seam's ends of a fold (a V-neck's point), not within it
        flat = flat and (fold and not inner or abs(turns - (0.0 if inner else np.pi)) <= MERGE_ANGLE_TOL)
    return flat, links


def _glue_motion(ea: dict, eb: dict):
    """(R (2, 2), t (2,)) of the rigid 2D motion taking edge eb onto edge ea run backwards."""
    p, q = ea["pts"][0], ea["pts"][-1]
    bp, bq = eb["pts"][0], eb["pts"][-1]
    ang = np.arctan2(*(p - q)[::-1]) - np.arctan2(*(bq - bp)[::-1])
    R = np.array([[np.cos(ang), -np.sin(ang)], [np.sin(ang), np.cos(ang)]])
    return R, q - R @ bp


def _fold(A: Piece, ia: int, B: Piece, ib: int) -> bool:
    """Whether panels A and B joined along A's edge ia and B's edge ib are what one piece cut on a
    fold makes: glued, B keeps its own frame's directions (its grain, as A's, within
    ``MERGE_ANGLE_TOL``) and is A mirrored across the seam (every point of either outline within
    ``FOLD_TOL`` of the other's): a centre-front or centre-back seam between mirror halves."""
    R, t = _glue_motion(A.edges[ia], B.edges[ib])
    if abs(np.arctan2(R[1, 0], R[0, 0])) > MERGE_ANGLE_TOL:
        return False
    p, q = A.edges[ia]["pts"][0], A.edges[ia]["pts"][-1]
    u = _dir(p, q)
    b = B.loop() @ R.T + t - p
    mirrored = p + 2.0 * np.outer(b @ u, u) - b  # reflected across the seam's line
    a = A.loop()
    return max(_to_outline(a, mirrored).max(), _to_outline(mirrored, a).max()) <= FOLD_TOL


def _to_outline(pts: np.ndarray, loop: np.ndarray) -> np.ndarray:
    """Each point's (N, 2) distance [m] to the closed polyline ``loop`` (M, 2)."""
    P, D = loop, np.roll(loop, -1, axis=0) - loop
    w = pts[:, None, :] - P[None]
    s = np.clip((w * D[None]).sum(-1) / np.maximum((D * D).sum(-1), 1e-30)[None], 0.0, 1.0)
    return np.linalg.norm(w - s[..., None] * D[None], axis=-1).min(axis=1)


def _glue(A: Piece, ia: int, B: Piece, ib: int, hidden: set):
    """Piece of A and B glued along A's edge ia and B's edge ib by the rigid 2D motion taking B's
    edge onto A's, the seams of ``hidden`` that then meet folded back at either seam end zipped
    too, or None where the two would overlap."""
    R, t = _glue_motion(A.edges[ia], B.edges[ib])
    Bedges = [dict(e, pts=e["pts"] @ R.T + t) for e in B.edges]
    edges = _zip(A.edges[ia + 1 :] + A.edges[:ia] + Bedges[ib + 1 :] + Bedges[:ib], hidden)
    loop = np.concatenate([e["pts"][:-1] for e in edges])
    area, _ = _area_centroid(loop)
    if abs(area - (A.area + B.area)) > 0.02 * (A.area + B.area) or not _overlap_on_seam(A, ia, Bedges, loop):
        return None
    c3 = (A.area * A.centroid3d + B.area * B.centroid3d) / (A.area + B.area)
    return Piece(A.names + B.names, edges, area, c3)


def _overlap_on_seam(A: Piece, ia: int, Bedges: list, loop: np.ndarray) -> bool:
    """Whether the glued outline ``loop`` is one piece: it does not cross itself but where the two
    panels (A, and B's glued edges) overlap across the seam's own line by at most ``OVERLAP_TOL``
    (the neck curves of mirror halves running a few mm past the centre line)."""
    c = _crossings(loop)
    if not len(c):
        return True
    p, q = A.edges[ia]["pts"][0], A.edges[ia]["pts"][-1]
    n = _dir(p, q) @ np.array([[0.0, 1.0], [-1.0, 0.0]])  # the seam's left normal: A's side
    b = np.concatenate([e["pts"] for e in Bedges])
    past = max(-((A.loop() - p) @ n).min(), ((b - p) @ n).max())
    return bool(np.abs((c - p) @ n).max() <= FOLD_TOL and past <= OVERLAP_TOL)


def _zip(edges: list, hidden: set) -> list:
    """The outline's edges without each pair of consecutive edges that is a seam of ``hidden`` run
    out and back (the outline turns by about half a turn between them): a seam closed by gluing
    its neighbour."""
    edges = list(edges)
    k = 0
    while len(edges) > 2 and k < len(edges):
        e, f = edges[k], edges[(k + 1) % len(edges)]
        back = abs(_turn(_dir(*e["pts"][-2:]), _dir(*f["pts"][:2]))) > np.pi - MERGE_ANGLE_TOL
        if back and frozenset((e["key"], f["key"])) in hidden:
            j = (k + 1) % len(edges)
            edges = [x for i, x in enumerate(edges) if i not in (k, j)]
            k = max(k - 1, 0)
        else:
            k += 1
    return edges


def _crossings(loop: np.ndarray) -> np.ndarray:
    """The points (K, 2) where a closed polyline (N, 2) crosses itself (segments other than neighbours)."""
    return _crossing_segments(loop)[2]


def _without_lenses(loop: np.ndarray) -> np.ndarray:
    """A closed polyline (N, 2) with each small loop it makes where it crosses itself cut off at
    the crossing (of the two loops a crossing splits it into, the one of smaller area): the
    outline of two overlapping glued panels' union."""
    while True:
        i, j, c = _crossing_segments(loop)
        if not len(c):
            return loop
        i, j, c = i[0], j[0], c[0]
        inner = np.vstack([c, loop[i + 1 : j + 1]])
        outer = np.vstack([loop[: i + 1], c, loop[j + 1 :]])
        loop = outer if abs(_area_centroid(inner)[0]) < abs(_area_centroid(outer)[0]) else inner


def _crossing_segments(loop: np.ndarray):
    """(i, j, points): segment i of a closed polyline (N, 2) (from point i to i + 1) crosses its
    segment j > i + 1 at the point; (K,), (K,), (K, 2)."""
    P, Q = loop, np.roll(loop, -1, axis=0)
    n = len(P)
    d = Q - P

    def cross(a, b):
        return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]

    i, j = np.triu_indices(n, 2)
    keep = ~((i == 0) & (j == n - 1))
    i, j = i[keep], j[keep]
    den = cross(d[i], d[j])
    ok = np.abs(den) > 1e-18
    i, j, den = i[ok], j[ok], den[ok]
    w = P[j] - P[i]
    s, u = cross(w, d[j]) / den, cross(w, d[i]) / den
    eps = 1e-9
    hit = (s > eps) & (s < 1 - eps) & (u > eps) & (u < 1 - eps)
    return i[hit], j[hit], P[i[hit]] + s[hit, None] * d[i[hit]]


def hidden_seams(spec: dict, panels: dict | None = None) -> list:
    """The specification's stitches between two panels that the 3D shape cannot show, in the
    file's order: list of ((panel, edge), (panel, edge)). A seam (the stitches of one run along
    two panels, linked where the edges next to a stitch are stitched to each other) hides when
    each of its stitches lies flat (``_stitch_flat``): a rule on the seam's two panels alone, not
    on what else either is sewn to."""
    panels = panels_of_spec(spec) if panels is None else panels
    pairs = [st for st in spec["pattern"].get("stitches", []) if len(st) == 2]
    stitched = {_seam_key(st) for st in pairs}
    flat, parent = {}, {}

    def root(k):
        while parent[k] != k:
            parent[k] = parent[parent[k]]
            k = parent[k]
        return k

    order = []
    for st in pairs:
        (pa, ka), (pb, kb) = (st[0]["panel"], st[0]["edge"]), (st[1]["panel"], st[1]["edge"])
        if pa == pb or pa not in panels or pb not in panels:
            continue
        A, B = panels[pa], panels[pb]
        ia = next((i for i, e in enumerate(A.edges) if e["key"] == (pa, ka)), None)
        ib = next((i for i, e in enumerate(B.edges) if e["key"] == (pb, kb)), None)
        if ia is None or ib is None:
            continue
        key = _seam_key(st)
        flat[key], links = _stitch_flat(A, ia, B, ib, stitched)
        parent.setdefault(key, key)
        for other in links:
            parent.setdefault(other, other)
            parent[root(other)] = root(key)
        order.append((key, ((pa, ka), (pb, kb))))
    shown = {root(k) for k, ok in flat.items() if not ok}
    shown |= {
        root(k) for k in parent if k not in flat
    }  # a seam going on into a stitch not between two panels
    return [seam for key, seam in order if root(key) not in shown]


def merge_invisible(spec: dict, pieces: dict | None = None) -> list:
    """The pattern's pieces after merging along every seam the 3D shape cannot show
    (``hidden_seams``: a rule on each seam's two panels alone, so the same seam merges whatever
    else either panel is sewn to), as far as the pieces lie flat without overlap: list of Piece.
    A piece grows from its first panel in the file by one panel at a time, each time the glue
    along a hidden seam that closes the most other hidden seams with it (the first in the file
    among equals); a tube stays open along one seam."""
    left = dict(panels_of_spec(spec) if pieces is None else pieces)
    seams = hidden_seams(spec, left)
    hidden = {frozenset(s) for s in seams}
    out = []
    while left:
        piece = left.pop(next(iter(left)))
        while True:
            best, best_zips = None, -1
            for seam in seams:
                for (p_in, k_in), (p_new, k_new) in (seam, seam[::-1]):
                    if p_in not in piece.names or p_new not in left:
                        continue
                    new = left[p_new]
                    ia = next((i for i, e in enumerate(piece.edges) if e["key"] == (p_in, k_in)), None)
                    ib = next(i for i, e in enumerate(new.edges) if e["key"] == (p_new, k_new))
                    M = None if ia is None else _glue(piece, ia, new, ib, hidden)
                    zips = -1 if M is None else (len(piece.edges) + len(new.edges) - 2 - len(M.edges)) // 2
                    if zips > best_zips:
                        best, best_zips = (M, p_new), zips
            if best is None:
                break
            piece = best[0]
            del left[best[1]]
        out.append(piece)
    return out


# ------------------------------------------------------------------ turning function


def turning_distance(loop_a: np.ndarray, loop_b: np.ndarray, n: int = TURNING_SAMPLES) -> float:
    """Arkin's turning-function distance [rad] between two closed counter-clockwise outlines
    (N, 2): both resampled at ``n`` equal arc-length steps of unit perimeter; the L2 distance of
    their tangent-angle functions minimized over the start point and a constant rotation."""
    ta, tb = _turning(loop_a, n), _turning(loop_b, n)
    best = np.inf
    for k in range(n):
        sh = np.r_[tb[k:], tb[:k] + 2 * np.pi]  # start at sample k; past the end the angle wraps by a turn
        diff = ta - sh
        best = min(best, float(np.sqrt(np.mean((diff - diff.mean()) ** 2))))
    return best


def _turning(loop: np.ndarray, n: int) -> np.ndarray:
    P = np.vstack([loop, loop[:1]])
    seg = np.linalg.norm(np.diff(P, axis=0), axis=1)
    s = np.r_[0.0, np.cumsum(seg)]
    u = np.linspace(0.0, s[-1], n, endpoint=False)
    Q = np.stack([np.interp(u, s, P[:, 0]), np.interp(u, s, P[:, 1])], axis=1)
    d = np.roll(Q, -1, axis=0) - Q
    return np.unwrap(np.arctan2(d[:, 1], d[:, 0]))


# ------------------------------------------------------------------ pattern against pattern


def drape_shares(true_x, true_panel, rec_x, rec_f, rec_panel) -> dict:
    """{recovered panel: {true panel: share of the recovered panel's draped area}}: each vertex of
    the recovered drape (``rec_x`` (N, 3) [m], triangles ``rec_f`` (F, 3), ``rec_panel`` (N,) its
    panel's name) weighs a third of its triangles' area and counts for the panel (``true_panel``
    (M,) names) of the nearest vertex of the true drape (``true_x`` (M, 3) [m]) within
    ``CORRESPOND_GATE``; the shares of a panel sum to at most one (the rest lies off the true cloth)."""
    from scipy.spatial import cKDTree

    rec_x, rec_f = np.asarray(rec_x, np.float64), np.asarray(rec_f, np.int64)
    tri = np.linalg.norm(
        np.cross(rec_x[rec_f[:, 1]] - rec_x[rec_f[:, 0]], rec_x[rec_f[:, 2]] - rec_x[rec_f[:, 0]]), axis=1
    )
    w = np.bincount(rec_f.ravel(), weights=np.repeat(tri / 6.0, 3), minlength=len(rec_x))
    d, idx = cKDTree(np.asarray(true_x, np.float64)).query(rec_x)
    true_panel, rec_panel = np.asarray(true_panel), np.asarray(rec_panel)
    out = {}
    for p in np.unique(rec_panel):
        mine = rec_panel == p
        near = mine & (d <= CORRESPOND_GATE)
        names, inv = np.unique(true_panel[idx[near]], return_inverse=True)
        got = np.bincount(inv, weights=w[near], minlength=len(names)) / max(w[mine].sum(), 1e-30)
        out[str(p)] = {str(n): float(g) for n, g in zip(names, got)}
    return out


def _share_matrix(T: list, Rp: list, spec_rec: dict, shares: dict) -> np.ndarray:
    """(len(T), len(Rp)) share of each recovered piece's area given to each true piece: its panels'
    ``shares`` weighed by their pattern areas, shares under ``SHARE_MIN`` dropped (the largest kept)."""
    raw = panels_of_spec(spec_rec)
    S = np.zeros((len(T), len(Rp)))
    for j, r in enumerate(Rp):
        for name in r.names:
            got = shares.get(name, {})
            for i, t in enumerate(T):
                S[i, j] += raw[name].area / r.area * sum(got.get(q, 0.0) for q in t.names)
        col = S[:, j]
        S[:, j] = np.where((col >= SHARE_MIN) | (col == col.max()), col, 0.0)
    return S


def _matched_by_placement(T: list, Rp: list) -> np.ndarray:
    """(len(T), len(Rp)) 0/1: a one-to-one Hungarian assignment on the distance of the pieces'
    placed 3D centroids [m] plus their relative area difference."""
    from scipy.optimize import linear_sum_assignment

    S = np.zeros((len(T), len(Rp)))
    if len(Rp):
        cost = [
            [np.linalg.norm(t.centroid3d - r.centroid3d) + abs(r.area - t.area) / t.area for r in Rp]
            for t in T
        ]
        S[linear_sum_assignment(np.array(cost))] = 1.0
    return S


def compare_patterns(spec_true: dict, spec_rec: dict, shares: dict | None = None) -> dict:
    """Per-panel errors of a recovered pattern against the true one, both merged first; ``shares``:
    ``drape_shares`` of the two garments' drapes (None: pieces matched by their placement):
    {"panel_err": mean relative area error over true pieces, "turning": mean turning distance
    over the true pieces it is measured on [rad], "panels_true", "panels_rec" (after merging),
    "panels_true_raw", "panels_rec_raw", "matched": [(true names, names of the recovered pieces
    giving it area, area error, turning or nan)]}."""
    T, Rp = merge_invisible(spec_true), merge_invisible(spec_rec)
    S = _matched_by_placement(T, Rp) if shares is None else _share_matrix(T, Rp, spec_rec, shares)
    given = S * np.array([r.area for r in Rp])[None]  # (T, R) area [m^2] each recovered piece gives
    area_err = np.ones(len(T))
    turn = np.full(len(T), np.nan)
    matched = []
    for i, t in enumerate(T):
        total = given[i].sum()
        if total <= 0:
            continue
        area_err[i] = abs(total - t.area) / t.area
        j = int(np.argmax(given[i]))
        if given[i, j] >= 0.5 * total:
            turn[i] = turning_distance(t.loop(), Rp[j].loop())
        names = [n for k in np.flatnonzero(given[i] > 0) for n in Rp[k].names]
        matched.append((t.names, names, round(float(area_err[i]), 4), round(float(turn[i]), 4)))
    return {
        "panel_err": float(area_err.mean()),
        "turning": float(np.nanmean(turn)) if np.isfinite(turn).any() else None,
        "panels_true": len(T),
        "panels_rec": len(Rp),
        "panels_true_raw": len(spec_true["pattern"]["panels"]),
        "panels_rec_raw": len(spec_rec["pattern"]["panels"]),
        "matched": matched,
    }
