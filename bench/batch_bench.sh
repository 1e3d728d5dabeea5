#!/usr/bin/env bash
# A class batch two ways on this machine (docs/deploy.md keeps the figures):
#   1. `shadelab grade --submissions` in one process (its own render workers);
#   2. `shadelab grade --submissions --server` through tools/cluster.sh (nginx, Redis, N replicas).
#   bench/batch_bench.sh [students, default 60] [replicas, default 3]
# Each student's fragment shader differs in an expression (not a comment: Mesa caches programs by
# their IR), and each run uses new ones, so no run is served from a cache.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
students=${1:-60} replicas=${2:-3}
bin=$root/build/shadelab
work=$(mktemp -d -t shadelab-batch.XXXXXX)
trap 'kill $cluster_pid 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT
cluster_pid=""

make_class() {  # DIR SEED
  local salt=$2
  for ((i = 0; i < students; i++)); do
    local d=$1/s$(printf %03d "$i")/shaders
    mkdir -p "$d"
    cp "$root/shaders/specular_vert.js" "$d/phong_vert.js"
    sed "s|void main(void) {|void main(void) {\n    if (gl_FragCoord.x < -$salt$i.0) discard;|" "$root/shaders/specular_frag.js" >"$d/phong_frag.js"
  done
}

seconds() { local start=$EPOCHREALTIME; "$@" >/dev/null 2>&1; awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.1f", b - a }'; }
rate() { awk -v n="$1" -v s="$2" 'BEGIN { printf "%.2f", n / s }'; }

make_class "$work/local" "1$RANDOM"
make_class "$work/cluster" "2$RANDOM"
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"
echo "students: $students, canonical size (640x480, 9 frames), specular checkpoint"
local_s=$(seconds "$bin" grade --submissions "$work/local" --reference specular --out "$work/local-grades")
echo "in one process:              ${local_s} s  ($(rate "$students" "$local_s") submissions/s)"

port=$((20000 + RANDOM % 20000))
SHADELAB_NGINX_API_RATE=1000 SHADELAB_NGINX_API_BURST=1000 \
  "$root/tools/cluster.sh" --replicas "$replicas" --port "$port" --dir "$work/cluster-run" 2>"$work/cluster.log" &
cluster_pid=$!
until grep -q "listening on" "$work/cluster.log"; do sleep 0.2; done
cluster_s=$(seconds "$bin" grade --submissions "$work/cluster" --reference specular --server "http://127.0.0.1:$port" \
  --concurrency 6 --out "$work/cluster-grades")
echo "through $replicas replicas + nginx: ${cluster_s} s  ($(rate "$students" "$cluster_s") submissions/s)"
for g in local-grades cluster-grades; do
  echo "$g: $(grep -c ',true,' "$work/$g/summary.csv") of $students passed"
done
