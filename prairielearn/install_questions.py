#!/usr/bin/env python3
"""Copies ShadeLab's two PrairieLearn question templates into a PrairieLearn course.

    prairielearn/install_questions.py PL_COURSE [--image IMAGE] [--checkpoint NAME] [--course PROFILE]

writes, under PL_COURSE/questions/:

  shadelab-hw2-hand-in/      upload the HW2 folder's files; graded test for test as on Gradescope
  shadelab-hw2-NAME/         edit the checkpoint's two shaders beside a live canvas; graded as code

Each question gets a fresh uuid; IMAGE is the grader image the course published (docs/deploy.md,
"On PrairieLearn"). The checkpoint question's editors open on the course's public starter, and its
canvas runs the homework page's own view (web/js) on the course's mesh, with what a student sees of
the course (`shadelab course show --as-student`): never a reference. With --course, the profile's
folder goes to PL_COURSE/serverFilesCourse/shadelab/ and the questions grade by it.

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

def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("pl_course", type=Path)
    parser.add_argument("--image", default="shadelab/prairielearn-grader")
    parser.add_argument("--checkpoint", default="specular")
    parser.add_argument("--course", help="a course profile (course.json) to grade by instead of the built-in course")
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
        server_files = args.pl_course / "serverFilesCourse" / "shadelab"
        if server_files.exists():
            shutil.rmtree(server_files)
        shutil.copytree(Path(args.course).resolve().parent, server_files)
        params["course"] = "serverFilesCourse/shadelab/" + Path(args.course).name
    questions = args.pl_course / "questions"
    questions.mkdir(parents=True, exist_ok=True)

    copy_question(TEMPLATES / "hand-in", questions / "shadelab-hw2-hand-in", args.image, params, bool(args.course))

    code = checkpoint["code"]
    target = questions / f"shadelab-hw2-{checkpoint['name']}"
    copy_question(TEMPLATES / "checkpoint", target, args.image, {**params, "checkpoint": checkpoint["name"]}, bool(args.course))
    html = (target / "question.html").read_text()
    html = html.replace("phong_vert.js", f"{code}_vert.js").replace("phong_frag.js", f"{code}_frag.js")
    html = html.replace("Edit the two shaders of the specular deliverable: ambient + diffuse + specular (Phong)",
                        f"Edit the two shaders of the {checkpoint['name']} deliverable: {checkpoint['title']}")
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
    print(f"install_questions: {questions / 'shadelab-hw2-hand-in'} and {target}, grading with {args.image}")


if __name__ == "__main__":
    main()
