#!/usr/bin/env bash
# Runs every fuzz target (tests/fuzz) for SECONDS each (default 60), NPROC at a time, and prints
# each one's executions, speed and coverage. Builds build-fuzz/ with clang, libFuzzer, ASan and
# UBSan first. Every crash, leak, timeout or out-of-memory input found is written to
# tests/fuzz/regressions/<target>/, which the test suite replays (ctest -L fuzz); the run then
# fails. New coverage goes to build-fuzz/corpus/<target>/ (seeded from tests/fuzz/corpus), so runs
# build on each other without touching the repository's seeds.
#
# SHADELAB_FUZZ_SEED=N fixes libFuzzer's seed, so a run retraces the same inputs (as far as the
# machine's speed takes it in SECONDS): the README's test command uses it, so CI checks the same
# ground each time; unset (the default), every run explores anew.
#
#   tools/fuzz.sh [SECONDS] [TARGET...]      e.g. tools/fuzz.sh 600 mesh_loader
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-60}
shift || true
root=$PWD
build=$root/build-fuzz

if [[ ! -f $build/build.ninja ]]; then
  CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DSHADELAB_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
fi
# Quiet when it builds; ninja writes a compiler's or linker's errors to stdout, so they are shown
# when it does not (a fuzz target that does not link is a red run that should say why).
if ! build_log=$(cmake --build "$build" -j "$(nproc)" 2>&1); then
  printf '%s\n' "$build_log" | grep -E -B2 -A8 'error|undefined reference' | head -60 >&2
  echo "fuzz: the fuzz build failed (build-fuzz/); its errors are above" >&2
  exit 1
fi

targets=("$@")
if ((${#targets[@]} == 0)); then
  for f in tests/fuzz/targets/*.cpp; do targets+=("$(basename "$f" .cpp)"); done
fi

run_target() {
  local target=$1 seconds=$2 root=$3 build=$4
  local corpus=$build/corpus/$target regressions=$root/tests/fuzz/regressions/$target log=$build/logs/$target.log
  mkdir -p "$corpus" "$regressions" "$(dirname "$log")"
  local dict=()
  [[ -f $root/tests/fuzz/dict/$target.dict ]] && dict=(-dict="$root/tests/fuzz/dict/$target.dict")
  # -timeout: an input slower than 10 s is a finding (a hang); -rss_limit_mb: so is one that
  # needs 2 GB, the workers' memory cap. Leaks are findings too (ASan's leak check is on).
  LSAN_OPTIONS=suppressions=$root/tools/sanitizers/lsan.supp:print_suppressions=0 \
    "$build/tests/fuzz/fuzz_$target" "$corpus" "$root/tests/fuzz/corpus/$target" "$regressions" \
    "${dict[@]}" ${SHADELAB_FUZZ_SEED:+-seed="$SHADELAB_FUZZ_SEED"} -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$regressions/" >"$log" 2>&1
  local status=$?
  # A crash wholly inside a system library (its sanitizer summary names only that library, or
  # assimp's own assertion fired) cannot be fixed here: the service survives it because such
  # parsers run only in render workers (tests/fault_test.cpp replays tests/fuzz/contained/ through
  # the real server). It is kept in contained/ and reported; anything else fails the run.
  local contained=""
  if ((status != 0)) && grep -qE '^SUMMARY: AddressSanitizer: [A-Za-z-]+ \(/(usr/)?lib/[^)]*\.so|ai_assert failure' "$log"; then
    mkdir -p "$root/tests/fuzz/contained/$target"
    # Only this run's input moves: the regressions already committed stay where they are.
    local found
    found=$(sed -n 's/.*Test unit written to //p' "$log" | tail -1)
    [[ -n $found && -e $found ]] && mv "$found" "$root/tests/fuzz/contained/$target/"
    contained="stopped on a crash inside a system library: kept in tests/fuzz/contained/$target"
    status=0
  fi
  local inited done_line execs speed
  inited=$(grep -m1 -o 'INITED cov: [0-9]*' "$log" | grep -o '[0-9]*$' || echo 0)
  done_line=$(grep -E '^#[0-9]+\s+DONE' "$log" | tail -1)
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  speed=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  local cov=${done_line#*cov: }
  cov=${cov%% *}
  printf '%-18s %12s execs %8s/s   coverage %5s -> %-5s %s\n' "$target" "${execs:-0}" "${speed:-0}" "$inited" "${cov:-?}" \
    "$( ((status == 0)) && echo "${contained:-ok}" || echo "FOUND A CRASH: see $log")"
  return $status
}
export -f run_target

echo "fuzz: ${#targets[@]} targets, ${seconds} s each, $(nproc) at a time; logs in $build/logs"
failed=0
printf '%s\n' "${targets[@]}" | xargs -P "$(nproc)" -I{} bash -c 'run_target "$@"' _ {} "$seconds" "$root" "$build" || failed=1
if ((failed)); then
  echo "fuzz: crashes were found; the inputs are in tests/fuzz/regressions/ (commit them with the fix)" >&2
  git -C "$root" status --short tests/fuzz/regressions >&2 || true
  exit 1
fi
