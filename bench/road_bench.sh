#!/usr/bin/env bash
# A passing and a failing code grade over HTTP (POST /api/grade, the course's specular checkpoint,
# its canvas and bunny), two builds side by side in one sitting: each build's server on its own
# port with warm reference stores, the grades sent to the two alternately, so load and heat fall on
# both alike. Every request's fragment shader differs in an expression (not a comment: Mesa caches
# programs by their IR), so no grade reuses another's program.
#   bench/road_bench.sh BASE_SHADELAB [HEAD_SHADELAB, default build/shadelab] [runs, default 6]
# Prints each build's median, min and max seconds for each grade (the request's wall time).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
base=${1:?usage: bench/road_bench.sh BASE_SHADELAB [HEAD_SHADELAB] [runs]}
head=${2:-$root/build/shadelab}
runs=${3:-6}
work=$(mktemp -d -t shadelab-road.XXXXXX)
pids=()
trap 'kill "${pids[@]}" 2>/dev/null; wait 2>/dev/null; rm -rf "$work"' EXIT

start() {  # NAME BIN: sets $port (not in a subshell: the trap must know each server's pid)
  local log=$work/$1.log
  "$2" serve --port 0 --workers 2 --cache-dir "$work/$1-store" >"$log" 2>&1 &
  pids+=($!)
  until grep -qo 'serving on [^ ]*:[0-9]*' "$log"; do sleep 0.1; done
  port=$(grep -o 'serving on [^ ]*:[0-9]*' "$log" | head -1 | sed 's/.*://')
}
start base "$base"
base_port=$port
start head "$head"
head_port=$port
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //')"

python3 - "$root" "$runs" "$base_port" "$head_port" <<'PY'
import json, statistics, sys, time, urllib.request
root, runs, ports = sys.argv[1], int(sys.argv[2]), {"base": sys.argv[3], "head": sys.argv[4]}
vert = open(root + "/shaders/specular_vert.js").read()
frag = open(root + "/shaders/specular_frag.js").read()
cases = {"passing": frag, "failing": frag.replace("normalize(uLightPosition - vPosition)", "normalize(uLightPosition)")}
assert cases["failing"] != frag
salt = [int(time.time()) % 100000]

def grade(port, fragment):
    salt[0] += 1
    fresh = fragment.replace("void main(void) {", "void main(void) {\n    if (gl_FragCoord.x < -%d.0) discard;" % salt[0], 1)
    body = json.dumps({"reference": "specular", "vertex": vert, "fragment": fresh}).encode()
    req = urllib.request.Request("http://127.0.0.1:%s/api/grade" % port, body, {"Content-Type": "application/json"})
    t = time.perf_counter()
    report = json.load(urllib.request.urlopen(req, timeout=300))
    return time.perf_counter() - t, report["pass"]

for build, port in ports.items():  # warm: the references rendered and stored, the workers' first JIT
    for name, fragment in cases.items():
        grade(port, fragment)
times = {(b, c): [] for b in ports for c in cases}
for _ in range(runs):
    for build, port in ports.items():
        for name, fragment in cases.items():
            seconds, passed = grade(port, fragment)
            assert passed == (name == "passing"), (build, name)
            times[(build, name)].append(seconds)
print("%d runs each, alternating" % runs)
for (build, name), s in sorted(times.items(), key=lambda kv: (kv[0][1], kv[0][0])):
    print("%-8s %-5s median %.3f s  (min %.3f, max %.3f)" % (name, build, statistics.median(s), min(s), max(s)))
PY
