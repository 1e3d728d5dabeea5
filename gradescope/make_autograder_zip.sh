#!/usr/bin/env bash
# Builds autograder.zip for a Gradescope programming assignment: the committed sources of this
# checkout (git archive HEAD) with setup.sh and run_autograder at the zip's root, as Gradescope
# expects. Upload it under "Configure Autograder" (Ubuntu base image); building takes a few minutes.
#
#   gradescope/make_autograder_zip.sh [OUTPUT] [COURSE_FOLDER]
#
# OUTPUT defaults to autograder.zip in the current folder. COURSE_FOLDER, when given, is the TA's
# course profile (docs/course-profile.md) as a folder: its course.json and the files it names
# relative to it, added to the zip as course/ (run_autograder then grades by it). The profile is
# checked first (`shadelab course check`, when a built shadelab is at hand), so a bad one is
# caught here, not in Gradescope.
set -euo pipefail
output=$(realpath -m "${1:-autograder.zip}")
course=${2:-}
here=$(cd "$(dirname "$0")" && pwd)
cd "$here/.."
if [[ -n $course ]]; then
  [[ -f $course/course.json ]] || { echo "make_autograder_zip: $course/course.json does not exist" >&2; exit 1; }
  [[ -x build/shadelab ]] && build/shadelab course check "$course/course.json" >/dev/null
fi
git archive --format=zip -o "$output" --add-file="$here/setup.sh" --add-file="$here/run_autograder" HEAD
if [[ -n $course ]]; then
  staging=$(mktemp -d)
  trap 'rm -rf "$staging"' EXIT
  cp -r "$course" "$staging/course"
  (cd "$staging" && zip -qr "$output" course)
fi
echo "wrote $output ($(git rev-parse --short HEAD)${course:+, course $course})"
