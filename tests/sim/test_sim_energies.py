"""Each energy: zero/minimal at rest, rigid-motion invariant, gradient and Hessian against
autograd (torch.func as the oracle) and finite differences, Hessian symmetry, PSD projection."""

import pytest
import torch
from sim._simcases import flat_embed, perturbed, random_rotation
from helpers import assert_close

from unsew.sim.assembly import scatter_vertex
from unsew.sim.energies.bending import bending_rest, dihedral_angle, energy_bending
from unsew.sim.energies.contact import energy_contact, friction_damping, project_out
from unsew.sim.energies.gravity import energy_gravity, mass_lumped
from unsew.sim.energies.membrane import energy_membrane, membrane_rest
from unsew.sim.energies.spring import energy_spring
from unsew.sim.meshes import grid_sheet
from unsew.sim.model import SimModel
from unsew.sim.sdf_analytic import CapsuleSDF, PlaneSDF, SphereSDF

GAMMA = torch.tensor([3000.0, 600.0, 2000.0, 150.0, 6e-6], dtype=torch.float64)


@pytest.fixture(scope="module")
def sheet():
    uv, f = grid_sheet(3, 3, 0.3, 0.3)
    m = SimModel.build(f, f)
    uv = torch.as_tensor(uv)
    area, B, _ = membrane_rest(uv, m.faces_uv)
    coef = bending_rest(uv, m.faces_uv, m.hinge_faces, m.hinge_uv_edges, area)
    return m, uv, area, B, coef


def _mem_E(m, area, B):
    return lambda x: energy_membrane(x, m.faces, area, B, GAMMA, hessian=False)[0]


def _bend_E(m, coef):
    return lambda x: energy_bending(x, m.hinges, coef, GAMMA, hessian=False)[0]


def _fd_grad(E, x, h=1e-6):
    g = torch.zeros_like(x)
    for i in range(x.shape[0]):
        for c in range(3):
            xp, xm = x.clone(), x.clone()
            xp[i, c] += h
            xm[i, c] -= h
            g[i, c] = (E(xp) - E(xm)) / (2 * h)
    return g


def _dense_hess(m_elems, n, H):
    k = m_elems.shape[1]
    out = torch.zeros(3 * n, 3 * n, dtype=torch.float64)
    dof = (3 * m_elems[:, :, None] + torch.arange(3)).reshape(-1, 3 * k)
    out.index_put_(
        (dof[:, :, None].expand(-1, -1, 3 * k), dof[:, None, :].expand(-1, 3 * k, -1)), H, accumulate=True
    )
    return out


# ---------------------------------------------------------------- membrane


def test_membrane_zero_at_rest_and_rigid_invariant(sheet):
    m, uv, area, B, _ = sheet
    x = flat_embed(uv)
    R, t = random_rotation(3), torch.tensor([0.1, -0.4, 2.0], dtype=torch.float64)
    for xr in (x, x @ R.T + t):
        e, g, h = energy_membrane(xr, m.faces, area, B, GAMMA)
        assert abs(float(e)) < 1e-20
        assert_close(g, 0.0, atol=1e-10, what="rest force ")
    xd = perturbed(x, 0.01)
    e1, g1, _ = energy_membrane(xd, m.faces, area, B, GAMMA)
    e2, g2, _ = energy_membrane(xd @ R.T + t, m.faces, area, B, GAMMA)
    assert_close(e2, e1, rtol=1e-12)
    assert_close(g2, g1 @ R.T, atol=1e-9, rtol=1e-9)


def test_membrane_gradient_vs_autograd_and_fd(sheet):
    m, uv, area, B, _ = sheet
    x = perturbed(flat_embed(uv), 0.01).requires_grad_()
    E = _mem_E(m, area, B)
    ga = torch.autograd.grad(E(x), x)[0]
    _, g, _ = energy_membrane(x, m.faces, area, B, GAMMA, hessian=False)
    gs = scatter_vertex(m.n, m.faces, g)
    assert_close(gs, ga, atol=1e-10, rtol=1e-10, what="membrane gradient vs autograd ")
    assert_close(gs, _fd_grad(E, x.detach()), atol=1e-5, rtol=1e-5, what="membrane gradient vs FD ")


def test_membrane_hessian_vs_torch_func_and_jacobian_fd(sheet):
    m, uv, area, B, _ = sheet
    x = perturbed(flat_embed(uv), 0.01)
    X = x[m.faces]  # per-element oracle: vmap(hessian) of the element energy

    def elem_E(Xe, Be, ae):
        Fd = Xe.T @ Be
        C = Fd.T @ Fd
        eps = torch.stack([0.5 * (C[0, 0] - 1), 0.5 * (C[1, 1] - 1), C[0, 1]])
        Hm = torch.tensor(
            [[GAMMA[0], GAMMA[1], 0], [GAMMA[1], GAMMA[2], 0], [0, 0, GAMMA[3]]], dtype=torch.float64
        )
        return 0.5 * ae * eps @ Hm @ eps

    Href = torch.func.vmap(torch.func.hessian(elem_E))(X, B, area).reshape(-1, 9, 9)
    _, _, H = energy_membrane(x, m.faces, area, B, GAMMA, project=False)
    assert_close(H, Href, atol=1e-9, rtol=1e-10, what="membrane Hessian vs torch.func ")
    assert_close(H, H.transpose(1, 2), atol=1e-12, what="symmetry ")
    # Jacobian of the assembled force against finite differences of the force
    Kd = _dense_hess(m.faces, m.n, H)

    def f(xx):
        grad = energy_membrane(xx, m.faces, area, B, GAMMA, hessian=False)[1]
        return -scatter_vertex(m.n, m.faces, grad).reshape(-1)

    h = 1e-7
    cols = [0, 5, 13, 20, 31, 44]
    for c in cols:
        xp, xm = x.reshape(-1).clone(), x.reshape(-1).clone()
        xp[c] += h
        xm[c] -= h
        Jc = (f(xp.reshape(-1, 3)) - f(xm.reshape(-1, 3))) / (2 * h)
        assert_close(-Kd[:, c], Jc, atol=1e-4, rtol=1e-6, what=f"force Jacobian column {c} ")


def test_membrane_projection_psd_under_compression(sheet):
    m, uv, area, B, _ = sheet
    x = flat_embed(uv)
    xc = x * torch.tensor([0.8, 1.0, 0.9], dtype=torch.float64)  # compress the sheet
    xc = perturbed(xc, 0.005)
    _, _, Hraw = energy_membrane(xc, m.faces, area, B, GAMMA, project=False)
    _, _, Hp = energy_membrane(xc, m.faces, area, B, GAMMA, project=True)
    assert float(torch.linalg.eigvalsh(Hraw).min()) < -1.0  # indefinite without projection
    ev = torch.linalg.eigvalsh(Hp)
    assert float(ev.min()) > -1e-8 * float(ev.abs().max())
    assert_close(Hp, Hp.transpose(1, 2), atol=1e-12)
    # under pure stretch (S positive definite) the projection changes nothing
    xs = x * torch.tensor([1.1, 1.0, 1.05], dtype=torch.float64)
    _, _, H1 = energy_membrane(xs, m.faces, area, B, GAMMA, project=False)
    _, _, H2 = energy_membrane(xs, m.faces, area, B, GAMMA, project=True)
    assert_close(H2, H1, atol=1e-12, rtol=1e-12)


def test_membrane_projected_hessian_gradient_vs_fd_while_active(sheet):
    """The drape's gradient goes through the PSD projection: on a compressed sheet, where the
    projection changes most elements' Hessians, the gradient of a weighted sum of the projected
    Hessians w.r.t. x and Gamma matches central finite differences (two step sizes agree, so no
    step crosses a branch of the projection); at rest the gradient is finite."""
    m, uv, area, B, _ = sheet
    x0 = perturbed(flat_embed(uv) * torch.tensor([0.8, 1.0, 0.9], dtype=torch.float64), 0.005)
    _, _, Hraw = energy_membrane(x0, m.faces, area, B, GAMMA, project=False)
    _, _, Hp = energy_membrane(x0, m.faces, area, B, GAMMA, project=True)
    active = (Hp - Hraw).abs().amax(dim=(1, 2)) > 1e-6 * float(Hraw.abs().max())
    assert int(active.sum()) >= len(active) // 2  # the projection is at work on most elements
    W = torch.randn(Hp.shape, generator=torch.Generator().manual_seed(0), dtype=torch.float64)

    def L(x, g):
        return (energy_membrane(x, m.faces, area, B, g)[2] * W).sum()

    x, g = x0.clone().requires_grad_(), GAMMA.clone().requires_grad_()
    gx, gg = torch.autograd.grad(L(x, g), (x, g))

    def fd(f, v, i, h):
        vp, vm = v.reshape(-1).clone(), v.reshape(-1).clone()
        vp[i] += h
        vm[i] -= h
        return (f(vp.reshape(v.shape)) - f(vm.reshape(v.shape))) / (2 * h)

    for i in (0, 4, 11, 19, 26, 33, 40, 47):
        d1, d2 = fd(lambda xx: L(xx, GAMMA), x0, i, 1e-6), fd(lambda xx: L(xx, GAMMA), x0, i, 5e-7)
        assert_close(d1, d2, rtol=1e-4, atol=1e-3, what=f"FD steps, x[{i}] ")
        assert_close(gx.reshape(-1)[i], d1, rtol=1e-4, atol=1e-3, what=f"dL/dx[{i}] vs FD ")
    for i in range(4):  # H00, H01, H11, H22 (k does not enter the membrane)
        h = 1e-6 * float(GAMMA[i])
        assert_close(
            gg[i], fd(lambda gv: L(x0, gv), GAMMA, i, h), rtol=1e-5, atol=1e-9, what=f"dL/dGamma[{i}] vs FD "
        )
    xr = flat_embed(uv).clone().requires_grad_()
    gr = torch.autograd.grad(energy_membrane(xr, m.faces, area, B, GAMMA)[2].pow(2).sum(), xr)[0]
    assert torch.isfinite(gr).all()


# ---------------------------------------------------------------- bending


def test_bending_zero_flat_rigid_invariant(sheet):
    m, uv, _, _, coef = sheet
    x = flat_embed(uv)
    e, g, _ = energy_bending(x, m.hinges, coef, GAMMA)
    assert abs(float(e)) < 1e-25 and float(g.abs().max()) < 1e-15
    xd = perturbed(x, 0.01)
    R, t = random_rotation(5), torch.tensor([1.0, 2.0, -3.0], dtype=torch.float64)
    e1, g1, _ = energy_bending(xd, m.hinges, coef, GAMMA)
    e2, g2, _ = energy_bending(xd @ R.T + t, m.hinges, coef, GAMMA)
    assert float(e1) > 0
    assert_close(e2, e1, rtol=1e-10)
    assert_close(g2, g1 @ R.T, atol=1e-15, rtol=1e-8)


def test_bending_of_a_triangle_flat_on_a_line_is_finite(sheet):
    """A placement that folds part of a panel onto a line (zero-area triangles, even coincident
    vertices) bends nothing there instead of giving NaN forces at step 0."""
    m, uv, _, _, coef = sheet
    x = perturbed(flat_embed(uv), 0.01)
    h0 = m.hinges[0]
    x[h0[:3], 1:] = x[h0[0], 1:]  # triangle (x0, x1, x2) on a line along x, as a fold clamps it
    h1 = m.hinges[7]
    x[h1[1]] = x[h1[0]]  # a zero-length hinge edge
    e, g, H = energy_bending(x, m.hinges, coef, GAMMA)
    assert torch.isfinite(e) and torch.isfinite(g).all() and torch.isfinite(H).all()
    theta, dth = dihedral_angle(x, m.hinges)
    assert torch.isfinite(theta).all() and torch.isfinite(dth).all()
    assert float(dth[0, 2].abs().max()) == 0.0 and float(dth[7].abs().max()) == 0.0  # nothing bends them


def test_bending_gradient_vs_autograd_and_fd(sheet):
    m, uv, _, _, coef = sheet
    x = perturbed(flat_embed(uv), 0.01).requires_grad_()
    theta, dth = dihedral_angle(x, m.hinges)
    for i in range(0, theta.shape[0], 5):
        gi = torch.autograd.grad(theta[i], x, retain_graph=True)[0][m.hinges[i]]
        assert_close(dth[i], gi, atol=1e-12, rtol=1e-9, what=f"d theta/dx hinge {i} ")
    E = _bend_E(m, coef)
    _, g, _ = energy_bending(x, m.hinges, coef, GAMMA, hessian=False)
    gs = scatter_vertex(m.n, m.hinges, g)
    assert_close(gs, torch.autograd.grad(E(x), x)[0], atol=1e-15, rtol=1e-9)
    assert_close(gs, _fd_grad(E, x.detach()), atol=1e-10, rtol=1e-5, what="bending gradient vs FD ")


def test_bending_hessian_gauss_newton_exact_at_rest_angle(sheet):
    # at theta = theta0 the dropped term (theta - theta0) d2theta vanishes: GN == exact Hessian
    m, uv, _, _, coef = sheet
    x = perturbed(flat_embed(uv), 0.01)
    theta, _ = dihedral_angle(x, m.hinges)

    def Ef(xx):
        return energy_bending(xx, m.hinges, coef, GAMMA, theta0=theta, hessian=False)[0]

    Href = torch.autograd.functional.hessian(Ef, x).reshape(3 * m.n, 3 * m.n)
    _, _, H = energy_bending(x, m.hinges, coef, GAMMA, theta0=theta)
    assert_close(_dense_hess(m.hinges, m.n, H), Href, atol=1e-12, rtol=1e-8)
    ev = torch.linalg.eigvalsh(H)
    assert float(ev.min()) > -1e-12 * float(ev.max())  # rank one, PSD up to round-off
    assert_close(H, H.transpose(1, 2), atol=0.0)


# ---------------------------------------------------------------- gravity, contact, springs


def test_gravity_masses_and_force():
    uv, f = grid_sheet(4, 2, 0.4, 0.2)
    uv, f = torch.as_tensor(uv), torch.as_tensor(f)
    area, _, _ = membrane_rest(uv, f)
    mass = mass_lumped(uv.shape[0], f, area, 0.2)
    assert_close(mass.sum(), 0.2 * 0.4 * 0.2, rtol=1e-12)
    x = flat_embed(uv).requires_grad_()
    e, g = energy_gravity(x, mass, 9.81)
    assert_close(g, torch.autograd.grad(e, x)[0], atol=1e-15)
    e2, _ = energy_gravity(x.detach() + torch.tensor([0.3, 0.0, -1.0], dtype=torch.float64), mass, 9.81)
    assert_close(e2, e.detach(), atol=1e-15)  # horizontal motion: invariant


@pytest.mark.parametrize(
    "sdf",
    [
        SphereSDF((0, 0, 0), 0.1),
        PlaneSDF((0, 0.02, 0), (0.3, 1, 0)),
        CapsuleSDF((0, -0.1, 0), (0, 0.1, 0), 0.08),
    ],
)
def test_contact_energy_gradient_hessian(sdf):
    g = torch.Generator().manual_seed(2)
    x = (0.1 + 0.004 * torch.randn(40, 3, generator=g, dtype=torch.float64)) * torch.nn.functional.normalize(
        torch.randn(40, 3, generator=g, dtype=torch.float64), dim=1
    )
    x = x.requires_grad_()
    a = torch.full((40,), 1e-4, dtype=torch.float64)
    kw = dict(stiffness=1e8, threshold=5e-3)

    def E(xx):
        d, n = sdf.query(xx)
        return energy_contact(d, n, a, **kw, hessian=False)[0]

    d, n = sdf.query(x)
    e, grad, H, fn = energy_contact(d, n, a, **kw)
    assert (fn > 0).any() and (fn == 0).any()
    assert_close(grad, torch.autograd.grad(E(x), x)[0], atol=1e-12, rtol=1e-10)
    assert_close(H, H.transpose(1, 2), atol=0.0)
    assert float(torch.linalg.eigvalsh(H.detach()).min()) > -1e-12
    if isinstance(sdf, PlaneSDF):  # flat SDF: the PSD Hessian is the exact one
        Href = torch.autograd.functional.hessian(E, x.detach()).reshape(120, 120)
        blocks = torch.block_diag(*H.detach())
        assert_close(blocks, Href, atol=1e-8, rtol=1e-8)
    # far away: no energy; invariant when body and cloth move together is covered by the plane case
    d2, n2 = sdf.query(x.detach() + torch.tensor([0.0, 10.0, 0.0], dtype=torch.float64))
    assert float(energy_contact(d2, n2, a, **kw)[0]) == 0.0


def test_friction_damping_is_tangential_psd():
    n = torch.nn.functional.normalize(
        torch.randn(10, 3, dtype=torch.float64, generator=torch.Generator().manual_seed(0)), dim=1
    )
    v = torch.randn(10, 3, dtype=torch.float64, generator=torch.Generator().manual_seed(1))
    D = friction_damping(v, n, torch.full((10,), 2.0, dtype=torch.float64), 0.3)
    assert_close(torch.einsum("nij,nj->ni", D, n), 0.0, atol=1e-12)
    assert float(torch.linalg.eigvalsh(D).min()) > -1e-12
    # sliding fast: friction force magnitude -> mu |f_n|
    vt = v - (v * n).sum(1, keepdim=True) * n
    Df = friction_damping(vt * 1e4, n, torch.full((10,), 2.0, dtype=torch.float64), 0.3)
    fnorm = torch.einsum("nij,nj->ni", Df, vt * 1e4).norm(dim=1)
    assert_close(fnorm, 0.6, rtol=1e-5)


def test_projection_out_of_body():
    sdf = SphereSDF((0, 0, 0), 0.1)
    x = torch.tensor([[0.0, 0.05, 0.0], [0.0, 0.2, 0.0]], dtype=torch.float64)
    d, n = sdf.query(x)
    xp = project_out(x, d, n, thickness=1e-3)
    assert_close(xp, torch.tensor([[0.0, 0.101, 0.0], [0.0, 0.2, 0.0]], dtype=torch.float64), atol=1e-15)


def test_spring_energy():
    x = torch.randn(4, 3, dtype=torch.float64, generator=torch.Generator().manual_seed(0)).requires_grad_()
    s = torch.tensor([[0, 1], [2, 3]])
    e, g, H = energy_spring(x, s, 50.0)
    assert_close(scatter_vertex(4, s, g), torch.autograd.grad(e, x)[0], atol=1e-12)
    Href = torch.autograd.functional.hessian(
        lambda xx: energy_spring(xx, s, 50.0, hessian=False)[0], x.detach()
    )
    assert_close(_dense_hess(s, 4, H), Href.reshape(12, 12), atol=1e-12)


def test_anchor_energy():
    from unsew.sim.energies.anchor import energy_anchor

    x = torch.randn(5, 3, dtype=torch.float64, generator=torch.Generator().manual_seed(2)).requires_grad_()
    idx = torch.tensor([1, 3])
    h = torch.tensor([0.2, -0.1], dtype=torch.float64)
    e, g, H = energy_anchor(x, idx, h, 40.0)
    grad = torch.zeros(5, 3, dtype=torch.float64).index_add(0, idx, g)
    assert_close(grad, torch.autograd.grad(e, x)[0], atol=1e-12)
    Href = torch.autograd.functional.hessian(
        lambda xx: energy_anchor(xx, idx, h, 40.0, hessian=False)[0], x.detach()
    )
    dense = torch.zeros(5, 3, 5, 3, dtype=torch.float64)
    for k, i in enumerate(idx.tolist()):
        dense[i, :, i, :] = H[k]
    assert_close(dense, Href, atol=1e-12)
    # only the height is held: moving an anchored vertex sideways costs nothing
    x2 = x.detach().clone()
    x2[idx, 0] += 0.3
    x2[idx, 2] -= 0.2
    assert_close(energy_anchor(x2, idx, h, 40.0)[0], e.detach(), atol=1e-12)
