#!/usr/bin/env bash
# The GPU check (tools/gpu_check/) packed from this build and run end to end here, on llvmpipe,
# at its smallest: the bundle loads only its own libraries, every step runs, and each figure the
# check exists for is in its summary.
#   tests/gpu_check_test.sh BUILD_DIR
set -euo pipefail
BUILD=$(cd "$1" && pwd); REPO=$(cd "$(dirname "$0")/.." && pwd)
T=$(mktemp -d); trap 'rm -rf "$T"' EXIT
"$REPO/tools/gpu_check/pack.sh" "$BUILD" "$T/check.tar.xz" >"$T/pack.log" 2>&1 || { cat "$T/pack.log"; exit 1; }
tar -C "$T" -xJf "$T/check.tar.xz"
GPU_CHECK_REQUESTS=2 GPU_CHECK_SOAK_S=0 GPU_CHECK_WORKERS="" "$T/sl/run.sh" "$T/out" >"$T/run.log" 2>&1 || { cat "$T/run.log"; exit 1; }
summary=$T/out/summary.txt
expect() { grep -q -E "$1" "$summary" || { echo "the summary lacks /$1/:"; cat "$summary"; exit 1; }; }
expect "^GL renderer: +llvmpipe"
expect "^\[  PASSED  \] [0-9]+ tests"
expect "^start to /readyz: [0-9]+ ms"
expect "^\| 16 \| 2 \| [0-9]+ \| [0-9]+ \| [0-9.]+ \|$"
expect "^where a 1-client job's time goes \(Server-Timing, p50 ms\): queue [0-9.]+ compile [0-9.]+ render [0-9.]+ readback [0-9.]+ encode [0-9.]+$"
expect "^cache hit \([0-9]+ KB grid\): p50 [0-9.]+ ms, p99 [0-9.]+ ms$"
fidelity=$(grep -c -E "^[a-z]+_[a-z]+: [0-9]+ pixels" "$summary")
[ "$fidelity" -ge 10 ] || { echo "fidelity for $fidelity preset-mesh pairs, not every one"; cat "$summary"; exit 1; }
echo "gpu check ran end to end: $(grep -c '^== ' "$summary") steps"
