#!/usr/bin/env bash
# Gradescope runs this once, as root, when it builds the autograder's image: autograder.zip is
# unpacked into /autograder/source (ShadeLab's sources, this file and run_autograder at its
# root). It installs what building ShadeLab needs and builds the shadelab binary there; no GPU is
# needed (Mesa's llvmpipe renders on the CPU, as in the student's grading everywhere else).
set -euo pipefail
source_dir=${AUTOGRADER_ROOT:-/autograder}/source
cd "$source_dir"
bash tools/setup.sh build
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHADELAB_BUILD_TESTS=OFF -DSHADELAB_BUILD_BENCH=OFF
cmake --build build -j "$(nproc)"
# The course's references and known mistakes, rendered once now, not once per student.
bash gradescope/warm_references.sh
# Gradescope runs /autograder/run_autograder; keep it executable whatever the zip kept.
install -m 755 run_autograder "${AUTOGRADER_ROOT:-/autograder}/run_autograder"
