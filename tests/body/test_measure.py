"""Body measurements: cross-section geometry on shapes with known answers, and the default
body's values (printed with -s) compared with published averages."""

import numpy as np
from helpers import assert_close

from unsew.body.body import default_body
from unsew.body.measure import hull_perimeter, measure_body, section_points
from unsew.pattern.measurements import Measurements


def test_section_of_cylinder_has_its_circumference():
    import trimesh

    m = trimesh.creation.cylinder(radius=0.15, height=1.0, sections=256)
    p = section_points(np.asarray(m.vertices), np.asarray(m.faces), np.zeros(3), np.array([0.0, 0.0, 1.0]))
    assert_close(hull_perimeter(p[:, :2]), 2 * np.pi * 0.15, rtol=1e-3, what="cylinder girth: ")


def test_hull_perimeter_of_square_and_degenerate():
    sq = np.array([[0, 0], [1, 0], [1, 1], [0, 1], [0.5, 0.5]], float)
    assert_close(hull_perimeter(sq), 4.0, rtol=1e-12)
    assert hull_perimeter(sq[:2]) == 0.0


def test_default_body_measurements_plausible_and_are_the_defaults(capsys):
    m = measure_body(default_body())
    with capsys.disabled():
        print("\ndefault body measurements [m]: " + ", ".join(f"{k}={v:.3f}" for k, v in m.as_dict().items()))
    # Plausibility for a 1.62 m adult (anny phenotypes 0.5 is a slim, androgynous adult):
    # ISO 8559 / EN 13402-3 women's size 36 (German DOB): bust 84, waist 68, hip 94 cm; SizeUK
    # (2004) average woman 1.62 m: bust 97, waist 82, hip 104 cm. The default body sits at a slim
    # size 36 (bust/waist within 2 cm, hip within 4 cm), about 10 cm under the SizeUK averages.
    assert 1.55 < m.height < 1.70
    assert 0.80 < m.bust < 1.00 and 0.62 < m.waist < 0.85 and 0.86 < m.hip < 1.05
    assert m.waist < m.bust and m.waist < m.hip
    assert 0.30 < m.neck < 0.42 and 0.22 < m.upper_arm < 0.34 and 0.42 < m.thigh < 0.62
    assert 0.33 < m.shoulder_width < 0.44  # biacromial breadth, adults 0.35-0.42
    assert 0.42 < m.arm_length < 0.62 and 0.70 < m.leg_length < 0.90
    assert m.crotch_height < m.waist_height < m.neck_height < m.height
    # Measurements' defaults describe the default body (the pattern engineer sizes from them)
    d = Measurements().as_dict()
    for k, v in m.as_dict().items():
        assert abs(d[k] - v) < 0.002, f"Measurements.{k} default {d[k]} but the default body measures {v:.3f}"


def test_measurements_scale_with_the_body():
    b = default_body()
    m1 = measure_body(b)
    m2 = measure_body(b.transformed(scale=1.1))
    for k in ("height", "bust", "waist", "hip", "arm_length", "leg_length"):
        assert_close(getattr(m2, k), 1.1 * getattr(m1, k), rtol=0.03, what=f"{k}: ")


def test_measure_body_without_weights_uses_nearest_bones():
    b = default_body()
    from unsew.body.body import Body

    nw = Body(b.verts, b.faces, b.skeleton, None)
    m, m0 = measure_body(nw), measure_body(b)
    for k in ("bust", "waist", "hip"):
        assert abs(getattr(m, k) - getattr(m0, k)) < 0.05, k
