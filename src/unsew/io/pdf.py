"""Tiled PDF of a sewing pattern at true scale (1:1) on A4 or US Letter pages, for printing at
home and taping together.

Page 1 holds a 10 cm test square at 1:1 (print at 100 %, "actual size", and measure it), how to
assemble the pages and a map of the page grid over the pieces. Then one page per tile of the
sheet (the same pieces as the SVG and DXF, :mod:`unsew.io.sheet`: cut lines solid, sew lines
dashed, notches on both, grain and fold lines, names, cutting notes and seam labels, laid out
again for the fewest pages: rows 2 to 9 tiles wide, in pattern order or tallest first); tiles
that hold nothing are left out, the others keep their place in the grid. Each tile page draws
its tile in a frame of exactly the tile's size; tiles are named by row letter (A at the top)
and column number (1 at the left), the name printed in the page margin, and at the middle of
every frame side that has a neighbour a half diamond and the neighbour's name: trim the margin
of one page, lay it on the next so the half diamonds make one, and tape.

Drawn with matplotlib's PDF backend; one axes per page whose size on paper equals its data
range in millimetres, so one millimetre of the pattern is one millimetre on the page.
"""

from __future__ import annotations

import os
import string

import numpy as np

from unsew.errors import InputError
from unsew.io.atomic import atomic_write
from unsew.io.sheet import TEST_SQUARE_M, Sheet, make_sheet
from unsew.pattern.model import Pattern

__all__ = ["write_pdf", "PAPER_MM", "PAGE_MARGIN_MM", "tile_grid"]

#: Paper sizes, portrait (width, height) [mm].
PAPER_MM = {"a4": (210.0, 297.0), "letter": (215.9, 279.4)}
#: Margin round the tile on each page [mm] (most printers cannot print the outer 5 mm).
PAGE_MARGIN_MM = 12.0
_PT = 72.0 / 25.4  # points per millimetre


def tile_grid(sheet_mm: np.ndarray, paper: str) -> tuple[np.ndarray, int, int]:
    """The tile size (2,) [mm] on ``paper`` and the grid's rows and columns covering a sheet of
    ``sheet_mm`` (2,) [mm]."""
    pw, ph = PAPER_MM[paper]
    tile = np.array([pw - 2 * PAGE_MARGIN_MM, ph - 2 * PAGE_MARGIN_MM])
    cols, rows = (int(np.ceil(s / t - 1e-9)) for s, t in zip(sheet_mm, tile))
    return tile, max(rows, 1), max(cols, 1)


def _tile_name(r: int, c: int) -> str:
    letters = string.ascii_uppercase
    row = letters[r] if r < 26 else letters[r // 26 - 1] + letters[r % 26]
    return f"{row}{c + 1}"


def _draw_pieces(
    ax, sheet: Sheet, box: tuple[float, float, float, float] | None, *, scale: float = 1.0, text: bool = True
) -> bool:
    """Draw the sheet's pieces [mm] on ``ax`` (only those meeting ``box`` = x0, y0, x1, y1 [mm]
    when given); ``scale``: drawing mm per page mm (line widths and text shrink by it). Returns
    whether anything was drawn."""
    from matplotlib import patheffects

    halo = [patheffects.withStroke(linewidth=2.0, foreground="white")]  # text readable over lines
    drew = False
    lw = 1.0 / scale
    for pc in sheet.pieces:
        cut = (pc.lines.cut + pc.offset) * 1000.0
        lo, hi = cut.min(0), cut.max(0)
        if box is not None and (hi[0] < box[0] or lo[0] > box[2] or hi[1] < box[1] or lo[1] > box[3]):
            continue
        drew = True
        sew = (pc.lines.sew + pc.offset) * 1000.0
        ax.fill(cut[:, 0], cut[:, 1], facecolor="#f4f4f4", edgecolor="black", linewidth=0.5 * _PT * lw)
        ax.fill(
            sew[:, 0],
            sew[:, 1],
            facecolor="none",
            edgecolor="#555555",
            linewidth=0.3 * _PT * lw,
            linestyle=(0, (3, 1.5)),
        )
        if not text:
            ax.text(*(0.5 * (lo + hi)), pc.name, ha="center", va="center", fontsize=6, clip_on=True)
            continue
        for a, b in pc.notches_sew + pc.notches_cut:
            s = (np.array([a, b]) + pc.offset) * 1000.0
            ax.plot(s[:, 0], s[:, 1], color="red", linewidth=0.4 * _PT)
        g = (pc.grain + pc.offset) * 1000.0
        ax.annotate(
            "",
            xy=g[1],
            xytext=g[0],
            arrowprops=dict(arrowstyle="<|-|>", lw=0.4 * _PT, color="black", mutation_scale=8),
            annotation_clip=True,
        )
        if pc.fold is not None:
            f = (pc.fold + pc.offset) * 1000.0
            ax.plot(f[:, 0], f[:, 1], color="#2f6fd0", linewidth=0.3 * _PT, linestyle=(0, (6, 2, 1, 2)))
        for lb in pc.labels:
            p = (lb.pos + pc.offset) * 1000.0
            seam = lb.kind == "seam"
            ax.text(
                p[0],
                p[1],
                lb.text,
                fontsize=lb.height * 1000.0 * _PT,
                clip_on=True,
                ha="center" if seam else "left",
                va="center",
                color="red" if seam else "black",
                fontweight="bold" if lb.kind == "name" else "normal",
                path_effects=halo,
            )
    return drew


def _page(fig_w: float, fig_h: float):
    import matplotlib.figure

    return matplotlib.figure.Figure(figsize=(fig_w / 25.4, fig_h / 25.4))


def _mm_axes(fig, page: tuple[float, float], x: float, y: float, w: float, h: float):
    """Axes at (x, y) [mm from the page's lower left], w x h [mm] on paper, no decorations."""
    ax = fig.add_axes((x / page[0], y / page[1], w / page[0], h / page[1]))
    ax.set_axis_off()
    return ax


def _test_square(fig, page: tuple[float, float], y: float) -> None:
    """The 10 cm test square, with cm ticks, at y [mm from the page's bottom], the page margin in."""
    pw, ph = page
    m, s_mm = PAGE_MARGIN_MM, TEST_SQUARE_M * 1000.0
    ax = _mm_axes(fig, (pw, ph), m, y, s_mm, s_mm)
    ax.plot([0, s_mm, s_mm, 0, 0], [0, 0, s_mm, s_mm, 0], color="black", linewidth=0.6, clip_on=False)
    for t in range(1, 10):
        ax.plot([t * 10, t * 10], [0, 3], color="black", linewidth=0.4, clip_on=False)
        ax.plot([0, 3], [t * 10, t * 10], color="black", linewidth=0.4, clip_on=False)
    ax.text(s_mm / 2, s_mm / 2, "10 cm", ha="center", va="center", fontsize=14)
    ax.set_xlim(0, s_mm)
    ax.set_ylim(0, s_mm)


def _page_map(fig, page: tuple[float, float], sheet, grid) -> None:
    """The page map, to scale, under the test square: the pieces and every tile, named where it
    is printed, grey where it is left out. grid = (tile [mm], rows, cols, top [mm], tiles printed)."""
    pw, ph = page
    m, s_mm = PAGE_MARGIN_MM, TEST_SQUARE_M * 1000.0
    tile, rows, cols, top, tiles = grid
    have = set(tiles)
    map_w, map_h = pw - 2 * m, ph - 2 * m - 60 - s_mm
    k = min(map_w / (cols * tile[0]), map_h / (rows * tile[1]))
    axm = _mm_axes(fig, (pw, ph), m, m, cols * tile[0] * k, rows * tile[1] * k)
    _draw_pieces(axm, sheet, None, scale=1.0 / max(k, 1e-6) / 4, text=False)
    for r in range(rows):
        for c in range(cols):
            b = _box(r, c, tile, top)
            on = (r, c) in have
            axm.add_patch(_rect(b, on))
            axm.text(
                (b[0] + b[2]) / 2,
                (b[1] + b[3]) / 2,
                _tile_name(r, c) if on else "",
                ha="center",
                va="center",
                fontsize=7,
                color="#2f6fd0",
            )
    axm.set_xlim(0, cols * tile[0])
    axm.set_ylim(top - rows * tile[1], top)
    fig.text(
        m / pw,
        (m + rows * tile[1] * k + 2) / ph,
        "Page map (grey: pages left out, nothing on them)",
        fontsize=8,
    )


#: How to print and assemble the tiles, on the first page.
_INSTRUCTIONS = (
    'Print at 100 % ("actual size", no fit to page), then measure the square: it must be 10 cm.',
    "Solid: cut line (seam allowance included). Dashed: sew line. Red ticks: notches;",
    "red letters: seams (sew edges with the same letter together, notches matching).",
    "Assemble: trim the margin of a page, lay it on its neighbour so the half diamonds",
    "at the frame sides make whole ones and the frame lines meet, then tape.",
)


def _tile_page(fig, page: tuple[float, float], sheet, grid, r: int, c: int) -> None:
    """Tile (r, c) of the sheet at 1:1 inside the page margin, framed, with the match marks
    towards its printed neighbours. grid as :func:`_page_map`."""
    tile, _, _, top, tiles = grid
    m = PAGE_MARGIN_MM
    b = _box(r, c, tile, top)
    ax = _mm_axes(fig, page, m, m, tile[0], tile[1])
    _draw_pieces(ax, sheet, b)
    ax.set_xlim(b[0], b[2])
    ax.set_ylim(b[1], b[3])
    ax.plot(
        [b[0], b[2], b[2], b[0], b[0]],
        [b[1], b[1], b[3], b[3], b[1]],
        color="#2f6fd0",
        linewidth=0.5,
        clip_on=False,
    )
    _match_marks(ax, b, r, c, set(tiles))


def write_pdf(
    pattern: Pattern,
    path: str | os.PathLike,
    *,
    paper: str = "a4",
    allowance: float | None = None,
    hem: float | None = None,
) -> int:
    """Write ``pattern`` as a tiled 1:1 PDF on ``paper`` ('a4' or 'letter'), atomically.
    allowance, hem: seam allowance of plain and hem edges [m] (default: the pattern's
    ``unsew.seam_allowance``, else 1 and 2 cm). Returns the number of pages."""
    paper = str(paper).lower()
    if paper not in PAPER_MM:
        raise InputError(f"paper {paper!r} is not known: use one of {', '.join(PAPER_MM)}")
    from matplotlib.backends.backend_pdf import PdfPages

    pw, ph = PAPER_MM[paper]
    m = PAGE_MARGIN_MM
    s_mm = TEST_SQUARE_M * 1000.0
    sheet, tile, rows, cols, top, tiles = _tiled(make_sheet(pattern, allowance=allowance, hem=hem), paper)
    grid = (tile, rows, cols, top, tiles)
    with (
        atomic_write(path) as tmp,
        PdfPages(tmp, metadata={"Title": f"{pattern.name}: sewing pattern, 1:1", "Creator": "unsew"}) as pdf,
    ):
        fig = _page(pw, ph)
        fig.text(
            m / pw,
            1 - m / ph,
            f"{pattern.name}: sewing pattern at 1:1 on {paper.upper()} ({len(tiles)} tile pages)",
            fontsize=13,
            fontweight="bold",
            va="top",
        )
        for k, line in enumerate(_INSTRUCTIONS):
            fig.text(m / pw, 1 - (m + 12 + 5.5 * k) / ph, line, fontsize=8.5, va="top")
        _test_square(fig, (pw, ph), ph - m - 50 - s_mm)
        _page_map(fig, (pw, ph), sheet, grid)
        pdf.savefig(fig)
        for i, (r, c) in enumerate(tiles):
            fig = _page(pw, ph)
            _tile_page(fig, (pw, ph), sheet, grid, r, c)
            fig.text(
                0.5,
                1 - 5 / ph,
                f"{pattern.name}   page {_tile_name(r, c)}   ({i + 2} of {len(tiles) + 1})",
                ha="center",
                va="center",
                fontsize=9,
            )
            pdf.savefig(fig)
    return len(tiles) + 1


def _box(r: int, c: int, tile: np.ndarray, top: float) -> tuple[float, float, float, float]:
    """Tile (r, c) as (x0, y0, x1, y1) [mm] on the sheet; row 0 is the top row, at ``top``."""
    x0, y1 = c * tile[0], top - r * tile[1]
    return (x0, y1 - tile[1], x0 + tile[0], y1)


def _tiled(sheet: Sheet, paper: str):
    """The pieces laid out for the fewest pages on ``paper`` (rows of 2 to 9 tiles' width, in
    pattern order or tallest first; the test square goes to page 1) and that layout's tiles:
    (sheet, tile (2,) [mm], rows, cols, top [mm], [(r, c) of the tiles holding ink])."""
    from unsew.io.sheet import relayout

    tile0, _, _ = tile_grid(np.ones(2), paper)
    best = None
    for k in range(2, 10):
        for tallest in (False, True):
            sh = relayout(sheet, row_width=k * tile0[0] / 1000.0 - 1e-6, tallest_first=tallest, square=False)
            size = sh.size * 1000.0
            tile, rows, cols = tile_grid(size, paper)
            top = float(size[1])
            boxes = [((pc.lines.cut + pc.offset) * 1000.0) for pc in sh.pieces]
            boxes = [(b.min(0), b.max(0)) for b in boxes]
            tiles = [
                (r, c)
                for r in range(rows)
                for c in range(cols)
                if any(_overlap(_box(r, c, tile, top), lo, hi) for lo, hi in boxes)
            ]
            if best is None or len(tiles) < len(best[5]):
                best = (sh, tile, rows, cols, top, tiles)
    return best


def _overlap(b, lo, hi) -> bool:
    return not (hi[0] < b[0] or lo[0] > b[2] or hi[1] < b[1] or lo[1] > b[3])


def _rect(b, on: bool):
    from matplotlib.patches import Rectangle

    return Rectangle(
        (b[0], b[1]),
        b[2] - b[0],
        b[3] - b[1],
        fill=not on,
        facecolor="#dddddd",
        edgecolor="#2f6fd0",
        linewidth=0.5,
    )


def _match_marks(ax, b, r: int, c: int, have: set) -> None:
    """A half diamond (6 mm) at the middle of each frame side that has a neighbouring page, and
    the neighbour's name beside it, inside the frame."""
    from matplotlib.patches import Polygon

    x0, y0, x1, y1 = b
    xm, ym, d = (x0 + x1) / 2, (y0 + y1) / 2, 6.0
    sides = {
        (r - 1, c): ([(xm - d, y1), (xm, y1 - d), (xm + d, y1)], (xm, y1 - d - 3), "center", "top"),
        (r + 1, c): ([(xm - d, y0), (xm, y0 + d), (xm + d, y0)], (xm, y0 + d + 3), "center", "bottom"),
        (r, c - 1): ([(x0, ym - d), (x0 + d, ym), (x0, ym + d)], (x0 + d + 3, ym), "left", "center"),
        (r, c + 1): ([(x1, ym - d), (x1 - d, ym), (x1, ym + d)], (x1 - d - 3, ym), "right", "center"),
    }
    for nb, (tri, at, ha, va) in sides.items():
        if nb in have:
            ax.add_patch(Polygon(tri, closed=True, facecolor="#2f6fd0", edgecolor="none", alpha=0.6))
            ax.text(
                *at,
                f"{_tile_name(*nb)}",
                ha=ha,
                va=va if va != "center" else "center",
                fontsize=8,
                color="#2f6fd0",
            )
