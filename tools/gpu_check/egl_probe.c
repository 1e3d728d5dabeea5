// Copied from the workplace gpu-bundle tool (tools/gpu_check/README.md says what this folder adds).
// Independent EGL probe: which devices, which extensions, where initialisation fails (eglGetError).
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GLES3/gl3.h>
#include <stdio.h>
#include <string.h>
static const char* errname(EGLint e) {
  switch (e) {
#define C(x) case x: return #x;
    C(EGL_SUCCESS) C(EGL_NOT_INITIALIZED) C(EGL_BAD_ACCESS) C(EGL_BAD_ALLOC) C(EGL_BAD_ATTRIBUTE)
    C(EGL_BAD_CONFIG) C(EGL_BAD_CONTEXT) C(EGL_BAD_CURRENT_SURFACE) C(EGL_BAD_DISPLAY) C(EGL_BAD_MATCH)
    C(EGL_BAD_NATIVE_PIXMAP) C(EGL_BAD_NATIVE_WINDOW) C(EGL_BAD_PARAMETER) C(EGL_BAD_SURFACE) C(EGL_CONTEXT_LOST)
#undef C
  }
  return "?";
}
int main(void) {
  const char* ce = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  printf("client extensions: %s (err %s)\n", ce ? ce : "(null)", errname(eglGetError()));
  PFNEGLQUERYDEVICESEXTPROC qd = (PFNEGLQUERYDEVICESEXTPROC)eglGetProcAddress("eglQueryDevicesEXT");
  PFNEGLQUERYDEVICESTRINGEXTPROC qs = (PFNEGLQUERYDEVICESTRINGEXTPROC)eglGetProcAddress("eglQueryDeviceStringEXT");
  PFNEGLGETPLATFORMDISPLAYEXTPROC gpd = (PFNEGLGETPLATFORMDISPLAYEXTPROC)eglGetProcAddress("eglGetPlatformDisplayEXT");
  printf("eglQueryDevicesEXT=%p eglQueryDeviceStringEXT=%p eglGetPlatformDisplayEXT=%p\n", (void*)qd, (void*)qs, (void*)gpd);
  if (!qd || !qs || !gpd) return 2;
  EGLDeviceEXT devs[16]; EGLint n = 0;
  EGLBoolean ok = qd(16, devs, &n);
  printf("eglQueryDevicesEXT -> %d, %d devices (err %s)\n", ok, n, errname(eglGetError()));
  int rendered = 0;
  for (int i = 0; i < n; ++i) {
    const char* de = qs(devs[i], EGL_EXTENSIONS);
    printf("device %d extensions: %s\n", i, de ? de : "(null)");
    if (de && strstr(de, "EGL_EXT_device_drm")) { const char* f = qs(devs[i], EGL_DRM_DEVICE_FILE_EXT); printf("  drm file: %s (err %s)\n", f ? f : "(null)", errname(eglGetError())); }
    EGLDisplay d = gpd(EGL_PLATFORM_DEVICE_EXT, devs[i], NULL);
    printf("  eglGetPlatformDisplayEXT -> %p (err %s)\n", d, errname(eglGetError()));
    EGLint ma = 0, mi = 0;
    if (!eglInitialize(d, &ma, &mi)) { printf("  eglInitialize FAILED: %s\n", errname(eglGetError())); continue; }
    printf("  eglInitialize OK %d.%d vendor=%s version=%s\n  display extensions: %s\n", ma, mi, eglQueryString(d, EGL_VENDOR), eglQueryString(d, EGL_VERSION), eglQueryString(d, EGL_EXTENSIONS));
    printf("  client APIs: %s\n", eglQueryString(d, EGL_CLIENT_APIS));
    if (!eglBindAPI(EGL_OPENGL_ES_API)) { printf("  eglBindAPI(ES) FAILED: %s\n", errname(eglGetError())); continue; }
    EGLint ca[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_NONE}; EGLConfig cfg = NULL; EGLint nc = 0;
    ok = eglChooseConfig(d, ca, &cfg, 1, &nc);
    printf("  eglChooseConfig(ES3) -> %d, %d configs (err %s)\n", ok, nc, errname(eglGetError()));
    if (nc < 1) cfg = NULL;
    EGLint robust[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_CONTEXT_OPENGL_ROBUST_ACCESS, EGL_TRUE, EGL_NONE};
    EGLint plain[] = {EGL_CONTEXT_MAJOR_VERSION, 3, EGL_CONTEXT_MINOR_VERSION, 0, EGL_NONE};
    {  /* how each config choice fares, independent of what ShadeLab does */
      EGLContext t = eglCreateContext(d, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, plain);
      printf("  [check] no-config ES3 context -> %p (err %s)\n", t, errname(eglGetError()));
      if (t != EGL_NO_CONTEXT) eglDestroyContext(d, t);
      EGLint pa[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE, EGL_OPENGL_ES3_BIT, EGL_NONE}; EGLConfig pc = NULL; EGLint pn = 0;
      eglChooseConfig(d, pa, &pc, 1, &pn);
      printf("  [check] eglChooseConfig(PBUFFER, ES3) -> %d configs\n", pn);
      if (pn > 0) { t = eglCreateContext(d, pc, EGL_NO_CONTEXT, robust); printf("  [check] pbuffer-config robust ES3 context -> %p (err %s)\n", t, errname(eglGetError())); if (t != EGL_NO_CONTEXT) eglDestroyContext(d, t); }
    }
    EGLContext c = eglCreateContext(d, cfg, EGL_NO_CONTEXT, robust);
    printf("  robust ES3 context -> %p (err %s)\n", c, errname(eglGetError()));
    if (c == EGL_NO_CONTEXT) { c = eglCreateContext(d, cfg, EGL_NO_CONTEXT, plain); printf("  plain ES3 context -> %p (err %s)\n", c, errname(eglGetError())); }
    if (c == EGL_NO_CONTEXT) continue;
    if (!eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, c)) { printf("  eglMakeCurrent(no surface) FAILED: %s\n", errname(eglGetError())); continue; }
    printf("  GL_VENDOR=%s\n  GL_RENDERER=%s\n  GL_VERSION=%s\n  GLSL=%s\n", glGetString(GL_VENDOR), glGetString(GL_RENDERER), glGetString(GL_VERSION), glGetString(GL_SHADING_LANGUAGE_VERSION));
    GLint ms = 0; glGetIntegerv(GL_MAX_SAMPLES, &ms); printf("  GL_MAX_SAMPLES=%d\n", ms);
    rendered = 1;
    eglMakeCurrent(d, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT); eglDestroyContext(d, c); eglTerminate(d);
  }
  return rendered ? 0 : 1;
}
