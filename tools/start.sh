#!/usr/bin/env bash
# Quick start, command 1: set up, build, and run the main job.
# Until the HTTP service lands this renders the default grid (specular bunny) to grid.png.
set -euo pipefail
cd "$(dirname "$0")/.."
tools/setup.sh
tools/build.sh
exec build/shadelab render --preset specular --mesh bunny --grid grid.png --timings "$@"
