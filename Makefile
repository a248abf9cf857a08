# Quick start: `make demo` runs the embedded default job, `make test` runs the test suite.
# Both create the virtual environment in .venv on first use and reuse it afterwards.
SHELL := /bin/bash
export OMP_WAIT_POLICY := PASSIVE
export PYTHONDONTWRITEBYTECODE := 1
VENV := .venv
# Test processes (pytest-xdist; each runs torch on one thread, tests/conftest.py): one per core of
# the two we are measured on. `--dist worksteal` evens out the minute-long fit tests at the end.
TEST_WORKERS ?= 2

.PHONY: setup demo test test-slow lint bench clean

setup:
	@bash scripts/setup-env.sh

demo: setup
	@$(VENV)/bin/unsew demo --overwrite $(ARGS)

test: setup
	@$(VENV)/bin/python -m pytest -q -m "not slow" -n $(TEST_WORKERS) --dist worksteal $(ARGS)

test-slow: setup
	@$(VENV)/bin/python -m pytest -q -m slow $(ARGS)

# pycodestyle, pyflakes, complexity and argument counts through ruff (settings in pyproject.toml),
# then no function over 60 lines; `ruff format` lays the code out.
lint: setup
	@$(VENV)/bin/ruff check src tests benchmarks
	@$(VENV)/bin/python scripts/check_function_length.py
	@! git grep -nE '^(<<<<<<<|>>>>>>>)( |$$)' -- . ':!*.patch' || { echo 'merge conflict markers left (above)'; exit 1; }

# `make bench NAME=fit ARGS="--edge-length 0.025"`; `make bench` lists the benchmarks.
bench: setup
	@$(VENV)/bin/python -m benchmarks $(NAME) $(ARGS)

clean:
	rm -rf $(VENV) .pytest_cache build src/*.egg-info
