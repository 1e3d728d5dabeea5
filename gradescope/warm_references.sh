#!/usr/bin/env bash
# Renders the course's references and known mistakes once into the autograder's reference store,
# so that grading a student costs that student's renders, not the grader's (docs/grading.md).
# setup.sh runs it when Gradescope builds the image; run_autograder reads the same folder.
#
#   AUTOGRADER_ROOT  where Gradescope's folders are (default /autograder)
#   SHADELAB_BIN     the shadelab binary (default: the one setup.sh built)
set -euo pipefail
root=${AUTOGRADER_ROOT:-/autograder}
bin=${SHADELAB_BIN:-$root/source/build/shadelab}
course=()
[[ -f $root/source/course/course.json ]] && course=(--course "$root/source/course/course.json")
"$bin" course warm --cache-dir "$root/source/reference-store" "${course[@]}"
