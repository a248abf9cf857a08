"""Tiled PDF: A4 and Letter pages, a cover page, one page per tile that holds part of a piece,
the tiles covering every piece."""

import re

import pytest

from unsew.errors import InputError
from unsew.io.pdf import PAPER_MM, tile_grid, write_pdf
from unsew.io.sheet import make_sheet
from unsew.pattern.base import make_base_pattern


@pytest.mark.parametrize("paper", ["a4", "letter"])
def test_pages_are_the_paper_size_and_cover_the_pieces(paper, tmp_path):
    p = make_base_pattern("skirt")
    f = tmp_path / "p.pdf"
    n = write_pdf(p, f, paper=paper)
    data = f.read_bytes()
    assert data.startswith(b"%PDF")
    boxes = re.findall(rb"/MediaBox \[\s*0 0 ([\d.]+) ([\d.]+)\s*\]", data)
    assert len(boxes) == n == len(re.findall(rb"/Type /Page\b", data))
    w, h = (float(v) for v in boxes[0])
    assert (w, h) == pytest.approx(tuple(x * 72 / 25.4 for x in PAPER_MM[paper]), abs=0.01)
    sheet = make_sheet(p)
    tile, rows, cols = tile_grid(sheet.size * 1000.0, paper)
    assert tile.min() > 150 and rows * tile[1] >= sheet.size[1] * 1000 and cols * tile[0] >= sheet.size[0] * 1000
    assert 1 + 1 <= n <= 1 + rows * cols  # the cover, then no more than one page per tile
    assert b"Title (skirt: sewing pattern, 1:1)" in data


def test_unknown_paper_is_refused(tmp_path):
    with pytest.raises(InputError, match="a4, letter"):
        write_pdf(make_base_pattern("skirt"), tmp_path / "p.pdf", paper="a3")
