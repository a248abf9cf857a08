"""A case whose meta.json names no garment type: the fit reads it off the target and says so."""

from pathlib import Path

import numpy as np
import pytest

from unsew.body.body import default_body
from unsew.errors import InputError
from unsew.fit.config import FitConfig
from unsew.fit.start import with_garment_read
from unsew.io.case import Case
from unsew.io.mesh import read_garment

CASES = Path(__file__).resolve().parents[2] / "benchmarks" / "foreign" / "cases"


def _case(*names):
    vs, fs, n = [], [], 0
    for name in names:
        if not (CASES / name / "target.obj").is_file():
            pytest.skip(f"benchmark case {name} not in this checkout")
        v, f, _ = read_garment(CASES / name / "target.obj")
        vs.append(v)
        fs.append(f + n)
        n += len(v)
    return Case(CASES / names[0], "", np.concatenate(vs), np.concatenate(fs), default_body())


def test_the_type_is_read_and_noted():
    said = []
    case = with_garment_read(_case("skirt_aline_knee__default"), FitConfig(), log=said.append)
    assert case.garment == "skirt"
    assert said and said[0] in case.notes and "skirt" in said[0]
    assert said[1].startswith("read: skirt") and "hem " in said[1]  # the design read, with its evidence
    assert case.design.garment == "skirt"  # the start drafts its candidates from it


def test_a_named_base_or_type_is_left_alone():
    case = _case("skirt_aline_knee__default")
    assert with_garment_read(case, FitConfig(base="pants"), log=lambda s: None) is case


def test_a_jumpsuit_gets_its_design_read():
    """The library has no jumpsuit base: the start drafts jumpsuit designs from the reading."""
    case = _case("trousers_slim__default", "tee_fitted_short__default")
    read = with_garment_read(case, FitConfig(), log=lambda s: None)
    assert read.garment == "jumpsuit" and read.design.garment == "jumpsuit"


def test_a_type_outside_the_design_space_is_refused_in_one_line(monkeypatch):
    import unsew.fit.start as start_mod

    monkeypatch.setattr(start_mod, "GARMENTS", ("tshirt",))
    with pytest.raises(InputError, match="skirt") as e:
        with_garment_read(_case("skirt_aline_knee__default"), FitConfig(), log=lambda s: None)
    assert "\n" not in str(e.value)
