"""TimeBudget (unsew.fit.budget) on a clock the test moves."""

import math

import pytest

from unsew.fit.budget import RESERVE_FACTOR, TimeBudget


class FakeClock:
    def __init__(self):
        self.t = 100.0

    def __call__(self):
        return self.t


def test_time_budget_counts_down_and_reserves_margin():
    clock, said = FakeClock(), []
    b = TimeBudget(60.0, clock=clock, log=said.append)
    clock.t += 20.0
    assert b.elapsed() == pytest.approx(20.0) and b.left() == pytest.approx(40.0)
    assert b.fits(40.0 / RESERVE_FACTOR - 1e-6) and not b.fits(40.0 / RESERVE_FACTOR + 1e-6)
    assert b.within(0.5) and not b.within(0.3)
    b.cut("mesh spread skipped")
    assert b.as_dict() == {"limit_s": 60.0, "cuts": ["mesh spread skipped"]}
    assert said == ["time limit 60 s: mesh spread skipped"]
    clock.t += 100.0
    assert b.left() < 0 and not b.fits(0.0 + 1e-9)


def test_no_limit_always_fits():
    clock = FakeClock()
    b = TimeBudget(0, clock=clock)
    clock.t += 1e6
    assert b.left() == math.inf and b.fits(1e9) and b.within(0.0)
    assert b.as_dict() == {"limit_s": None, "cuts": []}


def test_a_negative_time_limit_is_refused():
    from unsew.errors import InputError
    from unsew.fit.config import load_config

    assert load_config(time_limit=0).time_limit == 0.0
    with pytest.raises(InputError, match="time_limit must be >= 0"):
        load_config(time_limit=-5)


def test_the_limit_counts_from_when_the_command_started():
    """``started``: the budget counts from the command's start (loading the case and its body
    included), not from when it was made."""
    clock = FakeClock()
    b = TimeBudget(60.0, clock=clock, started=clock.t - 50.0)  # the case took 50 s to load
    assert b.elapsed() == pytest.approx(50.0) and b.left() == pytest.approx(10.0)
    assert not b.within(0.5)


def test_unsew_fit_starts_the_clock_before_loading_the_case(monkeypatch, tmp_path):
    """The command hands run_fit the time it began, taken before the case (and its anny body,
    minutes to build the first time on a machine) was loaded."""
    import time

    import unsew.body.case
    import unsew.commands.fit as command
    import unsew.fit.run
    from unsew.cli import main

    seen = {}
    monkeypatch.setattr(
        unsew.body.case, "load_case", lambda *a, **k: seen.setdefault("loaded", time.perf_counter())
    )
    monkeypatch.setattr(command, "_check_inputs", lambda case, cfg: None)
    monkeypatch.setattr(
        unsew.fit.run, "run_fit", lambda *a, started=None, **k: seen.setdefault("started", started)
    )
    assert main(["fit", str(tmp_path / "case"), "--out", str(tmp_path / "out")]) == 0
    assert seen["started"] is not None and seen["started"] <= seen["loaded"]


def test_grading_room_keeps_each_optional_drape_in_time():
    """Grading's optional drapes run while one more (the last one's duration, reserved
    RESERVE_FACTOR times over) ends in time; a refusal is recorded as a cut."""
    from unsew.fit.start import _grading_room

    clock, said = FakeClock(), []
    b = TimeBudget(540.0, clock=clock, log=said.append)
    clock.t += 400.0  # 140 s left
    room = _grading_room(b)
    assert room(100.0, "a")  # 1.3 x 100 = 130 s
    assert not room(110.0, "grading: passes 2-3 not draped")  # 1.3 x 110 = 143 s
    assert b.cuts == ["grading: passes 2-3 not draped (about 110 s a drape: it would overrun)"]
    assert said == ["time limit 540 s: " + b.cuts[0]]
    assert _grading_room(TimeBudget(0, clock=clock))(1e9, "c")  # no limit: always room
