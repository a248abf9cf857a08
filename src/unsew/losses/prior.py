"""Pull towards the starting pattern (not in the paper; ``FitConfig.lambda_prior``, default off)::

    L_prior(U) = mean_i |u_i - u0_i|^2   [m^2]

over all 2D rest vertices U (Nu, 2) [m], u0 the graded pattern the optimization starts from. It
keeps phase two from explaining what the pattern cannot (where one drape's folds happened to land,
a fabric the material fit has not found) by moving the pattern away from a graded one that is
already close. A rigid move of a whole panel costs too,
which also pins the 2D placement the simulator ignores.
"""

from __future__ import annotations

__all__ = ["loss_prior"]


def loss_prior(uv, uv0):
    """Mean squared move of the rest vertices [m^2], a 0-d tensor.

    uv: (Nu, 2) torch float64 [m], the current rest vertices (differentiable).
    uv0: (Nu, 2) [m], the starting ones (constant), same dtype and device.
    """
    if uv.shape != uv0.shape or uv.ndim != 2 or uv.shape[1] != 2:
        raise ValueError(f"uv and uv0 must both be (Nu, 2), got {tuple(uv.shape)} and {tuple(uv0.shape)}")
    return ((uv - uv0) ** 2).sum(dim=1).mean()
