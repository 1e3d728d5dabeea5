#!/usr/bin/env bash
# What the repair search of a failing code grade finds and costs (docs/grading.md, "Repairs").
# The specular checkpoint's reference with a mistake typed in as a student types it: the ones the
# formula and the catalogue leave unexplained (the issue's list), some they explain, and drawings
# no small edit repairs. For each: whether a repair was confirmed, its kind and line, whether
# the line it writes is one that draws as the reference's (the mistake undone, or its equal), and
# the candidates and confirming renders it spent. Then the cost, one sitting, whole processes on
# a warm reference store: a passing grade, a repaired one and an unrepairable one, each with the
# search (the default budget) and without it (--repair-candidates 0), alternating.
#   bench/repair_bench.sh [repeats, default 6]      SHADELAB_BIN: another build's shadelab
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
repeats=${1:-6}
bin=${SHADELAB_BIN:-$root/build/shadelab}
work=$(mktemp -d -t shadelab-repair.XXXXXX)
trap 'rm -rf "$work"' EXIT

python3 - "$root" "$work" "$bin" "$repeats" <<'PY'
import json, os, statistics, subprocess, sys, time
root, work, bin, repeats = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
store = os.path.join(work, "store")
S = os.path.join(root, "shaders")
L = "vec3 L = normalize(uLightPosition - vPosition);"
SPEC = "color += uSpecularColor * uLightColor * pow(max(0.0, dot(V, R)), specularAlpha);"
# (name, edits (find, replace, stage), lines that draw as the reference's; empty: none expected)
cases = [
    ("L not normalised", [(L, "vec3 L = uLightPosition - vPosition;", "f")], [L]),
    ("light moved up", [("normalize(uLightPosition - vPosition)", "normalize(uLightPosition + vec3(0.0, 4.0, 0.0) - vPosition)", "f")], [L]),
    ("light at half its position", [("normalize(uLightPosition - vPosition)", "normalize(0.5 * uLightPosition - vPosition)", "f")], [L]),
    ("specular colour from the diffuse", [("color += uSpecularColor", "color += uDiffuseColor", "f")], [SPEC]),
    ("pow without max", [("pow(max(0.0, dot(V, R)), specularAlpha)", "pow(dot(V, R), specularAlpha)", "f")], [SPEC]),
    ("normal with the translation", [("(uMeshToWorldRotMatrix * aVertexNormal).xyz", "(uMeshToWorldMatrix * vec4(aVertexNormal.xyz, 1.0)).xyz", "v")],
     ["vNormal = (uMeshToWorldMatrix * vec4(aVertexNormal.xyz, 0.0)).xyz;"]),
    ("position in clip space", [("vPosition = (uMeshToWorldMatrix * aVertexPosition).xyz;",
                                 "vPosition = (uWorldToClipSpaceMatrix * uMeshToWorldMatrix * aVertexPosition).xyz;", "v")],
     ["vPosition = (uMeshToWorldMatrix * aVertexPosition).xyz;"]),
    ("reflect(L, N)", [("reflect(-L, N)", "reflect(L, N)", "f")], ["vec3 R = reflect(-L, N);"]),
    ("view vector away", [("normalize(-vPosition)", "normalize(vPosition)", "f")], ["vec3 V = normalize(-vPosition);", "vec3 V = -normalize(vPosition);"]),
    ("one colour", [("fragColor = color;", "fragColor = vec4(0.3, 0.8, 0.2, 1.0);", "f")], []),
    ("noise", [("fragColor = color;", "fragColor = vec4(fract(sin(dot(gl_FragCoord.xy, vec2(12.9898, 78.233))) * 43758.5453), 0.5, 0.5, 1.0);", "f")], []),
]

def write(i, edits):
    v = open(os.path.join(S, "specular_vert.js")).read()
    f = open(os.path.join(S, "specular_frag.js")).read()
    for find, replace, stage in edits:
        text = v if stage == "v" else f
        assert find in text, find
        text = text.replace(find, replace, 1)
        if stage == "v": v = text
        else: f = text
    d = os.path.join(work, "c%02d" % i)
    os.makedirs(d, exist_ok=True)
    paths = (os.path.join(d, "phong_vert.js"), os.path.join(d, "phong_frag.js"))
    open(paths[0], "w").write(v)
    open(paths[1], "w").write(f)
    return paths

def grade(paths, extra=()):
    args = [bin, "grade", "--vert", paths[0], "--frag", paths[1], "--reference", "specular", "--cache-dir", store, *extra]
    start = time.monotonic()
    run = subprocess.run(args, capture_output=True, text=True)
    seconds = time.monotonic() - start
    out = run.stdout
    if "{" not in out:
        sys.exit("no grade from %s (exit %d): %s" % (" ".join(args), run.returncode, run.stderr[-2000:]))
    return seconds, json.loads(out[out.index("{"):out.rindex("}") + 1])

reference = write(99, [])
grade(reference)  # the references into the store
print("| mistake | repaired | kind, line | the line it writes draws as the reference's | candidates | confirming renders | seconds |")
print("| --- | --- | --- | --- | --- | --- | --- |")
repaired = right = expected = wrong = 0
for i, (name, edits, lines) in enumerate(cases):
    paths = write(i, edits)
    seconds, r = grade(paths)
    search = r.get("repairSearch", {})
    found = search.get("found")
    if r.get("pass"):
        print("| %s | passes | | | | | %.2f |" % (name, seconds)); continue
    if not search:
        why = (r.get("explanation") or {}).get("label") or r.get("diagnosis") or "explained"
        print("| %s | not searched (%s) | | | | | %.2f |" % (name, why, seconds)); continue
    expected += bool(lines)
    same = bool(found) and found.get("repairedLine") in lines
    repaired += bool(found)
    right += same
    wrong += bool(found) and not lines
    print("| %s | %s | %s | %s | %d | %d | %.2f |" % (
        name, "yes" if found else "no", "%s, %s line %d" % (found["kind"], found["file"], found["line"]) if found else "",
        ("yes" if same else "no: `%s`" % found.get("repairedLine")) if found else "", search["candidates"], search["confirmations"], seconds))
print("\nsearched and repaired %d of the %d searched with a repair to find; the mistake undone or its equal: %d; a repair where none was expected: %d\n" % (repaired, expected, right, wrong))

passing, fixable, hopeless = reference, write(0, cases[0][1]), write(90, cases[-2][1])
timings = {}
for _ in range(repeats):
    for label, paths in (("passing", passing), ("repaired", fixable), ("no repair", hopeless)):
        for budget in ("search", "no search"):
            extra = ["--repair-candidates", "0"] if budget == "no search" else []
            timings.setdefault((label, budget), []).append(grade(paths, extra)[0])
print("| grade (%d runs each, alternating) | with the search: median (spread) | --repair-candidates 0: median (spread) |" % repeats)
print("| --- | --- | --- |")
for label in ("passing", "repaired", "no repair"):
    cells = []
    for budget in ("search", "no search"):
        t = timings[(label, budget)]
        cells.append("%.2f s (%.2f-%.2f)" % (statistics.median(t), min(t), max(t)))
    print("| %s | %s | %s |" % (label, *cells))
PY
