"""Checkpoints of a fit: phase two's start (:class:`~unsew.fit.material.MaterialChoice`) and its
optimizer state (:meth:`~unsew.fit.optimize.PhaseTwo.state_dict`), written after every iteration
so ``--resume`` continues an interrupted fit."""

from __future__ import annotations

from pathlib import Path

import torch

from unsew.errors import InputError
from unsew.io.atomic import atomic_write

__all__ = ["save_checkpoint", "load_checkpoint", "CHECKPOINT_VERSION"]

#: Format of the checkpoint file (1: the single-function fit's dicts; 2: stages).
CHECKPOINT_VERSION = 2


def save_checkpoint(path: Path, choice, phase_two_state: dict) -> None:
    """Write ``choice`` (MaterialChoice) and ``phase_two_state`` to ``path`` atomically."""
    with atomic_write(path) as tmp:
        torch.save({"version": CHECKPOINT_VERSION, "choice": choice, "phase_two": phase_two_state}, tmp)


def load_checkpoint(path: Path) -> tuple:
    """(MaterialChoice, phase two state) from ``path``, its tensors on the CPU (a checkpoint written
    by a fit on a GPU resumes on any device: ``PhaseTwo.load_state_dict`` moves them to its own);
    InputError when it cannot be read."""
    try:
        data = torch.load(path, map_location="cpu", weights_only=False)
    except Exception as exc:
        raise InputError(
            f"checkpoint {path} cannot be read ({type(exc).__name__}); delete it to start afresh"
        ) from None
    if not isinstance(data, dict) or data.get("version") != CHECKPOINT_VERSION:
        raise InputError(
            f"checkpoint {path} was written by another version of unsew; delete it to start afresh"
        )
    return data["choice"], data["phase_two"]
