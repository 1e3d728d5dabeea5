#!/usr/bin/env python3
"""Copies ShadeLab's two PrairieLearn question templates into a PrairieLearn course.

    prairielearn/install_questions.py PL_COURSE [--image IMAGE] [--checkpoint NAME] [--course PROFILE]

writes, under PL_COURSE/questions/, the hand-in as a question per part (PrairieLearn's upload holds
5 MB a question; a real HW2 hand-in is 8.6 MB: 3.1 MB of saved frames, 4.5 MB of Blender renders,
1 MB of notebook):

  shadelab-hw2-frames-and-code/  the shaders and the frames saved from the page; graded as on Gradescope
  shadelab-hw2-blender/          the Blender renders; graded as on Gradescope
  shadelab-hw2-notebook/         the notebook, graded by hand (PrairieLearn's manual grading)
  shadelab-hw2-NAME/             edit the checkpoint's two shaders beside a live canvas; graded as code

(--whole: one question for the whole hand-in, shadelab-hw2-hand-in/, where it fits in 5 MB.) With
--course-instance CI, PL_COURSE/courseInstances/CI/assessments/shadelab-hw2/infoAssessment.json
puts the three part questions in one homework worth what Gradescope's autograder gives.

Each question gets a fresh uuid; IMAGE is the grader image the course published (docs/deploy.md,
"On PrairieLearn"). The checkpoint question's editors open on the course's public starter, and its
canvas runs the homework page's own view (web/js) on the course's mesh, with what a student sees of
the course (`shadelab course show --as-student`): never a reference. With --course, the files the
profile names (and only those: its folder may be a TA's working folder, submissions and all) go to
PL_COURSE/serverFilesCourse/shadelab/, with the profile rewritten to name them where they land, and
the questions grade by it. Files compiled into shadelab (builtin:...) stay named so.

SHADELAB_BIN names the shadelab binary (default: build/shadelab beside this script's repository).
"""
import argparse
import json
import os
import shutil
import subprocess
import sys
import uuid
from pathlib import Path

REPO = Path(__file__).resolve().parent.parent
TEMPLATES = REPO / "prairielearn" / "questions"
PAGE_MODULES = ["gl_view.js", "mat4.js", "obj.js", "shader_module.js"]


def shadelab(*args):
    binary = os.environ.get("SHADELAB_BIN", str(REPO / "build" / "shadelab"))
    return json.loads(subprocess.run([binary, *args], check=True, capture_output=True, text=True).stdout)


def course_file(named, profile):
    """A file as `course show` names it: builtin:PATH is the repository's, else absolute."""
    if named.startswith("builtin:"):
        return REPO / named[len("builtin:"):]
    return Path(named) if Path(named).is_absolute() else Path(profile).parent / named


def install_profile(full, server_files):
    """The profile as `course show` prints it (every file builtin:... or absolute), each absolute file
    copied beside it under its own name (made unique) and named so: a profile loads from wherever
    PrairieLearn puts serverFilesCourse."""
    if server_files.exists():
        shutil.rmtree(server_files)
    server_files.mkdir(parents=True)
    placed = {}

    def place(value):
        if isinstance(value, dict):
            return {key: place(item) for key, item in value.items()}
        if isinstance(value, list):
            return [place(item) for item in value]
        if isinstance(value, str) and os.path.isabs(value) and Path(value).is_file():
            source = Path(value).resolve()
            if source not in placed:
                name, k = source.name, 1
                while name in placed.values() or name == "course.json":
                    name, k = f"{source.stem}_{k}{source.suffix}", k + 1
                shutil.copy(source, server_files / name)
                placed[source] = name
            return placed[source]
        return value

    write_json(server_files / "course.json", place(full))
    return sorted(placed.values())


def task_paragraph(checkpoint, full):
    """What the checkpoint question asks, from the course's facts: the deliverable in its own words
    (the title after its name, which the page's heading already shows), the exponent only where the
    deliverable's formula has a specular term, a hidden light only where it is graded under one."""
    title = checkpoint["title"]
    what = title.split(": ", 1)[1] if ": " in title else title
    terms = checkpoint.get("formula", {}).get("terms")
    task = f"Edit the two shaders of the {checkpoint['name']} deliverable, {what}"
    if terms in ("lambert", "phong"):
        task += ", with the page's light and its values"
    exponent = full.get("specularExponent")
    if terms == "phong" and exponent:
        task += f" (<code>{exponent['variable']} = {exponent['value']}</code>)"
    graded = "graded"
    if checkpoint.get("probes"):
        graded += " under the page's light and under a hidden one"
    elif terms in ("lambert", "phong"):
        graded += " under the page's light"
    sentences = [task + ".", f"The canvas draws your shaders as you type, as the homework page does; submit to have them {graded}."]
    return "<p>\n    " + "\n    ".join(sentences) + "\n  </p>"


def write_json(path, value):
    path.write_text(json.dumps(value, indent=2) + "\n")


def copy_question(template, target, image, shadelab_params, server_files):
    if target.exists():
        shutil.rmtree(target)
    shutil.copytree(template, target)
    info = json.loads((target / "info.json").read_text())
    info["uuid"] = str(uuid.uuid4())
    info["externalGradingOptions"]["image"] = image
    if server_files:
        info["externalGradingOptions"]["serverFilesCourse"] = ["shadelab/"]
    write_json(target / "info.json", info)
    server = target / "server.py"
    lines = [f"SHADELAB = {json.dumps(shadelab_params)}" if line.startswith("SHADELAB = ") else line
             for line in server.read_text().splitlines()]
    server.write_text("\n".join(lines) + "\n")

def frame_glob(full):
    """The saved frames' names as a pattern: hw2_{prefix}_{k} -> hw2_*_*.png."""
    return full["frames"]["fileName"].replace("{prefix}", "*").replace("{k}", "*") + ".png"


def part_html(paragraphs, upload):
    panel = "".join(f"  <p>\n    {p}\n  </p>\n" for p in paragraphs)
    return (f"<pl-question-panel>\n{panel}</pl-question-panel>\n\n<pl-file-upload {upload}></pl-file-upload>\n\n"
            "<pl-submission-panel>\n  <pl-external-grader-results></pl-external-grader-results>\n"
            "  <pl-file-preview></pl-file-preview>\n</pl-submission-panel>\n")


def code_stems(full):
    return [c["code"] for c in full["checkpoints"] if c.get("code")]


def hand_in_parts(full):
    """The hand-in's parts as questions: (id, part or None for manual, title, html, points)."""
    first, last = full["checkpoints"][0], full["checkpoints"][-1]
    count = full["frames"]["count"]
    name = full["frames"]["fileName"]
    first_frame = name.replace("{prefix}", first["prefix"]).replace("{k}", "0") + ".png"
    last_frame = name.replace("{prefix}", last["prefix"]).replace("{k}", str(count - 1)) + ".png"
    shaders = ", ".join(f"<code>{stem}_vert.js</code>, <code>{stem}_frag.js</code>" for stem in code_stems(full))
    images = [Path(i["file"]).name for i in full["notebook"]["images"]]
    notebook = full["notebook"].get("file", "HW2.ipynb")
    graded = ("Each deliverable is graded as on Gradescope: your saved frames against the reference at the angles your "
              "page drew them, your code under the page's light and under a hidden one, and whether your frames are what "
              "your code draws. A test that fails says what differs, in the homework's terms, and shows where.")
    return [
        ("shadelab-hw2-frames-and-code", "deliverables", "HW2: your shaders and the frames you saved",
         part_html([f"Upload your shaders from <code>src/shaders/</code> ({shaders}) and the frames you saved from the page "
                    f"for each deliverable, from <code>images/</code> (<code>{first_frame}</code> to <code>{last_frame}</code>), "
                    "by the names they have there (the upload keeps no folders).", graded],
                   f'optional-file-patterns="*_vert.js, *_frag.js, {frame_glob(full)}"'),
         sum(c["points"] for c in full["checkpoints"])),
        ("shadelab-hw2-blender", "images", "HW2: your Blender renders",
         part_html([f"Upload your Blender renders: {', '.join(f'<code>{i}</code>' for i in images)}. Each is checked as on "
                    "Gradescope and shown to the TA.",
                    "The upload holds 5 MB for this question. If your renders pass it, save them again from Blender as PNG "
                    "with 8 bits a channel, RGB (no alpha) and 100% compression (Output Properties, Output); a real "
                    "hand-in's four 1920 x 1080 renders measured 4.46 MB in all."],
                   f'optional-file-names="{", ".join(images)}"'),
         sum(i.get("points") or 0 for i in full["notebook"]["images"])),
        ("shadelab-hw2-notebook", None, "HW2: your notebook",
         part_html([f"Upload your notebook, <code>{notebook}</code>, with your grids and answers. The course staff grade it "
                    "by hand."], f'file-names="{notebook}"'),
         0),
    ]


def install_part(questions, part_id, part, title, html, image, params, server_files):
    target = questions / part_id
    copy_question(TEMPLATES / "hand-in", target, image, {**params, "part": part} if part else params, server_files)
    (target / "question.html").write_text(html)
    info = json.loads((target / "info.json").read_text())
    info["title"] = title
    if part is None:  # graded by hand: no external grader
        info["gradingMethod"] = "Manual"
        del info["externalGradingOptions"]
        (target / "server.py").unlink()
    write_json(target / "info.json", info)


def write_assessment(pl_course, instance, parts):
    """The homework of the three part questions, worth the autograder's points (the notebook's
    points are the staff's to set: 0 here)."""
    folder = pl_course / "courseInstances" / instance / "assessments" / "shadelab-hw2"
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / "infoAssessment.json"
    kept = json.loads(path.read_text()).get("uuid") if path.exists() else None  # a reinstall keeps its identity
    questions = []
    for part_id, part, _, _, points in parts:
        questions.append({"id": part_id, "autoPoints": points} if part else {"id": part_id, "manualPoints": points})
    write_json(path, {"uuid": kept or str(uuid.uuid4()), "type": "Homework", "title": "HW2: shading and Blender",
                      "set": "Homework", "number": "2", "zones": [{"title": "HW2", "questions": questions}]})
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("pl_course", type=Path)
    parser.add_argument("--image", default="shadelab/prairielearn-grader")
    parser.add_argument("--checkpoint", default="specular")
    parser.add_argument("--course", help="a course profile (course.json) to grade by instead of the built-in course")
    parser.add_argument("--whole", action="store_true", help="one question for the whole hand-in instead of a question per part")
    parser.add_argument("--course-instance", help="write the part questions' homework into this course instance")
    args = parser.parse_args()

    course_args = ["--course", args.course] if args.course else []
    full = shadelab("course", "show", *course_args)
    public = shadelab("course", "show", "--as-student", *course_args)
    checkpoint = next((c for c in full["checkpoints"] if c["name"] == args.checkpoint), None)
    if not checkpoint or not checkpoint.get("code"):
        sys.exit(f"install_questions: '{args.checkpoint}' is not a checkpoint with code in this course "
                 f"(those with code: {', '.join(c['name'] for c in full['checkpoints'] if c.get('code'))})")

    params = {}
    if args.course:
        installed = install_profile(full, args.pl_course / "serverFilesCourse" / "shadelab")
        params["course"] = "serverFilesCourse/shadelab/course.json"
        print(f"install_questions: the profile and {len(installed)} of its files in serverFilesCourse/shadelab/")
    questions = args.pl_course / "questions"
    questions.mkdir(parents=True, exist_ok=True)

    if args.whole:
        copy_question(TEMPLATES / "hand-in", questions / "shadelab-hw2-hand-in", args.image, params, bool(args.course))
    else:
        parts = hand_in_parts(full)
        for part_id, part, title, html, _ in parts:
            install_part(questions, part_id, part, title, html, args.image, params, bool(args.course))
        if args.course_instance:
            print(f"install_questions: {write_assessment(args.pl_course, args.course_instance, parts)}")

    code = checkpoint["code"]
    target = questions / f"shadelab-hw2-{checkpoint['name']}"
    copy_question(TEMPLATES / "checkpoint", target, args.image, {**params, "checkpoint": checkpoint["name"]}, bool(args.course))
    html = (target / "question.html").read_text()
    html = html.replace("phong_vert.js", f"{code}_vert.js").replace("phong_frag.js", f"{code}_frag.js")
    template_task = html[html.index("<p>"):html.index("</p>") + len("</p>")]
    html = html.replace(template_task, task_paragraph(checkpoint, full))
    (target / "question.html").write_text(html)
    info = json.loads((target / "info.json").read_text())
    info["title"] = f"HW2: {checkpoint['title']}"
    write_json(target / "info.json", info)
    # The editors open on the starter as handed out: the page's own preset, public to students.
    starter = next(p for p in public["presets"] if p["name"] == public["pagePreset"])
    (target / f"{code}_vert.js").write_text(starter["vertex"]["source"])
    (target / f"{code}_frag.js").write_text(starter["fragment"]["source"])
    client = target / "clientFilesQuestion"
    for module in PAGE_MODULES:
        shutil.copy(REPO / "web" / "js" / module, client / module)
    mesh = next(m for m in full["meshes"] if m["name"] == full["defaultMesh"])
    shutil.copy(course_file(mesh["file"], args.course), client / f"{mesh['name']}.obj")
    write_json(client / "course.json", public)
    print(f"install_questions: the hand-in's questions and {target} in {questions}, grading with {args.image}")


if __name__ == "__main__":
    main()
