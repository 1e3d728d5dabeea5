#!/usr/bin/env bash
# The GPU check, run from the unpacked bundle (pack.sh): the renderer and its driver, fidelity
# against the approved images, the browser's verdict on every recorded case, and the service's
# figures, each step's whole output in OUT_DIR and its lines that carry a figure in summary.txt.
#
#   sl/run.sh [OUT_DIR=./gpu_check_out]
#   GPU_CHECK_REQUESTS  requests per level of the load benchmark (default 24)
#   GPU_CHECK_SOAK_S    seconds of the 8-client soak (default 30; 0 skips it)
#   GPU_CHECK_WORKERS   GL worker counts the load benchmark also runs at (default "1 2 4 8" and
#                       one per core; empty skips the sweep)
# About 8 minutes on a GPU; longer on llvmpipe, where it runs too. Exits non-zero when a test
# step fails; the figures are written either way.
set -uo pipefail
SL=$(cd "$(dirname "$0")" && pwd)
OUT=$(realpath -m "${1:-./gpu_check_out}"); mkdir -p "$OUT"
BIN=$SL/bin DATA=$SL/data
CORES=$(nproc)
REQUESTS=${GPU_CHECK_REQUESTS:-24} SOAK_S=${GPU_CHECK_SOAK_S:-30}
WORKERS=${GPU_CHECK_WORKERS-$(printf '%s\n' 1 2 4 8 "$CORES" | sort -nu | tr '\n' ' ')}

# The bundle's libraries; glvnd's dispatchers only where the machine has none of its own.
export LD_LIBRARY_PATH=$SL/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
has_system_egl() { for d in /usr/lib/x86_64-linux-gnu /usr/lib64 /usr/lib /lib/x86_64-linux-gnu; do [ -e "$d/libEGL.so.1" ] && return 0; done; return 1; }
has_system_egl || export LD_LIBRARY_PATH=$LD_LIBRARY_PATH:$SL/glvnd
# A driver installed outside glvnd's search path (as on the lent NVIDIA machines).
nvidia_vendor=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
[ -z "${__EGL_VENDOR_LIBRARY_FILENAMES:-}" ] && [ -e "$nvidia_vendor" ] && export __EGL_VENDOR_LIBRARY_FILENAMES=$nvidia_vendor
export SHADELAB_TEST_DATA=$DATA SHADELAB_GOLDEN_FAILURES=$OUT/golden_failures SHADELAB_WEB_ROOT=$DATA/web

failed=0
step() {  # step NAME COMMAND...: its output to OUT/NAME.txt, its time and status to the summary
  local name=$1; shift
  local start=$SECONDS
  "$@" >"$OUT/$name.txt" 2>&1; local rc=$?
  echo "== $name: rc $rc, $((SECONDS - start)) s" | tee -a "$OUT/summary.txt"
  return $rc
}
: >"$OUT/summary.txt"
date -u +"%F %T UTC" >>"$OUT/summary.txt"

# 1. The renderer and its driver.
step egl_probe "$BIN/egl_probe"
step info "$BIN/shadelab" info || failed=1
grep -i -E "renderer|version|vendor|device" "$OUT/info.txt" | head -8 >>"$OUT/summary.txt"

# 2. Fidelity: every preset on every mesh against the approved images (grader's tolerance).
step fidelity "$BIN/golden_test" || failed=1
grep -E "^[a-z]+_[a-z]+: " "$OUT/fidelity.txt" >>"$OUT/summary.txt"

# 3. The browser's verdict on every recorded case, on this driver.
step verdicts "$BIN/webgl_rules_test" --gtest_filter='WebglRulesTest.*' || failed=1
grep -E "^\[  (PASSED|FAILED)|tests ran" "$OUT/verdicts.txt" >>"$OUT/summary.txt"

# 4. The service: launch, a fresh course job over HTTP at 1-16 clients, where its time goes.
step service "$BIN/load_bench" "$BIN/shadelab" "$REQUESTS" || failed=1
grep -E "^start to|^renderer.*cores|^\| [0-9]|^where|^against|^cache|^two-objects|^the first failed|^worker" "$OUT/service.txt" >>"$OUT/summary.txt"
for w in $WORKERS; do
  step "service_workers_$w" "$BIN/load_bench" "$BIN/shadelab" "$REQUESTS" --workers "$w" || failed=1
  grep -E "^start to|^\| [0-9]" "$OUT/service_workers_$w.txt" | sed "s/^/workers $w: /" >>"$OUT/summary.txt"
done
# The soak with the server's own pool (sized to the device), and with one GL worker per core.
if [ "$SOAK_S" -gt 0 ]; then
  for pool in default per_core; do
    if [ $pool = per_core ]; then export SHADELAB_WORKERS=$CORES; fi
    step "soak_$pool" "$BIN/soak_bench" "$BIN/shadelab" "$SOAK_S" || failed=1
    grep -E "^\| (kind|render|grade|scene|hostile|resident|proportional) |^the first unexpected" "$OUT/soak_$pool.txt" | awk '!seen[$0]++' |
      sed "s/^/$pool pool: /" >>"$OUT/summary.txt"
  done
  unset SHADELAB_WORKERS
fi

cat "$OUT/summary.txt"
exit $failed
