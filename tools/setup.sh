#!/usr/bin/env bash
# Installs the Debian 12 packages ShadeLab needs, only those that are missing.
# Used by the README's two commands and by the Dockerfile, so all three agree.
#
#   tools/setup.sh          everything: building, running, every test, the cluster, fuzzing
#   tools/setup.sh build    only what building and running the shadelab binary needs (the
#                           Gradescope autograder's image: gradescope/setup.sh)
#   tools/setup.sh runtime  only the libraries a built shadelab loads, and Mesa's EGL and llvmpipe
#                           (the PrairieLearn grader image's last stage: Dockerfile)
set -euo pipefail
profile=${1:-all}
[[ $profile == all || $profile == build || $profile == runtime ]] || { echo "usage: tools/setup.sh [build|runtime]" >&2; exit 2; }

build_packages=(
  # toolchain
  build-essential cmake ninja-build pkg-config git ca-certificates
  # headless GL: EGL + GLES headers, Mesa's EGL and llvmpipe (the CPU device)
  libegl-dev libgles-dev libegl-mesa0 libgl1-mesa-dri
  # libraries
  libglm-dev libopenexr-dev libopencolorio-dev nlohmann-json3-dev libassimp-dev libcli11-dev
  libcpp-httplib-dev libssl-dev zlib1g-dev libbrotli-dev libzip-dev
  # the floor benchmark writes its PNG with libpng directly (bench/floor_bench.cpp)
  libpng-dev
  # WebGL 2's shader rules are checked on glslang's AST (Khronos' reference GLSL front end)
  glslang-dev
  # the optional shared store (Redis client)
  libhiredis-dev
  # the reference store's entries are zstd
  libzstd-dev
  # Blender's OCIO config and Filmic tables: the scenes' Filmic view transform is baked from them
  blender-data
  # the submission sheet: a student's notebook diffed with the handed-out one (dtl, header-only)
  libdtl-dev
  # the submission sheet: cairo writes the PDF, in DejaVu's fonts
  libcairo2-dev fonts-dejavu-core
)
test_packages=(
  # the GPU check's bundle is packed as .tar.xz (tools/gpu_check/pack.sh; readelf is binutils')
  xz-utils
  # the tests and benchmarks read ShadeLab's PNG and EXR outputs back with OpenImageIO
  libopenimageio-dev
  # the Kubernetes manifests' test (YAML)
  libyaml-cpp-dev
  # the local cluster and its tests: nginx in front of the replicas, Redis behind them
  nginx redis-server
  # tests and benchmarks; the browser tests drive Debian's chromium with playwright-core
  libgtest-dev libgmock-dev libbenchmark-dev chromium
  # the sheet's PDF read back as a reader would: its text (pdftotext) and its pages (pdftoppm)
  poppler-utils
  # the course profile's JSON Schema checked against the reader (tests/course_test.cpp), by Debian's python
  python3 python3-jsonschema
  # gradescope/make_autograder_zip.sh adds a TA's course folder to the zip
  zip
  # the fuzz targets (tools/fuzz.sh): clang with libFuzzer and its sanitizers
  clang libfuzzer-14-dev libclang-rt-14-dev
)
# What `ldd build/shadelab` resolves to on Debian 12, and the drivers EGL loads at run time.
runtime_packages=(
  libegl1 libgles2 libegl-mesa0 libgl1-mesa-dri
  libassimp5 libbrotli1 libcairo2 libcpp-httplib0.11 libhiredis0.14 libopencolorio2.1 libopenexr-3-1-30
  libpng16-16 libssl3 libzip4 libzstd1 zlib1g ca-certificates
)
packages=("${build_packages[@]}")
[[ $profile == runtime ]] && packages=("${runtime_packages[@]}")
[[ $profile == all ]] && packages+=("${test_packages[@]}")
# Node.js runs the browser tests; use the machine's own if it has one, else Debian's.
if [[ $profile == all ]] && { ! command -v node >/dev/null || ! command -v npm >/dev/null; }; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if ((${#missing[@]} == 0)); then
  echo "setup: all ${#packages[@]} packages present"
  exit 0
fi

echo "setup: installing ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "setup: need root or sudo to install packages" >&2; exit 1; }
  sudo=(sudo)
fi
export DEBIAN_FRONTEND=noninteractive
# nginx and redis-server would start their system services on install; ShadeLab starts its own
# instances (tools/cluster.sh, the tests), so the packages' services stay stopped. A policy-rc.d
# that denies every start does that, and is removed again unless the machine already had one.
policy=/usr/sbin/policy-rc.d
if [[ ! -e $policy ]]; then
  printf '#!/bin/sh\nexit 101\n' | "${sudo[@]}" tee "$policy" >/dev/null
  "${sudo[@]}" chmod 755 "$policy"
  trap '"${sudo[@]}" rm -f "$policy"' EXIT
fi
"${sudo[@]}" apt-get update -qq
"${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
