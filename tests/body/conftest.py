"""Fixtures of the body tests: the default body's SDF is built once per test run (and cached on
disk in $UNSEW_CACHE or ~/.cache/unsew, so later runs load it)."""

import pytest


@pytest.fixture(scope="session")
def default_sdf():
    from unsew.body.body import default_body
    from unsew.body.sdf import BodySDF

    return BodySDF.build(default_body())
