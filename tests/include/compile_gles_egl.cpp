// The same headers seen from C++: extern "C" linkage, and the handle
// constants usable in constant expressions without old-style casts.
#include <EGL/egl.h>
#include <GLES/gl.h>

#include <type_traits>

static_assert(std::is_same_v<decltype(&glClearColor), void (*)(GLfloat, GLfloat, GLfloat, GLfloat)>);
static_assert(std::is_same_v<decltype(&eglSwapBuffers), EGLBoolean (*)(EGLDisplay, EGLSurface)>);
static_assert(EGL_DONT_CARE == -1);
static_assert(GL_TEXTURE0 + 7 == GL_TEXTURE7);

namespace {
// Parameters are typed as the API's own types: a C++ caller may overload on them.
[[maybe_unused]] void draw_points(const GLfloat* positions, GLsizei count) {
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, positions);
  glDrawArrays(GL_POINTS, 0, count);
}
}  // namespace
