#!/usr/bin/env bash
# The suite under sanitizers, in its own build folder:
#   tools/sanitize.sh address   ASan + UBSan (build-asan/): every test, the real EGL context, the
#                               real server and its workers (the workers are the same binary, so
#                               they run instrumented too)
#   tools/sanitize.sh thread    TSan (build-tsan/): the concurrency tests: the pool, the cache and
#                               queue, the connection layer, the HTTP API, tenants, the shared store
# Extra arguments go to ctest (e.g. -L http). Suppressions, each with its reason, are in
# tools/sanitizers/: only what lies inside Mesa or another system library.
set -euo pipefail
cd "$(dirname "$0")/.."
kind=${1:-address}
shift || true
root=$PWD
case $kind in
  address)
    build=build-asan
    flags=(-DSHADELAB_SANITIZE=ON)
    labels=()
    # Leaks are checked by the fuzz targets (tools/fuzz.sh); here Mesa's and (in the tests) OpenImageIO's
    # process-lifetime allocations (caches, the DRI driver's screen) would report at exit.
    export ASAN_OPTIONS=detect_leaks=0:abort_on_error=1:detect_stack_use_after_return=0
    export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1:suppressions=$root/tools/sanitizers/ubsan.supp
    ;;
  thread)
    build=build-tsan
    flags=(-DCMAKE_CXX_FLAGS="-fsanitize=thread -fno-omit-frame-pointer" -DCMAKE_EXE_LINKER_FLAGS=-fsanitize=thread)
    labels=(-L "connection|http|tenant|store|metrics|wire|fault")
    export TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:history_size=7:suppressions=$root/tools/sanitizers/tsan.supp"
    ;;
  *) echo "usage: tools/sanitize.sh address|thread [ctest args]" >&2; exit 2 ;;
esac
tools/setup.sh
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADELAB_BUILD_BENCH=OFF "${flags[@]}" >/dev/null
cmake --build "$build" -j "$(nproc)"
(cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)
cd "$build"
ctest --output-on-failure -j "$(nproc)" --timeout 900 "${labels[@]}" "$@"
