"""Tiled PDF: A4 and Letter pages, a cover page, one page per tile that holds part of a piece,
the tiles covering every piece."""

import re

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.io.pdf import PAPER_MM, _tiled, tile_grid, write_pdf
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
    sheet, tile, rows, cols, top, tiles = _tiled(make_sheet(p), paper)
    assert n == 1 + len(tiles) and tile.min() > 150
    for pc in sheet.pieces:  # every point of every cut line lies on a page that is printed
        pts = (pc.lines.cut + pc.offset) * 1000.0
        r = np.floor((top - pts[:, 1]) / tile[1]).astype(int)
        c = np.floor(pts[:, 0] / tile[0]).astype(int)
        assert all((int(a), int(b)) in set(tiles) for a, b in zip(r, c)), pc.name
    # laid out for the pages: no more pages than the SVG's layout has tiles
    svg = make_sheet(p)
    t2, r2, c2 = tile_grid(svg.size * 1000.0, paper)
    assert len(tiles) <= r2 * c2
    assert b"Title (skirt: sewing pattern, 1:1)" in data


def test_unknown_paper_is_refused(tmp_path):
    with pytest.raises(InputError, match="a4, letter"):
        write_pdf(make_base_pattern("skirt"), tmp_path / "p.pdf", paper="a3")


def test_export_command_writes_the_pdf_and_refuses_an_allowance_in_centimetres(tmp_path, capsys):
    from unsew.cli import main
    from unsew.io.garmentcode import save_pattern

    src = tmp_path / "s.json"
    save_pattern(make_base_pattern("skirt"), src)
    out = tmp_path / "s.pdf"
    assert (
        main(
            [
                "pattern",
                "export",
                str(src),
                "--pdf",
                str(out),
                "--paper",
                "letter",
                "--seam-allowance",
                "0.015",
            ]
        )
        == 0
    )
    assert out.read_bytes().startswith(b"%PDF") and "pages" in capsys.readouterr().out
    assert (
        main(["pattern", "export", str(src), "--dxf", str(tmp_path / "s.dxf"), "--seam-allowance", "1.5"])
        == 2
    )
    assert "in metres" in capsys.readouterr().err and not (tmp_path / "s.dxf").exists()
