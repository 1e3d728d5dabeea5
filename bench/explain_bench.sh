#!/usr/bin/env bash
# What reading a failing grade by the homework's formula finds and costs (docs/grading.md, "Why a
# grade failed"). A written set of wrong submissions for the diffuse and specular checkpoints, each
# the course's reference with one change a student makes, graded at the course's canvas; for each,
# whether the explanation names the change (the expected variant, and the changed value's name).
# Then the cost, one sitting, whole processes on a warm reference store: the same failing and
# passing grades with the built-in course and with the same course less its checkpoints' `formula`
# (no explanation), alternating, against one render of the course's job (`shadelab render`).
#   bench/explain_bench.sh [repeats, default 5]      SHADELAB_BIN: another build's shadelab
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
repeats=${1:-5}
bin=${SHADELAB_BIN:-$root/build/shadelab}
work=$(mktemp -d -t shadelab-explain.XXXXXX)
trap 'rm -rf "$work"' EXIT

"$bin" course show > "$work/course.json"
python3 - "$work" <<'PY'
import json, sys
work = sys.argv[1]
course = json.load(open(work + "/course.json"))
for c in course["checkpoints"]:
    c.pop("formula", None)
json.dump(course, open(work + "/no_formula.json", "w"))
PY

python3 - "$root" "$work" "$bin" "$repeats" <<'PY'
import json, os, statistics, subprocess, sys, time
root, work, bin, repeats = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
store = os.path.join(work, "store")
S = os.path.join(root, "shaders")
flat = [("out vec3 vNormal;", "flat out vec3 vNormal;", "v"), ("in vec3 vNormal;", "flat in vec3 vNormal;", "f")]
# (name, checkpoint, edits (find, replace, stage), expected variant, expected value or "")
cases = [
    ("light as a direction", "specular", [("normalize(uLightPosition - vPosition)", "normalize(uLightPosition)", "f")], "light_as_direction", ""),
    ("view vector away", "specular", [("normalize(-vPosition)", "normalize(vPosition)", "f")], "view_away", ""),
    ("reflect(L, N)", "specular", [("reflect(-L, N)", "reflect(L, N)", "f")], "view_away|reflect_sign", ""),
    ("fixed view vector", "specular", [("normalize(-vPosition)", "vec3(0.0, 0.0, 1.0)", "f")], "fixed_view", ""),
    ("normal negated", "specular", [("vec3 N = normalize(vNormal);", "vec3 N = -normalize(vNormal);", "f")], "negated_normal", ""),
    ("normal not normalized", "specular", [("vec3 N = normalize(vNormal);", "vec3 N = vNormal;", "f")], "unnormalized_normal", ""),
    ("flat normals", "specular", flat, "flat_normal", ""),
    ("N.L not clamped", "specular", [("max(0.0, NdotL)", "NdotL", "f")], "unclamped_diffuse", ""),
    ("Blinn's half vector", "specular", [("vec3 R = reflect(-L, N);\n        color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);",
                                          "vec3 H = normalize(L + V);\n        color += uSpecularColor * uLightColor * pow(max(0.0, dot(N, H)), specularAlpha);", "f")], "half_vector", ""),
    ("specular where N.L <= 0", "specular", [("if (NdotL > 0.0) {", "{", "f")], "unguarded_specular", ""),
    ("light colour left out", "specular", [("uDiffuseColor * uLightColor * max", "uDiffuseColor * max", "f"), ("uSpecularColor * uLightColor * pow", "uSpecularColor * pow", "f")], "no_light_colour", ""),
    ("light colour left out of the specular", "specular", [("uSpecularColor * uLightColor * pow", "uSpecularColor * pow", "f")], "specular_without_light_colour", ""),
    ("ambient doubled", "specular", [("vec4 color = uAmbientColor +", "vec4 color = 2.0 * uAmbientColor +", "f")], "formula", "ambient"),
    ("specular halved", "specular", [("uSpecularColor * uLightColor * pow", "0.5 * uSpecularColor * uLightColor * pow", "f")], "formula", "specular"),
    ("specular missing", "specular", [("color += uSpecularColor", "color += 0.0 * uSpecularColor", "f")], "formula", "specular"),
    ("diffuse missing", "specular", [("uDiffuseColor * uLightColor * max(0.0, NdotL)", "vec4(0.0)", "f")], "formula", "diffuse"),
    ("exponent 12", "specular", [("float specularAlpha = 6.0;", "float specularAlpha = 12.0;", "f")], "formula", "exponent"),
    ("exponent 0.6", "specular", [("float specularAlpha = 6.0;", "float specularAlpha = 0.6;", "f")], "formula", "exponent"),
    ("colours swapped", "specular", [("vec4 color = uAmbientColor + uDiffuseColor", "vec4 color = uAmbientColor + uSpecularColor", "f"),
                                     ("color += uSpecularColor * uLightColor", "color += uDiffuseColor * uLightColor", "f")], "formula", "diffuse"),
    ("light moved", "specular", [("normalize(uLightPosition - vPosition)", "normalize(vec3(-10.0, 8.0, 4.0) - vPosition)", "f")], "formula", "lightPosition"),
    ("light as a direction", "diffuse", [("normalize(uLightPosition - vPosition)", "normalize(uLightPosition)", "f")], "light_as_direction", ""),
    ("normal negated", "diffuse", [("vec3 N = normalize(vNormal);", "vec3 N = -normalize(vNormal);", "f")], "negated_normal", ""),
    ("flat normals", "diffuse", flat, "flat_normal", ""),
    ("N.L not clamped", "diffuse", [("max(0.0, dot(N, L))", "dot(N, L)", "f")], "unclamped_diffuse", ""),
    ("light colour left out", "diffuse", [("uDiffuseColor * uLightColor * max", "uDiffuseColor * max", "f")], "no_light_colour", ""),
    ("ambient doubled", "diffuse", [("fragColor = uAmbientColor + diffuse;", "fragColor = 2.0 * uAmbientColor + diffuse;", "f")], "formula", "ambient"),
    ("diffuse halved", "diffuse", [("vec4 diffuse = uDiffuseColor", "vec4 diffuse = 0.5 * uDiffuseColor", "f")], "formula", "diffuse"),
    ("diffuse missing", "diffuse", [("max(0.0, dot(N, L))", "0.0", "f")], "formula", "diffuse"),
    ("one colour", "specular", [("fragColor = color;", "fragColor = vec4(0.3, 0.8, 0.2, 1.0);", "f")], "", ""),
    ("noise", "specular", [("fragColor = color;", "fragColor = vec4(fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453), 0.5, 0.5, 1.0);", "f")], "", ""),
    ("the normal's colour", "specular", [("fragColor = color;", "fragColor = vec4(abs(N), 1.0);", "f")], "", ""),
]

def write(i, checkpoint, edits):
    v = open(os.path.join(S, checkpoint + "_vert.js")).read()
    f = open(os.path.join(S, checkpoint + "_frag.js")).read()
    for find, replace, stage in edits:
        text = v if stage == "v" else f
        assert find in text, find
        text = text.replace(find, replace, 1)
        if stage == "v": v = text
        else: f = text
    paths = (os.path.join(work, "c%02d_vert.js" % i), os.path.join(work, "c%02d_frag.js" % i))
    open(paths[0], "w").write(v)
    open(paths[1], "w").write(f)
    return paths

def grade(paths, checkpoint, course=None):
    args = [bin, "grade", "--vert", paths[0], "--frag", paths[1], "--reference", checkpoint, "--cache-dir", store]
    if course: args += ["--course", course]
    start = time.monotonic()
    run = subprocess.run(args, capture_output=True, text=True)
    if "{" not in run.stdout:
        sys.exit("no grade from %s (exit %d): %s" % (" ".join(args), run.returncode, run.stderr[-2000:]))
    out = run.stdout
    return time.monotonic() - start, json.loads(out[out.index("{"):out.rindex("}") + 1])

print("| deliverable | change | explanation | expected | right |")
print("| --- | --- | --- | --- | --- |")
tally = {}
written = []
for i, (name, checkpoint, edits, variant, value) in enumerate(cases):
    paths = write(i, checkpoint, edits)
    written.append((paths, checkpoint))
    _, r = grade(paths, checkpoint)
    x = r.get("explanation", {})
    got = x.get("variant", "") if x.get("explained") else ""
    names = [p["name"] for p in x.get("parameters", [])]
    right = (got in variant.split("|") if variant else got == "") and (not value or value in names)
    wrong = bool(got) and not right
    t = tally.setdefault(checkpoint, [0, 0, 0, 0])
    t[0] += 1; t[1] += right; t[2] += wrong; t[3] += bool(variant)
    said = (x.get("label", "") or "(none)") if not r["pass"] else "passes"
    print("| %s | %s | %s | %s | %s |" % (checkpoint, name, said, (variant + (" " + value if value else "")) or "not explained", "yes" if right else ("WRONG" if wrong else "no")))
print()
for checkpoint, (n, right, wrong, explainable) in tally.items():
    print("%s: %d of %d read right (%d to be explained, the rest not); wrong explanations: %d" % (checkpoint, right, n, explainable, wrong))

# The cost: the failing grades above with and without the formula, and a passing one, alternating;
# against one render of the course's job.
no_formula = os.path.join(work, "no_formula.json")
failing = [written[k] for k in (0, 12, 16, 29)]  # light as a direction, ambient doubled, exponent 12, noise
passing = write(99, "specular", [])
samples = {"with": [], "without": [], "passing with": [], "passing without": [], "render": []}
for rep in range(repeats):
    order = [("with", None), ("without", no_formula)] if rep % 2 == 0 else [("without", no_formula), ("with", None)]
    for label, course in order:
        for paths, checkpoint in failing:
            samples[label].append(grade(paths, checkpoint, course)[0])
        samples["passing " + label].append(grade(passing, "specular", course)[0])
    start = time.monotonic()
    subprocess.run([bin, "render", "--preset", "specular", "--grid", os.path.join(work, "grid.png")], check=True, capture_output=True)
    samples["render"].append(time.monotonic() - start)
print()
print("| run | median s | range |")
print("| --- | --- | --- |")
for label, values in samples.items():
    print("| %s | %.2f | %.2f-%.2f |" % (label, statistics.median(values), min(values), max(values)))
print("explaining a failing grade costs %.2f s (median), one render of the job %.2f s" %
      (statistics.median(samples["with"]) - statistics.median(samples["without"]), statistics.median(samples["render"])))
PY
