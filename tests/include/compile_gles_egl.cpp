// The same headers seen from C++: extern "C" linkage, the handle constants
// usable in constant expressions without old-style casts, and the GL and
// EGL types the same as the Khronos platform types.
#include <EGL/egl.h>
#include <GLES/gl.h>
#include <GLES/glext.h>
#include <KHR/khrplatform.h>

#include <type_traits>

static_assert(std::is_same_v<decltype(&glClearColor), void (*)(GLfloat, GLfloat, GLfloat, GLfloat)>);
static_assert(std::is_same_v<decltype(&eglSwapBuffers), EGLBoolean (*)(EGLDisplay, EGLSurface)>);
static_assert(EGL_DONT_CARE == -1);
// The GL and EGL types are the Khronos platform types, as in Khronos' own
// headers, so code that mixes the two names compiles.
static_assert(std::is_same_v<GLfixed, khronos_int32_t> && std::is_same_v<GLclampx, khronos_int32_t>);
static_assert(std::is_same_v<GLbyte, khronos_int8_t> && std::is_same_v<GLubyte, khronos_uint8_t>);
static_assert(std::is_same_v<GLshort, khronos_int16_t> && std::is_same_v<GLushort, khronos_uint16_t>);
static_assert(std::is_same_v<GLfloat, khronos_float_t> && std::is_same_v<GLclampf, khronos_float_t>);
static_assert(std::is_same_v<GLintptr, khronos_intptr_t> && std::is_same_v<GLsizeiptr, khronos_ssize_t>);
static_assert(std::is_same_v<EGLint, khronos_int32_t>);
static_assert(GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES == 0x8B9B);
static_assert(GL_TEXTURE0 + 7 == GL_TEXTURE7);

namespace {
// Parameters are typed as the API's own types: a C++ caller may overload on them.
[[maybe_unused]] void draw_points(const GLfloat* positions, GLsizei count) {
  glEnableClientState(GL_VERTEX_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, positions);
  glDrawArrays(GL_POINTS, 0, count);
}
}  // namespace
