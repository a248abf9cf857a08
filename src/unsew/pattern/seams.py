"""Seam lengths of a parameterised pattern, and the projection that keeps them sewable.

Two edges stitched together must be as long as each other, up to the ease the pattern was
drafted with (a sleeve cap a little longer than its armhole). Phase two moves the control points
by gradient steps on the Chamfer distance; its seam loss (:mod:`unsew.losses.seam`) is soft, so
without a hold a fitted pattern can come out with dart legs or side seams whose lengths differ
by a centimetre or more: a pattern that does not sew (docs/decisions/013).

Edge lengths in K. :meth:`unsew.pattern.params.PatternParams.to_pattern` puts each panel corner
at ``uv(K)``; a Bezier edge's curvature is relative to its chord and a circular arc's radius is
scaled with it, so every edge keeps its shape up to a similarity and its length is

    L_e(K) = r_e |v_end(K) - v_start(K)|,   r_e = L_e / chord at rest  [m]

with v the rows of ``uv(K) = L_u K + b_u`` of the edge's two end vertices: cheap and exact.

The hold (:class:`SeamHold`) keeps, for every stitch, the ratio of its two edges' lengths that
the start pattern has, L_a - rho L_b = 0 with rho = L_a(K0) / L_b(K0): a ratio, not a difference,
so a pattern scaled as a whole (the area hold of ``area: target``) keeps it exactly. K is moved
by the smallest correction that meets these constraints (Gauss-Newton on the minimum-norm
solution, a few rounds because the lengths are not linear in K), optionally within the range of
per-point projectors (waistbands that keep their height).
"""

from __future__ import annotations

import numpy as np

from unsew.pattern.curves import edge_length

__all__ = ["SeamHold", "stitch_length_ratios", "stitch_length_gaps", "seam_changes_mm"]

#: Seam residual [m] below which the hold stops correcting.
SEAM_TOL = 1e-9


def _stitch_lengths(pattern) -> np.ndarray:
    """(S, 2) float64: the lengths L_a, L_b [m] of every stitch's two edges, in ``pattern.stitches`` order."""
    return np.array(
        [
            [
                edge_length(pattern.panels[s.a.panel], s.a.edge),
                edge_length(pattern.panels[s.b.panel], s.b.edge),
            ]
            for s in pattern.stitches
        ],
        dtype=np.float64,
    ).reshape(-1, 2)


def stitch_length_ratios(pattern) -> np.ndarray:
    """(S,) float64: L_a / L_b of every stitch of ``pattern`` (in ``pattern.stitches`` order) [-]."""
    lens = _stitch_lengths(pattern)
    return lens[:, 0] / lens[:, 1]


def stitch_length_gaps(pattern) -> np.ndarray:
    """(S,) float64: L_a - L_b of every stitch of ``pattern`` (in ``pattern.stitches`` order) [m]."""
    lens = _stitch_lengths(pattern)
    return lens[:, 0] - lens[:, 1]


def _sides(pattern) -> list[tuple]:
    return [(s.a.panel, s.a.edge, s.b.panel, s.b.edge) for s in pattern.stitches]


def seam_changes_mm(patterns: dict, base_key: str = "base") -> dict:
    """How far apart the stitched edges of each pattern are, for metrics.json and the benchmarks.

    patterns: name -> :class:`unsew.pattern.model.Pattern` (None entries skipped), one of them under
    ``base_key``. Returns ``{"gap_max_mm": {name: largest |L_a - L_b| over stitches [mm]},
    "change_from_base_max_mm": {name: largest change of a stitch's L_a - L_b from the base's [mm]}}``:
    the change leaves out the ease the base was drafted with (a sleeve cap longer than its
    armhole) and is given only for patterns stitched as the base is (same edges, same order).
    """
    gaps = {k: stitch_length_gaps(p) for k, p in patterns.items() if p is not None}
    out = {
        "gap_max_mm": {k: float(1e3 * np.abs(g).max()) if len(g) else 0.0 for k, g in gaps.items()},
        "change_from_base_max_mm": {},
    }
    base = patterns.get(base_key)
    if base is not None:
        for k, p in patterns.items():
            if p is not None and k != base_key and _sides(p) == _sides(base):
                d = gaps[k] - gaps[base_key]
                out["change_from_base_max_mm"][k] = float(1e3 * np.abs(d).max()) if len(d) else 0.0
    return out


class SeamHold:
    """Keeps every stitch's two edge lengths in the ratio they have at ``K0`` (module docstring).

    params: :class:`unsew.pattern.params.PatternParams`; K0: (Nk, 2) [m], torch or numpy, whose
    ratios are held; project: optional (Nk, 2, 2) symmetric projectors on each point's move (phase
    two's band projectors): the correction stays in their range.
    Call it on K (Nk, 2) torch [m]: returns the corrected K, same dtype and device (no gradient).
    """

    def __init__(self, params, K0, project=None):
        pat, mesh = params.pattern, params.mesh
        edges: dict[tuple[str, int], int] = {}
        for st in pat.stitches:
            for side in (st.a, st.b):
                edges.setdefault((side.panel, side.edge), len(edges))
        self.n_edges = len(edges)
        L = params.L_u.detach().cpu().numpy()
        b = params.b_u.detach().cpu().numpy()
        nk = params.n_k
        D = np.zeros((self.n_edges, 2, 2 * nk))  # chord = D K + d, per edge
        d = np.zeros((self.n_edges, 2))
        r = np.ones(self.n_edges)
        for (name, i), e in edges.items():
            vs = mesh.edge_verts[(name, i)]
            s, t = int(vs[0]), int(vs[-1])
            D[e] = L[2 * t : 2 * t + 2] - L[2 * s : 2 * s + 2]
            d[e] = b[2 * t : 2 * t + 2] - b[2 * s : 2 * s + 2]
            panel = pat.panels[name]
            chord = float(
                np.linalg.norm(panel.vertices[panel.edges[i].end] - panel.vertices[panel.edges[i].start])
            )
            r[e] = edge_length(panel, i) / chord if chord > 0 else 1.0
        self.D, self.d, self.r = D, d, r
        self.ia = np.array([edges[(st.a.panel, st.a.edge)] for st in pat.stitches], dtype=np.int64)
        self.ib = np.array([edges[(st.b.panel, st.b.edge)] for st in pat.stitches], dtype=np.int64)
        P = (
            None
            if project is None
            else np.asarray(
                project.detach().cpu().numpy() if hasattr(project, "detach") else project, dtype=np.float64
            )
        )
        # the projectors as one block-diagonal (2 Nk, 2 Nk) matrix on xy-flattened K, built once
        self.Pm = None if P is None else np.einsum("jab,jk->jakb", P, np.eye(nk)).reshape(2 * nk, 2 * nk)
        k0 = np.asarray(K0.detach().cpu().numpy() if hasattr(K0, "detach") else K0, dtype=np.float64).reshape(
            -1
        )
        la = self.lengths(k0)
        self.rho = la[self.ia] / la[self.ib]

    def lengths(self, k: np.ndarray) -> np.ndarray:
        """(E,) the stitched edges' lengths [m] at K flattened (2 Nk,) numpy."""
        c = self.D @ k + self.d
        return self.r * np.linalg.norm(c, axis=1)

    def residuals(self, K) -> np.ndarray:
        """(S,) L_a - rho L_b per stitch [m] at K (Nk, 2), torch or numpy."""
        k = np.asarray(K.detach().cpu().numpy() if hasattr(K, "detach") else K, dtype=np.float64).reshape(-1)
        lens = self.lengths(k)
        return lens[self.ia] - self.rho * lens[self.ib]

    def _jacobian(self, k: np.ndarray) -> np.ndarray:
        c = self.D @ k + self.d  # (E, 2)
        n = np.linalg.norm(c, axis=1, keepdims=True)
        dl = self.r[:, None] * np.einsum("ej,ejk->ek", c / np.maximum(n, 1e-12), self.D)  # (E, 2 Nk)
        return dl[self.ia] - self.rho[:, None] * dl[self.ib]

    def __call__(self, K, rounds: int = 8):
        """K (Nk, 2) torch [m] moved by the smallest correction (inside the projectors) that puts
        every stitch back in its ratio, to SEAM_TOL or for ``rounds`` Gauss-Newton rounds; same
        dtype and device, no gradient."""
        import torch

        if len(self.ia) == 0:
            return K
        k = K.detach().cpu().numpy().astype(np.float64).reshape(-1)
        Pm = self.Pm
        for _ in range(rounds):
            res = self.residuals(k)
            if np.abs(res).max() < SEAM_TOL:
                break
            J = self._jacobian(k)
            if Pm is not None:
                J = J @ Pm
            # the minimum-norm move that meets the linearised seams
            step = -np.linalg.lstsq(J, res, rcond=1e-10)[0]
            k = k + (Pm @ step if Pm is not None else step)
        return torch.as_tensor(k.reshape(-1, 2), dtype=K.dtype, device=K.device)
