"""What does the demo's result look like? The README's picture from a demo's result folder.

Puts a fit's two report figures side by side: ``figures/target_vs_result.png`` (target above,
result below, front and side) and ``figures/patterns.png`` (base, graded, true and final
patterns, panel by panel), both heights scaled to the taller one's. Nothing is measured here:
the picture shows the result folder given.

    python -m unsew demo --out DEMO --no-progress
    python -m benchmarks demo_figure DEMO/fit --out docs/figures/demo.png
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path


def compose(result_dir: Path, out: Path, *, dpi: int = 100) -> Path:
    """Write ``out`` (PNG): the result folder's target-vs-result and patterns figures side by side."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.image as mpimg
    import matplotlib.pyplot as plt

    names = ("target_vs_result.png", "patterns.png")
    paths = [result_dir / "figures" / n for n in names]
    missing = [str(p) for p in paths if not p.is_file()]
    if missing:
        raise SystemExit(
            f"demo_figure: {', '.join(missing)} missing; is {result_dir} a fit's result folder with a report?"
        )
    images = [mpimg.imread(p) for p in paths]
    h = max(im.shape[0] for im in images)
    widths = [im.shape[1] * h / im.shape[0] for im in images]
    fig = plt.figure(figsize=(sum(widths) / dpi, h / dpi), dpi=dpi)
    x = 0.0
    for im, w in zip(images, widths):
        ax = fig.add_axes((x / sum(widths), 0.0, w / sum(widths), 1.0))
        ax.imshow(im)
        ax.set_axis_off()
        x += w
    out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(out, dpi=dpi)
    plt.close(fig)
    return out


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("result", type=Path, help="a fit's result folder (the demo's: DEMO/fit)")
    ap.add_argument("--out", type=Path, default=Path("docs/figures/demo.png"), help="PNG to write")
    args = ap.parse_args(argv)
    print(f"wrote {compose(args.result, args.out)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
