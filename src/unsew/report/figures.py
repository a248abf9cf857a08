"""Plots of a fit: loss curves, sewing patterns overlaid panel by panel, distance histograms.

Every function writes one PNG (matplotlib, Agg, no window) and returns its path. Lengths in
patterns are metres in, centimetres on the page (the scale bar says so); distances are
millimetres.
"""

from __future__ import annotations

import math
import os
from pathlib import Path
from typing import Mapping, Sequence

import numpy as np

from unsew.errors import InputError
from unsew.pattern.curves import panel_outline

__all__ = [
    "plot_loss_curves",
    "legend_label",
    "plot_patterns",
    "pattern_outlines",
    "plot_histogram",
    "PATTERN_STYLES",
]

#: Default look of a pattern by a word in its label (first match wins, case-insensitive);
#: other labels cycle through matplotlib's tab10 colours.
PATTERN_STYLES: dict[str, dict] = {
    "base": {"color": "#8c8c8c", "linestyle": (0, (5, 3)), "linewidth": 1.3},
    "grad": {"color": "#2f6fd0", "linestyle": "-", "linewidth": 1.4},
    # the truth is drawn wide and under the others, so a final outline on it stays visible
    "true": {"color": "#e0413a", "linestyle": "-", "linewidth": 3.2, "zorder": -1},
    "truth": {"color": "#e0413a", "linestyle": "-", "linewidth": 3.2, "zorder": -1},
    "gt": {"color": "#e0413a", "linestyle": "-", "linewidth": 3.2, "zorder": -1},
    "ground": {"color": "#e0413a", "linestyle": "-", "linewidth": 3.2, "zorder": -1},
    "final": {"color": "#111111", "linestyle": "-", "linewidth": 1.9, "fill": "#111111"},
    "fit": {"color": "#111111", "linestyle": "-", "linewidth": 1.9, "fill": "#111111"},
    "result": {"color": "#111111", "linestyle": "-", "linewidth": 1.9, "fill": "#111111"},
}

_TOTAL_KEYS = ("total", "loss", "total_loss")


def _figure(size_px, dpi=100):
    """A detached Agg figure of exactly size_px = (w, h) pixels."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    w, h = int(size_px[0]), int(size_px[1])
    if w < 64 or h < 64:
        raise InputError(f"size_px must be at least 64 x 64 pixels, got {size_px}")
    fig = Figure(figsize=(w / dpi, h / dpi), dpi=dpi, facecolor="white")
    FigureCanvasAgg(fig)
    return fig


def _save(fig, path_png, dpi=100) -> Path:
    path = Path(path_png)
    path.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(os.fspath(path), dpi=dpi, facecolor="white", format="png")
    return path


# --------------------------------------------------------------------------------------------
# loss curves


def legend_label(name: str, values, *, log: bool = True) -> str:
    """A loss term's legend entry: its name and its last value, the value at the final iteration
    (also where a log axis hides it: a term that ends at 0 says ``last 0``), as metrics'
    ``loss_final`` has it. values: shape (N,), NaN for gaps."""
    v = np.asarray(values, dtype=np.float64).reshape(-1)
    raw = v[np.isfinite(v)]
    shown = raw[raw > 0] if log else raw
    if raw.size == 0:
        return f"{name}  (no value, not shown)"
    if shown.size == 0:
        return f"{name}  (last {raw[-1]:.3g}; all <= 0, not shown)"
    return f"{name}  (last {raw[-1]:.3g})"


def plot_loss_curves(
    path_png: str | os.PathLike,
    history: Mapping[str, Sequence[float]],
    *,
    log: bool = True,
    phases: Sequence[tuple[int, str]] | None = None,
    title: str | None = "Loss per iteration",
    size_px: tuple[int, int] = (900, 480),
) -> Path:
    """Total loss and each term against the iteration number.

    history: term name -> values, one per iteration from iteration 0 (lists may differ in
        length, e.g. a term switched on later can be padded with NaN at the start; NaN and
        None are gaps). The term named ``total`` (or ``loss``) is drawn thick and black.
    log: logarithmic y axis; values <= 0 are then gaps, and a term with none above zero is
        listed in the legend as not shown. The legend gives each term's last value: its value
        at the final iteration, also where the log axis hides it (0), as metrics' loss_final.
    phases: (first iteration, name) of each phase, e.g. ``[(0, "sewing"), (40, "pattern"),
        (120, "pattern + material")]``: a dashed line and the name at each start.
    size_px: (width, height) of the PNG in pixels. Returns the PNG's path.
    """
    series = _loss_series(history)
    fig = _figure(size_px)
    ax = fig.add_axes((0.085, 0.12, 0.6, 0.76 if title else 0.82))
    n_iter = _draw_loss_lines(ax, series, log=log)
    _loss_axes(ax, n_iter, log=log)
    if phases:
        _draw_phases(ax, phases, n_iter)
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1.0), frameon=False, fontsize=9)
    if title:
        fig.text(0.5, 0.975, title, ha="center", va="top", fontsize=13, weight="bold")
    return _save(fig, path_png)


def _loss_series(history: Mapping[str, Sequence[float]]) -> dict[str, np.ndarray]:
    """term name -> values (N,) float64, None as NaN; InputError when there is nothing to plot."""
    if not history:
        raise InputError("history is empty: nothing to plot")
    series = {}
    for name, vals in history.items():
        arr = np.array([np.nan if v is None else v for v in vals], dtype=np.float64).reshape(-1)
        series[str(name)] = arr
    if all(len(a) == 0 for a in series.values()):
        raise InputError("every loss term in history is empty: nothing to plot")
    return series


def _draw_loss_lines(ax, series: Mapping[str, np.ndarray], *, log: bool) -> int:
    """One line per term of ``series`` on ``ax``, the total first (thick, black), each labelled
    by :func:`legend_label`. Returns the number of iterations (the longest series)."""
    import matplotlib

    total = next((k for k in _TOTAL_KEYS if k in series), None)
    names = ([total] if total else []) + [k for k in series if k != total]
    colors = matplotlib.colormaps["tab10"].colors
    ci = 0
    n_iter = 0
    for name in names:
        y = series[name].copy()
        n_iter = max(n_iter, len(y))
        if log:
            y[~(y > 0)] = np.nan
        finite = y[np.isfinite(y)]
        if name == total:
            style = {"color": "black", "linewidth": 2.2, "zorder": 5}
        else:
            style = {"color": colors[ci % len(colors)], "linewidth": 1.3, "zorder": 3}
            ci += 1
        label = legend_label(name, series[name], log=log)
        if finite.size == 0:
            ax.plot([], [], label=label, **style)
            continue
        x = np.arange(len(y))
        ax.plot(x, y, label=label, **style)
        if finite.size == 1:  # a single point draws no line: mark it
            ax.plot(x[np.isfinite(y)], finite, "o", color=style["color"], markersize=4)
    return n_iter


def _loss_axes(ax, n_iter: int, *, log: bool) -> None:
    """Scale, limits, whole-number iteration ticks, labels and grid of the loss axes."""
    from matplotlib.ticker import MaxNLocator

    if log:
        ax.set_yscale("log")
    ax.set_xlim(0, max(n_iter - 1, 1))
    ax.xaxis.set_major_locator(MaxNLocator(integer=True))  # iterations are whole numbers
    ax.set_xlabel("iteration")
    ax.set_ylabel("loss (log scale)" if log else "loss")
    ax.grid(True, which="major", color="#dddddd", linewidth=0.8)
    ax.set_axisbelow(True)
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)


def _draw_phases(ax, phases: Sequence[tuple[int, str]], n_iter: int) -> None:
    """Each phase's start (first iteration, name): a dashed line (none at 0), the name above
    the axes, every other phase shaded."""
    from matplotlib.transforms import blended_transform_factory

    tr = blended_transform_factory(ax.transData, ax.transAxes)
    starts = sorted((int(i), str(n)) for i, n in phases)
    for k, (i, pname) in enumerate(starts):
        end = starts[k + 1][0] if k + 1 < len(starts) else max(n_iter - 1, 1)
        if k % 2 == 1:
            ax.axvspan(i, end, color="#f3f3f7", zorder=0)
        if i > 0:
            ax.axvline(i, color="#777777", linestyle="--", linewidth=1.0, zorder=1)
        ax.text(
            i,
            1.01,
            f" {pname}",
            transform=tr,
            ha="left",
            va="bottom",
            fontsize=8.5,
            color="#444444",
            clip_on=False,
        )


# --------------------------------------------------------------------------------------------
# patterns


def pattern_outlines(pattern, *, points_per_edge: int = 32) -> list[tuple[str, np.ndarray]]:
    """(panel name, closed outline (M, 2) float64 [m] in the panel's own frame) of each panel of
    a :class:`unsew.pattern.model.Pattern`, in ``panel_order`` (then any other panels), ready
    for :func:`plot_patterns`. Curved edges get ``points_per_edge`` segments."""
    order = [n for n in (pattern.panel_order or []) if n in pattern.panels]
    order += [n for n in pattern.panels if n not in order]
    return [(n, panel_outline(pattern.panels[n], points_per_edge=points_per_edge)) for n in order]


def _pattern_style(label: str, index: int, styles: Mapping[str, dict] | None) -> dict:
    import matplotlib

    low = label.lower()
    style = None
    for word, st in PATTERN_STYLES.items():
        if word in low.replace("-", " ").replace("_", " ").split() or low.startswith(word):
            style = dict(st)
            break
    if style is None:
        colors = matplotlib.colormaps["tab10"].colors
        style = {"color": colors[(index + 4) % len(colors)], "linestyle": "-", "linewidth": 1.4}
    if styles and label in styles:
        style.update(styles[label])
    return style


def _check_outline(o, what: str) -> np.ndarray:
    a = np.asarray(o, dtype=np.float64)
    if a.ndim != 2 or a.shape[1] != 2 or len(a) < 3:
        raise InputError(f"{what}: outline must have shape (M, 2) with M >= 3, got {a.shape}")
    if not np.isfinite(a).all():
        raise InputError(f"{what}: outline has NaN or infinite points")
    return a


def _nice_length(x: float) -> float:
    """The largest of 1, 2, 5 x 10^k not above x (x > 0)."""
    k = math.floor(math.log10(x))
    for m in (5, 2, 1):
        if m * 10**k <= x:
            return m * 10**k
    return 10**k


def plot_patterns(
    path_png: str | os.PathLike,
    patterns: Sequence[tuple[str, Sequence[tuple]]],
    *,
    styles: Mapping[str, dict] | None = None,
    layout: str = "grid",
    title: str | None = "Sewing patterns",
    width_px: int = 1100,
    max_row_width_m: float | None = None,
) -> Path:
    """Several versions of a sewing pattern overlaid, panel by panel, at true scale.

    patterns: list of (label, panels); panels a list of (panel name, outline (M, 2) [m]) or
        (panel name, outline (M, 2) [m], placement_xy (2,) [m]). Outlines are closed polylines
        (last point not repeated) in the panel's own frame, e.g. from :func:`pattern_outlines`.
        Later patterns are drawn over earlier ones.
    styles: label -> matplotlib line style overrides (``color``, ``linestyle``, ``linewidth``;
        ``fill`` a colour for a faint fill; ``zorder`` to draw a pattern under (negative) or
        over the others, default its position in the list). Defaults by words in the label
        (:data:`PATTERN_STYLES`): base dashed grey, graded blue, final black, true red.
    layout: ``"grid"``: each panel name gets a cell, its versions overlaid in the panel frame,
        cells packed in rows under one scale, names under the panels. ``"placed"``: all panels
        in one frame, each moved by its ``placement_xy``.
    width_px: width of the PNG in pixels; the height follows from the layout's proportions.
    max_row_width_m: width [m] at which a row of cells wraps (default: about square overall).
    Equal aspect everywhere, with a scale bar in centimetres. Returns the PNG's path.
    """
    if layout not in ("grid", "placed"):
        raise InputError(f"layout must be 'grid' or 'placed', got {layout!r}")
    if not patterns:
        raise InputError("no patterns to plot")
    cells, labels = _pattern_cells(patterns, layout)
    boxes, offsets, label_h, (xmin, xmax, ymin) = _pack_cells(cells, layout, max_row_width_m)
    ymax = 0.0
    bar = _nice_length(0.25 * (xmax - xmin))
    bar_h = 0.08 * (ymax - ymin) + 0.02
    ymin_all = ymin - bar_h
    dx, dy = xmax - xmin, ymax - ymin_all
    pad = 0.03 * max(dx, dy)

    W = int(width_px)
    head = (40 if title else 8) + 30  # title and legend band [px]
    ax_w = W - 40
    H = int(min(max(head + ax_w * (dy + 2 * pad) / (dx + 2 * pad) + 12, 240), 3000))
    fig = _figure((W, H))
    ax = fig.add_axes((20 / W, 12 / H, ax_w / W, (H - head - 12) / H))
    ax.set_axis_off()
    ax.set_aspect("equal", adjustable="datalim", anchor="N")
    pstyles = [_pattern_style(lbl, i, styles) for i, lbl in enumerate(labels)]
    _draw_cells(ax, cells, boxes, offsets, pstyles, layout=layout, label_h=label_h)
    _draw_scale_bar(ax, xmin, ymin - 0.45 * bar_h, bar, 0.12 * bar_h)
    ax.set_xlim(xmin - pad, xmax + pad)
    ax.set_ylim(ymin_all - pad, ymax + pad)
    _pattern_legend(fig, labels, pstyles, top=(36 if title else 4) / H)
    if title:
        fig.text(0.5, 1 - 8 / H, title, ha="center", va="top", fontsize=13, weight="bold")
    return _save(fig, path_png)


def _pattern_legend(fig, labels, pstyles, *, top: float) -> None:
    """One legend line per pattern label in its style, centred ``top`` (a fraction of the
    figure's height) below the figure's top."""
    from matplotlib.lines import Line2D

    handles = [
        Line2D(
            [], [], color=st["color"], linestyle=st.get("linestyle", "-"), linewidth=st.get("linewidth", 1.4)
        )
        for st in pstyles
    ]
    fig.legend(
        handles,
        labels,
        loc="upper center",
        ncol=min(len(labels), 6),
        frameon=False,
        fontsize=10,
        bbox_to_anchor=(0.5, 1 - top),
    )


def _pattern_cells(patterns, layout: str) -> tuple[dict[str, list[tuple[int, np.ndarray, str]]], list[str]]:
    """The outlines of ``patterns`` (as :func:`plot_patterns` takes them), checked, by cell.

    Returns (cell -> list of (pattern index, outline (M, 2) [m], panel name), pattern labels).
    In the ``"grid"`` layout each panel name is a cell and outlines stay in the panel frame; in
    ``"placed"`` everything shares one cell, each outline moved by its placement_xy."""
    cells: dict[str, list[tuple[int, np.ndarray, str]]] = {}
    labels = []
    for pi, item in enumerate(patterns):
        try:
            label, panels = item
        except (TypeError, ValueError):
            raise InputError("each pattern must be a (label, panels) pair") from None
        labels.append(str(label))
        for entry in panels:
            if len(entry) not in (2, 3):
                raise InputError(
                    f"pattern {label!r}: a panel must be (name, outline) or (name, outline, placement_xy)"
                )
            name, outline = str(entry[0]), _check_outline(entry[1], f"{label}/{entry[0]}")
            if len(entry) == 3 and layout == "placed":
                off = np.asarray(entry[2], dtype=np.float64).reshape(2)
                outline = outline + off
            key = name if layout == "grid" else "(all)"
            cells.setdefault(key, []).append((pi, outline, name))
    if not cells:
        raise InputError("the patterns hold no panels")
    return cells, labels


def _pack_cells(cells, layout: str, max_row_width_m: float | None):
    """A shelf packing of the cells into rows under one scale, panels bottom-aligned in a row,
    room for the names under each row (grid layout).

    Returns (cell -> bounding box (lo (2,), hi (2,)) [m] in its own frame, cell -> offset (2,)
    [m] into the page, the height of a row's name band [m], (xmin, xmax, ymin) [m]: the page's
    extent, from y = 0 at the top down to the bottom of the last row's names)."""
    boxes = {}
    for name, items in cells.items():
        allp = np.concatenate([o for _, o, _ in items])
        boxes[name] = (allp.min(axis=0), allp.max(axis=0))
    sizes = np.array([hi - lo for lo, hi in boxes.values()])
    gap = 0.12 * float(np.max(sizes)) if len(cells) > 1 else 0.0
    label_h = 0.07 * float(np.max(sizes[:, 1])) if layout == "grid" else 0.0
    if max_row_width_m is None:
        area = float(np.sum((sizes[:, 0] + gap) * (sizes[:, 1] + gap + label_h)))
        max_row_width_m = max(1.25 * math.sqrt(area), float(sizes[:, 0].max()))
    offsets, rows, x, row = {}, [], 0.0, []
    for name, (lo, hi) in boxes.items():
        w = hi[0] - lo[0]
        if row and x + w > max_row_width_m:
            rows.append(row)
            row, x = [], 0.0
        row.append(name)
        x += w + gap
    rows.append(row)
    y_top = 0.0
    for row in rows:
        h = max(boxes[n][1][1] - boxes[n][0][1] for n in row)
        x = 0.0
        for n in row:
            lo, hi = boxes[n]
            # bottom-align panels in a row; the name goes under the row's cells
            offsets[n] = np.array([x - lo[0], y_top - h - lo[1]])
            x += hi[0] - lo[0] + gap
        y_top -= h + label_h + gap
    xmin = min(offsets[n][0] + boxes[n][0][0] for n in cells)
    xmax = max(offsets[n][0] + boxes[n][1][0] for n in cells)
    return boxes, offsets, label_h, (xmin, xmax, y_top + gap)


def _draw_cells(ax, cells, boxes, offsets, pstyles, *, layout: str, label_h: float) -> None:
    """Every outline of every cell at its offset, in the style of its pattern (a faint fill
    where the style has ``fill``), with the panel names (under each cell in the grid layout,
    at each panel's middle in the placed layout)."""
    from matplotlib.patches import Polygon

    for name, items in cells.items():
        off = offsets[name]
        named = set()
        for pi, outline, pname in items:
            st = pstyles[pi]
            if layout == "placed" and pname not in named:  # name each panel once, at its middle
                named.add(pname)
                mid = (outline.min(axis=0) + outline.max(axis=0)) / 2 + off
                ax.text(
                    mid[0], mid[1], pname, ha="center", va="center", fontsize=9, color="#333333", zorder=50
                )
            pts = outline + off
            if st.get("fill"):
                ax.add_patch(
                    Polygon(pts, closed=True, facecolor=st["fill"], alpha=0.07, edgecolor="none", zorder=1)
                )
            z = st.get("zorder", pi)
            ax.add_patch(
                Polygon(
                    pts,
                    closed=True,
                    fill=False,
                    edgecolor=st["color"],
                    linestyle=st.get("linestyle", "-"),
                    linewidth=st.get("linewidth", 1.4),
                    joinstyle="round",
                    zorder=10 + z + pi / 100,
                )
            )
        if layout == "grid":
            lo, hi = boxes[name]
            ax.text(
                off[0] + (lo[0] + hi[0]) / 2,
                off[1] + lo[1] - 0.25 * label_h,
                name,
                ha="center",
                va="top",
                fontsize=10,
                color="#333333",
            )


def _draw_scale_bar(ax, x0: float, yb: float, bar: float, tick: float) -> None:
    """A scale bar of length ``bar`` [m] from (x0, yb) [m] with ticks ``tick`` [m] high at its
    ends and middle, labelled 0 and its length in centimetres."""
    ax.plot([x0, x0 + bar], [yb, yb], color="black", linewidth=2.0, solid_capstyle="butt")
    for xt in (x0, x0 + bar / 2, x0 + bar):
        ax.plot([xt, xt], [yb - tick, yb + tick], color="black", linewidth=1.0)
    ax.text(x0, yb - 1.6 * tick, "0", ha="center", va="top", fontsize=8.5)
    ax.text(x0 + bar, yb - 1.6 * tick, f"{bar * 100:g} cm", ha="center", va="top", fontsize=8.5)


# --------------------------------------------------------------------------------------------
# histogram


def plot_histogram(
    path_png: str | os.PathLike,
    values: np.ndarray,
    *,
    bins: int = 60,
    xlabel: str = "distance to target [mm]",
    title: str | None = "Per-vertex distance",
    size_px: tuple[int, int] = (800, 400),
) -> Path:
    """Histogram of per-vertex values (e.g. distance to the target [mm], shape (V,), float),
    with the mean, median and 95th percentile marked. NaNs are dropped (and counted in the
    title); the x axis label carries the unit. Returns the PNG's path."""
    v = np.asarray(values, dtype=np.float64).reshape(-1)
    ok = np.isfinite(v)
    if not ok.any():
        raise InputError("no finite values to draw a histogram of")
    n_bad = int((~ok).sum())
    v = v[ok]
    fig = _figure(size_px)
    ax = fig.add_axes((0.09, 0.14, 0.86, 0.72 if title else 0.8))
    lo, hi = float(v.min()), float(v.max())
    if not hi - lo > 1e-9 * max(abs(hi), 1.0):  # one value (or nearly): a bar of width 1 % around it
        half = 0.005 * max(abs(hi), 1e-3)
        lo, hi = lo - half, hi + half
    ax.hist(v, bins=int(bins), range=(lo, hi), color="#5b8fd0", edgecolor="white", linewidth=0.4)
    marks = [
        ("mean", float(v.mean()), "#111111", "-"),
        ("median", float(np.median(v)), "#d62728", "--"),
        ("95th pct", float(np.percentile(v, 95)), "#8c8c8c", ":"),
    ]
    for name, x, c, ls in marks:
        ax.axvline(x, color=c, linestyle=ls, linewidth=1.5, label=f"{name} {x:.3g}")
    ax.set_xlabel(xlabel)
    ax.set_ylabel("vertices")
    for side in ("top", "right"):
        ax.spines[side].set_visible(False)
    ax.grid(True, axis="y", color="#e6e6e6")
    ax.set_axisbelow(True)
    ax.legend(frameon=False, fontsize=9)
    if title:
        t = title + (f"  ({n_bad} without a value left out)" if n_bad else "")
        fig.text(0.5, 0.97, t, ha="center", va="top", fontsize=13, weight="bold")
    return _save(fig, path_png)
