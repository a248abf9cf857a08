#!/usr/bin/env bash
# One short GPU check of unsew on a lent device machine (.library/device/README.md).
# Run from the repository root:   bash benchmarks/gpu_check.sh
# Needs the wheels of the packages that the device image lacks in .whl/ (run's carry: [".whl"]).
# No anny and no anny cache: the default body is embedded, the case below uses it.
#
# Steps: install the wheels; versions; the CUDA pytest; make a small known-truth t-shirt case
# (on the default body, drape settings of tests/fit/test_fit_small.py's "small mode") once;
# fit it with the CLI on cuda, then on cpu (same machine), each under `timeout 200`; if time is
# left, a medium fit (3 cm mesh, 12 iterations, 12 drape steps) on cuda and cpu; a table.
# About 2-4 minutes on 16 cores + H200 (dev box, 2 cores: small cpu fit 21 s, medium 42 s); each
# fit is cut by `timeout` so that the whole script ends within ~6 minutes (GPU_CHECK_DEADLINE=340 s).
#
# Logs go to $OUT (default /tmp/gpu_check_out): at most 8 files come back from the device, so
# the full result folders stay in /tmp/gpu_check and only each fit's metrics.json is copied:
#   check.log (versions, CUDA pytest) fits.log summary.txt metrics_{cuda,cpu}.json
#   metrics_{cuda,cpu}_medium.json
# Dry run on a dev machine:  OUT=/tmp/gco PY=.venv/bin/python GPU_CHECK_NO_WHEELS=1 bash benchmarks/gpu_check.sh

set -u
set -o pipefail
[ -f pyproject.toml ] && [ -d src/unsew ] || { echo "FAILED: run from the repository root"; exit 1; }

OUT="${OUT:-/tmp/gpu_check_out}"
WORK=/tmp/gpu_check
PY=${PY:-python3}
mkdir -p "$OUT" || exit 1
rm -rf "$WORK" && mkdir -p "$WORK" || exit 1
DEADLINE=${GPU_CHECK_DEADLINE:-340}   # [s]: the fits are cut (timeout) so that the script ends by about then
SECONDS=0
say() { printf '\n=== %s (t=%ds)\n' "$*" "$SECONDS"; }

say "install wheels"
if [ -n "${GPU_CHECK_NO_WHEELS:-}" ]; then
    echo "skipped (GPU_CHECK_NO_WHEELS set)"
elif ! ls .whl/*.whl >/dev/null 2>&1; then
    echo "FAILED: no .whl/*.whl here (name .whl in run's carry)"; exit 3
elif ! $PY -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade --target /tmp/site .whl/*.whl \
        >"$WORK/pip_install.log" 2>&1; then
    echo "FAILED: pip install of .whl/*.whl:"; cat "$WORK/pip_install.log"; exit 3
else
    ls .whl/
fi
export PYTHONPATH=/tmp/site:$PWD/src${PYTHONPATH:+:$PYTHONPATH}
export OMP_WAIT_POLICY=PASSIVE PYTHONUNBUFFERED=1 MPLBACKEND=Agg

if command -v taskset >/dev/null && [ "$(nproc)" -ge 4 ]; then
    PY="taskset -c 0,1 $PY"
    export OMP_NUM_THREADS=2
fi

say "environment"
{
    nvidia-smi -L 2>&1
    nvidia-smi --query-gpu=name,memory.total,driver_version --format=csv,noheader 2>&1
    echo "cpus: $(nproc)"
} | tee "$OUT/check.log"
$PY - <<'EOF' 2>&1 | tee -a "$OUT/check.log"
import sys, platform, torch
print("python", sys.version.split()[0], platform.machine())
print("torch", torch.__version__, "| cuda", torch.version.cuda, "| cuda available:", torch.cuda.is_available(),
      "| threads", torch.get_num_threads())
if torch.cuda.is_available():
    print("device 0:", torch.cuda.get_device_name(0))
import numpy, scipy, trimesh, igl, cholespy, triangle, rtree, ezdxf, unsew
print("numpy", numpy.__version__, "| scipy", scipy.__version__, "| trimesh", trimesh.__version__,
      "| ezdxf", ezdxf.__version__, "| unsew from", unsew.__file__)
EOF
[ "${PIPESTATUS[0]}" = 0 ] || { echo "FAILED: imports (see above)"; exit 4; }

say "pytest: the CUDA tests + the fit CLI tests"
# the tests that run on CUDA (skipped without it): the SDF query, phase two and the drape on cuda
# against cpu, the CLI fit on cuda; in test_fit_cli.py
# test_unavailable_device is expected to SKIP here ("a CUDA device is present").
timeout 150 $PY -m pytest -q -p no:cacheprovider -rs \
    tests/body/test_sdf.py::test_query_on_cuda tests/fit/test_cuda.py tests/sim/test_sim_device.py \
    tests/commands/test_fit_cli.py 2>&1 | tee -a "$OUT/check.log"
PYTEST_RC=${PIPESTATUS[0]}
echo "pytest exit code: $PYTEST_RC"

say "make the small case (cpu, once)"
# tests/fit/test_fit_small.py's SMALL settings, as a fit config for the CLI
cat >"$WORK/small.yaml" <<'EOF'
drape:
  edge_length: 0.04
  steps: 8
  sew_steps: 60
  settle_steps: 20
optimizer:
  iterations: 3
loss:
  target_points: 1500
material:
  start: cotton
  start_iteration: 1
EOF
timeout 90 $PY - "$WORK" <<'EOF' 2>&1 | tail -5
import sys, time
from pathlib import Path
from unsew.fit.config import load_config
from unsew.fit.demo import make_truth_case
w = Path(sys.argv[1])
t = time.perf_counter()
d = make_truth_case(w / "case", settings=load_config(w / "small.yaml").drape)
print(f"case {d} made in {time.perf_counter() - t:.1f} s")
EOF
[ -f "$WORK/case/target.obj" ] || { echo "FAILED: no case made"; exit 5; }

: >"$OUT/fits.log"
fit() {  # fit DEVICE NAME LIMIT_S [flags...]: a CLI fit of the case, timed; metrics.json -> $OUT/metrics_NAME.json
    local dev=$1 name=$2 limit=$3 t1 t2 rc
    shift 3
    [ $((DEADLINE - SECONDS)) -lt "$limit" ] && limit=$((DEADLINE - SECONDS))
    if [ "$limit" -lt 15 ]; then
        say "fit $name skipped: ${SECONDS}s used, deadline ${DEADLINE}s"; echo "### fit $name skipped" >>"$OUT/fits.log"; return
    fi
    say "fit $name (--device $dev $*; limit ${limit}s)"
    echo "### fit $name: --device $dev $*" >>"$OUT/fits.log"
    t1=$(date +%s.%N)
    timeout "$limit" $PY -m unsew fit "$WORK/case" --out "$WORK/fit_$name" --config "$WORK/small.yaml" \
        --device "$dev" --no-progress "$@" >"$WORK/fit_$name.log" 2>&1
    rc=$?
    t2=$(date +%s.%N)
    cat "$WORK/fit_$name.log" >>"$OUT/fits.log"
    tail -4 "$WORK/fit_$name.log"
    [ "$rc" = 124 ] && echo "TIMED OUT after $limit s" | tee -a "$OUT/fits.log"
    cp "$WORK/fit_$name/metrics.json" "$OUT/metrics_$name.json" 2>/dev/null || echo "no metrics.json for $name"
    awk -v a="$t1" -v b="$t2" 'BEGIN { printf "%.1f\n", b - a }' >"$WORK/wall_$name"
    echo "$rc" >"$WORK/rc_$name"
    echo "fit $name: exit $rc, wall $(cat "$WORK/wall_$name") s" | tee -a "$OUT/fits.log"
}
fit cuda cuda 200
fit cpu cpu 200
MEDIUM="--edge-length 0.03 --iterations 12 --steps 12"
if [ "$SECONDS" -lt 150 ]; then
    fit cuda cuda_medium 120 $MEDIUM
    fit cpu cpu_medium 120 $MEDIUM
else
    say "medium fits skipped: ${SECONDS}s used already"
fi

say "summary"
$PY - "$WORK" "$OUT" "$PYTEST_RC" <<'EOF' 2>&1 | tee "$OUT/summary.txt"
import json, sys
from pathlib import Path
work, out, pytest_rc = Path(sys.argv[1]), Path(sys.argv[2]), sys.argv[3]
print(f"pytest exit code: {pytest_rc}")
print("fit (small: tests' small mode; medium: 3 cm mesh, 12 iterations, 12 steps); times in s")
print(f"{'run':<12} {'exit':>4} {'wall':>6} {'fit_total':>9} {'optim':>6} {'chamfer_mm':>10} {'base_mm':>7} {'iters':>5} {'peak_MB':>7}")
for name in ("cuda", "cpu", "cuda_medium", "cpu_medium"):
    if not (work / f"rc_{name}").exists():
        continue
    rc = (work / f"rc_{name}").read_text().strip()
    wall = (work / f"wall_{name}").read_text().strip()
    tot = opt = ch = base = it = peak = "-"
    try:
        m = json.loads((out / f"metrics_{name}.json").read_text())
        t = m.get("timings_s", {})
        tot, opt = f"{t.get('total_s', float('nan')):.1f}", f"{t.get('optimization_s', float('nan')):.1f}"
        ch, base = f"{m['surface']['chamfer_mm']:.2f}", f"{m['surface_base']['chamfer_mm']:.2f}"
        it, peak = m.get("iterations", "-"), f"{m.get('peak_memory_mb', float('nan')):.0f}"
    except FileNotFoundError:
        ch = "(none)"
    except Exception as e:  # noqa: BLE001
        ch = f"({type(e).__name__})"
    print(f"{name:<12} {rc:>4} {wall:>6} {tot:>9} {opt:>6} {ch:>10} {base:>7} {it!s:>5} {peak:>7}")
EOF
say "done"
