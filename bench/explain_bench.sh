#!/usr/bin/env bash
# What reading a failing grade by the homework's formula finds and costs (docs/grading.md, "Why a
# grade failed"). A written set of wrong submissions for the three checkpoints, each
# the course's reference with one change a student makes, graded at the course's canvas; for each,
# whether the explanation names the change (the expected variant, and the changed value's name).
# The same for saved frames: each submission drawn as a 60 Hz page saves it (`shadelab render
# --angles`, 0.05-0.3 degrees behind each frame's angle) and graded as the page grades it.
# Then the cost, one sitting, whole processes on a warm reference store: the same failing and
# passing grades (code, and saved frames) with the built-in course and with the same course less
# its checkpoints' `formula` and its mistakes' readings (no explanation; every known mistake
# rendered), alternating, against one render of the course's job (`shadelab render`).
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
    for m in c.get("mistakes", []):
        m.pop("reading", None)  # a reading is the formula's: without it, every mistake is rendered
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
colour = "vColor = vec4(normalize(abs(normal.xyz)), 1.0);"
channels = lambda swizzle: [("normalize(abs(normal.xyz))", "normalize(abs(normal.%s))" % swizzle, "v")]
cases += [
    ("abs() missing", "normals", [("normalize(abs(normal.xyz))", "normalize(normal.xyz)", "v")], "missing_abs", ""),
    ("0.5 N + 0.5", "normals", [("normalize(abs(normal.xyz))", "0.5 * normalize(normal.xyz) + 0.5", "v")], "offset_normal", ""),
    ("flat colour", "normals", [("out vec4 vColor;", "flat out vec4 vColor;", "v"), ("in vec4 vColor;", "flat in vec4 vColor;", "f")], "flat_colour", ""),
    ("colour per fragment", "normals", [("out vec4 vColor;", "out vec3 vN;", "v"), (colour, "vN = normal.xyz;", "v"), ("in vec4 vColor;", "in vec3 vN;", "f"),
                                        ("fragColor = vColor;", "fragColor = vec4(normalize(abs(vN)), 1.0);", "f")], "fragment_colour", ""),
    ("red and blue swapped", "normals", channels("zyx"), "swapped_red_blue", ""),
    ("red and green swapped", "normals", channels("yxz"), "swapped_red_green", ""),
    ("green and blue swapped", "normals", channels("xzy"), "swapped_green_blue", ""),
    ("channels rotated", "normals", channels("yzx"), "rotated_channels", ""),
    ("channels rotated back", "normals", channels("zxy"), "rotated_channels_back", ""),
    ("one colour", "normals", [("fragColor = vColor;", "fragColor = vec4(0.3, 0.8, 0.2, 1.0);", "f")], "", ""),
    ("noise", "normals", [("fragColor = vColor;", "fragColor = vec4(fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453), 0.5, 0.5, 1.0);", "f")], "", ""),
    ("the position's colour", "normals", [(colour, "vColor = vec4(abs(normalize(aVertexPosition.xyz)), 1.0);", "v")], "", ""),
    ("the normal not rotated", "normals", [("uMeshToWorldRotMatrix * aVertexNormal", "aVertexNormal", "v")], "", ""),
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

def run_grade(args):
    start = time.monotonic()
    run = subprocess.run(args, capture_output=True, text=True)
    if "{" not in run.stdout:
        sys.exit("no grade from %s (exit %d): %s" % (" ".join(args), run.returncode, run.stderr[-2000:]))
    out = run.stdout
    return time.monotonic() - start, json.loads(out[out.index("{"):out.rindex("}") + 1])

def grade(paths, checkpoint, course=None):
    # The formula's own reading of code: with a repair search, a confirmed repair explains code
    # and the formula reads only what no repair was found for (bench/mutation_bench.py measures those).
    args = [bin, "grade", "--vert", paths[0], "--frag", paths[1], "--reference", checkpoint, "--cache-dir", store, "--repair-candidates", "0"]
    return run_grade(args + (["--course", course] if course else []))

PAGE_ANGLES = ["0", "19.88", "39.79", "59.95", "79.7", "99.83", "119.74", "139.91", "159.77"]

def saved_frames(i, paths, checkpoint):
    folder = os.path.join(work, "saved%02d" % i)
    subprocess.run([bin, "render", "--vert", paths[0], "--frag", paths[1], "--angles"] + PAGE_ANGLES +
                   ["--frames-dir", os.path.join(folder, "images"), "--prefix", checkpoint], check=True, capture_output=True)
    return folder

def grade_saved(folder, checkpoint, course=None):
    args = [bin, "grade", "--saved-frames", folder, "--reference", checkpoint, "--cache-dir", store]
    seconds, r = run_grade(args + (["--course", course] if course else []))
    return seconds, r["frames"]

def read_right(r, variant, value):
    x = r.get("explanation", {})
    got = x.get("variant", "") if x.get("explained") else ""
    names = [p["name"] for p in x.get("parameters", [])]
    right = (got in variant.split("|") if variant else got == "") and (not value or value in names)
    return x, right, bool(got) and not right

def verdict(r, x, right, wrong):
    said = (x.get("label", "") or "(none)") if not r["pass"] else "passes"
    return said, "yes" if right else ("WRONG" if wrong else "no")

print("| deliverable | change | code: explanation | right | saved frames: explanation | right | expected |")
print("| --- | --- | --- | --- | --- | --- | --- |")
tally = {}
written = []
for i, (name, checkpoint, edits, variant, value) in enumerate(cases):
    paths = write(i, checkpoint, edits)
    folder = saved_frames(i, paths, checkpoint)
    written.append((paths, checkpoint, folder))
    _, r = grade(paths, checkpoint)
    _, s = grade_saved(folder, checkpoint)
    x, right, wrong = read_right(r, variant, value)
    xs, right_s, wrong_s = read_right(s, variant, value)
    for kind, ok, bad in (("code", right, wrong), ("saved frames", right_s, wrong_s)):
        t = tally.setdefault((checkpoint, kind), [0, 0, 0, 0])
        t[0] += 1; t[1] += ok; t[2] += bad; t[3] += bool(variant)
    print("| %s | %s | %s | %s | %s | %s | %s |" % ((checkpoint, name) + verdict(r, x, right, wrong) + verdict(s, xs, right_s, wrong_s) +
                                               ((variant + (" " + value if value else "")) or "not explained",)))
print()
for (checkpoint, kind), (n, right, wrong, explainable) in tally.items():
    print("%s, %s: %d of %d read right (%d to be explained, the rest not); wrong explanations: %d" % (checkpoint, kind, right, n, explainable, wrong))

# The cost: the failing grades above with and without the formula, and a passing one, alternating;
# against one render of the course's job.
no_formula = os.path.join(work, "no_formula.json")
failing = [written[k] for k in (0, 12, 16, 29)]  # light as a direction, ambient doubled, exponent 12, noise
catalogued = [written[k] for k in (14, 17)]  # specular missing, exponent 0.6: the catalogue's, read by the formula
normals = [written[k] for k in (31, 35)]  # abs() missing (the catalogue's), red and blue swapped
flat_normals = written[6]  # specular flat normals (the catalogue's): read on each sample's flat normal, fetched for it
flat_colour = written[[c[0] for c in cases].index("flat colour")]  # the normals' (the catalogue's): saved frames placed by their edges
passing = write(99, "specular", [])
passing_saved = saved_frames(99, passing, "specular")
samples = {k: [] for k in ("with", "without", "catalogued with", "catalogued without", "normals with", "normals without", "flat with", "flat without",
                           "passing with", "passing without", "saved with", "saved without", "saved flat with", "saved flat without",
                           "saved passing with", "saved passing without", "saved normals with", "saved normals without", "saved flat colour with", "saved flat colour without", "render")}
for rep in range(repeats):
    order = [("with", None), ("without", no_formula)] if rep % 2 == 0 else [("without", no_formula), ("with", None)]
    for label, course in order:
        for paths, checkpoint, folder in failing:
            samples[label].append(grade(paths, checkpoint, course)[0])
            samples["saved " + label].append(grade_saved(folder, checkpoint, course)[0])
        for paths, checkpoint, _ in catalogued:
            samples["catalogued " + label].append(grade(paths, checkpoint, course)[0])
        for paths, checkpoint, folder in normals:
            samples["normals " + label].append(grade(paths, checkpoint, course)[0])
            samples["saved normals " + label].append(grade_saved(folder, checkpoint, course)[0])
        samples["flat " + label].append(grade(flat_normals[0], flat_normals[1], course)[0])
        samples["saved flat " + label].append(grade_saved(flat_normals[2], flat_normals[1], course)[0])
        samples["saved flat colour " + label].append(grade_saved(flat_colour[2], flat_colour[1], course)[0])
        samples["passing " + label].append(grade(passing, "specular", course)[0])
        samples["saved passing " + label].append(grade_saved(passing_saved, "specular", course)[0])
    start = time.monotonic()
    subprocess.run([bin, "render", "--preset", "specular", "--grid", os.path.join(work, "grid.png")], check=True, capture_output=True)
    samples["render"].append(time.monotonic() - start)
print()
print("| run | median s | range |")
print("| --- | --- | --- |")
for label, values in samples.items():
    print("| %s | %.2f | %.2f-%.2f |" % (label, statistics.median(values), min(values), max(values)))
m = lambda k: statistics.median(samples[k])
print("explaining a failing grade costs %.2f s (median; a catalogued mistake the formula reads %.2f s; the normals' %.2f s; specular flat normals %.2f s), "
      "failing saved frames %.2f s (flat normals %.2f s; the normals' %.2f s, their flat colour %.2f s); one render of the job %.2f s" % (
          m("with") - m("without"), m("catalogued with") - m("catalogued without"), m("normals with") - m("normals without"),
          m("flat with") - m("flat without"), m("saved with") - m("saved without"), m("saved flat with") - m("saved flat without"),
          m("saved normals with") - m("saved normals without"), m("saved flat colour with") - m("saved flat colour without"), m("render")))
PY
