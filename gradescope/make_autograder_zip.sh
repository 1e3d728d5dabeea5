#!/usr/bin/env bash
# Builds autograder.zip for a Gradescope programming assignment: the committed sources of this
# checkout (git archive HEAD) with setup.sh and run_autograder at the zip's root, as Gradescope
# expects. Upload it under "Configure Autograder" (Ubuntu base image); building takes a few minutes.
#
#   gradescope/make_autograder_zip.sh [OUTPUT]     default: autograder.zip in the current folder
set -euo pipefail
output=$(realpath -m "${1:-autograder.zip}")
here=$(cd "$(dirname "$0")" && pwd)
cd "$here/.."
git archive --format=zip -o "$output" --add-file="$here/setup.sh" --add-file="$here/run_autograder" HEAD
echo "wrote $output ($(git rev-parse --short HEAD))"
