"""What do drafts of the design space look like? A picture of a few designs' panels.

For each design, its panels as placed around the default body (seen from the front, world
metres) above its flat panels laid side by side (panel frames, metres). Nothing is measured here.

    python -m benchmarks design_figure --out docs/figures/design_space.png
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

#: The designs shown: (title, Design fields).
SHOWN = (
    (
        "tee: V front, long two-piece sleeves, cuffs",
        dict(neckline_front="v", sleeves="long", sleeve_pieces=2, cuffs=True),
    ),
    (
        "dress: bodice + 6-gore A-line, square neck",
        dict(garment="dress", waist_seam=True, panels=6, neckline_front="square"),
    ),
    (
        "dress: bodice + 3/4-circle skirt, boat neck",
        dict(
            garment="dress",
            waist_seam=True,
            skirt="circle",
            circle_fraction=0.75,
            neckline_front="boat",
            neckline_back="boat",
            sleeves="none",
        ),
    ),
    (
        "skirt: 8-gore full circle, waistband",
        dict(garment="skirt", skirt="circle", circle_fraction=1.0, panels=8, waistband=True),
    ),
    ("skirt: 4-panel pencil", dict(garment="skirt", skirt="pencil", panels=4)),
    ("jumpsuit: knee length, short sleeves", dict(garment="jumpsuit", leg="knee", neckline_front="v")),
)


def _flat_layout(ax, pattern, outline) -> None:
    """The flat panels side by side, each in its own frame, a 5 cm gap between them."""
    x0 = 0.0
    for p in pattern.ordered_panels():
        o = outline(p)
        o = o - [o[:, 0].min() - x0, 0.0]
        ax.fill(o[:, 0], o[:, 1], alpha=0.35)
        ax.plot(*np.vstack([o, o[:1]]).T, lw=0.6, color="k")
        x0 = o[:, 0].max() + 0.05
    ax.set_aspect("equal")
    ax.set_axis_off()


def render(out: Path, *, dpi: int = 110) -> Path:
    """Write ``out`` (PNG): each design of :data:`SHOWN` drafted for the default body."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from unsew.pattern.curves import panel_outline
    from unsew.pattern.design import Design, draft

    outline = lambda p: panel_outline(p, points_per_edge=24)  # noqa: E731
    fig, axes = plt.subplots(
        2, len(SHOWN), figsize=(3.0 * len(SHOWN), 5.6), gridspec_kw={"height_ratios": [3, 1.2]}
    )
    for col, (title, kw) in enumerate(SHOWN):
        pattern = draft(Design(**kw))
        ax = axes[0, col]
        # back panels first, so the front ones are drawn over them
        for p in sorted(pattern.ordered_panels(), key=lambda p: p.rotation_matrix()[2, 2]):
            w = p.to_world(outline(p))
            ax.fill(w[:, 0], w[:, 1], alpha=0.45)
            ax.plot(*np.vstack([w, w[:1]])[:, :2].T, lw=0.6, color="k")
        ax.set_aspect("equal")
        ax.set_xlim(-0.9, 0.9)
        ax.set_ylim(0.0, 1.5)
        ax.set_title(title, fontsize=8)
        ax.tick_params(labelsize=6)
        _flat_layout(axes[1, col], pattern, outline)
        axes[1, col].set_title(f"{len(pattern.panels)} panels, {len(pattern.stitches)} seams", fontsize=7)
    fig.tight_layout()
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=dpi, bbox_inches="tight")
    plt.close(fig)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--out", type=Path, default=Path("docs/figures/design_space.png"), help="PNG to write")
    args = ap.parse_args(argv)
    print(f"wrote {render(args.out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
