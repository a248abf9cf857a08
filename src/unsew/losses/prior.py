"""Pull towards the starting pattern (not in the paper; ``FitConfig.lambda_prior``, default off)::

    L_prior(U) = mean_i |u_i - u0_i|^2   [m^2]

over all 2D rest vertices U (Nu, 2) [m], u0 the graded pattern the optimization starts from. It
keeps phase two from explaining what the pattern cannot (where one drape's folds happened to land,
a fabric the material fit has not found) by moving the pattern away from a graded one that is
already close. A rigid move of a whole panel costs too,
which also pins the 2D placement the simulator ignores.
"""

from __future__ import annotations

__all__ = ["loss_prior", "loss_moves", "moves_pull", "MOVE_EPS", "MOVE_SCALE"]


def loss_prior(uv, uv0):
    """Mean squared move of the rest vertices [m^2], a 0-d tensor.

    uv: (Nu, 2) torch float64 [m], the current rest vertices (differentiable).
    uv0: (Nu, 2) [m], the starting ones (constant), same dtype and device.
    """
    if uv.shape != uv0.shape or uv.ndim != 2 or uv.shape[1] != 2:
        raise ValueError(f"uv and uv0 must both be (Nu, 2), got {tuple(uv.shape)} and {tuple(uv0.shape)}")
    return ((uv - uv0) ** 2).sum(dim=1).mean()


#: Smoothing length of :func:`loss_moves` at zero move [m] (a move far below a mesh edge).
MOVE_EPS = 1e-5
#: Length over which :func:`loss_moves`' pull on a move fades to half [m].
MOVE_SCALE = 5e-3


def _move_lengths(K, K0):
    """|K_k - K0_k| smoothed at zero (MOVE_EPS), (Nk,) [m], and the (Nk, 2) unit directions."""
    dK = K - K0
    s = ((dK**2).sum(dim=1) + MOVE_EPS**2).sqrt()
    return s - MOVE_EPS, dK / s[:, None]


def loss_moves(K, K0, weights):
    """Weighted log-distance of the effective control points from their start [m], a 0-d tensor::

        L_moves(K) = sum_k w_k s log(1 + r_k / s),   r_k = |K_k - K0_k| (smoothed at 0, MOVE_EPS)

    with ``weights`` w_k the share of the pattern's control points point k moves (they sum to 1)
    and s = MOVE_SCALE. A prior in pattern space that an edit is either none or real: near the
    start it is the L1 distance, whose pull (w_k per unit of the loss's weight) does not fade as a
    move gets small, so a point whose gradient stays below that pull stays where the graded pattern
    has it; beyond s the pull fades (w_k s / (s + r_k)), so a move the target asks for by
    centimetres pays about once, not in proportion (a squared distance would shrink every move
    alike, an L1 one the large moves most).

    K, K0: (Nk, 2) torch float64 [m] (K differentiable, K0 constant); weights: (Nk,) float64.
    """
    if K.shape != K0.shape or K.ndim != 2 or K.shape[1] != 2 or weights.shape != K.shape[:1]:
        raise ValueError(
            f"K and K0 must both be (Nk, 2) and weights (Nk,), got {tuple(K.shape)}, {tuple(K0.shape)}, "
            f"{tuple(weights.shape)}"
        )
    r, _ = _move_lengths(K, K0)
    return (weights * MOVE_SCALE * (r / MOVE_SCALE).log1p()).sum()


def moves_pull(K, K0, weights):
    """The size of d L_moves / dK_k (:func:`loss_moves`) at K's moves, (Nk, 1) [-], and its
    direction, (Nk, 2) unit vectors; without autograd (K, K0 detached)."""
    r, u = _move_lengths(K, K0)
    return (weights * MOVE_SCALE / (MOVE_SCALE + r))[:, None], u
