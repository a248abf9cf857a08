"""drape/sew: boundary checks, divergence message, sewing closes seams, merge."""

import numpy as np
import pytest
import torch
from helpers import assert_close

from unsew.errors import InputError, PatternError, SimulationError
from unsew.sim import (
    MATERIALS,
    Cloth,
    DrapeSettings,
    PlaneSDF,
    SimModel,
    SimState,
    SphereSDF,
    drape,
    merge_sewn,
    sew,
)
from unsew.sim.meshes import grid_sheet, two_panels

GAMMA = MATERIALS["cotton"].gamma()


def _sheet(n=4, size=0.2, y=0.12):
    uv, f = grid_sheet(n, n, size, size)
    m = SimModel.build(f, f)
    x = np.c_[uv[:, 0] - size / 2, np.full(len(uv), y), uv[:, 1] - size / 2]
    return m, torch.as_tensor(uv), SimState.at_rest(x)


def test_drape_over_sphere_stays_outside():
    m, uv, st = _sheet(8, 0.3)
    sdf = SphereSDF((0, 0, 0), 0.1)
    out = drape(m, st, sdf, Cloth(uv, GAMMA, 0.12), steps=20)
    d, _ = sdf.query(out.x)
    assert float(d.min()) >= 1e-3 - 1e-12  # projected at least to the collision thickness
    assert float(out.x[:, 1].min()) < 0.05  # the corners fell around the sphere


def test_missing_sdf_bad_material_bad_shapes():
    m, uv, st = _sheet()
    with pytest.raises(InputError, match="SDF"):
        drape(m, st, None, Cloth(uv, GAMMA, 0.1))
    bad = GAMMA.clone()
    bad[0] = -5.0
    with pytest.raises(InputError, match="stiffness"):
        drape(m, st, PlaneSDF(), Cloth(uv, bad, 0.1))
    with pytest.raises(InputError, match="uv"):
        drape(m, st, PlaneSDF(), Cloth(uv[:-1], GAMMA, 0.1))
    with pytest.raises(InputError, match="float64"):
        drape(m, SimState(st.x.float(), st.v.float()), PlaneSDF(), Cloth(uv, GAMMA, 0.1))


def test_degenerate_rest_triangle_is_a_pattern_error():
    m, uv, st = _sheet()
    uv2 = uv.clone()
    uv2[6] = uv2[0]  # collapse a vertex onto another: zero-area triangles
    with pytest.raises(PatternError, match="triangle"):
        drape(m, st, PlaneSDF((0, -1, 0)), Cloth(uv2, GAMMA, 0.1))


def test_divergence_names_step_and_vertex():
    m, uv, st = _sheet()
    v = st.v.clone()
    v[7, 1] = -30.0  # one vertex thrown fast
    with pytest.raises(SimulationError, match=r"step 0: vertex \d+"):  # the full linearized step
        drape(
            m,
            SimState(st.x, v),
            PlaneSDF((0, -1, 0)),
            Cloth(uv, GAMMA, 0.1),
            steps=20,
            settings=DrapeSettings(max_speed=5.0, line_search=False),
        )
    # backtracked on the step's incremental potential (the default), the same throw is damped
    out = drape(
        m,
        SimState(st.x, v),
        PlaneSDF((0, -1, 0)),
        Cloth(uv, GAMMA, 0.1),
        steps=3,
        settings=DrapeSettings(max_speed=5.0),
    )
    assert float(out.v.norm(dim=1).max()) < 5.0
    x = st.x.clone()
    x[3, 0] = float("nan")
    with pytest.raises(InputError, match="NaN"):
        drape(m, SimState(x, st.v), PlaneSDF((0, -1, 0)), Cloth(uv, GAMMA, 0.1))


def test_sew_closes_seam_and_merge():
    p = two_panels(4, 0.1)
    mu = SimModel.build(p["faces_uv"], p["faces_uv"], springs=p["seam_pairs"])
    uv = torch.as_tensor(p["uv"])
    # panels placed as a tent over a sphere, 2 cm gap at the seam
    x = np.c_[p["uv"][:, 0] - 0.1125, 0.11 + 0.0 * p["uv"][:, 0], p["uv"][:, 1] - 0.05]
    xs = sew(
        mu,
        x,
        SphereSDF((0, 0, 0), 0.1),
        Cloth(uv, GAMMA, 0.12),
        settings=DrapeSettings(sew_steps=60, sew_dt=0.02, spring_stiffness=100.0),
    )
    gap = (xs[p["seam_pairs"][:, 0]] - xs[p["seam_pairs"][:, 1]]).norm(dim=1)
    assert float(gap.max()) < 2e-3  # from 25 mm apart to closed within 2 mm
    xm = merge_sewn(xs, p["x_of_u"], p["n_x"])
    assert xm.shape == (p["n_x"], 3)
    a, b = p["seam_pairs"][0]
    assert_close(xm[p["x_of_u"][a]], 0.5 * (xs[a] + xs[b]), rtol=1e-12)
    with pytest.raises(InputError):
        merge_sewn(xs, p["x_of_u"], p["n_x"] + 1)


def test_pinned_vertices_hold_and_sewing_hold():
    uv, f = grid_sheet(3, 3, 0.1, 0.1)
    m = SimModel.build(f, f, pinned=[0, 3])
    x = np.c_[uv[:, 0], np.zeros(len(uv)), uv[:, 1]]
    out = drape(m, SimState.at_rest(x), PlaneSDF((0, -1, 0)), Cloth(torch.as_tensor(uv), GAMMA, 0.1), steps=5)
    assert_close(out.x[[0, 3]], torch.as_tensor(x[[0, 3]]), atol=0.0)
    assert float(out.x[15, 1]) < -0.01


def test_friction_eps_bounds_the_creep_on_a_slope():
    """A sheet on a 10-degree slope (tan 10 deg = 0.18 < mu 0.3: friction should hold it) creeps
    downhill at up to the viscous slip speed friction_eps; a 100x smaller eps creeps far less."""
    th = np.radians(10.0)
    normal = np.array([np.sin(th), np.cos(th), 0.0])  # the slope falls towards +x
    m, uv, st = _sheet(6, 0.2, y=0.0)
    x = st.x.numpy()
    # lay the sheet on the slope, 2 mm above it (inside the contact layer)
    e1 = np.array([np.cos(th), -np.sin(th), 0.0])
    x = x[:, :1] * e1 + x[:, 2:3] * np.array([0.0, 0.0, 1.0]) + 0.002 * normal
    st = SimState.at_rest(x)
    plane = PlaneSDF((0.0, 0.0, 0.0), tuple(normal))

    def creep(eps):
        out = drape(
            m,
            st,
            plane,
            Cloth(uv, GAMMA, 0.12, friction=0.3),
            steps=40,
            settings=DrapeSettings(friction_eps=eps),
        )
        return float(((out.x - st.x).numpy() @ e1).mean())  # mean downhill travel [m] (e1 points downhill)

    fast, slow = creep(1e-2), creep(1e-4)
    assert fast > 1e-3  # the shipped eps lets it slide millimetres in 2 s
    assert slow < 0.1 * fast
