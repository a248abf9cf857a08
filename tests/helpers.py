"""Shared test helpers (STYLE.md habit 10)."""

from __future__ import annotations

import contextlib
import os
import traceback

import numpy as np

__all__ = ["assert_close", "contact_points", "no_default_device"]


def assert_close(actual, expected, *, atol: float = 0.0, rtol: float = 1e-7, what: str = "") -> None:
    """Assert ``|actual - expected| <= atol + rtol*|expected|`` elementwise; on failure report the
    largest difference, where it is, and both shapes."""
    try:
        import torch

        if isinstance(actual, torch.Tensor):
            actual = actual.detach().cpu().numpy()
        if isinstance(expected, torch.Tensor):
            expected = expected.detach().cpu().numpy()
    except ImportError:  # pragma: no cover
        pass
    a = np.asarray(actual, dtype=np.float64)
    e = np.asarray(expected, dtype=np.float64)
    if a.shape != e.shape:
        try:
            np.broadcast_shapes(a.shape, e.shape)
        except ValueError:
            raise AssertionError(f"{what}shape mismatch: actual {a.shape} vs expected {e.shape}") from None
    a_b, e_b = np.broadcast_arrays(a, e)
    if not np.isfinite(a_b).all():
        bad = np.argwhere(~np.isfinite(a_b))[0]
        raise AssertionError(f"{what}non-finite value at {tuple(bad)} (shape {a.shape})")
    diff = np.abs(a_b - e_b)
    tol = atol + rtol * np.abs(e_b)
    if (diff <= tol).all():
        return
    excess = diff - tol
    idx = np.unravel_index(int(np.argmax(excess)), excess.shape) if excess.ndim else ()
    raise AssertionError(
        f"{what}not close: largest difference {diff[idx]:.3e} at index {tuple(int(i) for i in idx)} "
        f"(actual {a_b[idx]!r}, expected {e_b[idx]!r}, atol {atol:g}, rtol {rtol:g}); "
        f"shapes actual {a.shape} expected {e.shape}; {int((diff > tol).sum())} of {diff.size} out of "
        "tolerance"
    )


@contextlib.contextmanager
def no_default_device():
    """Inside, a torch factory (zeros, ones, empty, full, eye, arange, linspace, tensor, as_tensor
    of non-tensor data, rand, randn, randint) called from unsew's own source without ``device=``
    raises AssertionError naming the line. Such a tensor lands on the default device (the CPU)
    whatever its inputs' device, and breaks a fit on a GPU: this finds them on a CPU-only machine.
    ``torch.from_numpy`` is not checked (always the CPU; follow it with ``.to(device)``)."""
    import torch
    from torch.overrides import TorchFunctionMode

    import unsew

    root = os.path.dirname(os.path.abspath(unsew.__file__)) + os.sep
    factories = {
        torch.zeros,
        torch.ones,
        torch.empty,
        torch.full,
        torch.eye,
        torch.arange,
        torch.linspace,
        torch.tensor,
        torch.as_tensor,
        torch.rand,
        torch.randn,
        torch.randint,
    }

    class _Check(TorchFunctionMode):
        def __torch_function__(self, func, types, args=(), kwargs=None):
            kwargs = kwargs or {}
            if (
                func in factories
                and kwargs.get("device") is None
                and not (func is torch.as_tensor and args and torch.is_tensor(args[0]))
            ):
                caller = [f for f in traceback.extract_stack()[:-1] if f.filename != __file__][-1]
                if os.path.abspath(caller.filename).startswith(root):
                    raise AssertionError(
                        f"{func.__name__} without device= at {caller.filename}:{caller.lineno} "
                        f"({caller.line}): it lands on the default device, not its inputs'"
                    )
            return func(*args, **kwargs)

    with _Check():
        yield


def contact_points(model, x):
    """The points the body repels (N + E, 3) [m]: x's vertices and its mesh edges' midpoints."""
    import torch

    from unsew.sim.integrator import _mesh_edges

    e = _mesh_edges(model)
    return torch.cat([x, 0.5 * (x[e[:, 0]] + x[e[:, 1]])])
