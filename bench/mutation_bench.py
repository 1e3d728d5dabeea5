#!/usr/bin/env python3
"""The repair search measured on mutants of the course's reference programs (docs/grading.md,
"Repairs: measured on mutants").

Mutants come from three places, none of them the search's own code:
  single   every operator below at every site of each checkpoint's reference where it applies:
           the classic mutation operators of a shader (a call removed or added, a sign, an
           operator, arguments swapped, a name or matrix of the same type, a literal, a
           statement removed or moved out of its guard, a varying made flat);
  typed    mistakes as students type them: the issue's list, whole statements rewritten, and
           the course profile's catalogue of mistakes (courses/*.json);
  pair     a fixed sample (seeded) of two single mutants of one checkpoint made together.
Each mutant is graded as a TA grades it (`shadelab grade`, which shows staff the repaired line).
A mutant that does not compile, or still passes, is dropped and counted. For the rest: explained
without a search (the formula or the catalogue named it), repaired, or neither. A repair is
"undone" when its line reads as the reference's line, "equal" when it is another line at a
place the mutation changed (a render confirmed it draws as the reference), and "elsewhere" when
it is at a line the mutation did not touch: a claim about a change the mutation did not make,
counted as wrong and listed for a reader to judge.

  bench/mutation_bench.py [--pairs N] [--seed S] [--jobs J] [--only single,typed,pair]
                          [--checkpoints normals,diffuse,specular] [--limit N] [--list]
  bench/mutation_bench.py --sample     the fixed sample a test runs (tests/CMakeLists.txt,
                                       `mutation_sample`): exits 1 unless each is repaired at a
                                       line the mutation changed, and none elsewhere
  SHADELAB_BIN: another build's shadelab.
"""
import argparse
import concurrent.futures
import json
import os
import random
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHADERS = os.path.join(ROOT, "shaders")
CHECKPOINTS = ("normals", "diffuse", "specular")
STAGES = ("vert", "frag")
FLOAT = r"\d+\.\d*"


class Edit:
    """One span of one stage's file replaced: a mutation."""

    def __init__(self, op, stage, begin, end, text):
        self.op, self.stage, self.begin, self.end, self.text = op, stage, begin, end, text


class Mutant:
    def __init__(self, source, checkpoint, name, edits, also=()):
        self.source, self.checkpoint, self.name, self.edits = source, checkpoint, name, edits
        self.also = list(also)  # further edits made with it (the other stage's half of one change)

    def all_edits(self):
        return self.edits + self.also


def read_reference(checkpoint):
    return {s: open(os.path.join(SHADERS, "%s_%s.js" % (checkpoint, s))).read() for s in STAGES}


def main_body(text):
    """The byte range of main's body: mutations stay inside it (a declaration's mutant is a
    compile error, not a homework's mistake), but for the `flat` operator."""
    start = text.index("void main(void) {") + len("void main(void) {")
    depth, i = 1, start
    while depth:
        depth += {"{": 1, "}": -1}.get(text[i], 0)
        i += 1
    return start, i - 1


def closing_paren(text, open_at):
    depth = 0
    for i in range(open_at, len(text)):
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        if depth == 0:
            return i
    raise ValueError("unbalanced")


def split_args(text, open_at):
    """The argument spans of the call whose '(' is at open_at."""
    close = closing_paren(text, open_at)
    spans, depth, start = [], 0, open_at + 1
    for i in range(open_at + 1, close):
        depth += {"(": 1, ")": -1}.get(text[i], 0)
        if text[i] == "," and depth == 0:
            spans.append((start, i))
            start = i + 1
    spans.append((start, close))
    return [(b + len(text[b:e]) - len(text[b:e].lstrip()), e) for b, e in spans], close


def calls(text, name, body):
    for m in re.finditer(r"\b%s\(" % name, text[body[0]:body[1]]):
        yield body[0] + m.start(), body[0] + m.end() - 1


def declared(text):
    """Names by type: uniforms, inputs, and main's locals (with where each is declared)."""
    names = {}
    for m in re.finditer(r"^\s*(?:uniform|in)\s+(vec[234]|mat[234]|float)\s+(\w+);", text, re.M):
        names.setdefault(m.group(1), []).append((m.group(2), 0))
    body = main_body(text)
    for m in re.finditer(r"\b(vec[234]|float)\s+(\w+)\s*=", text[body[0]:body[1]]):
        names.setdefault(m.group(1), []).append((m.group(2), body[0] + m.end()))
    return names


def statements(text, body):
    """main's statements that end in ';', as (begin, end) spans with their text."""
    for m in re.finditer(r"^[ \t]*([^\n;{}]*;)[ \t]*\n", text[body[0]:body[1]], re.M):
        if not m.group(1).lstrip().startswith("//"):
            yield body[0] + m.start(1), body[0] + m.end(1), m.group(1)


# The operators. Each yields Edits of one stage's file; `flat` yields the pair of both stages.

def op_normalize_removed(stage, text, body):
    for at, paren in calls(text, "normalize", body):
        close = closing_paren(text, paren)
        inner = text[paren + 1:close]
        yield Edit("normalize removed", stage, at, close + 1, inner if re.fullmatch(r"[\w.]+|\w+\(.*\)", inner) else "(" + inner + ")")


def op_normalize_added(stage, text, body):
    for m in re.finditer(r"\b(?:vec[34]\s+\w+|vNormal|vPosition)\s*=\s*([^;]+);", text[body[0]:body[1]]):
        rhs = m.group(1)
        if rhs.startswith("normalize("):
            continue
        b = body[0] + m.start(1)
        yield Edit("normalize added", stage, b, b + len(rhs), "normalize(%s)" % rhs)


def op_negated(stage, text, body):
    for fn in ("dot", "reflect"):
        for _, paren in calls(text, fn, body):
            args, _ = split_args(text, paren)
            for b, e in args:
                arg = text[b:e]
                if not arg.startswith("-"):
                    yield Edit("negated", stage, b, e, "-" + arg if re.fullmatch(r"[\w.]+", arg) else "-(" + arg + ")")
    for m in re.finditer(r"\bvec3\s+\w+\s*=\s*([^;]+);", text[body[0]:body[1]]):
        b = body[0] + m.start(1)
        yield Edit("negated", stage, b, b + len(m.group(1)), "-" + m.group(1) if m.group(1).endswith(")") else "-(" + m.group(1) + ")")


def op_negation_removed(stage, text, body):
    for m in re.finditer(r"(?<=[(,=]|\s)-(?=[\w(])", text[body[0]:body[1]]):
        before = text[:body[0] + m.start()].rstrip()
        if before and before[-1] in "(,=":
            yield Edit("negation removed", stage, body[0] + m.start(), body[0] + m.end(), "")


def op_operator_swapped(stage, text, body):
    for m in re.finditer(r"(?<=\s)([+-])(=?)(?=\s)", text[body[0]:body[1]]):
        yield Edit("operator swapped", stage, body[0] + m.start(1), body[0] + m.end(1), "-" if m.group(1) == "+" else "+")


def op_arguments_swapped(stage, text, body):
    for fn in ("reflect", "pow", "dot", "max"):
        for _, paren in calls(text, fn, body):
            args, close = split_args(text, paren)
            if len(args) == 2:
                (b0, e0), (b1, e1) = args
                yield Edit("arguments swapped", stage, paren + 1, close, "%s, %s" % (text[b1:e1], text[b0:e0]))


def op_clamp_removed(stage, text, body):
    for at, paren in calls(text, "max", body):
        args, close = split_args(text, paren)
        if len(args) == 2 and re.fullmatch(FLOAT, text[args[0][0]:args[0][1]]):
            yield Edit("clamp removed", stage, at, close + 1, text[args[1][0]:args[1][1]])


def op_clamp_added(stage, text, body):
    for at, paren in calls(text, "dot", body):
        if not text[:at].rstrip().endswith("0.0,"):
            close = closing_paren(text, paren)
            yield Edit("clamp added", stage, at, close + 1, "max(0.0, %s)" % text[at:close + 1])


def op_name_replaced(stage, text, body):
    for type_, names in declared(text).items():
        for name, visible_from in names:
            for m in re.finditer(r"(?<![\w.])%s\b" % name, text[body[0]:body[1]]):
                at = body[0] + m.start()
                if text[at + len(name):].lstrip().startswith("=") and not text[at + len(name):].lstrip().startswith("=="):
                    continue  # the name assigned: a declaration's or an output's
                if re.search(r"\b%s\s+$" % type_, text[:at]):
                    continue
                for other, other_from in names:
                    if other != name and other_from <= at:
                        yield Edit("name replaced", stage, at, at + len(name), other)


def op_matrix_removed(stage, text, body):
    for m in re.finditer(r"\b(u\w*Matrix)\s*\*\s*", text[body[0]:body[1]]):
        yield Edit("matrix removed", stage, body[0] + m.start(), body[0] + m.end(), "")


def op_w_changed(stage, text, body):
    for m in re.finditer(r"\*\s*(aVertex(Position|Normal))\b", text[body[0]:body[1]]):
        w = "0.0" if m.group(2) == "Position" else "1.0"
        yield Edit("w changed", stage, body[0] + m.start(1), body[0] + m.end(1), "vec4(%s.xyz, %s)" % (m.group(1), w))
    for m in re.finditer(r"vec4\(([^;]+), (1\.0|0\.0)\)", text[body[0]:body[1]]):
        yield Edit("w changed", stage, body[0] + m.start(2), body[0] + m.end(2), "0.0" if m.group(2) == "1.0" else "1.0")


def op_literal_changed(stage, text, body):
    for m in re.finditer(r"(?<![\w.])(%s)(?![\w.])" % FLOAT, text[body[0]:body[1]]):
        value = float(m.group(1))
        yield Edit("literal changed", stage, body[0] + m.start(), body[0] + m.end(), repr(value * 2) if value else "0.5")


def op_statement_removed(stage, text, body):
    for b, e, s in statements(text, body):
        if not re.match(r"(vec[234]|float|mat[234])\s", s):  # a declaration's removal does not compile
            yield Edit("statement removed", stage, b, e, "")


def op_guard_moved(stage, text, body):
    for m in re.finditer(r"if \(([^)]*)\) \{", text[body[0]:body[1]]):
        b = body[0] + m.start(1)
        yield Edit("guard removed", stage, b, b + len(m.group(1)), "true")
        close = text.index("\n    }", body[0] + m.end())
        for sb, se, s in statements(text, (body[0] + m.end(), close + 1)):
            if not re.match(r"(vec[234]|float)\s", s):
                # the statement moved to just after the guard's block
                yield Edit("out of the guard", stage, sb, close + len("\n    }"), text[se:close + len("\n    }")].lstrip() + "\n    " + s)


SINGLE_OPERATORS = (op_normalize_removed, op_normalize_added, op_negated, op_negation_removed, op_operator_swapped,
                    op_arguments_swapped, op_clamp_removed, op_clamp_added, op_name_replaced, op_matrix_removed,
                    op_w_changed, op_literal_changed, op_statement_removed, op_guard_moved)


def flat_mutants(checkpoint, ref):
    for m in re.finditer(r"^out (vec[34]) (v\w+);", ref["vert"], re.M):
        fm = re.search(r"^in %s %s;" % (m.group(1), m.group(2)), ref["frag"], re.M)
        if fm:
            yield Mutant("single", checkpoint, "flat %s" % m.group(2),
                         [Edit("flat", "vert", m.start(), m.start(), "flat ")], [Edit("flat", "frag", fm.start(), fm.start(), "flat ")])


def masked(text):
    """`text` with its comments blanked (the same length, so spans agree): no operator mutates a
    comment."""
    return re.sub(r"//[^\n]*", lambda m: " " * len(m.group(0)), text)


def single_mutants(checkpoint, ref):
    out = []
    for stage in STAGES:
        code = masked(ref[stage])
        body = main_body(code)
        seen = set()
        for op in SINGLE_OPERATORS:
            for e in op(stage, code, body):
                key = (e.begin, e.end, e.text)
                if key in seen or ref[stage][e.begin:e.end] == e.text:
                    continue
                seen.add(key)
                line = ref[stage].count("\n", 0, e.begin) + 1
                out.append(Mutant("single", checkpoint, "%s, %s line %d: `%s` -> `%s`" % (e.op, stage, line, ref[stage][e.begin:e.end].strip()[:48], e.text.strip()[:48]), [e]))
    out.extend(flat_mutants(checkpoint, ref))
    return out


# Mistakes as students type them: (checkpoint, name, [(stage, find, replace)]).
TYPED = [
    ("specular", "L not normalised", [("frag", "vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = uLightPosition - vPosition;")]),
    ("specular", "light moved up", [("frag", "normalize(uLightPosition - vPosition)", "normalize(uLightPosition + vec3(0.0, 4.0, 0.0) - vPosition)")]),
    ("specular", "light at half its position", [("frag", "normalize(uLightPosition - vPosition)", "normalize(0.5 * uLightPosition - vPosition)")]),
    ("specular", "specular colour from the diffuse", [("frag", "color += uSpecularColor", "color += uDiffuseColor")]),
    ("specular", "pow without max", [("frag", "pow(max(0.0, dot(V, R)), specularAlpha)", "pow(dot(V, R), specularAlpha)")]),
    ("specular", "normal with the translation", [("vert", "(uMeshToWorldRotMatrix * aVertexNormal).xyz", "(uMeshToWorldMatrix * vec4(aVertexNormal.xyz, 1.0)).xyz")]),
    ("specular", "position in clip space", [("vert", "vPosition = (uMeshToWorldMatrix * aVertexPosition).xyz;", "vPosition = (uWorldToClipSpaceMatrix * uMeshToWorldMatrix * aVertexPosition).xyz;")]),
    ("specular", "half vector for R", [("frag", "vec3 R = reflect(-L, N);", "vec3 R = normalize(L + V);")]),
    ("specular", "R written out", [("frag", "vec3 R = reflect(-L, N);", "vec3 R = 2.0 * dot(N, L) * N + L;")]),
    ("specular", "V from the light", [("frag", "vec3 V = normalize(-vPosition);", "vec3 V = normalize(uLightPosition - vPosition);")]),
    ("specular", "fixed view vector", [("frag", "vec3 V = normalize(-vPosition);", "vec3 V = vec3(0.0, 0.0, 1.0);")]),
    ("specular", "light used as a direction", [("frag", "vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = normalize(uLightPosition);")]),
    ("specular", "specular outside the guard", [("frag", "        color += uSpecularColor", "        vec4 s = uSpecularColor"), ("frag", "    fragColor = color;", "    fragColor = color + s;")]),
    ("specular", "exponent doubled", [("frag", "float specularAlpha = 6.0;", "float specularAlpha = 12.0;")]),
    ("specular", "two: L not normalised, the specular colour from the diffuse",
     [("frag", "vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = uLightPosition - vPosition;"), ("frag", "color += uSpecularColor", "color += uDiffuseColor")]),
    ("diffuse", "L not normalised", [("frag", "vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = uLightPosition - vPosition;")]),
    ("diffuse", "light direction reversed", [("frag", "normalize(uLightPosition - vPosition)", "normalize(vPosition - uLightPosition)")]),
    ("diffuse", "N.L not clamped", [("frag", "max(0.0, dot(N, L))", "dot(N, L)")]),
    ("diffuse", "light used as a direction", [("frag", "vec3 L = normalize(uLightPosition - vPosition);", "vec3 L = normalize(uLightPosition);")]),
    ("diffuse", "ambient multiplied", [("frag", "fragColor = uAmbientColor + diffuse;", "fragColor = uAmbientColor * diffuse;")]),
    ("diffuse", "normal with the translation", [("vert", "(uMeshToWorldRotMatrix * aVertexNormal).xyz", "(uMeshToWorldMatrix * vec4(aVertexNormal.xyz, 1.0)).xyz")]),
    ("normals", "normal in mesh space", [("vert", "vec4 normal = uMeshToWorldRotMatrix * aVertexNormal;", "vec4 normal = aVertexNormal;")]),
    ("normals", "colour not normalised", [("vert", "normalize(abs(normal.xyz))", "abs(normal.xyz)")]),
]


# The sample a test grades (--sample): one mutant of each kind of mistake the search must repair,
# single operators and typed alike, by checkpoint and the start of its name.
SAMPLE = [
    ("specular", "L not normalised"),
    ("specular", "normal with the translation"),
    ("diffuse", "operator swapped, frag line 22"),
    ("diffuse", "matrix removed, vert line 19"),
    ("specular", "name replaced, frag line 21: `N` -> `L`"),
    ("specular", "two: L not normalised, the specular colour from the diffuse"),
    ("diffuse", "statement removed, vert line 19"),
    ("specular", "literal changed, frag line 27"),
]


def typed_mutants(refs, checkpoints):
    out = []
    for checkpoint, name, edits in TYPED:
        if checkpoint in checkpoints:
            out.append(Mutant("typed", checkpoint, name, found_edits(refs[checkpoint], edits, "typed")))
    course = json.load(open(os.path.join(ROOT, "courses", "cs148-summer2022.json")))
    for cp in course["checkpoints"]:
        if cp["name"] not in checkpoints:
            continue
        for m in cp.get("mistakes", []):
            if "edits" in m:
                edits = [("vert" if e["stage"] == "vertex" else "frag", e["find"], e["replace"]) for e in m["edits"]]
                out.append(Mutant("typed", cp["name"], "catalogue: " + m["id"], found_edits(refs[cp["name"]], edits, "catalogue")))
    return out


def found_edits(ref, edits, op):
    out = []
    for stage, find, replace in edits:
        at = ref[stage].find(find)
        assert at >= 0, (stage, find)
        out.append(Edit(op, stage, at, at + len(find), replace))
    return out


def overlap(a, b):
    return a.stage == b.stage and a.begin < b.end and b.begin < a.end if (a.begin != a.end and b.begin != b.end) else a.stage == b.stage and a.begin == b.begin


def pair_mutants(failing_singles, count, seed):
    rng = random.Random(seed)
    by_checkpoint = {}
    for m in failing_singles:
        by_checkpoint.setdefault(m.checkpoint, []).append(m)
    pool = [(c, ms) for c, ms in sorted(by_checkpoint.items()) if len(ms) > 1]
    out, seen, tries = [], set(), 0
    while len(out) < count and pool and tries < count * 50:
        tries += 1
        checkpoint, ms = pool[rng.randrange(len(pool))]
        a, b = rng.sample(ms, 2)
        if any(overlap(x, y) for x in a.all_edits() for y in b.all_edits()) or (a.name, b.name) in seen or (b.name, a.name) in seen:
            continue
        seen.add((a.name, b.name))
        out.append(Mutant("pair", checkpoint, a.name + " + " + b.name, a.edits + b.edits, a.also + b.also))
    return out


def mutated(ref, mutant):
    files = dict(ref)
    for e in sorted(mutant.all_edits(), key=lambda e: (e.stage, -e.begin)):
        files[e.stage] = files[e.stage][:e.begin] + e.text + files[e.stage][e.end:]
    return files


def changed_lines(ref, mutant):
    """For each stage, the mutated file's lines the mutation wrote (1-based)."""
    lines = {}
    for stage in STAGES:
        edits = sorted((e for e in mutant.all_edits() if e.stage == stage), key=lambda e: e.begin)
        shift = 0
        for e in edits:
            first = ref[stage].count("\n", 0, e.begin) + 1 + shift
            written = e.text.count("\n")
            lines.setdefault(stage, set()).update(range(first, first + written + 1))
            shift += written - ref[stage].count("\n", e.begin, e.end)
    return lines


def grade(binary, store, work, index, ref, mutant):
    files = mutated(ref, mutant)
    d = os.path.join(work, "m%04d" % index)
    os.makedirs(d, exist_ok=True)
    paths = {s: os.path.join(d, "phong_%s.js" % s) for s in STAGES}
    for s in STAGES:
        open(paths[s], "w").write(files[s])
    args = [binary, "grade", "--vert", paths["vert"], "--frag", paths["frag"], "--reference", mutant.checkpoint, "--cache-dir", store]
    start = time.monotonic()
    run = subprocess.run(args, capture_output=True, text=True)
    seconds = time.monotonic() - start
    out = run.stdout
    if "{" not in out:
        raise SystemExit("no grade for %s (exit %d): %s" % (mutant.name, run.returncode, run.stderr[-2000:]))
    return seconds, json.loads(out[out.index("{"):out.rindex("}") + 1]), files


def classify(ref, mutant, report, files):
    """(outcome, detail): dropped-compile, dropped-pass, explained, undone, equal, elsewhere, none."""
    if report.get("diagnostics") or not report.get("frames"):
        return "does not compile", ""
    if report.get("pass"):
        return "still passes", ""
    search = report.get("repairSearch")
    found = (search or {}).get("found")
    e = report.get("explanation") or {}
    named = e.get("explained") or report.get("diagnosis", "") not in ("", "nan")
    if not search or (not found and named):
        # No search (the grader's own diagnosis), or one that found no repair and left the
        # formula or the catalogue to name it.
        return "explained", e.get("label") or report.get("diagnosis") or ""
    if not found:
        return "not repaired", ""
    changed = changed_lines(ref, mutant)
    parts = [found] + ([search["also"]] if search.get("also") else [])
    verdicts, where = [], []
    for part in parts:
        stage = "vert" if part["file"].endswith("vert.js") else "frag"
        line = part["line"]
        where.append("%s, %s line %d" % (part["kind"], stage, line))
        if line not in changed.get(stage, set()):
            verdicts.append("elsewhere")
            where[-1] += ": `%s`" % part.get("repairedLine", "")
            continue
        if part["kind"] in ("statement_restored", "write_restored"):  # the reference's own statement, never shown as a line
            verdicts.append("undone")
            continue
        # The reference's line at the same place: the mutated file's line count may differ only
        # where the mutation wrote more or fewer lines, which the typed mutants do not.
        ref_lines = ref[stage].split("\n")
        said = " ".join(part.get("repairedLine", "").split())
        if line - 1 < len(ref_lines) and " ".join(ref_lines[line - 1].split()) == said:
            verdicts.append("undone")
        else:
            verdicts.append("equal")
            where[-1] += ": `%s`" % part.get("repairedLine", "")
    outcome = "elsewhere" if "elsewhere" in verdicts else "equal" if "equal" in verdicts else "undone"
    return outcome, "; ".join(where)


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pairs", type=int, default=200)
    ap.add_argument("--seed", type=int, default=148)
    ap.add_argument("--jobs", type=int, default=1)
    ap.add_argument("--only", default="single,typed,pair")
    ap.add_argument("--checkpoints", default=",".join(CHECKPOINTS))
    ap.add_argument("--limit", type=int, default=0, help="grade only the first N mutants of each source (a sample)")
    ap.add_argument("--match", help="grade only the mutants whose name holds this text")
    ap.add_argument("--list", action="store_true", help="list the mutants, grade none")
    ap.add_argument("--json", help="write every mutant's outcome here")
    ap.add_argument("--singles-from", help="pairs only: the failing singles as an earlier run's --json says, not graded again")
    ap.add_argument("--sample", action="store_true", help="grade the fixed sample alone, and exit 1 unless each is repaired where the mutation was")
    args = ap.parse_args()
    if args.sample:
        args.only, args.checkpoints = "single,typed", ",".join(sorted({c for c, _ in SAMPLE}))
    binary = os.environ.get("SHADELAB_BIN", os.path.join(ROOT, "build", "shadelab"))
    checkpoints = args.checkpoints.split(",")
    sources = args.only.split(",")
    refs = {c: read_reference(c) for c in checkpoints}

    groups = {"single": [m for c in checkpoints for m in single_mutants(c, refs[c])] if "single" in sources or "pair" in sources else [],
              "typed": typed_mutants(refs, checkpoints) if "typed" in sources else []}
    if args.sample:
        chosen = lambda m: any(m.checkpoint == c and m.name.startswith(n) for c, n in SAMPLE)
        groups = {source: [m for m in ms if chosen(m)] for source, ms in groups.items()}
        assert sum(map(len, groups.values())) == len(SAMPLE), "a sample mutant is no longer made: %s" % groups
    if args.match:
        groups = {source: [m for m in ms if args.match in m.name] for source, ms in groups.items()}
    if args.list:
        for source, ms in groups.items():
            for m in ms:
                print(source, m.checkpoint, m.name)
        return

    work = tempfile.mkdtemp(prefix="shadelab-mutants.")
    store = os.path.join(work, "store")
    shutil.copy2(binary, os.path.join(work, "shadelab"))  # a rebuild meanwhile does not change the measured build
    binary = os.path.join(work, "shadelab")
    for c in checkpoints:  # the references into the store first: their renders are not the search's
        grade(binary, store, work, 9000 + CHECKPOINTS.index(c), refs[c], Mutant("reference", c, "reference", []))

    results = []

    def run_all(mutants):
        if args.limit:
            mutants = mutants[:args.limit]
        first = len(results)
        def one(numbered):
            i, m = numbered
            seconds, report, files = grade(binary, store, work, i, refs[m.checkpoint], m)
            outcome, detail = classify(refs[m.checkpoint], m, report, files)
            search = report.get("repairSearch") or {}
            print("%4d %s %s: %s %s (%.1f s)" % (i, m.checkpoint, m.name[:90], outcome, detail[:80], seconds), file=sys.stderr, flush=True)
            return {"source": m.source, "checkpoint": m.checkpoint, "mutant": m.name, "outcome": outcome, "detail": detail,
                    "seconds": seconds, "candidates": search.get("candidates", 0), "confirmations": search.get("confirmations", 0),
                    "words": ((report.get("messages") or [""])[1:2] or [""])[0] if outcome in ("undone", "equal", "elsewhere") else "",
                    "mutant_object": m}
        with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
            done = list(ex.map(one, enumerate(mutants, first)))
        results.extend(done)
        return done

    if "single" in sources:
        singles = run_all(groups["single"])
    if "typed" in sources:
        run_all(groups["typed"])
    if "pair" in sources:
        if args.singles_from:
            earlier = {(r["checkpoint"], r["mutant"]): r["outcome"] for r in json.load(open(args.singles_from)) if r["source"] == "single"}
            singles = [{"mutant_object": m, "outcome": earlier.get((m.checkpoint, m.name), "does not compile")} for m in groups["single"]]
        elif "single" not in sources:
            singles = run_all(groups["single"])
        failing = [r["mutant_object"] for r in singles if r["outcome"] not in ("does not compile", "still passes")]
        run_all(pair_mutants(failing, args.pairs, args.seed))

    shutil.rmtree(work, ignore_errors=True)
    report(results, sources, checkpoints, args)
    if args.json:
        json.dump([{k: v for k, v in r.items() if k != "mutant_object"} for r in results], open(args.json, "w"), indent=1)
    if args.sample:
        missed = [r["mutant"] + ": " + r["outcome"] for r in results if r["outcome"] not in ("undone", "equal")]
        if missed:
            sys.exit("not repaired where the mutation was:\n  " + "\n  ".join(missed))


REPAIRED = ("undone", "equal", "elsewhere")


def cost_ratio(results):
    """A repaired grade's time against a passing one's, graded in the same run and under the same load:
    the mutants that still pass are passing grades of the same programs' size."""
    passing = [r["seconds"] for r in results if r["outcome"] == "still passes"]
    for label, outcomes in (("repaired", REPAIRED), ("not repaired (budget spent)", ("not repaired",))):
        failing = [r["seconds"] for r in results if r["outcome"] in outcomes]
        if passing and failing:
            p, f = statistics.median(passing), statistics.median(failing)
            print("a %s grade, median %.2f s over %d; a passing grade, median %.2f s over %d: %.1fx" % (label, f, len(failing), p, len(passing), f / p))


def report(results, sources, checkpoints, args):
    print("| mutants | checkpoint | made | do not compile | still pass | failing | explained without a search | repaired | of them undone / equal | wrong (elsewhere) | not repaired | repaired share of the failing, searched | candidates per repair (median) | confirming renders per repair | seconds per repair (median) |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for source in ("single", "typed", "pair"):
        if source not in sources:
            continue
        for checkpoint in checkpoints + ["all"]:
            rs = [r for r in results if r["source"] == source and (checkpoint == "all" or r["checkpoint"] == checkpoint)]
            if not rs:
                continue
            n = lambda *o: sum(r["outcome"] in o for r in rs)
            failing = len(rs) - n("does not compile", "still passes")
            searched = failing - n("explained")
            repaired = [r for r in rs if r["outcome"] in REPAIRED]
            med = lambda key: statistics.median(r[key] for r in repaired) if repaired else 0
            print("| %s | %s | %d | %d | %d | %d | %d | %d | %d / %d | %d | %d | %s | %s | %s | %s |" % (
                source, checkpoint, len(rs), n("does not compile"), n("still passes"), failing, n("explained"), len(repaired),
                n("undone"), n("equal"), n("elsewhere"), n("not repaired"),
                "%.0f%%" % (100.0 * len(repaired) / searched) if searched else "-",
                "%g" % med("candidates"), "%g" % med("confirmations"), "%.2f" % med("seconds")))
    print()
    cost_ratio(results)
    print()
    print("| operator | failing | explained | repaired | not repaired |")
    print("| --- | --- | --- | --- | --- |")
    ops = {}
    for r in results:
        if r["source"] != "single" or r["outcome"] in ("does not compile", "still passes"):
            continue
        op = r["mutant"].split(",")[0]
        row = ops.setdefault(op, [0, 0, 0, 0])
        row[0] += 1
        row[1] += r["outcome"] == "explained"
        row[2] += r["outcome"] in REPAIRED
        row[3] += r["outcome"] == "not repaired"
    for op, row in sorted(ops.items()):
        print("| %s | %d | %d | %d | %d |" % (op, *row))
    print()
    for r in results:
        if r["outcome"] in ("not repaired", "elsewhere", "equal") and r["source"] != "pair":
            print("- %s %s %s: %s %s" % (r["source"], r["checkpoint"], r["mutant"], r["outcome"], r["detail"]))
    wrong = sum(r["outcome"] == "elsewhere" for r in results)
    print("\nwrong: %d" % wrong)


if __name__ == "__main__":
    main()
