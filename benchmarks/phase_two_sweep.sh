#!/usr/bin/env bash
# Which small-mode settings let phase two lower the pattern error where grading cannot fit?
# Runs `python -m benchmarks phase_two` (the dress taken in 3 cm at the hip, fitted from its
# graded pattern) once per line of SETTINGS below, JOBS at a time, one thread each, and prints
# every run's table with its wall time. Meant for a machine with many cores (the lent device
# machine's 16, beside benchmarks/gpu_check.sh); on 2 cores run a few lines at a time.
#
#   JOBS=12 LIMIT=480 bash benchmarks/phase_two_sweep.sh > sweep.txt
set -u
PY=${PY:-python3}
JOBS=${JOBS:-12}
LIMIT=${LIMIT:-480}
WORK=${SWEEP_WORK:-/tmp/phase_two_sweep}
rm -rf "$WORK" && mkdir -p "$WORK" || exit 1
export OMP_NUM_THREADS=1 OMP_WAIT_POLICY=PASSIVE PYTHONUNBUFFERED=1 MPLBACKEND=Agg
# edge [m], drape steps, iterations, lr [m per step], loss.prior (optional, default 0)
SETTINGS=${SETTINGS:-"0.04 8 6 0.004
0.04 20 6 0.004
0.04 40 6 0.004
0.05 20 6 0.004
0.05 40 6 0.004
0.04 20 10 0.004
0.04 12 10 0.004
0.04 20 6 0.006
0.05 20 8 0.006
0.05 12 8 0.004
0.04 16 8 0.004
0.05 30 6 0.004"}
i=0
while read -r edge steps iters lr prior; do
    prior=${prior:-0}
    [ -z "$edge" ] && continue
    i=$((i + 1))
    while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do sleep 2; done
    (
        t1=$(date +%s)
        timeout "$LIMIT" $PY -m benchmarks phase_two --edge-length "$edge" --steps "$steps" --iterations "$iters" \
            --lr "$lr" --prior "$prior" --warm-steps "$steps" --out "$WORK/run$i" >"$WORK/log$i" 2>&1
        rc=$?
        echo "exit $rc, wall $(( $(date +%s) - t1 )) s" >>"$WORK/log$i"
    ) &
    echo "run$i: edge $edge, steps $steps, iterations $iters, lr $lr, prior $prior" >"$WORK/head$i"
done <<<"$SETTINGS"
wait
for k in $(seq 1 "$i"); do
    echo "### $(cat "$WORK/head$k")"
    grep -v -i "warp\|cuda\|devices\|kernel cache\|\"cpu\"\|/.cache/\|Module anny" "$WORK/log$k" | tail -12
    echo
done
