// The OpenGL ES 1.1 entry points: each checks for a current context and
// forwards to it. Without a current context a call does nothing (and a
// query returns 0), as the GL leaves that case undefined.
#include <GLES/gl.h>
#include <GLES/glext.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "gl/context.h"
#include "gl/context_internal.h"
#include "gl/entry_point.h"
#include "gl/texture_formats.h"

using tessera::gl::Context;

namespace {

// Number of values a vector query returns, GL_INVALID_ENUM if unknown.
bool query(Context* c, GLenum name, std::vector<float>& values) {
  const int count = c->query_count(name);
  if (count == 0) {
    c->error(GL_INVALID_ENUM);
    return false;
  }
  values.assign(static_cast<size_t>(count), 0.0f);
  c->get_floats(name, values.data());
  return true;
}

// The matrix whose bits an OES_matrix_get name asks for, 0 for another name.
GLenum matrix_of_float_bits(GLenum name) {
  switch (name) {
    case GL_MODELVIEW_MATRIX_FLOAT_AS_INT_BITS_OES: return GL_MODELVIEW_MATRIX;
    case GL_PROJECTION_MATRIX_FLOAT_AS_INT_BITS_OES: return GL_PROJECTION_MATRIX;
    case GL_TEXTURE_MATRIX_FLOAT_AS_INT_BITS_OES: return GL_TEXTURE_MATRIX;
    default: return 0;
  }
}

bool is_color_query(GLenum name) {
  return name == GL_COLOR_CLEAR_VALUE || name == GL_CURRENT_COLOR || name == GL_LIGHT_MODEL_AMBIENT ||
         name == GL_FOG_COLOR || name == GL_DEPTH_RANGE || name == GL_DEPTH_CLEAR_VALUE || name == GL_ALPHA_TEST_REF;
}

int light_param_count(GLenum name) {
  switch (name) {
    case GL_AMBIENT:
    case GL_DIFFUSE:
    case GL_SPECULAR:
    case GL_POSITION:
    case GL_EMISSION:
    case GL_AMBIENT_AND_DIFFUSE:
    case GL_LIGHT_MODEL_AMBIENT: return 4;
    case GL_SPOT_DIRECTION: return 3;
    default: return 1;
  }
}

}  // namespace

extern "C" {

GL_API GLenum GL_APIENTRY glGetError(void) {
  WITH_CONTEXT(GL_NO_ERROR)
  return c->get_error();
}
GL_API const GLubyte* GL_APIENTRY glGetString(GLenum name) {
  WITH_CONTEXT(nullptr)
  return c->get_string(name);
}
GL_API void GL_APIENTRY glFinish(void) {
  WITH_CONTEXT() c->finish();
}
GL_API void GL_APIENTRY glFlush(void) {
  WITH_CONTEXT() c->flush();
}
GL_API void GL_APIENTRY glHint(GLenum target, GLenum mode) {
  WITH_CONTEXT() c->hint(target, mode);
}
GL_API void GL_APIENTRY glEnable(GLenum cap) {
  WITH_CONTEXT() c->enable(cap, true);
}
GL_API void GL_APIENTRY glDisable(GLenum cap) {
  WITH_CONTEXT() c->enable(cap, false);
}
GL_API GLboolean GL_APIENTRY glIsEnabled(GLenum cap) {
  WITH_CONTEXT(GL_FALSE)
  return c->is_enabled(cap) ? GL_TRUE : GL_FALSE;
}
GL_API void GL_APIENTRY glGetBooleanv(GLenum pname, GLboolean* data) {
  WITH_CONTEXT()
  std::vector<float> v;
  if (!query(c, pname, v)) return;
  for (size_t i = 0; i < v.size(); ++i) data[i] = v[i] != 0 ? GL_TRUE : GL_FALSE;
}
GL_API void GL_APIENTRY glGetFloatv(GLenum pname, GLfloat* data) {
  WITH_CONTEXT()
  std::vector<float> v;
  if (!query(c, pname, v)) return;
  for (size_t i = 0; i < v.size(); ++i) data[i] = v[i];
}
GL_API void GL_APIENTRY glGetIntegerv(GLenum pname, GLint* data) {
  WITH_CONTEXT()
  std::vector<float> v;
  // OES_matrix_get: the matrix's floats, each as the integer of the same
  // 32 bits (IEEE 754 single), so that a program without float keeps them
  // exactly. Only glGetIntegerv takes these names.
  if (const GLenum matrix = matrix_of_float_bits(pname)) {
    if (!query(c, matrix, v)) return;
    std::memcpy(data, v.data(), v.size() * sizeof(float));
    return;
  }
  if (!query(c, pname, v)) return;
  // Colours and depths map [0, 1] to the full integer range (GL 2.2.1).
  for (size_t i = 0; i < v.size(); ++i)
    data[i] = is_color_query(pname) ? tessera::gl::int_from_unit_float(v[i]) : tessera::gl::int_from_float(v[i]);
}
GL_API void GL_APIENTRY glGetPointerv(GLenum pname, void** params) {
  WITH_CONTEXT() c->get_pointer(pname, params);
}

GL_API void GL_APIENTRY glEnableClientState(GLenum array) {
  WITH_CONTEXT() c->enable_client_state(array, true);
}
GL_API void GL_APIENTRY glDisableClientState(GLenum array) {
  WITH_CONTEXT() c->enable_client_state(array, false);
}
GL_API void GL_APIENTRY glClientActiveTexture(GLenum texture) {
  WITH_CONTEXT() c->active_texture(texture, true);
}
GL_API void GL_APIENTRY glActiveTexture(GLenum texture) {
  WITH_CONTEXT() c->active_texture(texture, false);
}

GL_API void GL_APIENTRY glVertexPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  WITH_CONTEXT()
  c->array_pointer(c->vertex_array(), size, type, stride, pointer, size >= 2 && size <= 4,
                   type == GL_BYTE || type == GL_SHORT || type == GL_FIXED || type == GL_FLOAT);
}
GL_API void GL_APIENTRY glNormalPointer(GLenum type, GLsizei stride, const void* pointer) {
  WITH_CONTEXT()
  c->array_pointer(c->normal_array(), 3, type, stride, pointer, true,
                   type == GL_BYTE || type == GL_SHORT || type == GL_FIXED || type == GL_FLOAT);
}
GL_API void GL_APIENTRY glColorPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  WITH_CONTEXT()
  c->array_pointer(c->color_array(), size, type, stride, pointer, size == 4,
                   type == GL_UNSIGNED_BYTE || type == GL_FIXED || type == GL_FLOAT);
}
GL_API void GL_APIENTRY glTexCoordPointer(GLint size, GLenum type, GLsizei stride, const void* pointer) {
  WITH_CONTEXT()
  c->array_pointer(c->texcoord_array(), size, type, stride, pointer, size >= 2 && size <= 4,
                   type == GL_BYTE || type == GL_SHORT || type == GL_FIXED || type == GL_FLOAT);
}
// OES_point_size_array: one size per vertex, GL_FIXED or GL_FLOAT.
GL_API void GL_APIENTRY glPointSizePointerOES(GLenum type, GLsizei stride, const void* pointer) {
  WITH_CONTEXT()
  c->array_pointer(c->point_size_array(), 1, type, stride, pointer, true, type == GL_FIXED || type == GL_FLOAT);
}
GL_API void GL_APIENTRY glDrawArrays(GLenum mode, GLint first, GLsizei count) {
  WITH_CONTEXT()
  c->draw_arrays(mode, first, count);
}
GL_API void GL_APIENTRY glDrawElements(GLenum mode, GLsizei count, GLenum type, const void* indices) {
  WITH_CONTEXT()
  c->draw_elements(mode, count, type, indices);
}

GL_API void GL_APIENTRY glColor4f(GLfloat r, GLfloat g, GLfloat b, GLfloat a) {
  WITH_CONTEXT() c->color(r, g, b, a);
}
GL_API void GL_APIENTRY glColor4ub(GLubyte r, GLubyte g, GLubyte b, GLubyte a) {
  WITH_CONTEXT()
  c->color(r / 255.0f, g / 255.0f, b / 255.0f, a / 255.0f);
}
GL_API void GL_APIENTRY glNormal3f(GLfloat x, GLfloat y, GLfloat z) {
  WITH_CONTEXT() c->normal(x, y, z);
}
GL_API void GL_APIENTRY glMultiTexCoord4f(GLenum target, GLfloat s, GLfloat t, GLfloat r, GLfloat q) {
  WITH_CONTEXT()
  c->tex_coord(target, s, t, r, q);
}

GL_API void GL_APIENTRY glGenBuffers(GLsizei n, GLuint* buffers) {
  WITH_CONTEXT() c->gen_buffers(n, buffers);
}
GL_API void GL_APIENTRY glDeleteBuffers(GLsizei n, const GLuint* buffers) {
  WITH_CONTEXT() c->delete_buffers(n, buffers);
}
GL_API GLboolean GL_APIENTRY glIsBuffer(GLuint buffer) {
  WITH_CONTEXT(GL_FALSE)
  return c->is_buffer(buffer) ? GL_TRUE : GL_FALSE;
}
GL_API void GL_APIENTRY glBindBuffer(GLenum target, GLuint buffer) {
  WITH_CONTEXT() c->bind_buffer(target, buffer);
}
GL_API void GL_APIENTRY glBufferData(GLenum target, GLsizeiptr size, const void* data, GLenum usage) {
  WITH_CONTEXT()
  c->buffer_data(target, size, data, usage);
}
GL_API void GL_APIENTRY glBufferSubData(GLenum target, GLintptr offset, GLsizeiptr size, const void* data) {
  WITH_CONTEXT()
  c->buffer_sub_data(target, offset, size, data);
}
GL_API void GL_APIENTRY glGetBufferParameteriv(GLenum target, GLenum pname, GLint* params) {
  WITH_CONTEXT()
  c->get_buffer_parameter(target, pname, params);
}

GL_API void GL_APIENTRY glMatrixMode(GLenum mode) {
  WITH_CONTEXT() c->matrix_mode(mode);
}
GL_API void GL_APIENTRY glLoadIdentity(void) {
  WITH_CONTEXT() c->load_matrix(glm::mat4(1));
}
GL_API void GL_APIENTRY glLoadMatrixf(const GLfloat* m) {
  WITH_CONTEXT() c->load_matrix(glm::make_mat4(m));
}
GL_API void GL_APIENTRY glMultMatrixf(const GLfloat* m) {
  WITH_CONTEXT() c->mult_matrix(glm::make_mat4(m));
}
GL_API void GL_APIENTRY glPushMatrix(void) {
  WITH_CONTEXT() c->push_matrix();
}
GL_API void GL_APIENTRY glPopMatrix(void) {
  WITH_CONTEXT() c->pop_matrix();
}
GL_API void GL_APIENTRY glRotatef(GLfloat angle, GLfloat x, GLfloat y, GLfloat z) {
  WITH_CONTEXT()
  const glm::vec3 axis(x, y, z);
  const float length = glm::length(axis);
  if (!(length > 0)) return c->charge_call();  // a zero axis rotates by nothing
  c->charge(tessera::costs::HostCost::gl_rotation);
  c->mult_matrix(glm::rotate(glm::mat4(1), glm::radians(angle), axis / length));
}
GL_API void GL_APIENTRY glScalef(GLfloat x, GLfloat y, GLfloat z) {
  WITH_CONTEXT()
  c->mult_matrix(glm::scale(glm::mat4(1), glm::vec3(x, y, z)));
}
GL_API void GL_APIENTRY glTranslatef(GLfloat x, GLfloat y, GLfloat z) {
  WITH_CONTEXT()
  c->mult_matrix(glm::translate(glm::mat4(1), glm::vec3(x, y, z)));
}
GL_API void GL_APIENTRY glFrustumf(GLfloat l, GLfloat r, GLfloat b, GLfloat t, GLfloat n, GLfloat f) {
  WITH_CONTEXT()
  c->frustum(l, r, b, t, n, f);
}
GL_API void GL_APIENTRY glOrthof(GLfloat l, GLfloat r, GLfloat b, GLfloat t, GLfloat n, GLfloat f) {
  WITH_CONTEXT()
  c->ortho(l, r, b, t, n, f);
}
GL_API void GL_APIENTRY glViewport(GLint x, GLint y, GLsizei width, GLsizei height) {
  WITH_CONTEXT()
  c->viewport(x, y, width, height);
}
GL_API void GL_APIENTRY glDepthRangef(GLfloat n, GLfloat f) {
  WITH_CONTEXT() c->depth_range(n, f);
}
GL_API void GL_APIENTRY glClipPlanef(GLenum plane, const GLfloat* equation) {
  WITH_CONTEXT() c->clip_plane(plane, equation);
}
GL_API void GL_APIENTRY glGetClipPlanef(GLenum plane, GLfloat* equation) {
  WITH_CONTEXT()
  c->get_clip_plane(plane, equation);
}
GL_API void GL_APIENTRY glShadeModel(GLenum mode) {
  WITH_CONTEXT() c->shade_model(mode);
}

GL_API void GL_APIENTRY glLightf(GLenum light, GLenum pname, GLfloat param) {
  WITH_CONTEXT()
  if (light_param_count(pname) != 1) return c->error(GL_INVALID_ENUM);
  c->light(light, pname, &param, 1);
}
GL_API void GL_APIENTRY glLightfv(GLenum light, GLenum pname, const GLfloat* params) {
  WITH_CONTEXT()
  c->light(light, pname, params, light_param_count(pname));
}
GL_API void GL_APIENTRY glGetLightfv(GLenum light, GLenum pname, GLfloat* params) {
  WITH_CONTEXT()
  c->get_light(light, pname, params);
}
GL_API void GL_APIENTRY glLightModelf(GLenum pname, GLfloat param) {
  WITH_CONTEXT()
  if (light_param_count(pname) != 1) return c->error(GL_INVALID_ENUM);
  c->light_model(pname, &param, 1);
}
GL_API void GL_APIENTRY glLightModelfv(GLenum pname, const GLfloat* params) {
  WITH_CONTEXT()
  c->light_model(pname, params, light_param_count(pname));
}
GL_API void GL_APIENTRY glMaterialf(GLenum face, GLenum pname, GLfloat param) {
  WITH_CONTEXT()
  if (light_param_count(pname) != 1) return c->error(GL_INVALID_ENUM);
  c->material(face, pname, &param, 1);
}
GL_API void GL_APIENTRY glMaterialfv(GLenum face, GLenum pname, const GLfloat* params) {
  WITH_CONTEXT()
  c->material(face, pname, params, light_param_count(pname));
}
GL_API void GL_APIENTRY glGetMaterialfv(GLenum face, GLenum pname, GLfloat* params) {
  WITH_CONTEXT()
  c->get_material(face, pname, params);
}
GL_API void GL_APIENTRY glFogf(GLenum pname, GLfloat param) {
  WITH_CONTEXT()
  if (pname == GL_FOG_COLOR) return c->error(GL_INVALID_ENUM);
  c->fog(pname, &param, 1);
}
GL_API void GL_APIENTRY glFogfv(GLenum pname, const GLfloat* params) {
  WITH_CONTEXT()
  c->fog(pname, params, pname == GL_FOG_COLOR ? 4 : 1);
}
GL_API void GL_APIENTRY glPointSize(GLfloat size) {
  WITH_CONTEXT() c->point_size(size);
}
GL_API void GL_APIENTRY glPointParameterf(GLenum pname, GLfloat param) {
  WITH_CONTEXT() c->point_parameter(pname, &param, 1);
}
GL_API void GL_APIENTRY glPointParameterfv(GLenum pname, const GLfloat* params) {
  WITH_CONTEXT()
  if (!params) return c->error(GL_INVALID_VALUE);
  c->point_parameter(pname, params, pname == GL_POINT_DISTANCE_ATTENUATION ? 3 : 1);
}
GL_API void GL_APIENTRY glLineWidth(GLfloat width) {
  WITH_CONTEXT() c->line_width(width);
}
GL_API void GL_APIENTRY glCullFace(GLenum mode) {
  WITH_CONTEXT() c->cull_face(mode);
}
GL_API void GL_APIENTRY glFrontFace(GLenum mode) {
  WITH_CONTEXT() c->front_face(mode);
}
GL_API void GL_APIENTRY glPolygonOffset(GLfloat factor, GLfloat units) {
  WITH_CONTEXT() c->polygon_offset(factor, units);
}
GL_API void GL_APIENTRY glSampleCoverage(GLfloat value, GLboolean invert) {
  WITH_CONTEXT()
  c->sample_coverage(value, invert != GL_FALSE);
}
GL_API void GL_APIENTRY glScissor(GLint x, GLint y, GLsizei width, GLsizei height) {
  WITH_CONTEXT()
  c->scissor(x, y, width, height);
}
GL_API void GL_APIENTRY glAlphaFunc(GLenum func, GLfloat ref) {
  WITH_CONTEXT() c->alpha_func(func, ref);
}
GL_API void GL_APIENTRY glStencilFunc(GLenum func, GLint ref, GLuint mask) {
  WITH_CONTEXT() c->stencil_func(func, ref, mask);
}
GL_API void GL_APIENTRY glStencilOp(GLenum fail, GLenum zfail, GLenum zpass) {
  WITH_CONTEXT()
  c->stencil_op(fail, zfail, zpass);
}
GL_API void GL_APIENTRY glDepthFunc(GLenum func) {
  WITH_CONTEXT() c->depth_func(func);
}
GL_API void GL_APIENTRY glBlendFunc(GLenum sfactor, GLenum dfactor) {
  WITH_CONTEXT() c->blend_func(sfactor, dfactor);
}
GL_API void GL_APIENTRY glLogicOp(GLenum opcode) {
  WITH_CONTEXT() c->logic_op(opcode);
}
GL_API void GL_APIENTRY glColorMask(GLboolean r, GLboolean g, GLboolean b, GLboolean a) {
  WITH_CONTEXT()
  c->color_mask(r != GL_FALSE, g != GL_FALSE, b != GL_FALSE, a != GL_FALSE);
}
GL_API void GL_APIENTRY glDepthMask(GLboolean flag) {
  WITH_CONTEXT() c->depth_mask(flag != GL_FALSE);
}
GL_API void GL_APIENTRY glStencilMask(GLuint mask) {
  WITH_CONTEXT() c->stencil_mask(mask);
}
GL_API void GL_APIENTRY glClearColor(GLfloat r, GLfloat g, GLfloat b, GLfloat a) {
  WITH_CONTEXT() c->clear_color(r, g, b, a);
}
GL_API void GL_APIENTRY glClearDepthf(GLfloat depth) {
  WITH_CONTEXT() c->clear_depth(depth);
}
GL_API void GL_APIENTRY glClearStencil(GLint s) {
  WITH_CONTEXT() c->clear_stencil(s);
}
GL_API void GL_APIENTRY glClear(GLbitfield mask) {
  WITH_CONTEXT() c->clear(mask);
}
GL_API void GL_APIENTRY glPixelStorei(GLenum pname, GLint param) {
  WITH_CONTEXT() c->pixel_store(pname, param);
}
GL_API void GL_APIENTRY glReadPixels(GLint x, GLint y, GLsizei width, GLsizei height, GLenum format, GLenum type,
                                     void* pixels) {
  WITH_CONTEXT()
  c->read_pixels(x, y, width, height, format, type, pixels);
}

GL_API void GL_APIENTRY glGenTextures(GLsizei n, GLuint* textures) {
  WITH_CONTEXT() c->gen_textures(n, textures);
}
GL_API void GL_APIENTRY glDeleteTextures(GLsizei n, const GLuint* textures) {
  WITH_CONTEXT() c->delete_textures(n, textures);
}
GL_API GLboolean GL_APIENTRY glIsTexture(GLuint texture) {
  WITH_CONTEXT(GL_FALSE)
  return c->is_texture(texture) ? GL_TRUE : GL_FALSE;
}
GL_API void GL_APIENTRY glBindTexture(GLenum target, GLuint texture) {
  WITH_CONTEXT() c->bind_texture(target, texture);
}
GL_API void GL_APIENTRY glTexImage2D(GLenum target, GLint level, GLint internalformat, GLsizei width, GLsizei height,
                                     GLint border, GLenum format, GLenum type, const void* pixels) {
  WITH_CONTEXT()
  c->tex_image(target, level, internalformat, width, height, border, format, type, pixels);
}
GL_API void GL_APIENTRY glTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei width,
                                        GLsizei height, GLenum format, GLenum type, const void* pixels) {
  WITH_CONTEXT()
  c->tex_sub_image(target, level, xoffset, yoffset, width, height, format, type, pixels);
}
// The compressed formats are OES_compressed_paletted_texture's ten.
GL_API void GL_APIENTRY glCompressedTexImage2D(GLenum target, GLint level, GLenum internalformat, GLsizei width,
                                               GLsizei height, GLint border, GLsizei image_size, const void* data) {
  WITH_CONTEXT()
  c->compressed_tex_image(target, level, internalformat, width, height, border, image_size, data);
}
// A paletted texture cannot be updated in part (OES_compressed_paletted_texture).
GL_API void GL_APIENTRY glCompressedTexSubImage2D(GLenum, GLint, GLint, GLint, GLsizei, GLsizei, GLenum format, GLsizei,
                                                  const void*) {
  WITH_CONTEXT()
  c->charge_call();
  c->error(tessera::gl::find_palette_format(format) ? GL_INVALID_OPERATION : GL_INVALID_ENUM);
}
GL_API void GL_APIENTRY glCopyTexImage2D(GLenum target, GLint level, GLenum internalformat, GLint x, GLint y,
                                         GLsizei width, GLsizei height, GLint border) {
  WITH_CONTEXT()
  if (internalformat != GL_RGBA && internalformat != GL_RGB && internalformat != GL_LUMINANCE &&
      internalformat != GL_ALPHA && internalformat != GL_LUMINANCE_ALPHA)
    return c->error(GL_INVALID_ENUM);
  // Larger than any texture: refused before the copy is allocated.
  if (width < 0 || height < 0 || width > tessera::gl::MAX_TEXTURE_SIZE || height > tessera::gl::MAX_TEXTURE_SIZE)
    return c->error(GL_INVALID_VALUE);
  std::vector<uint8_t> pixels(static_cast<size_t>(width) * height * 4);
  if (!pixels.empty()) c->read_pixels(x, y, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  // The level gets the internal format asked for (texture completeness
  // compares the levels' formats): the frame's RGBA repacked to its
  // components, rows padded to GL_UNPACK_ALIGNMENT as tex_image reads them.
  const unsigned bytes = tessera::gl::pixel_bytes(internalformat, GL_UNSIGNED_BYTE);
  float alignment_value = 4;
  c->get_floats(GL_UNPACK_ALIGNMENT, &alignment_value);
  const auto alignment = static_cast<size_t>(alignment_value);
  const size_t stride = (static_cast<size_t>(width) * bytes + alignment - 1) / alignment * alignment;
  std::vector<uint8_t> packed(stride * static_cast<size_t>(height));
  for (GLsizei j = 0; j < height; ++j) {
    for (GLsizei i = 0; i < width; ++i) {
      const uint8_t* in = &pixels[(static_cast<size_t>(j) * width + i) * 4];
      uint8_t* out = &packed[j * stride + static_cast<size_t>(i) * bytes];
      switch (internalformat) {
        case GL_LUMINANCE: out[0] = in[0]; break;
        case GL_ALPHA: out[0] = in[3]; break;
        case GL_LUMINANCE_ALPHA: out[0] = in[0], out[1] = in[3]; break;
        default: std::copy(in, in + bytes, out);  // RGB, RGBA
      }
    }
  }
  c->tex_image(target, level, static_cast<GLint>(internalformat), width, height, border, internalformat,
               GL_UNSIGNED_BYTE, packed.data());
}
GL_API void GL_APIENTRY glCopyTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLint x, GLint y,
                                            GLsizei width, GLsizei height) {
  WITH_CONTEXT()
  if (width < 0 || height < 0 || width > tessera::gl::MAX_TEXTURE_SIZE || height > tessera::gl::MAX_TEXTURE_SIZE)
    return c->error(GL_INVALID_VALUE);
  std::vector<uint8_t> pixels(static_cast<size_t>(width) * height * 4);
  if (!pixels.empty()) c->read_pixels(x, y, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  c->tex_sub_image(target, level, xoffset, yoffset, width, height, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
}
GL_API void GL_APIENTRY glTexParameterf(GLenum target, GLenum pname, GLfloat param) {
  WITH_CONTEXT()
  c->tex_parameter(target, pname, param);
}
GL_API void GL_APIENTRY glTexParameterfv(GLenum target, GLenum pname, const GLfloat* params) {
  WITH_CONTEXT()
  c->tex_parameter(target, pname, params[0]);
}
GL_API void GL_APIENTRY glTexParameteri(GLenum target, GLenum pname, GLint param) {
  WITH_CONTEXT()
  c->tex_parameter(target, pname, static_cast<float>(param));
}
GL_API void GL_APIENTRY glTexParameteriv(GLenum target, GLenum pname, const GLint* params) {
  WITH_CONTEXT()
  c->tex_parameter(target, pname, static_cast<float>(params[0]));
}
GL_API void GL_APIENTRY glGetTexParameterfv(GLenum target, GLenum pname, GLfloat* params) {
  WITH_CONTEXT()
  c->get_tex_parameter(target, pname, params);
}
GL_API void GL_APIENTRY glGetTexParameteriv(GLenum target, GLenum pname, GLint* params) {
  WITH_CONTEXT()
  float v = 0;
  c->get_tex_parameter(target, pname, &v);
  *params = tessera::gl::int_from_float(v);
}
GL_API void GL_APIENTRY glTexEnvf(GLenum target, GLenum pname, GLfloat param) {
  WITH_CONTEXT()
  if (target == GL_POINT_SPRITE_OES) return c->point_sprite_env(pname, &param);
  if (pname == GL_TEXTURE_ENV_COLOR) return c->error(GL_INVALID_ENUM);
  c->tex_env(target, pname, &param, 1);
}
GL_API void GL_APIENTRY glTexEnvfv(GLenum target, GLenum pname, const GLfloat* params) {
  WITH_CONTEXT()
  if (target == GL_POINT_SPRITE_OES) return c->point_sprite_env(pname, params);
  c->tex_env(target, pname, params, pname == GL_TEXTURE_ENV_COLOR ? 4 : 1);
}
GL_API void GL_APIENTRY glTexEnvi(GLenum target, GLenum pname, GLint param) {
  WITH_CONTEXT()
  glTexEnvf(target, pname, static_cast<float>(param));
}
GL_API void GL_APIENTRY glTexEnviv(GLenum target, GLenum pname, const GLint* params) {
  WITH_CONTEXT()
  if (pname == GL_TEXTURE_ENV_COLOR) {
    float color[4];
    for (int i = 0; i < 4; ++i) color[i] = static_cast<float>(params[i]) / 2147483647.0f;
    return c->tex_env(target, pname, color, 4);
  }
  glTexEnvf(target, pname, static_cast<float>(params[0]));
}
GL_API void GL_APIENTRY glGetTexEnvfv(GLenum target, GLenum pname, GLfloat* params) {
  WITH_CONTEXT()
  if (target == GL_POINT_SPRITE_OES) return c->get_point_sprite_env(pname, params);
  c->get_tex_env(target, pname, params);
}
GL_API void GL_APIENTRY glGetTexEnviv(GLenum target, GLenum pname, GLint* params) {
  WITH_CONTEXT()
  float v[4] = {0, 0, 0, 0};
  if (target == GL_POINT_SPRITE_OES)
    c->get_point_sprite_env(pname, v);
  else
    c->get_tex_env(target, pname, v);
  if (pname == GL_TEXTURE_ENV_COLOR)
    for (int i = 0; i < 4; ++i) params[i] = tessera::gl::int_from_unit_float(v[i]);
  else
    params[0] = tessera::gl::int_from_float(v[0]);
}

}  // extern "C"
