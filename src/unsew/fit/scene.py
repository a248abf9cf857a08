"""What the stages of a fit share: :class:`Scene` (the wearer, the target, the body's SDF, the
config, where progress is shown and where one-line messages go) and :class:`FitContext`, the
Scene of one fit with its case, time limit, contact and checkpoint, built once
(:func:`unsew.fit.stages.build_context`) and handed to every stage, ``stage(ctx, previous)``."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from pathlib import Path
from typing import Callable

from unsew.fit.budget import TimeBudget
from unsew.fit.config import FitConfig
from unsew.fit.progress import Progress
from unsew.fit.target import Target

__all__ = ["Scene", "FitContext"]


@dataclass(frozen=True)
class Scene:
    """The fit's fixed inputs, handed to every stage together.

    body: the wearer (:class:`~unsew.body.body.Body`); target: the garment to invert
    (:class:`~unsew.fit.target.Target`); sdf: the body's signed distance
    (:class:`~unsew.body.sdf.BodySDF`); cfg: the :class:`~unsew.fit.config.FitConfig`;
    progress: where each stage shows its progress (:class:`~unsew.fit.progress.Progress`); log:
    where one-line messages go.
    """

    body: object
    target: Target
    sdf: object
    cfg: FitConfig
    progress: Progress = field(default_factory=lambda: Progress(False))
    log: Callable[[str], None] = print

    def replace(self, **changes) -> "Scene":
        """A copy with ``changes`` applied."""
        return dataclasses.replace(self, **changes)


@dataclass(frozen=True)
class FitContext(Scene):
    """A :class:`Scene` with what the rest of one fit's stages read: built once, never changed
    (its budget records what gave way, as its log records lines).

    case: the loaded case (:func:`unsew.body.case.load_case`), its garment type read; budget:
    the fit's :class:`~unsew.fit.budget.TimeBudget`; contact: the body contact every drape uses,
    for metrics.json (:func:`unsew.fit.contact.contact_for_target`; ``cfg`` holds it already);
    checkpoint: the file phase two writes after every iteration (None: none); callback: called
    with every phase-two :class:`~unsew.fit.optimize.Iteration` (None: none).
    """

    case: object = None
    budget: TimeBudget = field(default_factory=lambda: TimeBudget(0))
    contact: dict = field(default_factory=dict)
    checkpoint: Path | None = None
    callback: Callable | None = None
