"""A picture of a body and its skeleton, front and side, to look at a rig (matplotlib)."""

from __future__ import annotations

import os

import numpy as np

from unsew.io.atomic import atomic_write

__all__ = ["render_rig_preview"]


def render_rig_preview(body, path: str | os.PathLike, *, title: str | None = None) -> None:
    """Write a PNG: the body's vertices (grey) and its bones and joints (red), seen from the
    front (X right is the body's left, Y up) and from its left side (Z to the right, Y up).

    body: a ``Body`` (verts (V, 3) float64 [m], skeleton). Written atomically.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    V = np.asarray(body.verts)
    sk = body.skeleton
    step = max(len(V) // 15000, 1)
    fig, axes = plt.subplots(1, 2, figsize=(9, 7), dpi=110)
    for ax, (i, label) in zip(axes, ((0, "front (x)"), (2, "left side (z)"))):
        ax.scatter(V[::step, i], V[::step, 1], s=0.3, c="0.75", lw=0)
        for b in sk.bones():
            ax.plot([b.a[i], b.b[i]], [b.a[1], b.b[1]], c="tab:red", lw=1.5)
        ax.scatter(sk.positions[:, i], sk.positions[:, 1], s=14, c="tab:red", zorder=3)
        ax.set_aspect("equal")
        ax.set_xlabel(f"{label} [m]")
        ax.set_ylabel("y [m]")
    fig.suptitle(
        title
        or f"{body.name}: {'rigged from its mesh' if getattr(body, 'rigged', False) else 'skeleton given'}"
    )
    fig.tight_layout()
    with atomic_write(path) as tmp:
        fig.savefig(tmp, format="png")
    plt.close(fig)
