#!/usr/bin/env python3
"""The repair search measured on programs written as students write them (issue 79's harness).

bench/mutation_bench.py mutates the course's own references: its programs are written as the
reference is, so a search that aligns by name reads them well. This bench writes the specular
checkpoint in five shapes (bench/shapes/specular.py: as the reference; a tutorial's names;
coefficient locals with += and R = -reflect(L, N); the guard as arithmetic; each term in a helper
function), types each shape's mistakes into it, the left-out kinds among them (a factor, a term, a
guard, a clamp, an exponent, a normalisation), singly and in pairs, and grades each as a TA does
(`shadelab grade`, which shows staff the repaired line).

A failing program is "at the line" when the search's repair (each part of it, for a pair) is at a
line the mistake wrote, and every mistake of a pair has a part at its line; "elsewhere" when a
part is at a line no mistake touched (a claim about a change never made: wrong); "named" when no
search ran or none found a repair and the formula or the catalogue named what is off; "no line"
otherwise. Mistakes that delete a line count the lines on either side of where it stood.

  bench/shapes_bench.py [--pairs N] [--seed S] [--jobs J] [--shapes a,b] [--only single,pair] [--json FILE]
  SHADELAB_BIN: another build's shadelab.
"""
import argparse
import concurrent.futures
import itertools
import json
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "bench"))
from shapes import specular  # noqa: E402


def module(body):
    """The reference's fragment module with `body` in place of its main."""
    ref = open(os.path.join(ROOT, "shaders", "specular_frag.js")).read()
    head = ref[:ref.index("void main(void) {")]
    return head + body + "\n`;\n"


def mutate(body, mistakes):
    """The module with every mistake made, and for each mistake the mutated file's lines it wrote
    (1-based; a deletion: the lines either side of where it stood). Each new text is written
    between markers first, so the lines are read off the final text whatever the order."""
    text = module(body)
    for k, replacements in enumerate(mistakes):
        for old, new in replacements:
            assert text.count(old) == 1, "%r occurs %d times" % (old, text.count(old))
            text = text.replace(old, "\x01%d\x02%s\x03" % (k, new))
    lines = [set() for _ in mistakes]
    clean, line, i = [], 1, 0
    while i < len(text):
        c = text[i]
        if c == "\x01":
            k = int(text[i + 1:text.index("\x02", i)])
            i = text.index("\x02", i) + 1
            close = text.index("\x03", i)
            new = text[i:close]
            if new:
                lines[k].update(range(line, line + new.rstrip("\n").count("\n") + 1))
            else:
                lines[k].update((line - 1, line) if clean and clean[-1] == "\n" else (line, line + 1))
            clean.append(new)
            line += new.count("\n")
            i = close + 1
            continue
        clean.append(c)
        line += c == "\n"
        i += 1
    return "".join(clean), lines


def grade(binary, store, work, name, vert, frag):
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    paths = {"vert": os.path.join(d, "phong_vert.js"), "frag": os.path.join(d, "phong_frag.js")}
    open(paths["vert"], "w").write(vert)
    open(paths["frag"], "w").write(frag)
    start = time.monotonic()
    run = subprocess.run([binary, "grade", "--vert", paths["vert"], "--frag", paths["frag"], "--reference", "specular", "--cache-dir", store],
                         capture_output=True, text=True)
    seconds = time.monotonic() - start
    out = run.stdout
    if "{" not in out:
        raise SystemExit("no grade for %s (exit %d): %s" % (name, run.returncode, run.stderr[-2000:]))
    return seconds, json.loads(out[out.index("{"):out.rindex("}") + 1])


def classify(report, lines):
    """(outcome, where): does not compile, still passes, named, at the line, elsewhere, no line."""
    if report.get("diagnostics") or not report.get("frames"):
        return "does not compile", ""
    if report.get("pass"):
        return "still passes", ""
    search = report.get("repairSearch") or {}
    found = search.get("found")
    if not found:
        e = report.get("explanation") or {}
        named = e.get("explained") or report.get("diagnosis", "") not in ("", "nan")
        return ("named" if named else "no line"), e.get("label") or report.get("diagnosis") or ""
    parts = [found] + ([search["also"]] if search.get("also") else [])
    frag_parts = [p for p in parts if p["file"].endswith("frag.js")]
    where = "; ".join("%s line %d" % (p["kind"], p["line"]) for p in parts)
    if len(frag_parts) < len(parts) or any(not any(p["line"] in ls for ls in lines) for p in parts):
        return "elsewhere", where
    if not all(any(p["line"] in ls for p in parts) for ls in lines):
        return "elsewhere", where + " (a mistake without its line)"
    return "at the line", where


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--pairs", type=int, default=200, help="pairs in all, spread over the shapes")
    ap.add_argument("--seed", type=int, default=79)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--shapes", default=",".join(s for s in specular.SHAPES if s not in specular.HELD_OUT),
                    help="the five the rules were written beside; 'step guard' is held out and runs only when named")
    ap.add_argument("--only", default="single,pair")
    ap.add_argument("--match", help="singles whose mistake holds this text")
    ap.add_argument("--json", help="write every program's outcome here")
    args = ap.parse_args()
    binary = os.environ.get("SHADELAB_BIN", os.path.join(ROOT, "build", "shadelab"))
    shapes = args.shapes.split(",")
    work = tempfile.mkdtemp(prefix="shadelab-shapes.")
    store = os.path.join(work, "store")
    shutil.copy2(binary, os.path.join(work, "shadelab"))
    binary = os.path.join(work, "shadelab")
    vert = open(os.path.join(ROOT, "shaders", "specular_vert.js")).read()

    programs = []  # (shape, kind, name, groups, text, lines)
    for shape in shapes:
        body, mistakes = specular.SHAPES[shape], specular.MISTAKES[shape]
        programs.append((shape, "right", "as written", (), module(body), []))
        if "single" in args.only.split(","):
            for name, (group, replacements) in mistakes.items():
                if args.match and args.match not in name:
                    continue
                text, lines = mutate(body, [replacements])
                programs.append((shape, "single", name, (group,), text, lines))
    if "pair" in args.only.split(","):
        rng = random.Random(args.seed)
        per_shape = -(-args.pairs // len(shapes))
        for shape in shapes:
            body, mistakes = specular.SHAPES[shape], specular.MISTAKES[shape]
            candidates = []
            for (a, (ga, ra)), (b, (gb, rb)) in itertools.combinations(mistakes.items(), 2):
                olds = [o for o, _ in ra + rb]
                if any(x != y and (x in y or y in x) for x, y in itertools.permutations(olds, 2)) or len(set(olds)) < len(olds):
                    continue
                try:
                    text, lines = mutate(body, [ra, rb])
                except (AssertionError, ValueError):
                    continue
                candidates.append((shape, "pair", a + " + " + b, (ga, gb), text, lines))
            rng.shuffle(candidates)
            programs.extend(candidates[:per_shape])

    # The reference into the store first: its renders are not the search's.
    grade(binary, store, work, "warm", vert, open(os.path.join(ROOT, "shaders", "specular_frag.js")).read())

    def one(numbered):
        i, (shape, kind, name, groups, text, lines) = numbered
        seconds, report = grade(binary, store, work, "p%04d" % i, vert, text)
        outcome, where = classify(report, lines)
        words = (report.get("messages") or [""])[1:2]
        print("%4d %-16s %-6s %-60s %-17s %s (%.1f s)" % (i, shape, kind, name[:60], outcome, where[:70], seconds), file=sys.stderr, flush=True)
        search = report.get("repairSearch") or {}
        return {"shape": shape, "kind": kind, "mistake": name, "groups": list(groups), "outcome": outcome, "where": where,
                "seconds": seconds, "candidates": search.get("candidates", 0), "words": words[0] if words else ""}

    with concurrent.futures.ThreadPoolExecutor(max_workers=args.jobs) as ex:
        results = list(ex.map(one, enumerate(programs)))
    shutil.rmtree(work, ignore_errors=True)
    if args.json:
        json.dump(results, open(args.json, "w"), indent=1)
    summary(results, shapes)


def summary(results, shapes):
    print("| shape | programs | right as written | single: failing | at the line | named, no line | no line | elsewhere | of the left-out singles at the line | pairs: failing | at the line | elsewhere |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for shape in shapes + ["all"]:
        rs = [r for r in results if shape in ("all", r["shape"])]
        right = [r for r in rs if r["kind"] == "right"]
        singles = [r for r in rs if r["kind"] == "single" and r["outcome"] not in ("does not compile", "still passes")]
        pairs = [r for r in rs if r["kind"] == "pair" and r["outcome"] not in ("does not compile", "still passes")]
        left = [r for r in singles if "leaves out" in r["groups"]]
        n = lambda xs, o: sum(r["outcome"] == o for r in xs)
        share = lambda a, b: "%d of %d (%.0f%%)" % (a, b, 100.0 * a / b) if b else "-"
        print("| %s | %d | %s | %d | %s | %d | %d | %d | %s | %d | %s | %d |" % (
            shape, len(rs), "yes" if all(r["outcome"] == "still passes" for r in right) else "NO", len(singles),
            share(n(singles, "at the line"), len(singles)), n(singles, "named"), n(singles, "no line"), n(singles, "elsewhere"),
            share(n(left, "at the line"), len(left)), len(pairs), share(n(pairs, "at the line"), len(pairs)), n(pairs, "elsewhere")))
    passing = [r["seconds"] for r in results if r["outcome"] == "still passes"]
    for label, outcomes in (("repaired at the line", ("at the line",)), ("no repair found", ("named", "no line"))):
        failing = [r["seconds"] for r in results if r["outcome"] in outcomes]
        if passing and failing:
            p, f = statistics.median(passing), statistics.median(failing)
            print("a grade %s: median %.2f s over %d; a passing grade: median %.2f s over %d: %.1fx" % (label, f, len(failing), p, len(passing), f / p))
    misses = [r for r in results if r["kind"] == "single" and r["outcome"] in ("named", "no line", "elsewhere")]
    if misses:
        print("\nsingles without their line:")
        for r in misses:
            print("- %s, %s: %s %s" % (r["shape"], r["mistake"], r["outcome"], r["where"][:100]))


if __name__ == "__main__":
    main()
