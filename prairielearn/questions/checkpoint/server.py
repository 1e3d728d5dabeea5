# One checkpoint's code: the student edits its two shaders and submits them; graded as code (its
# code and hidden-light tests, no saved frames). The checkpoint is a name of the course profile's.
SHADELAB = {"checkpoint": "specular"}


def generate(data):
    data["params"]["shadelab"] = SHADELAB
