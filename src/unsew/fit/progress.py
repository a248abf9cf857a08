"""Progress of a fit, honest on any stream: on a terminal, bars whose figures are the ones the
report uses (the Chamfer distance in mm); off a terminal (a pipe, CI, a batch log), one plain
line per phase and one every few iterations or seconds, with no carriage returns or cursor codes.

:func:`is_terminal` is the one place that decides whether a stream gets bars: every command's
progress (fit, drape, batch, demo) goes through it."""

from __future__ import annotations

import sys
import time
from contextlib import contextmanager
from typing import Callable, TextIO

__all__ = ["Progress", "BAR_SAMPLES", "is_terminal"]

#: Surface samples per side of the Chamfer distance shown beside phase two's bar (a cheaper
#: estimate of the figure metrics.json reports with 50,000).
BAR_SAMPLES = 5_000


def is_terminal(stream: TextIO | None) -> bool:
    """Whether ``stream`` is an interactive terminal, the only kind that gets tqdm bars (their
    redraws are carriage returns and cursor codes: noise in a file, a pipe or a CI log)."""
    try:
        return bool(stream is not None and stream.isatty())
    except (AttributeError, ValueError, OSError):  # no isatty, or a closed stream
        return False


class Progress:
    """Where a fit reports its progress.

    enabled: False prints nothing. stream: where to write (default stderr). A stream that is a
    terminal (``isatty()``) gets tqdm bars, any other stream plain lines: one when a phase starts
    and, in phase two, one every ``every`` iterations or ``seconds`` seconds (whichever comes
    first) and one at the end.
    """

    def __init__(
        self, enabled: bool = True, *, stream: TextIO | None = None, every: int = 10, seconds: float = 30.0
    ):
        self.enabled = enabled
        self.stream = stream if stream is not None else sys.stderr
        self.tty = is_terminal(self.stream)
        self.every, self.seconds = max(int(every), 1), float(seconds)

    def line(self, text: str) -> None:
        """One plain line (off a terminal) or a line printed above the bars (on one)."""
        if not self.enabled:
            return
        if self.tty:
            from tqdm import tqdm

            tqdm.write(text, file=self.stream)
        else:
            print(text, file=self.stream, flush=True)

    @contextmanager
    def phase(self, desc: str):
        """A context yielding a ``progress(phase, k, n)`` callback for :func:`unsew.dress.dress`
        (None when disabled); the bars close when the context ends."""
        if not self.enabled:
            yield None
            return
        bars: dict = {}

        def cb(phase: str, k: int, n: int) -> None:
            if self.tty:
                from tqdm import tqdm

                b = bars.get(phase)
                if b is None:
                    b = bars[phase] = tqdm(
                        total=n,
                        desc=f"{desc}: {phase}",
                        unit="step",
                        leave=False,
                        dynamic_ncols=True,
                        file=self.stream,
                    )
                b.update(k - b.n)
            elif phase not in bars:
                bars[phase] = None
                self.line(f"{desc}: {phase} ({n} step{'s' if n != 1 else ''})")

        try:
            yield cb
        finally:
            for b in bars.values():
                if b is not None:
                    b.close()

    def iterations(
        self, total: int, initial: int, chamfer_mm: Callable[[object], float]
    ) -> "IterationProgress":
        """A callback for :meth:`unsew.fit.optimize.PhaseTwo.run`; ``chamfer_mm(info)`` gives the
        Chamfer distance [mm] of an iteration's drape (computed only when it is shown)."""
        return IterationProgress(self, total, initial, chamfer_mm)


class IterationProgress:
    """Phase two's progress: a bar with the drape's Chamfer [mm], or plain lines."""

    def __init__(self, progress: Progress, total: int, initial: int, chamfer_mm):
        self.p, self.total, self.chamfer_mm = progress, total, chamfer_mm
        self.t0 = self.last = time.perf_counter()
        self.bar = None
        if progress.enabled and progress.tty:
            from tqdm import tqdm

            self.bar = tqdm(
                total=total,
                initial=initial,
                desc="fit",
                unit="it",
                leave=False,
                dynamic_ncols=True,
                file=progress.stream,
            )
        elif progress.enabled:
            progress.line(f"fit: phase two, iterations {initial + 1}-{total}")

    def __call__(self, info) -> None:
        if not self.p.enabled:
            return
        done = info.iteration + 1
        if self.bar is not None:
            self.bar.update(1)
            # redraws: an iteration takes seconds
            self.bar.set_postfix_str(f"Chamfer {self.chamfer_mm(info):.2f} mm")
            return
        now = time.perf_counter()
        if done % self.p.every == 0 or now - self.last >= self.p.seconds or done == self.total or info.last:
            self.last = now
            self.p.line(
                f"fit: iteration {done}/{self.total}, Chamfer {self.chamfer_mm(info):.2f} mm, "
                f"{now - self.t0:.0f} s" + (" (converged)" if info.last and done < self.total else "")
            )

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()
