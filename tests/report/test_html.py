"""write_report: self-contained, every metric and caption present, atomic on failure."""

import base64
import re

import numpy as np
import pytest

from unsew.errors import InputError
from unsew.report.figures import plot_histogram
from unsew.report.html import pretty_key, write_report

PNG_SIG = b"\x89PNG\r\n\x1a\n"


@pytest.fixture
def figs(tmp_path):
    rng = np.random.default_rng(0)
    a = plot_histogram(tmp_path / "figs" / "a.png", rng.random(100), size_px=(200, 120), title=None)
    b = plot_histogram(tmp_path / "figs" / "b.png", rng.random(100) * 3, size_px=(200, 120))
    return [("Distance to the target", a), ("Loss <per> iteration & phases", b)]


METRICS = {
    "chamfer_mm": 1.834,
    "normal_error_deg": np.float64(7.25),
    "iterations": 200,
    "converged": True,
    "panels": {
        "front": {"area_error_pct": 1.25, "turning": 0.0125},
        "sleeve": {"area_error_pct": 2.5, "turning": 0.05},
    },
    "material": {"fitted": {"bend_n_m": 3.5e-6, "density_kg_per_m2": 0.15}, "note": "ok"},
}


def test_report_holds_metrics_captions_and_images(tmp_path, figs):
    out = write_report(
        tmp_path / "res" / "report.html",
        title="Fit of case <t-shirt>",
        summary={"garment": "tshirt", "chamfer_mm": 1.834, "time_s": 61.5},
        metrics=METRICS,
        figures=figs,
        config={"lr": 1e-3, "betas": (0.9, 0.999)},
        notes=["material fixed: <b>not</b> optimized"],
    )
    text = out.read_text(encoding="utf-8")
    assert text.startswith("<!DOCTYPE html>") and text.rstrip().endswith("</html>")
    for shown in [
        "chamfer [mm]",
        "1.834",
        "normal error [deg]",
        "7.25",
        "iterations",
        "200",
        "area error [%]",
        "1.25",
        "2.5",
        "turning",
        "0.0125",
        "front",
        "sleeve",
        "bend [N·m]",
        "3.5e-06",
        "density [kg/m²]",
        "0.15",
        "time [s]",
        "61.5",
    ]:
        assert shown in text, shown
    # captions and user text are escaped, not interpreted
    assert "Distance to the target" in text
    assert "Loss &lt;per&gt; iteration &amp; phases" in text
    assert "&lt;b&gt;not&lt;/b&gt;" in text and "Fit of case &lt;t-shirt&gt;" in text
    assert "lr: 0.001" in text and "- 0.999" in text
    # every figure is embedded as a valid base64 PNG equal to the file (no external references)
    uris = re.findall(r'src="data:image/png;base64,([A-Za-z0-9+/=]+)"', text)
    assert len(uris) == len(figs)
    for (_, path), uri in zip(figs, uris):
        assert base64.b64decode(uri, validate=True) == path.read_bytes()
    assert not re.search(r'src="(?!data:)', text)
    assert [p.name for p in out.parent.iterdir()] == ["report.html"]  # no temporary left


def test_missing_figure_writes_nothing(tmp_path, figs):
    out = tmp_path / "res" / "report.html"
    bad = figs + [("heat map", tmp_path / "nowhere.png")]
    with pytest.raises(InputError, match="heat map.*not found"):
        write_report(out, title="t", summary={}, metrics=METRICS, figures=bad)
    assert not out.exists()
    assert not out.parent.exists() or not any(out.parent.iterdir())

    # a file that is not an image is refused the same way
    (tmp_path / "notes.txt").write_text("hello")
    with pytest.raises(InputError, match="not a PNG"):
        write_report(out, title="t", summary={}, metrics={}, figures=[("x", tmp_path / "notes.txt")])
    assert not out.exists()


def test_failure_while_writing_keeps_the_old_report_and_leaves_no_temporary(tmp_path, figs, monkeypatch):
    out = tmp_path / "report.html"
    out.write_text("previous report")
    import pathlib

    def boom(self, *a, **k):
        raise OSError("disk full")

    monkeypatch.setattr(pathlib.Path, "write_text", boom)
    with pytest.raises(OSError, match="disk full"):
        write_report(out, title="t", summary={"a": 1}, metrics={"b": 2}, figures=figs)
    monkeypatch.undo()
    assert out.read_text() == "previous report"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["figs", "report.html"]


def test_relative_figure_paths_resolve_beside_the_report(tmp_path, figs, monkeypatch):
    monkeypatch.chdir(tmp_path.parent)
    out = write_report(
        tmp_path / "report.html", title="t", summary={}, metrics={}, figures=[("a", "figs/a.png")]
    )
    assert "data:image/png;base64," in out.read_text()


def test_pretty_key():
    assert pretty_key("chamfer_mm") == "chamfer [mm]"
    assert pretty_key("mean_area_error_pct") == "mean area error [%]"
    assert pretty_key("h00_n_per_m") == "h00 [N/m]"
    assert pretty_key("time [s]") == "time [s]"
    assert pretty_key("iterations") == "iterations"
    assert pretty_key("m") == "m"


def test_write_fit_report_makes_every_figure(tmp_path, meshes):
    from unsew.report.fit_report import nearest_distance_mm, write_fit_report

    gv, gf = meshes.box((0.3, 0.5, 0.2), n=3)
    tv = gv * 1.02
    bv, bf = meshes.box((0.2, 0.7, 0.12), n=3)
    d = nearest_distance_mm(gv, tv)
    assert d.shape == (len(gv),) and d.max() > 0 and d.max() < 20
    rect = [("sleeve", np.array([[0, 0], [0.4, 0], [0.4, 0.25], [0, 0.25]]))]
    out = write_fit_report(
        tmp_path / "res",
        title="fit",
        summary={"chamfer_mm": 1.0},
        metrics={"chamfer_mm": 1.0},
        target=(tv, gf),
        result=(gv, gf),
        body=(bv, bf),
        history={"total": [1.0, 0.5, 0.25]},
        patterns=[("base", rect), ("final", rect)],
        views=("front",),
    )
    names = sorted(p.name for p in (tmp_path / "res" / "figures").iterdir())
    assert names == ["distance.png", "distance_hist.png", "loss.png", "patterns.png", "target_vs_result.png"]
    text = out.read_text()
    assert text.count("data:image/png;base64,") == 5
    assert "nearest target vertex" in text
