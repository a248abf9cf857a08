"""Pattern symmetry detection (paper 3.2 "Symmetry detection", Algorithm 1).

Two steps, on the control points C = {C_p} of :mod:`unsew.pattern.controls`:

1. *Inter-panel*: for each panel p (in ``panel_order``) and each later-unpaired panel q with as
   many control points, try every cyclic correspondence between their control points, in reversed
   order with a reflection (mirror images reverse orientation) and in the same order with a rotation
   (rotated copies), and fit the orthogonal matrix by Procrustes (Schönemann 1966) after centring.
   The fit is made, and its error measured, on the control points *and* on points sampled along
   the curves between them, so two panels with equal corners but different curves (a deep and a
   shallow neckline) are not paired. The error is the *largest* point residual divided by the
   RMS radius of the points (scale-free, and stricter than an RMS residual, which a local
   difference such as a neckline would hardly move); the best fit with error below ``tol``
   (``unsew.tolerances.SYMMETRY_REL_TOL``) is accepted and q is removed from K.
2. *Intra-panel*: for each panel left in K, every mirror correspondence of its CCW control points
   (j -> (s - j) mod n, s = 0..n-1; this covers even and odd counts, with 0, 1 or 2 points on the
   axis) is fitted with a reflection; the best one under the threshold is accepted. The mirrored
   half leaves K; points on the axis stay in K but may move only along the axis.

All control points are rebuilt from K by one linear map ``C = L @ K + b`` (flattened xy order),
built once by :meth:`Symmetry.rebuild_map`:
- a kept point is itself;
- a mirrored point is the reflection of its partner about the fixed axis (point a0, unit
  direction d): ``c' = a0 + H (c - a0) + r`` with ``H = 2 d d^T - I``;
- an on-axis point is projected on the axis: ``c = a0 + d d^T (k - a0) + r``;
- a paired panel's points follow the source panel's, translation included:
  ``c_q,i = M c_p,perm[i] + o_i``. (Recentring on the source's current centroid instead would pin
  the copy's centroid: grading a skirt's front hem and waist then shifted the back panel 1.8 cm
  against the front in 2D, so the two were placed, and sewn, at different heights.)
The constant offsets ``r``, ``o`` are chosen so that ``L @ K0 + b`` equals the original control
points exactly; for an exactly symmetric pattern ``r`` is zero, and for a pattern symmetric only
within the tolerance both keep its small asymmetry.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from unsew.pattern.controls import ControlPoints, find_control_points
from unsew.pattern.curves import edge_point_fn
from unsew.pattern.model import Pattern
from unsew.tolerances import SYMMETRY_REL_TOL

__all__ = ["PanelPair", "MirrorAxis", "Symmetry", "detect_symmetry", "procrustes", "curve_samples"]

_SAMPLES_PER_CURVE = 8


@dataclass
class PanelPair:
    """Inter-panel symmetry: ``target`` is ``source`` moved by an orthogonal matrix.

    perm: (n,) int64; the target's local control point i corresponds to the source's perm[i].
    matrix: (2, 2) float64 orthogonal M with ``C_target[i] - mean ~= M (C_source[perm[i]] - mean)``.
    mirrored: True when M is a reflection (correspondence in reversed order).
    error: largest point residual / RMS radius (dimensionless).
    """

    source: str
    target: str
    perm: np.ndarray
    matrix: np.ndarray
    mirrored: bool
    error: float


@dataclass
class MirrorAxis:
    """Intra-panel mirror symmetry of panel ``panel``.

    point: a point on the axis [m], (2,) float64 (panel frame). direction: unit axis, (2,) float64.
    pairs: (m, 2) int64 local control point indices (kept, mirrored); the mirrored one leaves K.
    on_axis: (k,) int64 local indices of control points on the axis (they move along it only).
    error: largest point residual / RMS radius (dimensionless).
    """

    panel: str
    point: np.ndarray
    direction: np.ndarray
    pairs: np.ndarray
    on_axis: np.ndarray
    error: float


@dataclass
class Symmetry:
    """Result of Algorithm 1 and the data needed to rebuild all control points from K.

    panel_names: = pattern.panel_order. offsets: (P+1,) int64, first control point of each panel.
    c0: original control points [m], (Nc, 2) float64, panel by panel, CCW.
    k_indices: global control point indices (Nk,) int64 forming K, increasing.
    pairs, mirrors: the detected symmetries.
    """

    panel_names: list[str]
    offsets: np.ndarray
    c0: np.ndarray
    k_indices: np.ndarray
    pairs: list[PanelPair] = field(default_factory=list)
    mirrors: list[MirrorAxis] = field(default_factory=list)
    tol: float = SYMMETRY_REL_TOL

    @property
    def n_control(self) -> int:
        """Number of all control points Nc."""
        return int(len(self.c0))

    @property
    def n_k(self) -> int:
        """Number of effective control points Nk."""
        return int(len(self.k_indices))

    def rebuild_map(self) -> tuple[np.ndarray, np.ndarray]:
        """The linear rebuild of all control points from K, flattened in xy order:
        ``C.reshape(-1) = L @ K.reshape(-1) + b``.

        Returns L (2 Nc, 2 Nk) float64 and b (2 Nc,) float64 [m].
        """
        nc, nk = self.n_control, self.n_k
        L = np.zeros((2 * nc, 2 * nk))
        b = np.zeros(2 * nc)
        done = np.zeros(nc, dtype=bool)
        kpos = {int(g): k for k, g in enumerate(self.k_indices)}
        for g, k in kpos.items():
            L[2 * g : 2 * g + 2, 2 * k : 2 * k + 2] = np.eye(2)
            done[g] = True
        eye = np.eye(2)
        for mir in self.mirrors:
            o = int(self.offsets[self.panel_names.index(mir.panel)])
            d = mir.direction / np.linalg.norm(mir.direction)
            a0 = mir.point
            P = np.outer(d, d)
            H = 2 * P - eye
            for j in mir.on_axis:
                g = o + int(j)
                blk = slice(2 * kpos[g], 2 * kpos[g] + 2)
                L[2 * g : 2 * g + 2, :] = 0.0
                L[2 * g : 2 * g + 2, blk] = P
                r = self.c0[g] - (a0 + P @ (self.c0[g] - a0))
                b[2 * g : 2 * g + 2] = (eye - P) @ a0 + r
            for i, j in mir.pairs:
                gi, gj = o + int(i), o + int(j)
                L[2 * gj : 2 * gj + 2, :] = H @ L[2 * gi : 2 * gi + 2, :]
                r = self.c0[gj] - (a0 + H @ (self.c0[gi] - a0))
                b[2 * gj : 2 * gj + 2] = H @ b[2 * gi : 2 * gi + 2] + (eye - H) @ a0 + r
                done[gj] = True
        for pr in self.pairs:
            ps, pt = self.panel_names.index(pr.source), self.panel_names.index(pr.target)
            os_, ot = int(self.offsets[ps]), int(self.offsets[pt])
            n = int(self.offsets[ps + 1]) - os_
            Ls = L[2 * os_ : 2 * (os_ + n)].reshape(n, 2, -1)
            bs = b[2 * os_ : 2 * (os_ + n)].reshape(n, 2)
            M = pr.matrix
            for i in range(n):
                g, s = ot + i, os_ + int(pr.perm[i])
                L[2 * g : 2 * g + 2, :] = M @ Ls[pr.perm[i]]
                b[2 * g : 2 * g + 2] = M @ bs[pr.perm[i]] + self.c0[g] - M @ self.c0[s]
                done[g] = True
        if not done.all():  # pragma: no cover - a bug, not a user error
            raise AssertionError(f"control points {np.flatnonzero(~done).tolist()} not rebuilt")
        return L, b

    def rebuild(self, K: np.ndarray) -> np.ndarray:
        """All control points [m], (Nc, 2) float64, from K [m], (Nk, 2) float64 (numpy)."""
        L, b = self.rebuild_map()
        return (L @ np.asarray(K, dtype=np.float64).reshape(-1) + b).reshape(-1, 2)

    def k0(self) -> np.ndarray:
        """The original effective control points [m], (Nk, 2) float64."""
        return self.c0[self.k_indices].copy()

    def to_dict(self) -> dict:
        """Plain-JSON form for the pattern's ``unsew`` key (lengths in metres)."""
        return {
            "panels": list(self.panel_names),
            "offsets": self.offsets.tolist(),
            "control_points": self.c0.tolist(),
            "k_indices": self.k_indices.tolist(),
            "tol": self.tol,
            "pairs": [
                {
                    "source": p.source,
                    "target": p.target,
                    "perm": np.asarray(p.perm).tolist(),
                    "matrix": np.asarray(p.matrix).tolist(),
                    "mirrored": bool(p.mirrored),
                    "error": float(p.error),
                }
                for p in self.pairs
            ],
            "mirrors": [
                {
                    "panel": m.panel,
                    "point": np.asarray(m.point).tolist(),
                    "direction": np.asarray(m.direction).tolist(),
                    "pairs": np.asarray(m.pairs).reshape(-1, 2).tolist(),
                    "on_axis": np.asarray(m.on_axis).tolist(),
                    "error": float(m.error),
                }
                for m in self.mirrors
            ],
        }

    @classmethod
    def from_dict(cls, d: dict) -> "Symmetry":
        """Inverse of :meth:`to_dict`."""
        return cls(
            panel_names=list(d["panels"]),
            offsets=np.asarray(d["offsets"], dtype=np.int64),
            c0=np.asarray(d["control_points"], dtype=np.float64).reshape(-1, 2),
            k_indices=np.asarray(d["k_indices"], dtype=np.int64),
            tol=float(d.get("tol", SYMMETRY_REL_TOL)),
            pairs=[
                PanelPair(
                    p["source"],
                    p["target"],
                    np.asarray(p["perm"], dtype=np.int64),
                    np.asarray(p["matrix"], dtype=np.float64),
                    bool(p["mirrored"]),
                    float(p["error"]),
                )
                for p in d.get("pairs", [])
            ],
            mirrors=[
                MirrorAxis(
                    m["panel"],
                    np.asarray(m["point"], dtype=np.float64),
                    np.asarray(m["direction"], dtype=np.float64),
                    np.asarray(m["pairs"], dtype=np.int64).reshape(-1, 2),
                    np.asarray(m["on_axis"], dtype=np.int64),
                    float(m["error"]),
                )
                for m in d.get("mirrors", [])
            ],
        )


def procrustes(x: np.ndarray, y: np.ndarray, *, det: int | None = None) -> tuple[np.ndarray, float]:
    """Orthogonal Procrustes (Schönemann 1966): the orthogonal R (2, 2) minimizing
    sum |R x_i - y_i|^2 for centred point sets x, y (n, 2) float64 [m].

    det: +1 (rotation only), -1 (reflection only) or None (either).
    Returns (R (2, 2) float64, RMS residual [m]).
    """
    h = y.T @ x  # (2, 2) = sum_i y_i x_i^T
    u, _, vt = np.linalg.svd(h)
    r = u @ vt
    if det is not None and np.sign(np.linalg.det(r)) != det:
        r = u @ np.diag([1.0, -1.0]) @ vt
    res = x @ r.T - y
    return r, float(np.sqrt((res**2).sum(axis=1).mean()))


def curve_samples(
    pattern: Pattern, controls: ControlPoints, p: int, *, m: int = _SAMPLES_PER_CURVE
) -> np.ndarray:
    """Points (n, m, 2) float64 [m] along each of panel p's n curves (the outline between control
    point j and j+1, CCW), at arc-length fractions k/m, k = 0..m-1 (so [:, 0] are the control points)."""
    name = controls.panel_names[p]
    panel = pattern.panels[name]
    idx = controls.of_panel(p)
    cverts = controls.vertex[idx]
    # dense outline, starting at edge 0's start, with the position of each panel vertex
    pts, where = [], {}
    for e in panel.edges:
        where[e.start] = sum(len(q) for q in pts)
        f = edge_point_fn(panel.vertices[e.start], panel.vertices[e.end], e.curvature)
        t = np.linspace(0.0, 1.0, 65 if e.curvature is not None else 2)[:-1]
        pts.append(f(t))
    dense = np.concatenate(pts, axis=0)
    total = len(dense)
    out = np.zeros((len(cverts), m, 2))
    for j in range(len(cverts)):
        i0 = where[int(cverts[j])]
        i1 = where[int(cverts[(j + 1) % len(cverts)])]
        n_seg = (i1 - i0) % total or total
        seg = dense[(i0 + np.arange(n_seg + 1)) % total]
        s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(seg, axis=0), axis=1))])
        tgt = np.arange(m) / m * s[-1]
        out[j, :, 0] = np.interp(tgt, s, seg[:, 0])
        out[j, :, 1] = np.interp(tgt, s, seg[:, 1])
    return out


def _corresponding_samples(samples: np.ndarray, sigma: np.ndarray, reverse: bool) -> np.ndarray:
    """Samples of the curves that correspond, under the control point map sigma (n,), to each
    sample of the identity order. samples (n, m, 2) -> (n, m, 2)."""
    n, m, _ = samples.shape
    if not reverse:  # curve j -> curve sigma(j), same fractions
        return samples[sigma]
    # reversed: curve j (c_j -> c_j+1) corresponds to curve sigma(j+1) -> sigma(j) run backwards
    # (n, m+1, 2) incl. end
    nxt = np.concatenate([samples[:, 1:], samples[np.roll(np.arange(n), -1), :1]], axis=1)
    out = np.empty_like(samples)
    for j in range(n):
        c = sigma[(j + 1) % n]  # the corresponding curve runs from sigma(j+1) to sigma(j)
        full = np.concatenate([samples[c], nxt[c, -1:]], axis=0)  # (m+1, 2) from c to c+1
        out[j] = full[::-1][:m]
    return out


def _fit(src: np.ndarray, dst: np.ndarray, det: int) -> tuple[np.ndarray, float]:
    """Fit dst ~ R (src - mean) + mean' on (N, 2) point sets; error = largest residual / RMS radius."""
    xs, ys = src - src.mean(axis=0), dst - dst.mean(axis=0)
    r, _ = procrustes(xs, ys, det=det)
    radius = float(np.sqrt((xs**2).sum(axis=1).mean()))
    worst = float(np.linalg.norm(xs @ r.T - ys, axis=1).max())
    return r, (worst / radius if radius > 0 else np.inf)


def detect_symmetry(
    pattern: Pattern, *, controls: ControlPoints | None = None, tol: float = SYMMETRY_REL_TOL
) -> Symmetry:
    """Algorithm 1: inter-panel pairs, then intra-panel mirror axes, and the effective control
    points K.

    pattern: the sewing pattern.
    controls: its control points (default: :func:`find_control_points`).
    tol: acceptance threshold, largest residual / RMS radius (scale-free).

    Returns a :class:`Symmetry`.
    """
    if controls is None:
        controls = find_control_points(pattern)
    names = controls.panel_names
    P = len(names)
    samples = [curve_samples(pattern, controls, p) for p in range(P)]
    counts = [int(controls.offsets[p + 1] - controls.offsets[p]) for p in range(P)]

    pairs, dropped = _panel_pairs(names, samples, counts, tol)
    mirrors, removed = [], set()
    for p in range(P):
        if p in dropped:
            continue
        axis = _mirror_axis(names[p], samples[p], counts[p], tol)
        if axis is not None:
            o = int(controls.offsets[p])
            removed.update(o + int(j) for _, j in axis.pairs)
            mirrors.append(axis)

    keep = [g for g in range(len(controls)) if int(controls.panel[g]) not in dropped and g not in removed]
    return Symmetry(
        panel_names=list(names),
        offsets=controls.offsets.copy(),
        c0=controls.positions.copy(),
        k_indices=np.asarray(keep, dtype=np.int64),
        pairs=pairs,
        mirrors=mirrors,
        tol=float(tol),
    )


def _panel_pairs(names, samples, counts, tol: float) -> tuple[list[PanelPair], set[int]]:
    """Inter-panel symmetry: for each panel the best mirrored or congruent partner with as many
    control points, fit error below ``tol``. Returns the pairs and the panel indices they drop."""
    pairs: list[PanelPair] = []
    dropped, sources = set(), set()
    for p in range(len(names)):
        if p in dropped:
            continue
        best = None
        for q in range(len(names)):
            if q == p or q in dropped or q in sources or counts[q] != counts[p]:
                continue
            n = counts[p]
            for reverse in (True, False):
                for s in range(n):
                    i = np.arange(n)
                    sigma = (s - i) % n if reverse else (i + s) % n  # target i <- source sigma[i]
                    # curve samples of the target correspond to the source's under sigma
                    src = _corresponding_samples(samples[p], sigma, reverse).reshape(-1, 2)
                    dst = samples[q].reshape(-1, 2)
                    r, err = _fit(src, dst, -1 if reverse else 1)
                    if err < tol and (best is None or err < best[0] - 1e-12):
                        best = (err, q, sigma, r, reverse)
        if best is not None:
            err, q, sigma, r, reverse = best
            pairs.append(PanelPair(names[p], names[q], sigma.astype(np.int64), r, reverse, float(err)))
            dropped.add(q)
            sources.add(p)
    return pairs, dropped


def _mirror_axis(name: str, samples: np.ndarray, n: int, tol: float) -> MirrorAxis | None:
    """Intra-panel mirror symmetry of one panel with ``n`` control points and its curve
    ``samples``: the best reflection with fit error below ``tol``, or None."""
    best = None
    for s in range(n):
        i = np.arange(n)
        sigma = (s - i) % n
        src = _corresponding_samples(samples, sigma, True).reshape(-1, 2)
        dst = samples.reshape(-1, 2)
        r, err = _fit(src, dst, -1)
        if err < tol and (best is None or err < best[0] - 1e-12):
            best = (err, sigma, r)
    if best is None:
        return None
    err, sigma, r = best
    theta = 0.5 * np.arctan2(r[1, 0], r[0, 0])  # reflection about the line at angle theta
    d = np.array([np.cos(theta), np.sin(theta)])
    point = samples.reshape(-1, 2).mean(axis=0)
    pr = sorted({(min(j, int(sigma[j])), max(j, int(sigma[j]))) for j in range(n) if sigma[j] != j})
    on_axis = [j for j in range(n) if sigma[j] == j]
    pairs = np.asarray(pr, dtype=np.int64).reshape(-1, 2)
    return MirrorAxis(name, point, d, pairs, np.asarray(on_axis, dtype=np.int64), float(err))
