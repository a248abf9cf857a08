"""Vertex-clustering decimation for robustness tests (no extra dependency): vertices in the same
cubic cell are merged at their mean; the cell size is bisected to keep about ``ratio`` of them."""

import numpy as np


def cluster_decimate(v, f, ratio=0.5):
    """(V', 3) vertices and (F', 3) faces with about ``ratio * V`` vertices; degenerate faces dropped."""
    v = np.asarray(v, float)
    f = np.asarray(f)
    lo, hi = 1e-4, 0.2
    best = None
    for _ in range(30):
        h = 0.5 * (lo + hi)
        key = np.floor((v - v.min(0)) / h).astype(np.int64)
        _, lab = np.unique(key, axis=0, return_inverse=True)
        lab = lab.reshape(-1)
        n = lab.max() + 1
        if n > ratio * len(v):
            lo = h
        else:
            hi = h
        best = (lab, n)
    lab, n = best
    nv = np.zeros((n, 3))
    np.add.at(nv, lab, v)
    nv /= np.bincount(lab, minlength=n)[:, None]
    nf = lab[f]
    keep = (nf[:, 0] != nf[:, 1]) & (nf[:, 1] != nf[:, 2]) & (nf[:, 0] != nf[:, 2])
    nf = np.unique(np.sort(nf[keep], axis=1), axis=0, return_index=True)[1]
    faces = lab[f][keep][np.sort(nf)]
    used = np.unique(faces)
    remap = -np.ones(n, np.int64)
    remap[used] = np.arange(len(used))
    return nv[used], remap[faces]
