"""benchmarks/bench_render.py in its small mode: one small render per kind, and the body-bleed
table at one gap."""

from benchmarks_loader import load_benchmark


def test_small_mode_renders_and_writes_pngs(tmp_path, capsys):
    load_benchmark("bench_render").main(["--sizes", "400", "--repeat", "1", "--out", str(tmp_path)])
    row = [ln.split() for ln in capsys.readouterr().out.splitlines() if ln.strip()[:1].isdigit()]
    assert len(row) == 1 and all(float(x) > 0 for x in row[0][1:4])
    assert sorted(p.name[0] for p in tmp_path.glob("*400.png")) == ["b", "g", "h"]
