"""Gradient of a loss after a 20-step drape of two panels sewn along an edge, over a rail (capsule SDF),
w.r.t. the rest shape uv, Gamma and the initial state, against central finite differences
(relative 1e-5), and the adjoint drape against backprop through a dense (plain autograd) solve."""

import numpy as np
import pytest
import torch
from helpers import assert_close, contact_points

from unsew.sim import CapsuleSDF, Cloth, DrapeSettings, SimModel, SimState, drape
from unsew.sim.meshes import two_panels

GAMMA = torch.tensor([800.0, 80.0, 600.0, 60.0, 6e-5], dtype=torch.float64)
DENSITY = 0.15
WARM = 12  # steps of warm start: the cloth hangs over the rail and still moves
# a horizontal rail (capsule along z): the panels hang over it in tension, no buckling,
# so the drape is a smooth function of its inputs (a sheet over a sphere wrinkles: bifurcations)
SDF = CapsuleSDF((0.0, -0.05, -0.3), (0.0, -0.05, 0.3), 0.05)


def _case(edge_contact: bool, n=4, size=0.1):
    p = two_panels(n, size)
    m = SimModel.build(p["faces"], p["faces_uv"], n=p["n_x"])
    uv = torch.as_tensor(p["uv"])
    # sewn flat start: panel B moved back next to A, centred over the sphere, 5 mm above it
    xy = np.zeros((p["n_x"], 2))
    shift = np.where(np.arange(uv.shape[0]) >= uv.shape[0] // 2, size * 0.25, 0.0)
    xy[p["x_of_u"]] = p["uv"] - np.c_[shift, np.zeros_like(shift)]
    x0 = np.c_[xy[:, 0] - size, np.full(p["n_x"], 0.003), xy[:, 1] - size / 2]
    # warm start, as the fitting loop does (paper 3.4.1): a slack flat sheet is ill-conditioned
    # (its out-of-plane stiffness is its tension, zero at rest), a hanging one is not
    with torch.no_grad():
        warm = drape(
            m,
            SimState.at_rest(x0),
            SDF,
            Cloth(uv, GAMMA, DENSITY),
            steps=WARM,
            settings=DrapeSettings(edge_contact=edge_contact),
        )
    return m, uv, warm, edge_contact


def _loss(state):
    g = torch.Generator().manual_seed(7)
    w = torch.randn(state.x.shape, generator=g, dtype=torch.float64)
    return (w * state.x).sum() + 10.0 * (state.x**2).sum() + 0.1 * (w * state.v).sum()


def _run(ec, m, uv, gamma, st, checkpoint=False, fused=True, anchors=None):
    return _loss(
        drape(
            m,
            st,
            SDF,
            Cloth(uv, gamma, DENSITY, anchors=anchors),
            steps=20,
            checkpoint=checkpoint,
            settings=DrapeSettings(dt=0.05, fused=fused, edge_contact=ec),
        )
    )


@pytest.fixture(scope="module", params=[True, False], ids=["edge contact", "vertex contact"])
def case(request):
    """The warm case with the body repelling edges' midpoints too (dress()'s last fallback) or
    vertices only (the default; they then rest in the contact band, so friction acts)."""
    return _case(request.param)


def test_drape_touches_the_sphere(case):
    m, uv, st, ec = case
    out = drape(m, st, SDF, Cloth(uv, GAMMA, DENSITY), steps=20, settings=DrapeSettings(edge_contact=ec))
    d, _ = SDF.query(contact_points(m, out.x) if ec else out.x)
    assert float(d.min()) < 5e-3  # in the contact band: the test exercises contact (vertices': friction)
    assert float(d.min()) > 0.0


def test_gradient_vs_central_differences(case):
    m, uv, st, ec = case
    uvp = uv.clone().requires_grad_()
    gp = GAMMA.clone().requires_grad_()
    x0 = st.x.clone().requires_grad_()
    L = _run(ec, m, uvp, gp, SimState(x0, st.v))
    g_uv, g_gamma, g_x0 = torch.autograd.grad(L, (uvp, gp, x0))
    gen = torch.Generator().manual_seed(3)
    with torch.no_grad():
        for k in range(2):  # directional derivatives along random rest-shape perturbations
            dirn = torch.randn(uv.shape, generator=gen, dtype=torch.float64)
            # [m]; the edges' midpoints rest in the stiff contact band: the FD error of direction 1
            # falls 2.5e-4, 2.0e-4, 2e-7 relative at h = 1e-7, 1e-8, 1e-9 (truncation, not round-off)
            h = 1e-9
            fd = (_run(ec, m, uv + h * dirn, GAMMA, st) - _run(ec, m, uv - h * dirn, GAMMA, st)) / (2 * h)
            assert_close((g_uv * dirn).sum(), fd, rtol=1e-5, what=f"uv direction {k} ")
        for i in range(5):  # each material parameter, relative step
            h = 1e-4 * float(GAMMA[i])  # smooth in Gamma: truncation ~1e-8 relative, round-off small
            e = torch.zeros(5, dtype=torch.float64)
            e[i] = h
            fd = (_run(ec, m, uv, GAMMA + e, st) - _run(ec, m, uv, GAMMA - e, st)) / (2 * h)
            assert_close(g_gamma[i], fd, rtol=1e-5, what=f"gamma[{i}] ")
        dirn = torch.randn(st.x.shape, generator=gen, dtype=torch.float64)
        # [m]; as for uv, truncation in the contact band: 1e-9 tests the gradient, not the FD
        h = 1e-9
        fd = (
            _run(ec, m, uv, GAMMA, SimState(st.x + h * dirn, st.v))
            - _run(ec, m, uv, GAMMA, SimState(st.x - h * dirn, st.v))
        ) / (2 * h)
        assert_close((g_x0 * dirn).sum(), fd, rtol=1e-5, what="initial state ")


def test_adjoint_matches_dense_unrolled_and_checkpoint(case, monkeypatch):
    m, uv, st, ec = case
    uvp = uv.clone().requires_grad_()
    gp = GAMMA.clone().requires_grad_()
    L = _run(ec, m, uvp, gp, st)
    ref_grads = torch.autograd.grad(L, (uvp, gp))
    L2 = _run(ec, m, uvp, gp, st, checkpoint=True)
    ck = torch.autograd.grad(L2, (uvp, gp))
    for a, b in zip(ck, ref_grads):
        assert_close(a, b, rtol=1e-10, atol=1e-12, what="checkpointed ")
    # the unfused path (assembly Functions + sparse_solve), then the same with a dense solve
    L4 = _run(ec, m, uvp, gp, st, fused=False)
    unfused = torch.autograd.grad(L4, (uvp, gp))
    assert_close(L4, L, rtol=1e-12)
    for a, b in zip(unfused, ref_grads):
        assert_close(b, a, rtol=1e-9, atol=1e-12, what="fused vs unfused adjoint ")
    import unsew.sim.integrator as integ

    monkeypatch.setattr(integ, "sparse_solve", lambda A, b, pat, backend: torch.linalg.solve(pat.dense(A), b))
    L3 = _run(ec, m, uvp, gp, st, fused=False)
    dense = torch.autograd.grad(L3, (uvp, gp))
    assert_close(L3, L, rtol=1e-12)
    for a, b in zip(dense, ref_grads):
        assert_close(b, a, rtol=1e-8, atol=1e-10, what="adjoint vs dense autograd ")


def test_gradient_with_held_vertices_vs_central_differences(case):
    """The same check with two rest vertices held 1 cm below where they hang (unsew.sim.energies.anchor)."""
    m, uv, st, ec = case
    idx = torch.tensor([0, 1])
    x_of_u = torch.full((m.n_rest,), -1, dtype=torch.int64)
    x_of_u[m.faces_uv.reshape(-1)] = m.faces.reshape(-1)
    anchors = (idx, st.x[x_of_u[idx], 1] - 0.01)
    uvp = uv.clone().requires_grad_()
    x0 = st.x.clone().requires_grad_()
    L = _run(ec, m, uvp, GAMMA, SimState(x0, st.v), anchors=anchors)
    g_uv, g_x0 = torch.autograd.grad(L, (uvp, x0))
    gen = torch.Generator().manual_seed(5)
    with torch.no_grad():
        assert abs(float(L - _run(ec, m, uv, GAMMA, st))) > 1e-3  # the hold changes the drape
        dirn = torch.randn(uv.shape, generator=gen, dtype=torch.float64)
        h = 1e-8
        fd = (
            _run(ec, m, uv + h * dirn, GAMMA, st, anchors=anchors)
            - _run(ec, m, uv - h * dirn, GAMMA, st, anchors=anchors)
        ) / (2 * h)
        assert_close((g_uv * dirn).sum(), fd, rtol=1e-5, what="uv, held ")
        dirn = torch.randn(st.x.shape, generator=gen, dtype=torch.float64)
        fd = (
            _run(ec, m, uv, GAMMA, SimState(st.x + h * dirn, st.v), anchors=anchors)
            - _run(ec, m, uv, GAMMA, SimState(st.x - h * dirn, st.v), anchors=anchors)
        ) / (2 * h)
        assert_close((g_x0 * dirn).sum(), fd, rtol=1e-5, what="initial state, held ")
