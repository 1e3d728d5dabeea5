#!/usr/bin/env bash
# A PrairieLearn grade as PrairieLearn runs it (prairielearn/entrypoint on a job folder), warm and
# cold: the whole hand-in (every deliverable's saved frames and code, the Blender half; the files
# flat, as PrairieLearn's upload keeps them; the specular code left at the diffuse reference, so
# one deliverable fails and is explained) and the checkpoint question (the specular pair alone).
#   warm: the references already in the store, as the grader image warms them at build time
#   cold: an empty store, every reference rendered during the grade (an image built without warming)
# Each run is a new process on a new copy of the job; every run's code differs in an expression
# (not a comment: Mesa caches programs by IR), so no run reuses another's compiled student program.
#   bench/prairielearn_bench.sh [runs, default 5] [SHADELAB, default build/shadelab]
# Prints the median, min and max seconds of each. SHADELAB_BENCH_LIMITS=prairielearn runs each
# grade inside a cgroup with PrairieLearn's external-grader limits (0.9 of one CPU, 2 GiB;
# apps/grader-host/src/lib/config.ts): cgroup v2, or v1's cpu and memory controllers; needs root.
# There each kind also reports the cgroup's peak memory over its runs. SHADELAB_CORES=64 beside it
# sizes the grader's pool as a 64-core host would without reading the cgroup (before it did).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
runs=${1:-5}
bin=$(readlink -f "${2:-$root/build/shadelab}")
work=$(mktemp -d -t shadelab-pl-bench.XXXXXX)
trap 'rm -rf "$work"' EXIT
angles=0,19.88,39.79,59.95,79.7,99.83,119.74,139.91,159.77

hand_in=$work/hand-in
mkdir -p "$hand_in"
for p in normals diffuse specular; do "$bin" render --preset "$p" --prefix "$p" --frames-dir "$hand_in" --angles "$angles" >/dev/null; done
for lens in 25 50 100; do cp "$root/tests/blender_half/blender_camera_$lens.png" "$hand_in/camera_$lens.png"; done
cp "$root/tests/blender_half/blender_two_objects_eevee.png" "$hand_in/eevee0001.png"
echo '{}' >"$hand_in/HW2.ipynb"
"$bin" course warm --cache-dir "$work/warm-store" >/dev/null

# A job for run $2 of kind $1 (hand-in, checkpoint) in $3.
job() {
  local kind=$1 run=$2 dir=$3
  mkdir -p "$dir/student" "$dir/data"
  # The run's own program: the colour scaled by a factor that differs in the 7th digit.
  local factor edit
  factor=$(printf '1.%06d' "$run")
  edit="s/fragColor = \(.*\);/fragColor = (\1) * $factor;/"
  sed "$edit" "$root/shaders/normals_frag.js" >"$dir/student/starter_frag.js"
  cp "$root/shaders/normals_vert.js" "$dir/student/starter_vert.js"
  cp "$root/shaders/specular_vert.js" "$dir/student/phong_vert.js"
  if [[ $kind == hand-in ]]; then
    cp "$hand_in"/* "$dir/student/"
    sed "$edit" "$root/shaders/diffuse_frag.js" >"$dir/student/phong_frag.js"
    echo '{"params": {"shadelab": {}}}' >"$dir/data/data.json"
  else
    rm "$dir/student/starter_frag.js" "$dir/student/starter_vert.js"
    sed "$edit" "$root/shaders/specular_frag.js" >"$dir/student/phong_frag.js"
    echo '{"params": {"shadelab": {"checkpoint": "specular"}}}' >"$dir/data/data.json"
  fi
}

# Seconds of one entrypoint run on a fresh job; the results file must be gradable.
grade_once() {
  local kind=$1 store=$2 run=$3
  local dir=$work/job-$kind-$run
  job "$kind" "$run" "$dir"
  local t0 t1
  t0=$(date +%s.%N)
  PRAIRIELEARN_JOB=$dir SHADELAB_BIN=$bin SHADELAB_REFERENCE_STORE=$store SHADELAB_TIME_LIMIT_S=300 \
    in_limits bash "$root/prairielearn/entrypoint" >/dev/null
  t1=$(date +%s.%N)
  grep -q '"gradable": true' "$dir/results/results.json" || { echo "not gradable: $(head -c 400 "$dir/results/results.json")" >&2; exit 1; }
  rm -rf "$dir"
  echo "$t1 - $t0" | bc
}

# Runs a command in PrairieLearn's grader limits where SHADELAB_BENCH_LIMITS asks for them.
limits=${SHADELAB_BENCH_LIMITS:-}
group=shadelab-pl-bench-$$
if [[ $limits == prairielearn ]]; then
  if [[ -f /sys/fs/cgroup/cgroup.controllers ]]; then
    groups=(/sys/fs/cgroup/$group)
    mkdir "${groups[0]}"
    echo '90000 100000' >"${groups[0]}/cpu.max"
    echo $((2 << 30)) >"${groups[0]}/memory.max"
  else
    groups=(/sys/fs/cgroup/cpu/$group /sys/fs/cgroup/memory/$group)
    mkdir "${groups[@]}"
    echo 90000 >"${groups[0]}/cpu.cfs_quota_us"
    echo $((2 << 30)) >"${groups[1]}/memory.limit_in_bytes"
  fi
  trap 'rm -rf "$work"; sleep 0.2; rmdir "${groups[@]}" 2>/dev/null || true' EXIT
fi
# The cgroup's peak memory since the last reset, in MiB ("" outside the limits).
peak_mib() {
  [[ $limits == prairielearn ]] || return 0
  local f=${groups[-1]}/memory.max_usage_in_bytes
  [[ -f $f ]] || f=${groups[0]}/memory.peak
  [[ -f $f ]] && echo $(($(cat "$f") >> 20))
}
reset_peak() {
  [[ $limits == prairielearn ]] || return 0
  local f=${groups[-1]}/memory.max_usage_in_bytes
  [[ -f $f ]] && echo 0 >"$f" 2>/dev/null || true
}
in_limits() {
  if [[ $limits != prairielearn ]]; then "$@"; return; fi
  # shellcheck disable=SC2016
  sh -c 'for g in "$@"; do [ "$g" = -- ] && break; echo $$ >"$g/cgroup.procs"; done; while [ "$1" != -- ]; do shift; done; shift; exec "$@"' \
    sh "${groups[@]}" -- "$@"
}

summary() { sort -n | awk '{a[NR]=$1} END {printf "median %.2f s (min %.2f, max %.2f, %d runs)\n", a[int((NR+1)/2)], a[1], a[NR], NR}'; }

echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')${limits:+, in the PrairieLearn grader limits (0.9 CPU, 2 GiB)}"
for kind in hand-in checkpoint; do
  for temperature in warm cold; do
    reset_peak
    line=$(for ((i = 0; i < runs; i++)); do
      if [[ $temperature == warm ]]; then store=$work/warm-store; else store=$work/cold-store-$i; fi
      grade_once "$kind" "$store" "$((i + 1))"
      rm -rf "$work/cold-store-$i"
    done | summary)
    peak=$(peak_mib)
    echo "$kind, $temperature: $line${peak:+, $peak MiB peak}"
  done
done
