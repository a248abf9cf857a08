"""The fit's time limit (``FitConfig.time_limit``): the optional work of a fit gives way so the
whole fit ends in time, and what gave way is recorded (metrics.json's ``time_limit``). The limit
counts from the command's start (``unsew fit``, ``unsew batch``): loading the case and building
its body can take minutes the first time an anny body is built on a machine (its cache), and the
fit's own clock would not see them.

What gives way, in the order a fit reaches it:

- the runner-up of a tie in the base choice is graded only while less than half the limit is
  spent and a grading as long as the chosen base's still ends in time;
- grading's passes after the first and its lift choice's drapes run only while one more (timed
  as the last graded drape) still ends in time;
- the material choice drapes the fabrics only while each (timed as the one before it; the first
  estimated from the base's drape from scratch by its number of steps) and the check's drape from
  scratch still end in time; otherwise the start fabric (cotton) stays, unless the drape graded
  in it fails the checks a result passes (then every fabric is draped, past the limit);
- the material choice's optional steps (grading again in other fabrics, the stiffness search)
  run only while less than half the limit is spent;
- phase two stops before an iteration that would leave too little time for one more iteration
  and the re-dress check on the fit's mesh (one drape from scratch);
- the re-dress check's four drapes on the other two meshes and the graded pattern's on the
  fit's mesh (``unsew.fit.checks.REDRESS_MESHES`` 3) run only when five more drapes fit (the re-dress
  on the fit's mesh, timed, is the estimate); otherwise phase two is judged on one mesh;
- the mesh spread (two drapes from scratch, a diagnostic; the three-mesh check's own when that
  ran) is skipped when it would not fit.

The base choice, the chosen base's first grading pass and the re-dress check on the fit's mesh
always run: without them there is no result, or no judgement of phase two's. Times to come are
estimated from ones measured in this fit: a drape from scratch (the base's, in phase one), the
graded drapes and phase two's iterations.
"""

from __future__ import annotations

import math
import time
from typing import Callable

__all__ = ["TimeBudget", "RESERVE_FACTOR"]

#: an estimated duration is reserved this many times over (drapes of a moved pattern, on another
#: mesh, settle in more or fewer steps than the one timed) [-]
RESERVE_FACTOR = 1.3


class TimeBudget:
    """Seconds left of ``limit_s`` (0 or less: no limit) since ``started`` (a ``clock`` reading:
    when the command began, so that loading the case and building its body count; default: when
    the budget was made); ``cuts`` lists, in words, what was left out to stay within it."""

    def __init__(
        self,
        limit_s: float,
        *,
        log: Callable[[str], None] = print,
        clock: Callable[[], float] = time.perf_counter,
        started: float | None = None,
    ):
        self.limit_s = float(limit_s)
        self._clock, self._log = clock, log
        self.t0 = clock() if started is None else float(started)
        self.cuts: list[str] = []

    @property
    def limited(self) -> bool:
        """Whether there is a limit at all (``limit_s`` > 0)."""
        return self.limit_s > 0

    def elapsed(self) -> float:
        """Seconds since the budget was made [s]."""
        return self._clock() - self.t0

    def left(self) -> float:
        """Seconds left [s] (inf without a limit; negative once overrun)."""
        return self.limit_s - self.elapsed() if self.limited else math.inf

    def fits(self, seconds: float) -> bool:
        """Whether work estimated at ``seconds`` [s], reserved RESERVE_FACTOR times over, ends in time."""
        return self.left() >= RESERVE_FACTOR * seconds

    def within(self, share: float) -> bool:
        """Whether less than ``share`` (0-1) of the limit is spent (always, without a limit)."""
        return not self.limited or self.elapsed() < share * self.limit_s

    def cut(self, what: str) -> None:
        """Record (and log) that ``what`` was left out for the limit."""
        self.cuts.append(what)
        self._log(f"time limit {self.limit_s:.0f} s: {what}")

    def as_dict(self) -> dict:
        """{"limit_s": the limit [s] or None, "cuts": what gave way}, as metrics.json holds it."""
        return {"limit_s": self.limit_s if self.limited else None, "cuts": list(self.cuts)}
