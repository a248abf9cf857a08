"""Exact nearest-neighbour search between point sets, for the Chamfer losses.

Indices carry no gradient (they are piecewise constant in the positions); the losses gather the
neighbours with these indices and recompute the distances with autograd, so gradients flow
through the distances only.

Two exact back ends, chosen by ``method``:

- ``"kdtree"``: ``scipy.spatial.cKDTree`` built on ``points``, queried with all cores
  (``workers=-1``). O((N + M) log M).
- ``"cdist"``: ``torch.cdist`` in row chunks of the query, then ``argmin``. O(N M) work, memory
  bounded by ``chunk * M``; stays on the tensors' device (the only choice on a GPU).

``"auto"`` takes the KD-tree for CPU tensors and cdist for tensors on another device
(measured in ``benchmarks/bench_losses.py``: on 2 CPU cores the KD-tree is several times faster
at 10K points).
"""

from __future__ import annotations

__all__ = ["nearest_indices"]

_CHUNK_ELEMS = 1 << 24  # cdist chunk size: rows * M <= 16M distances (128 MB in float64)


def nearest_indices(query, points, *, method: str = "auto", compute_mode: str = "use_mm_for_euclid_dist"):
    """Index of the nearest point of ``points`` to each query point (Euclidean, exact up to ties).

    query: positions [m], shape (N, 3) (any D), float64 torch tensor.
    points: positions [m], shape (M, D), float64 torch tensor, M >= 1.
    method: ``"auto"``, ``"kdtree"`` or ``"cdist"`` (see module docstring).
    compute_mode: ``torch.cdist``'s mode for ``"cdist"`` (the matmul form is much faster on CPU:
        ``python -m benchmarks losses``).
    Returns: (N,) int64 torch tensor on ``query``'s device, no gradient.
    """
    import torch

    if points.shape[0] == 0:
        raise ValueError("nearest_indices: empty point set")
    if method == "auto":
        method = "kdtree" if query.device.type == "cpu" else "cdist"
    q = query.detach()
    p = points.detach()
    if method == "kdtree":
        from scipy.spatial import cKDTree

        qn = q.cpu().numpy()
        pn = p.cpu().numpy()
        _, idx = cKDTree(pn).query(qn, k=1, workers=-1)
        return torch.as_tensor(idx, dtype=torch.int64, device=query.device)
    if method == "cdist":
        n, m = q.shape[0], p.shape[0]
        rows = max(1, _CHUNK_ELEMS // max(m, 1))
        out = torch.empty(n, dtype=torch.int64, device=query.device)
        for s in range(0, n, rows):
            # the matmul expansion is inexact only to ~1e-16 |x|^2: it can swap near-ties, which
            # changes neither the gathered distance nor the loss beyond that rounding
            d = torch.cdist(q[s : s + rows], p, compute_mode=compute_mode)
            out[s : s + rows] = d.argmin(dim=1)
        return out
    raise ValueError(f"nearest_indices: unknown method {method!r} (use 'auto', 'kdtree' or 'cdist')")
