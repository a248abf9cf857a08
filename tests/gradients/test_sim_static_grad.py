"""Quasi-static drape (sim/static.py): the equilibrium agrees with a long friction-free dynamic
drape, and its implicit-function-theorem gradients (exact adjoint) match central differences;
gradcheck of the Function on a tiny case."""

import numpy as np
import pytest
import torch
from helpers import assert_close

from unsew.errors import InputError
from unsew.sim import CapsuleSDF, Cloth, SimModel, SimState, drape
from unsew.sim.meshes import two_panels
from unsew.sim.static import StaticInfo, StaticSettings, drape_static

GAMMA = torch.tensor([800.0, 80.0, 600.0, 60.0, 6e-5], dtype=torch.float64)
DENSITY = 0.15
# a rail just behind a hanging curtain (two panels sewn along a vertical seam, top row pinned):
# it pushes the cloth forward, so contact is active at the solution (min distance ~4.6 mm < 5 mm)
SDF = CapsuleSDF((-0.3, -0.06, -0.045), (0.3, -0.06, -0.045), 0.05)


def curtain(n=3, size=0.1):
    """Model (top row pinned), uv (Nu, 2) [m], x0 (N, 3) [m]: a flat vertical curtain at z = 0."""
    p = two_panels(n, size)
    uv = torch.as_tensor(p["uv"])
    xy = np.zeros((p["n_x"], 2))
    shift = np.where(np.arange(uv.shape[0]) >= uv.shape[0] // 2, size * 0.25, 0.0)
    xy[p["x_of_u"]] = p["uv"] - np.c_[shift, np.zeros_like(shift)]
    x0 = torch.as_tensor(np.c_[xy[:, 0] - size, -xy[:, 1], np.zeros(p["n_x"])])
    top = np.nonzero(xy[:, 1] < 1e-9)[0]
    m = SimModel.build(p["faces"], p["faces_uv"], n=p["n_x"], pinned=top)
    return m, uv, x0


@pytest.fixture(scope="module")
def case():
    return curtain()


def _loss(x):
    w = torch.randn(x.shape, generator=torch.Generator().manual_seed(7), dtype=torch.float64)
    return (w * x).sum() + 10.0 * (x**2).sum()


def test_equilibrium_matches_long_dynamic_drape(case):
    m, uv, x0 = case
    info = StaticInfo()
    xs = drape_static(m, x0, SDF, Cloth(uv, GAMMA, DENSITY), info=info)
    assert info.residual <= 1e-8 and info.iterations < 40
    assert all(b <= a + 1e-15 for a, b in zip(info.energies, info.energies[1:]))  # monotone descent
    d, _ = SDF.query(xs)
    assert 0.0 < float(d.min()) < 5e-3  # in the contact band
    assert_close(xs[m.pinned], x0[m.pinned], atol=0.0, what="pinned ")
    with torch.no_grad():
        dyn = drape(m, SimState.at_rest(x0), SDF, Cloth(uv, GAMMA, DENSITY, friction=0.0), steps=200)
    assert_close(dyn.x, xs, atol=1e-7, what="dynamic (200 steps) vs static [m] ")


def test_ift_gradient_vs_central_differences(case):
    m, uv, x0 = case
    uvp = uv.clone().requires_grad_()
    gp = GAMMA.clone().requires_grad_()
    dp = torch.tensor(DENSITY, dtype=torch.float64, requires_grad=True)
    x0p = x0.clone().requires_grad_()
    info = StaticInfo()
    xs = drape_static(m, x0p, SDF, Cloth(uvp, gp, dp), info=info, settings=StaticSettings(tol=1e-11))
    g_uv, g_gamma, g_density, g_x0 = torch.autograd.grad(_loss(xs), (uvp, gp, dp, x0p))
    assert info.adjoint_residual <= 1e-10

    def L(**kw):
        args = dict(uv=uv, gamma=GAMMA, density=DENSITY, x0=x0)
        args.update(kw)
        cloth = Cloth(args["uv"], args["gamma"], args["density"])
        return float(_loss(drape_static(m, args["x0"], SDF, cloth, settings=StaticSettings(tol=1e-11))))

    gen = torch.Generator().manual_seed(3)
    dirn = torch.randn(uv.shape, generator=gen, dtype=torch.float64)
    h = 1e-7  # [m]: FD error 1.3e-4 at 1e-6, 1.3e-6 at 1e-7 (truncation)
    fd = (L(uv=uv + h * dirn) - L(uv=uv - h * dirn)) / (2 * h)
    assert_close((g_uv * dirn).sum(), fd, rtol=1e-5, what="uv direction ")
    for i in range(5):
        e = torch.zeros(5, dtype=torch.float64)
        e[i] = 1e-4 * float(GAMMA[i])
        fd = (L(gamma=GAMMA + e) - L(gamma=GAMMA - e)) / (2 * float(e[i]))
        assert_close(g_gamma[i], fd, rtol=1e-5, what=f"gamma[{i}] ")
    fd = (L(density=DENSITY + 1e-6) - L(density=DENSITY - 1e-6)) / 2e-6
    assert_close(g_density, fd, rtol=1e-5, what="density ")
    # x0: no gradient on free vertices; pinned ones move the solution
    assert float(g_x0[~m.pinned].abs().max()) == 0.0
    dirn = torch.zeros_like(x0)
    dirn[m.pinned] = torch.randn(int(m.pinned.sum()), 3, generator=gen, dtype=torch.float64)
    h = 1e-7
    fd = (L(x0=x0 + h * dirn) - L(x0=x0 - h * dirn)) / (2 * h)
    assert_close((g_x0 * dirn).sum(), fd, rtol=1e-5, what="pinned x0 ")


def test_gradcheck_static_drape_tiny():
    m, uv, x0 = curtain(n=2, size=0.08)

    def f(uv_, s_, rho_):  # Gamma through a relative scale so one eps suits all its entries
        return drape_static(
            m, x0, SDF, Cloth(uv_, GAMMA * (1.0 + s_), rho_), settings=StaticSettings(tol=1e-11)
        )

    uvp = uv.clone().requires_grad_()
    s = torch.zeros(5, dtype=torch.float64, requires_grad=True)
    rho = torch.tensor(DENSITY, dtype=torch.float64, requires_grad=True)
    assert torch.autograd.gradcheck(f, (uvp, s, rho), eps=1e-7, atol=1e-6, rtol=1e-4, fast_mode=True)


def test_bad_adjoint_is_refused(case):
    m, uv, x0 = case
    with pytest.raises(InputError, match="adjoint"):
        drape_static(m, x0, SDF, Cloth(uv, GAMMA, DENSITY), settings=StaticSettings(adjoint="approx"))
