// A driver that accepts every shader and program, made from the real one: preloaded
// (LD_PRELOAD) into ShadeLab and its workers, it wraps Mesa's libGLESv2 and changes only what the
// driver *reports* about compiling and linking: always successful, with an empty log. Everything
// else, the compile and link themselves included, is the real driver's.
//
// Some GPU drivers accept what the browser refuses (NVIDIA's takes `float a; a += vec2(1.0);`)
// and answer a refused link with a banner for a log. ShadeLab's verdict must not depend on
// either: under this library, every refusal has to come from ShadeLab's own front end, in its
// own words (tests/webgl_rules_test.cpp, label webgl_rules_any_driver). Fault injection over the
// real GL, like SHADELAB_FAULT_INJECTION; not a mock: nothing is drawn by it.
#include <GLES3/gl3.h>
#include <dlfcn.h>

namespace {

using GetStatus = void (*)(GLuint, GLenum, GLint*);

GetStatus real(const char* name) { return reinterpret_cast<GetStatus>(dlsym(RTLD_NEXT, name)); }

// A status the driver reports; the log's length is always 0 and the status always GL_TRUE.
bool reported(GLenum pname, GLenum status, GLint* params) {
  if (pname == status) {
    *params = GL_TRUE;
    return true;
  }
  if (pname == GL_INFO_LOG_LENGTH) {
    *params = 0;
    return true;
  }
  return false;
}

void empty_log(GLsizei size, GLsizei* length, GLchar* log) {
  if (length) *length = 0;
  if (log && size > 0) log[0] = '\0';
}

}  // namespace

extern "C" {

void glGetShaderiv(GLuint shader, GLenum pname, GLint* params) {
  if (reported(pname, GL_COMPILE_STATUS, params)) return;
  real("glGetShaderiv")(shader, pname, params);
}

void glGetProgramiv(GLuint program, GLenum pname, GLint* params) {
  if (reported(pname, GL_LINK_STATUS, params)) return;
  real("glGetProgramiv")(program, pname, params);
}

void glGetShaderInfoLog(GLuint, GLsizei size, GLsizei* length, GLchar* log) {
  empty_log(size, length, log);
}

void glGetProgramInfoLog(GLuint, GLsizei size, GLsizei* length, GLchar* log) {
  empty_log(size, length, log);
}

}  // extern "C"
