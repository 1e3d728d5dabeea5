#!/usr/bin/env bash
# Quick start, command 2: set up, build, and run every test (CTest; real EGL on llvmpipe where
# there is no GPU). .ci/run calls this and nothing else.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
tools/build.sh -DSHADELAB_WERROR=ON
# playwright-core for the browser tests, pinned by tests/browser/package-lock.json (no browser
# download: the tests drive Debian's chromium).
(cd tests/browser && npm ci --no-audit --no-fund --loglevel=error)
(cd build && ctest --output-on-failure -j "$(nproc)" --timeout 300)
# Every fuzz target for 20 s (clang, libFuzzer, ASan, UBSan; build-fuzz/): a crash fails the run
# and leaves its input in tests/fuzz/regressions/. The suite above replayed the corpora already.
# A fixed seed: CI retraces the same inputs each time, so a red run means the change under test
# (new ground is for the long runs, docs/reliability.md).
SHADELAB_FUZZ_SEED=1 tools/fuzz.sh 20
