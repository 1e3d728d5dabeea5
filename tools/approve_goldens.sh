#!/usr/bin/env bash
# Re-approves the golden images in tests/golden/ from the current renderer. Deliberate: look at
# the new images (git diff shows which changed) before committing them.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/build.sh
SHADELAB_APPROVE_GOLDENS=1 build/tests/golden_test
SHADELAB_APPROVE_GOLDENS=1 build/tests/scene_test --gtest_filter="*Golden*"
git status --short tests/golden
