# The whole hand-in, graded test for test as on Gradescope: no checkpoint named. A course with its
# own profile puts it in serverFilesCourse/shadelab/ and names it here ("course": PATH inside the
# job; prairielearn/install_questions.py --course does both).
SHADELAB = {}


def generate(data):
    data["params"]["shadelab"] = SHADELAB
