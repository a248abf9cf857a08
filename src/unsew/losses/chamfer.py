"""Chamfer losses between the simulated garment X and the target T (paper eqs. 6 and 7).

Plain (squared) Chamfer distance, the mean over each side::

    L_CF(X, T) = 1/|X| sum_x ||x - t~(x)||^2 + 1/|T| sum_t ||t - x~(t)||^2

with ``t~(x)`` the nearest target point to ``x`` and ``x~(t)`` the nearest simulated point to
``t``. The curvature-weighted form (eq. 7, after [BRPW22]) multiplies each term by the target's
curvature weight: ``kappa(t~(x))`` in the first sum (the weight of the nearest target point),
``kappa(t)`` in the second. Weights come from :func:`unsew.losses.curvature.curvature_weights`,
normalised so that a flat target has all weights exactly 1 and the weighted loss equals the
plain one.

Nearest neighbours come from :func:`unsew.losses.nn.nearest_indices` (no gradient); distances are
recomputed from the gathered points, so the loss is differentiable with respect to both point
sets (and its gradient is the exact gradient of the piecewise-smooth Chamfer function).
"""

from __future__ import annotations

from unsew.losses.nn import nearest_indices

__all__ = ["loss_chamfer"]


def loss_chamfer(x, t, *, weights_x=None, weights_t=None, method: str = "auto"):
    """Squared Chamfer distance of eq. 7 (plain when no weights are given).

    x: simulated points [m], shape (N, 3), float64 torch tensor, N >= 1.
    t: target points [m], shape (M, 3), float64 torch tensor, M >= 1.
    weights_x: optional per-simulated-point weights, shape (N,), dimensionless; multiply the
        x -> T term (on top of the target weight at the nearest target point).
    weights_t: optional per-target-point weights (e.g. curvature weights), shape (M,),
        dimensionless; weight the T -> X term at each target point and the X -> T term at the
        nearest target point of each x.
    method: nearest-neighbour back end (see :mod:`unsew.losses.nn`).
    Returns: scalar tensor [m^2], differentiable w.r.t. ``x``, ``t`` and the weights.
    """
    if x.ndim != 2 or t.ndim != 2 or x.shape[1] != t.shape[1]:
        raise ValueError(f"loss_chamfer: x {tuple(x.shape)} and t {tuple(t.shape)} must be (N, D) and (M, D)")
    if x.shape[0] == 0 or t.shape[0] == 0:
        raise ValueError("loss_chamfer: empty point set")
    i_xt = nearest_indices(x, t, method=method)  # (N,) nearest target point of each x
    i_tx = nearest_indices(t, x, method=method)  # (M,) nearest simulated point of each t
    d_x = ((x - t[i_xt]) ** 2).sum(dim=1)  # (N,) [m^2]
    d_t = ((t - x[i_tx]) ** 2).sum(dim=1)  # (M,) [m^2]
    if weights_t is not None:
        if weights_t.shape != (t.shape[0],):
            raise ValueError(f"loss_chamfer: weights_t {tuple(weights_t.shape)} must be ({t.shape[0]},)")
        d_x = d_x * weights_t[i_xt]
        d_t = d_t * weights_t
    if weights_x is not None:
        if weights_x.shape != (x.shape[0],):
            raise ValueError(f"loss_chamfer: weights_x {tuple(weights_x.shape)} must be ({x.shape[0]},)")
        d_x = d_x * weights_x
    return d_x.mean() + d_t.mean()
