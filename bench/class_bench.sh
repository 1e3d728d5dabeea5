#!/usr/bin/env bash
# A class of 24 specular submissions graded in one process, against rendering the canonical job
# once per student (issue: "a class graded at the speed of rendering"). docs/performance-log.md keeps
# the figures. The class: 8 correct, 8 with a mistake the catalogue holds (its own edits, from the
# course profile), 8 with one it does not (another exponent, the light's colour ignored, ...).
# Every fragment shader differs in a never-taken branch on its own constant (Mesa caches programs
# by their IR), so no student is served from another's compile; the branch changes a colour, not a
# `discard`, which would make a grade draw its lights one at a time (docs/grading.md). The reference store is warmed first (`course warm`, as a
# Gradescope image is built), then both sides run on an idle machine, whole processes counted; the
# renders the grades drew are counted too (the journal's `renders`), a figure no load moves.
#   bench/class_bench.sh [repeats, default 1]      SHADELAB_BIN: another build's shadelab
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
repeats=${1:-1}
bin=${SHADELAB_BIN:-$root/build/shadelab}
work=$(mktemp -d -t shadelab-class.XXXXXX)
trap 'rm -rf "$work"' EXIT

python3 - "$root" "$work/class" <<'PY'
import json, os, sys, random
root, out = sys.argv[1], sys.argv[2]
course = json.load(open(os.path.join(root, "courses/cs148-summer2022.json")))
vert = open(os.path.join(root, "shaders/specular_vert.js")).read()
frag = open(os.path.join(root, "shaders/specular_frag.js")).read()
spec = next(c for c in course["checkpoints"] if c["name"] == "specular")
catalogued = [m for m in spec["mistakes"] if "edits" in m]
uncatalogued = [("float specularAlpha = 6.0;", "float specularAlpha = 12.0;"),
                ("float specularAlpha = 6.0;", "float specularAlpha = 3.0;"),
                ("uDiffuseColor * uLightColor", "uDiffuseColor"),
                ("uDiffuseColor * uLightColor", "0.5 * uDiffuseColor * uLightColor")]
salt = random.randrange(1, 1 << 30)
def student(i, v, f):
    d = os.path.join(out, "s%02d" % i, "shaders")
    os.makedirs(d)
    f = f.replace("    fragColor = color;", "    if (gl_FragCoord.x < -%d.0) color.r += 1.0;\n    fragColor = color;" % (salt + i), 1)
    assert "gl_FragCoord" in f
    open(os.path.join(d, "phong_vert.js"), "w").write(v)
    open(os.path.join(d, "phong_frag.js"), "w").write(f)
for i in range(24):
    v, f = vert, frag
    if 8 <= i < 16:
        for e in catalogued[(i - 8) % len(catalogued)]["edits"]:
            if e["stage"] == "vertex": v = v.replace(e["find"], e["replace"])
            else: f = f.replace(e["find"], e["replace"])
    elif i >= 16:
        find, repl = uncatalogued[(i - 16) % len(uncatalogued)]
        assert find in f, find
        f = f.replace(find, repl)
    student(i, v, f)
PY

seconds() { local start=$EPOCHREALTIME; "$@" >/dev/null 2>&1; awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }'; }
export SHADELAB_CACHE_DIR=$work/store
"$bin" course warm >/dev/null 2>&1
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); renderer: $("$bin" info 2>/dev/null | grep -m1 -i renderer | sed 's/^ *//')"
for ((r = 0; r < repeats; r++)); do
  render_s=0
  for d in "$work"/class/s*; do
    s=$(seconds "$bin" render --vert "$d/shaders/phong_vert.js" --frag "$d/shaders/phong_frag.js" --grid "$work/grid.png")
    render_s=$(awk -v a="$render_s" -v b="$s" 'BEGIN { printf "%.2f", a + b }')
  done
  rm -rf "$work/grades"
  grade_s=$(seconds "$bin" grade --submissions "$work/class" --reference specular --out "$work/grades")
  echo "24 renders of the job, one process each: ${render_s} s; the class graded: ${grade_s} s ($(awk -v g="$grade_s" -v r="$render_s" 'BEGIN { printf "%.2f", g / r }')x)"
done
echo "passed: $(grep -c ',true,' "$work/grades/summary.csv") of 24 (8 are correct)"
# The same cost counted, not timed (the same on any machine): the renders each grade drew at the
# grade's frames (its own, each repair's confirmation, a second grade) and the candidates screened.
python3 - "$work/grades/graded.jsonl" <<'PY'
import json, sys
last = {}  # a student searched again beside the class has a second line, counting both searches
for l in open(sys.argv[1]):
    if l.strip(): last[json.loads(l)["student"]] = json.loads(l)
rows = list(last.values())
renders, screened = sum(r["renders"] for r in rows), sum(r["screened"] for r in rows)
print("counted: %d renders at the grade's frames for %d students (%.2f a student), %d candidates screened on a small canvas"
      % (renders, len(rows), renders / len(rows), screened))
PY
awk -F, 'NR > 1 { print $0 }' "$work/grades/summary.csv" | cut -d, -f1-5 | sort | head -24
