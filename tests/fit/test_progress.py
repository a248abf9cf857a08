"""Progress of a fit: plain lines off a terminal (no carriage returns, no cursor codes), bars on
one, and the figure shown is the Chamfer distance in mm the report uses."""

import io
import re
from types import SimpleNamespace

from unsew.fit.progress import Progress

CONTROL = re.compile(r"[\r\x1b]")


class _Terminal(io.StringIO):
    def isatty(self):
        return True


def _iterations(p, n, chamfer=lambda info: 12.345):
    cb = p.iterations(n, 0, chamfer)
    for i in range(n):
        cb(SimpleNamespace(iteration=i, last=i == n - 1))
    cb.close()


def test_off_a_terminal_plain_lines_per_phase_and_every_n_iterations():
    buf = io.StringIO()
    p = Progress(stream=buf, every=5, seconds=1e9)
    with p.phase("drape base") as bar:
        for k in range(1, 81):
            bar("sew", k, 80)
        for k in range(1, 41):
            bar("settle", k, 40)
    _iterations(p, 12)
    text = buf.getvalue()
    assert not CONTROL.search(text)
    lines = text.splitlines()
    assert lines[:2] == ["drape base: sew (80 steps)", "drape base: settle (40 steps)"]
    it_lines = [ln for ln in lines if ln.startswith("fit: iteration")]
    assert [ln.split(",")[0] for ln in it_lines] == [
        "fit: iteration 5/12",
        "fit: iteration 10/12",
        "fit: iteration 12/12",
    ]
    assert all("Chamfer 12.35 mm" in ln for ln in it_lines)


def test_off_a_terminal_a_line_every_few_seconds_too():
    buf = io.StringIO()
    _iterations(Progress(stream=buf, every=1000, seconds=0.0), 3)
    assert len([ln for ln in buf.getvalue().splitlines() if ln.startswith("fit: iteration")]) == 3


def test_on_a_terminal_the_bar_shows_the_chamfer_in_mm():
    buf = _Terminal()
    seen = []

    def chamfer(info):
        seen.append(info.iteration)
        return 3.21

    _iterations(Progress(stream=buf), 4, chamfer)
    assert "Chamfer 3.21 mm" in buf.getvalue() and seen == [0, 1, 2, 3]
    assert "\r" in buf.getvalue()  # a bar, redrawn in place


def test_disabled_prints_nothing():
    buf = io.StringIO()
    p = Progress(False, stream=buf)
    with p.phase("x") as bar:
        assert bar is None
    _iterations(p, 3)
    p.line("hello")
    assert buf.getvalue() == ""
