"""What the fit report says: loss legends that agree with the tables, no walls of numbers, the
panel measurements and the fitted material, the body not showing through close cloth."""

import numpy as np
import pytest

from unsew.report.figures import legend_label
from unsew.report.html import _fmt


def test_legend_gives_the_final_value_even_when_the_log_axis_hides_it():
    # the material term fell to 0 at the end: the legend said "last 0.82" while the table said 0
    assert legend_label("material", [0.9, 0.82, 0.0]) == "material  (last 0)"
    assert legend_label("chamfer", [3e-4, 2e-4]) == "chamfer  (last 0.0002)"
    assert "all <= 0, not shown" in legend_label("prior", [0.0, 0.0])
    assert legend_label("x", [np.nan]) == "x  (no value, not shown)"


def test_long_series_are_summarised_not_dumped():
    assert _fmt([1.0, 2.0]) == "1, 2"
    text = _fmt([float(i) for i in range(40)])
    assert text.startswith("40 values, 0 → 39") and "max 39" in text and "17" not in text


def test_panel_measurements_read_the_labelled_edges():
    from unsew.pattern.base import make_base_pattern
    from unsew.pattern.curves import edge_length
    from unsew.report.measure import measurement_table, panel_measurements

    t = make_base_pattern("tshirt")
    m = panel_measurements(t)
    hem = sum(edge_length(t.panels[n], 0) for n in ("front", "back"))  # edge 0 is each hem
    assert m["hem"] == pytest.approx(hem) and 0.8 < m["hem"] < 1.2
    assert set(m) == {"hem", "side seam", "sleeve", "chest girth", "sleeve girth"}
    pants = panel_measurements(make_base_pattern("pants"))
    assert {"inseam", "waist", "side seam", "hem"} <= set(pants) and pants["inseam"] > 0.5
    assert 0.6 < pants["waist"] < 0.9  # the whole waist girth, four panels
    rows = measurement_table([("final", make_base_pattern("pants")), ("base", t)])
    assert list(rows[0]) == ["measurement", "base [cm]", "final [cm]"]
    by = {r["measurement"]: r for r in rows}
    assert by["sleeve"]["final [cm]"] is None and by["inseam"]["base [cm]"] is None
    assert by["hem"]["base [cm]"] == pytest.approx(100 * hem, abs=0.01)


def test_fit_report_has_measurements_material_and_no_loss_dump(tmp_path, meshes):
    from unsew.pattern.base import make_base_pattern
    from unsew.report.fit_report import write_fit_report

    v, f = meshes.plane(0.4, 0.6, n=6, z=0.1)
    hist = {
        "total": [0.9, 0.5, 0.25, 0.125, 0.0625, 0.03, 0.02, 0.01],
        "material": [0.8, 0.82, 0, 0, 0, 0, 0, 0],
    }
    material = {"H00_N_per_m": 2855.17, "bending_N_m": 5.6e-6, "friction": 0.35}
    out = write_fit_report(
        tmp_path / "res",
        target=(v, f),
        result=(v + 0.001, f),
        history=hist,
        phases=[(0, "pattern"), (4, "pattern + material")],
        patterns=[("base", make_base_pattern("tshirt"))],
        material=material,
        metrics={"loss_history": hist, "loss_final": {"material": 0.0}},
    )
    html = out.read_text()
    assert "panel measurements" in html.lower() and "side seam" in html
    assert "material of the result" in html.lower() and "2855" in html
    assert "loss history" not in html.lower() and "0.0625" not in html


def test_body_does_not_show_through_close_cloth(tmp_path):
    """The body's torso pushed out 2 +- 3 mm as cloth (`python -m benchmarks render --bleed`): with
    the body's depth bias, far fewer body pixels inside the cloth than without it."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
    try:
        from bench_render import _bleed, _cloth
    finally:
        sys.path.pop(0)
    import unsew.report.render as render
    from unsew.body.body import default_body

    body = default_body()
    bv, bf = np.asarray(body.verts, dtype=np.float64), np.asarray(body.faces)
    c = bv[bf].mean(axis=1)
    bf = bf[(np.abs(c[:, 0]) < 0.2) | (c[:, 1] < 0.9)]
    cv, cf = _cloth(bv, bf, 0.002)
    mask = render.render_mesh(tmp_path / "cloth.png", cv, cf, view="side", frame="all", size_px=(300, 400))
    fixed = render.render_mesh(
        tmp_path / "fixed.png", cv, cf, view="side", body=(bv, bf), frame="all", size_px=(300, 400)
    )
    old = render.BODY_DEPTH_BIAS
    render.BODY_DEPTH_BIAS = 0.0
    try:
        plain = render.render_mesh(
            tmp_path / "plain.png", cv, cf, view="side", body=(bv, bf), frame="all", size_px=(300, 400)
        )
    finally:
        render.BODY_DEPTH_BIAS = old
    b_fixed, b_plain = _bleed(fixed, mask), _bleed(plain, mask)
    assert b_plain > 1.0 and b_fixed < 0.5 * b_plain, (b_plain, b_fixed)


def test_units_follow_the_table_and_min_is_not_minutes():
    from unsew.report.html import _metrics_html, pretty_key

    assert pretty_key("y_min") == "y min" and pretty_key("peak_memory_mb") == "peak memory [MB]"
    html = _metrics_html({"peak_memory_stages_mb": {"body_sdf_s": 959.5}, "timings_s": {"body_sdf_s": 3.2}})
    assert "body sdf [s]" not in html and "value [MB]" in html and "value [s]" in html
    assert html.count(">body sdf<") == 2


def test_seam_table_and_girths_of_a_tshirt():
    from unsew.io.sheet import seam_marks
    from unsew.pattern.base import make_base_pattern
    from unsew.pattern.curves import edge_length
    from unsew.report.measure import panel_measurements, seam_table

    t = make_base_pattern("tshirt")
    rows = seam_table(t)
    assert list(rows) == sorted({m.code for m in seam_marks(t)}, key=lambda c: (len(c), c))
    st = t.stitches[0]
    assert rows["A"]["a [cm]"] == pytest.approx(100 * edge_length(t.panels[st.a.panel], st.a.edge), abs=0.01)
    assert rows["A"]["side a"] == f"{st.a.panel}: {t.panels[st.a.panel].edges[st.a.edge].label}"
    m = panel_measurements(t)
    # the bodice is a little narrower at the armhole's foot than at the hem, a sleeve at the
    # underarm narrower than its cap is long
    assert 0.6 * m["hem"] < m["chest girth"] <= 1.05 * m["hem"]
    assert 0.2 < m["sleeve girth"] < 0.6


def test_graded_and_final_said_to_coincide_and_the_phases_honest():
    from types import SimpleNamespace

    from unsew.fit.report import (
        choices_made,
        loss_phases,
        material_for_reading,
        patterns_coincide,
    )
    from unsew.pattern.base import make_base_pattern

    a = make_base_pattern("skirt")
    b = a.copy()
    assert patterns_coincide(a, b)
    b.panels["front"].vertices = b.panels["front"].vertices + 1e-4
    assert not patterns_coincide(a, b)
    r = SimpleNamespace(
        material_start_iteration=20,
        iterations=10,
        gamma_last=None,
        start_material=None,
        material_fitted=False,
        base_name="skirt",
    )
    assert loss_phases(r, {}) == [(0, "pattern")]  # the material would have joined after the last iteration
    r.material_start_iteration = 4
    rd = {"phase_two_kept": False, "fit_redressed_mm": 6.1, "graded_mm": 5.9}
    assert loss_phases(r, {"redress": rd}) == [
        (0, "pattern (not kept)"),
        (4, "pattern + material (not kept)"),
    ]
    words = material_for_reading({"H00_N_per_m": 3000.0, "H22_N_per_m": 140.0, "friction": 0.35})
    assert all("N_per_m" not in k for k in words) and any("shear" in k and "(H22)" in k for k in words)
    said = choices_made(
        r,
        {
            "redress": rd,
            "material_choice": [
                {"material": "denim", "chamfer_mm": 4.2},
                {"material": "cotton", "chamfer_mm": 5.0},
            ],
        },
    )
    assert any("denim" in c and "4.20 mm" in c and "cotton 5.00 mm" in c for c in said)
    assert any(c.startswith("Phase two:") and "6.10" in c and "graded pattern" in c for c in said)


def test_grading_edits_read_as_words_not_python_lists():
    from unsew.fit.report import _flat

    row = _flat(
        {
            "edits": ["front:hem move +6.4 cm", "back:hem move +6.4 cm"],
            "lengths_m": [0.98, 1.04],
            "bone": "spine",
            "nested": {"a_m": 0.1},
        }
    )
    assert row["edits"] == "front:hem move +6.4 cm; back:hem move +6.4 cm" and "[" not in row["edits"]
    assert row["lengths_m"] == [0.98, 1.04] and row["nested.a_m"] == 0.1
