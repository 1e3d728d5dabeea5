#!/usr/bin/env bash
# Quick start, command 1: set up, build, and serve ShadeLab on port 8889 (the handout's port).
# Extra arguments go to `shadelab serve` (see `build/shadelab serve --help`).
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
tools/build.sh
exec build/shadelab serve --port "${SHADELAB_PORT:-8889}" "$@"
