#!/usr/bin/env bash
# A class whose students write the homework as a tutorial does, not as the course's reference
# does (`lightDir`, `reflectDir`, `spec` where the reference writes L, R and the exponent's
# constant): ten with one mistake, one with two, one with three, beside classmates who pass (issue
# 53, item 1: candidates aligned with the class's passing programs). Counts, the same on any
# machine: how many failing students the first search repaired (beside the reference alone), how
# many the second (beside the class), and what the second cost in screens and renders. Then the
# batch timed with and without the second search (`--class-candidates 0`), alternating in one
# sitting, each run's first changing. docs/grading.md keeps the figures.
#   bench/class_repair_bench.sh [repeats, default 3]      SHADELAB_BIN: another build's shadelab
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
repeats=${1:-3}
bin=${SHADELAB_BIN:-$root/build/shadelab}
work=$(mktemp -d -t shadelab-class-repair.XXXXXX)
trap 'rm -rf "$work"' EXIT

python3 - "$root" "$work/class" <<'PY'
import os, sys, random
root, out = sys.argv[1], sys.argv[2]
vert = open(os.path.join(root, "shaders/specular_vert.js")).read()
frag = open(os.path.join(root, "shaders/specular_frag.js")).read()
head = frag[:frag.index("void main(void) {")]
tutorial = head + """void main(void) {
    vec3 norm = normalize(vNormal);
    vec3 lightDir = normalize(uLightPosition - vPosition);
    float diff = max(dot(norm, lightDir), 0.0);
    vec4 color = uAmbientColor + diff * uDiffuseColor * uLightColor;
    if (diff > 0.0) {
        vec3 viewDir = normalize(-vPosition);
        vec3 reflectDir = reflect(-lightDir, norm);
        float spec = pow(max(dot(viewDir, reflectDir), 0.0), 6.0);
        color += spec * uSpecularColor * uLightColor;
    }
    fragColor = color;
}
`;
"""
mistakes = [  # (name, find, replace) in the tutorial's words
    ("the half vector for R", "reflect(-lightDir, norm)", "normalize(lightDir + viewDir)"),
    ("half-Lambert diffuse", "max(dot(norm, lightDir), 0.0);", "dot(norm, lightDir) * 0.5 + 0.5;"),
    ("the ambient left out", "uAmbientColor + diff * uDiffuseColor", "diff * uDiffuseColor"),
    ("the light's colour left out of the specular", "spec * uSpecularColor * uLightColor", "spec * uSpecularColor"),
    ("L not normalised", "normalize(uLightPosition - vPosition)", "(uLightPosition - vPosition)"),
    ("a fixed view vector", "normalize(-vPosition)", "vec3(0.0, 0.0, 1.0)"),
    ("exponent 32", "0.0), 6.0)", "0.0), 32.0)"),
    ("the specular unclamped", "pow(max(dot(viewDir, reflectDir), 0.0), 6.0)", "pow(dot(viewDir, reflectDir), 6.0)"),
    ("the specular in the diffuse colour", "spec * uSpecularColor", "spec * uDiffuseColor"),
    ("V towards the surface", "normalize(-vPosition)", "normalize(vPosition)"),
    # Two mistakes, each one a classmate's value mends: a pair of the class's edits.
    ("the half vector and the ambient left out", "reflect(-lightDir, norm)|uAmbientColor + diff * uDiffuseColor",
     "normalize(lightDir + viewDir)|diff * uDiffuseColor"),
    # Three: more than a repair's two edits. What a second search costs where it finds nothing.
    ("three mistakes", "reflect(-lightDir, norm)|uAmbientColor + diff * uDiffuseColor|0.0), 6.0)",
     "normalize(lightDir + viewDir)|diff * uDiffuseColor|0.0), 32.0)"),
]
salt = random.randrange(1, 1 << 30)
def student(name, i, v, f):
    d = os.path.join(out, name, "shaders")
    os.makedirs(d)
    # A never-taken branch on the student's own constant: no student is served another's compile.
    f = f.replace("    fragColor = color;", "    if (gl_FragCoord.x < -%d.0) color.r += 1.0;\n    fragColor = color;" % (salt + i), 1)
    open(os.path.join(d, "phong_vert.js"), "w").write(v)
    open(os.path.join(d, "phong_frag.js"), "w").write(f)
for i in range(3): student("pass-reference-%d" % i, i, vert, frag)
for i in range(3): student("pass-tutorial-%d" % i, 10 + i, vert, tutorial)
for i, (name, finds, repls) in enumerate(mistakes):
    f = tutorial
    for find, repl in zip(finds.split("|"), repls.split("|")):
        assert find in f, find
        f = f.replace(find, repl, 1)
    student("fail-%02d" % i, 20 + i, vert, f)
open(os.path.join(out, "..", "mistakes.txt"), "w").write("\n".join("fail-%02d %s" % (i, m[0]) for i, m in enumerate(mistakes)) + "\n")
PY

seconds() { local start=$EPOCHREALTIME; "$@" >/dev/null 2>&1; awk -v a="$start" -v b="$EPOCHREALTIME" 'BEGIN { printf "%.2f", b - a }'; }
export SHADELAB_CACHE_DIR=$work/store
"$bin" course warm >/dev/null 2>&1
echo "machine: $(nproc) cores, $(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | sed 's/^ //'); renderer: $("$bin" info 2>/dev/null | grep -m1 -i renderer | sed 's/^ *//')"
for ((r = 0; r < repeats; r++)); do
  rm -rf "$work/once" "$work/twice"
  # Which goes first alternates: a sitting's first batch is its slowest.
  if ((r % 2 == 0)); then
    once=$(seconds "$bin" grade --submissions "$work/class" --reference specular --class-candidates 0 --out "$work/once")
    twice=$(seconds "$bin" grade --submissions "$work/class" --reference specular --out "$work/twice")
  else
    twice=$(seconds "$bin" grade --submissions "$work/class" --reference specular --out "$work/twice")
    once=$(seconds "$bin" grade --submissions "$work/class" --reference specular --class-candidates 0 --out "$work/once")
  fi
  echo "run $((r + 1)): the class graded with one search: ${once} s; with the second beside the class: ${twice} s"
done
python3 - "$work/twice/graded.jsonl" "$work/mistakes.txt" <<'PY'
import json, sys
first, last = {}, {}
for line in open(sys.argv[1]):
    if not line.strip(): continue
    row = json.loads(line)
    first.setdefault(row["student"], row)
    last[row["student"]] = row
mistakes = dict(l.rstrip("\n").split(" ", 1) for l in open(sys.argv[2]) if l.strip())
failing = [s for s in sorted(last) if not last[s]["pass"]]
def repaired(row): return row["screened"] > 0 and not row["unrepaired"]
again = [s for s in failing if last[s]["withClass"]]
print("passing: %d of %d; failing: %d" % (sum(r["pass"] for r in last.values()), len(last), len(failing)))
print("repaired by the first search (beside the reference): %d of %d" % (sum(repaired(first[s]) for s in failing), len(failing)))
print("repaired after the second (beside the class's %d passing programs): %d of %d"
      % (sum(r["pass"] for r in last.values()), sum(repaired(last[s]) for s in failing), len(failing)))
print("the second search: %d students, %d candidates screened, %d renders at the grade's frames"
      % (len(again), sum(last[s]["screened"] - first[s]["screened"] for s in again), sum(last[s]["renders"] - first[s]["renders"] for s in again)))
print("renders at the grade's frames a student: %.2f after the first search, %.2f after both"
      % (sum(r["renders"] for r in first.values()) / len(first), sum(r["renders"] for r in last.values()) / len(last)))
for s in failing:
    how = "second search" if last[s]["withClass"] and repaired(last[s]) else "first search" if repaired(first[s]) else "not repaired"
    print("  %-45s %-14s %s" % (mistakes.get(s, s), how, last[s]["explanation"]))
PY
