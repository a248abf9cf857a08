"""The simulation on another device: a SimModel moves with ``to``, a drape refuses a model on
another device than its state, nothing inside a drape or its backward is made on the default
device (checked on the CPU with :func:`helpers.no_default_device`), and on a GPU a drape and its
gradients match the CPU's (skipped without CUDA)."""

import numpy as np
import pytest
import torch
from helpers import assert_close, no_default_device

from unsew.errors import InputError
from unsew.sim import MATERIALS, Cloth, DrapeSettings, SimModel, SimState, SphereSDF, drape, merge_sewn, sew
from unsew.sim.meshes import grid_sheet, two_panels

GAMMA = MATERIALS["cotton"].gamma()
CUDA = pytest.mark.skipif(not torch.cuda.is_available(), reason="no CUDA device")


def _sheet(n=5, size=0.3, y=0.12, stretch=1.03):
    """A sheet above the sphere, stretched by ``stretch`` and jittered 4 mm in height. Stretched, so
    its gradients are well defined: at zero stress the PSD projection of the membrane's geometric
    stiffness (energies/membrane.py) sits on its kink, and round-off alone (another device, a
    1e-13 m move of uv) changes d/duv by half."""
    uv, f = grid_sheet(n, n, size, size)
    jitter = 0.004 * np.random.default_rng(0).standard_normal(len(uv))
    x = np.c_[stretch * (uv[:, 0] - size / 2), y + jitter, stretch * (uv[:, 1] - size / 2)]
    return SimModel.build(f, f), torch.as_tensor(uv), torch.as_tensor(x)


def _drape_and_grads(model, uv, x, device, fused):
    """A sheet draped 6 steps over a sphere on ``device``; (x (N, 3), d loss/d uv, d loss/d gamma) on the
    CPU."""
    uv = uv.detach().clone().to(device).requires_grad_(True)  # leaves of their own (.to("cpu") is a no-op)
    gamma = GAMMA.detach().clone().to(device).requires_grad_(True)
    out = drape(
        model.to(device),
        SimState.at_rest(x.to(device)),
        SphereSDF((0, 0, 0), 0.1),
        Cloth(uv, gamma, 0.12),
        steps=6,
        settings=DrapeSettings(fused=fused),
    )
    (out.x[:, 1] ** 2).sum().backward()
    return out.x.detach().cpu(), uv.grad.cpu(), gamma.grad.cpu()


def test_model_to_moves_every_tensor():
    uv, f = grid_sheet(3, 3, 0.1, 0.1)
    m = SimModel.build(f, f, springs=[[0, 5]], pinned=[1])
    assert m.to("cpu") is m and m.device == torch.device("cpu")
    moved = m.to("meta")
    tensors = {k: v for k, v in vars(moved).items() if torch.is_tensor(v)}
    assert set(tensors) == {k for k, v in vars(m).items() if torch.is_tensor(v)} and len(tensors) >= 19
    assert all(v.device.type == "meta" for v in tensors.values())
    assert (moved.n, moved.n_rest, moved.nnz, moved.bending_stencil) == (
        m.n,
        m.n_rest,
        m.nnz,
        m.bending_stencil,
    )
    assert m.faces.device.type == "cpu"  # the original stays


def test_drape_refuses_a_model_on_another_device():
    m, uv, x = _sheet(3)
    with pytest.raises(InputError, match=r"SimModel on meta: move the model with model.to\('cpu'\)"):
        drape(m.to("meta"), SimState.at_rest(x), SphereSDF(), Cloth(uv, GAMMA, 0.1), steps=1)


@pytest.mark.parametrize("fused", [True, False])
def test_drape_makes_nothing_on_the_default_device(fused):
    """A drape, its backward (fused step_solve, or assembly + sparse_solve) and the sewing phase
    create every tensor on their inputs' device."""
    m, uv, x = _sheet(4)
    with no_default_device():
        xo, guv, gg = _drape_and_grads(m, uv, x, "cpu", fused)
        assert torch.isfinite(guv).all() and torch.isfinite(gg).all()
        tp = two_panels(3, 0.1)
        mu = SimModel.build(tp["faces_uv"], tp["faces_uv"], springs=tp["seam_pairs"])
        u2 = tp["uv"]
        x0 = torch.as_tensor(np.c_[u2[:, 0], np.full(len(u2), 0.2), u2[:, 1]])
        xs = sew(
            mu,
            x0,
            SphereSDF((0, 0, 0), 0.05),
            Cloth(torch.as_tensor(u2), GAMMA, 0.1),
            settings=DrapeSettings(sew_steps=3, hold_steps=2, fused=fused),
            hold=[0],
        )
        assert merge_sewn(xs, tp["x_of_u"], tp["n_x"]).shape == (tp["n_x"], 3)


@CUDA
@pytest.mark.parametrize("fused", [True, False])
def test_drape_on_cuda_matches_cpu(fused):  # pragma: no cover - no GPU on the dev machines
    """The same drape on the GPU (assembly there, the factorization on the CPU) and its gradients
    in uv and Gamma agree with the CPU's to round-off (GPU sums run in another order)."""
    m, uv, x = _sheet()
    x_cpu, guv_cpu, gg_cpu = _drape_and_grads(m, uv, x, "cpu", fused)
    x_gpu, guv_gpu, gg_gpu = _drape_and_grads(m, uv, x, "cuda", fused)
    assert_close(x_gpu, x_cpu, atol=1e-12, rtol=1e-9, what="x ")
    assert_close(guv_gpu, guv_cpu, atol=1e-9 * float(guv_cpu.abs().max()), rtol=1e-6, what="d/duv ")
    assert_close(gg_gpu, gg_cpu, atol=1e-9 * float(gg_cpu.abs().max()), rtol=1e-6, what="d/dgamma ")
