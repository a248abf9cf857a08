"""benchmarks/bench_band_gap.py: the true band's edges and a bad case name."""

from benchmarks_loader import load_benchmark

from unsew.pattern.base import make_base_pattern


def test_band_edges_are_the_bands_top_and_bottom_girth():
    """The base skirt_darts' band is a strip: its top and bottom edges, times two pieces, are the
    same girth; a pattern without a band has none."""
    mod = load_benchmark("bench_band_gap")
    top, low = mod.band_edges(make_base_pattern("skirt_darts"))
    assert 0.5 < top < 1.5 and abs(top - low) < 1e-6
    assert mod.band_edges(make_base_pattern("tshirt")) is None


def test_an_unknown_case_is_refused_in_one_line(capsys):
    mod = load_benchmark("bench_band_gap")
    assert mod.main(["--cases", "no_such_case"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "no such case: no_such_case" in err[0]
