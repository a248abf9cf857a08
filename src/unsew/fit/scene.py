"""What the stages of a fit share (:class:`Scene`): the wearer, the target, the body's SDF, the
config, where progress is shown and where one-line messages go."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Callable

from unsew.fit.config import FitConfig
from unsew.fit.progress import Progress
from unsew.fit.target import Target

__all__ = ["Scene"]


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
