"""Changing simulation data: positions and velocities (STYLE.md habit 6)."""

from __future__ import annotations

from dataclasses import dataclass

import torch

__all__ = ["SimState"]


@dataclass
class SimState:
    """Cloth state.

    Attributes:
        x: vertex positions [m], shape (N, 3), float64 torch.
        v: vertex velocities [m/s], shape (N, 3), float64 torch.
    """

    x: torch.Tensor
    v: torch.Tensor

    @classmethod
    def at_rest(cls, x) -> "SimState":
        """State at positions x (N, 3) [m] (array or tensor) with zero velocity."""
        x = torch.as_tensor(x, dtype=torch.float64)
        return cls(x=x, v=torch.zeros_like(x))

    def detach(self) -> "SimState":
        """A copy cut from the autograd graph (for warm starts)."""
        return SimState(self.x.detach().clone(), self.v.detach().clone())
