#!/usr/bin/env bash
# Create or reuse the project's virtual environment in .venv.
# Installs exactly torch==2.13.0 (the CPU build that pip finds in the local wheel folder on our
# machines; never the multi-GB CUDA build), then unsew itself in editable mode with its test extra,
# and, where it can be built, the optional CHOLMOD solver (below).
# A second run finds the stamp up to date and returns in well under a second.
set -euo pipefail
cd "$(dirname "$0")/.."
PY=${PYTHON:-python3.11}
command -v "$PY" >/dev/null 2>&1 || PY=python3
VENV=.venv
STAMP=$VENV/.unsew-setup
want=$(cat pyproject.toml scripts/setup-env.sh | sha256sum | cut -d' ' -f1)
if [ -f "$STAMP" ] && [ "$(cat "$STAMP")" = "$want" ] && [ -x "$VENV/bin/unsew" ]; then
    exit 0
fi
echo "unsew: setting up $VENV (first run only; about a minute)" >&2
[ -x "$VENV/bin/python" ] || "$PY" -m venv "$VENV"
pip_args=(--disable-pip-version-check -q)
# pip's noise about this machine's empty extra index folders is dropped; errors stay.
pipq() { "$VENV/bin/pip" "$@" 2>&1 | { grep -v "is ignored: it is neither a file nor a directory" || true; }; return "${PIPESTATUS[0]}"; }
links=()
for d in /opt/wheels; do [ -d "$d" ] && links+=(--find-links "$d"); done
if ! "$VENV/bin/python" -c "import torch, sys; sys.exit(0 if torch.__version__.startswith('2.13.0') else 1)" 2>/dev/null; then
    # A CPU build of torch 2.13.0 is what we want. Where the local wheel folder has it, pip takes it;
    # elsewhere the CPU wheel index is asked explicitly, so the CUDA build is never pulled.
    if ls /opt/wheels/torch-2.13.0+cpu-*.whl >/dev/null 2>&1; then
        pipq install "${pip_args[@]}" "${links[@]}" "torch==2.13.0"
    else
        pipq install "${pip_args[@]}" "torch==2.13.0" --index-url https://download.pytorch.org/whl/cpu
    fi
fi
pipq install "${pip_args[@]}" "${links[@]}" -e ".[test]"
# Optional: CHOLMOD (scikit-sparse) on OpenBLAS factorizes the drape's systems about twice as fast as
# cholespy, and a fit's stages run up to a quarter faster (docs/decisions/010-cholmod.md). It builds
# against Debian's libsuitesparse-dev: as root with apt-get, that and libopenblas0-pthread are
# installed here. Anywhere else, or with UNSEW_NO_CHOLMOD=1, the drape uses cholespy.
if [ "${UNSEW_NO_CHOLMOD:-0}" != 1 ] && ! "$VENV/bin/python" -c "import sksparse.cholmod" 2>/dev/null; then
    if [ ! -f /usr/include/suitesparse/cholmod.h ] && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "unsew: installing Debian's libsuitesparse-dev and libopenblas0-pthread for CHOLMOD (UNSEW_NO_CHOLMOD=1 skips)" >&2
        DEBIAN_FRONTEND=noninteractive timeout 300 apt-get install -y -q libsuitesparse-dev libopenblas0-pthread \
            >/dev/null 2>&1 || echo "unsew: apt-get could not install them; the drape uses cholespy" >&2
    fi
    if [ -f /usr/include/suitesparse/cholmod.h ]; then
        pipq install "${pip_args[@]}" "${links[@]}" -e ".[test,cholmod]" \
            || echo "unsew: scikit-sparse did not build; the drape uses cholespy" >&2
    fi
fi
echo "$want" > "$STAMP"
