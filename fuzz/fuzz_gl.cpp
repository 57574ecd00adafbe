// Fuzz target: the GL ES 1.1 entry points (sw_driver/gl): a random sequence
// of calls with random arguments against one context, made current over a
// host that keeps system memory in a vector and a renderer that only
// counts, as the GL unit tests do (no SoC, no back end).
//
// Input: a byte stream read as calls: one byte picks the entry point (of
// every one in <GLES/gl.h>), the next bytes give its arguments: an enum from
// the header's list or any 32-bit value, a float or fixed from a list of
// edge values or any bits, small or any integers. Client pointers point into
// a buffer whose first 64 KiB hold the input itself; counts, strides and
// sizes of client memory the call will read or write are kept within that
// buffer, and pointers are null only where the GL allows it (a vector of
// parameters too short or null is the application's fault, not the
// driver's).
// Buffer objects, texture sizes and offsets are not capped: the driver must
// check those itself.
//
// Checks: no crash and no sanitizer report; an exception out of a call is a
// fault except the driver's heap running out ("GL driver: out of system
// memory"), a fatal error soc_sim reports; glGetError returns GL_NO_ERROR or
// one of the GL's error codes; the renderer gets triangles with 0.24 depths.
#include <GLES/gl.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "device/app_environment.h"
#include "fuzz_support.h"
#include "gl/context.h"
#include "gl/runtime.h"

namespace {

using tessera::fuzz::ByteReader;
using tessera::fuzz::fail;

// System memory: the driver's heap (textures, depth buffers) lives in it.
class FuzzHost : public tessera::HostApi {
 public:
  FuzzHost() : m_memory(16u << 20, 0) {}
  void compute(tessera::Op, uint64_t) override {}
  void compute_cycles(uint64_t) override {}
  uint32_t read32(uint32_t address) override {
    uint32_t v;
    std::memcpy(&v, at(address, 4), 4);
    return v;
  }
  uint16_t read16(uint32_t address) override {
    uint16_t v;
    std::memcpy(&v, at(address, 2), 2);
    return v;
  }
  uint8_t read8(uint32_t address) override { return *at(address, 1); }
  void write32(uint32_t address, uint32_t value) override { std::memcpy(at(address, 4), &value, 4); }
  void write16(uint32_t address, uint16_t value) override { std::memcpy(at(address, 2), &value, 2); }
  void write8(uint32_t address, uint8_t value) override { *at(address, 1) = value; }
  void read_words(uint32_t address, uint32_t* words, unsigned count) override {
    std::memcpy(words, at(address, 4 * count), 4 * size_t{count});
  }
  void write_words(uint32_t address, const uint32_t* words, unsigned count) override {
    std::memcpy(at(address, 4 * count), words, 4 * size_t{count});
  }
  const uint8_t* load_span(uint32_t address, unsigned size, unsigned count) override {
    return at(address, size * count);
  }
  uint8_t* store_span(uint32_t address, unsigned size, unsigned count) override { return at(address, size * count); }
  void wait_irq(unsigned) override {}
  bool irq_pending(unsigned) override { return false; }
  double now_seconds() const override { return 0; }
  double clock_hz() const override { return 192e6; }
  uint32_t memory_bytes() const { return static_cast<uint32_t>(m_memory.size()); }

 private:
  // The driver only reaches memory it allocated from the heap.
  uint8_t* at(uint32_t address, uint64_t bytes) {
    if (address + bytes > m_memory.size())
      fail("the driver accessed system memory at " + std::to_string(address) + " beyond its end");
    return m_memory.data() + address;
  }
  std::vector<uint8_t> m_memory;
};

class CountingRenderer : public tessera::gl::Renderer {
 public:
  const char* name() const override { return "fuzz"; }
  tessera::gl::RendererCapabilities capabilities() const override { return {12, 4}; }
  unsigned width() const override { return 64; }
  unsigned height() const override { return 48; }
  tessera::PixelFormat color_format() const override { return tessera::PixelFormat::rgb565; }
  void clear(const tessera::gl::ClearRequest&) override {}
  void draw(const tessera::gl::RasterState&, const tessera::gl::Triangle* triangles, size_t count) override {
    for (size_t i = 0; i < count; ++i)
      for (const tessera::gl::ScreenVertex& v : triangles[i].v)
        if (v.z > 0xffffffu) fail("a triangle vertex with a depth beyond 0.24");
  }
  void read_pixels(int, int, int w, int h, uint8_t* rgba) override {
    if (w < 0 || h < 0) fail("read_pixels with a negative size");
    std::memset(rgba, 0x5a, static_cast<size_t>(w) * static_cast<size_t>(h) * 4);
  }
  void finish() override {}
  void present() override {}
};

constexpr GLenum ENUMS[] = {
    GL_FALSE,
    GL_TRUE,
    GL_NO_ERROR,
    GL_INVALID_ENUM,
    GL_INVALID_VALUE,
    GL_INVALID_OPERATION,
    GL_STACK_OVERFLOW,
    GL_STACK_UNDERFLOW,
    GL_OUT_OF_MEMORY,
    GL_VENDOR,
    GL_RENDERER,
    GL_EXTENSIONS,
    GL_BYTE,
    GL_UNSIGNED_BYTE,
    GL_SHORT,
    GL_UNSIGNED_SHORT,
    GL_FLOAT,
    GL_FIXED,
    GL_POINTS,
    GL_LINES,
    GL_LINE_LOOP,
    GL_LINE_STRIP,
    GL_TRIANGLES,
    GL_TRIANGLE_STRIP,
    GL_TRIANGLE_FAN,
    GL_POINT_SMOOTH,
    GL_LINE_SMOOTH,
    GL_CULL_FACE,
    GL_LIGHTING,
    GL_COLOR_MATERIAL,
    GL_FOG,
    GL_DEPTH_TEST,
    GL_STENCIL_TEST,
    GL_NORMALIZE,
    GL_ALPHA_TEST,
    GL_DITHER,
    GL_BLEND,
    GL_COLOR_LOGIC_OP,
    GL_SCISSOR_TEST,
    GL_TEXTURE_2D,
    GL_POLYGON_OFFSET_FILL,
    GL_RESCALE_NORMAL,
    GL_MULTISAMPLE,
    GL_SAMPLE_ALPHA_TO_COVERAGE,
    GL_SAMPLE_ALPHA_TO_ONE,
    GL_SAMPLE_COVERAGE,
    GL_CLIP_PLANE0,
    GL_CLIP_PLANE1,
    GL_CLIP_PLANE2,
    GL_CLIP_PLANE3,
    GL_CLIP_PLANE4,
    GL_CLIP_PLANE5,
    GL_LIGHT0,
    GL_LIGHT1,
    GL_LIGHT2,
    GL_LIGHT3,
    GL_LIGHT4,
    GL_LIGHT5,
    GL_LIGHT6,
    GL_LIGHT7,
    GL_VERTEX_ARRAY,
    GL_NORMAL_ARRAY,
    GL_COLOR_ARRAY,
    GL_TEXTURE_COORD_ARRAY,
    GL_DEPTH_BUFFER_BIT,
    GL_STENCIL_BUFFER_BIT,
    GL_COLOR_BUFFER_BIT,
    GL_NEVER,
    GL_LESS,
    GL_EQUAL,
    GL_LEQUAL,
    GL_GREATER,
    GL_NOTEQUAL,
    GL_GEQUAL,
    GL_ALWAYS,
    GL_ZERO,
    GL_ONE,
    GL_SRC_COLOR,
    GL_ONE_MINUS_SRC_COLOR,
    GL_SRC_ALPHA,
    GL_ONE_MINUS_SRC_ALPHA,
    GL_DST_ALPHA,
    GL_ONE_MINUS_DST_ALPHA,
    GL_DST_COLOR,
    GL_ONE_MINUS_DST_COLOR,
    GL_SRC_ALPHA_SATURATE,
    GL_CLEAR,
    GL_AND,
    GL_AND_REVERSE,
    GL_COPY,
    GL_AND_INVERTED,
    GL_NOOP,
    GL_XOR,
    GL_OR,
    GL_NOR,
    GL_EQUIV,
    GL_INVERT,
    GL_OR_REVERSE,
    GL_COPY_INVERTED,
    GL_OR_INVERTED,
    GL_NAND,
    GL_SET,
    GL_KEEP,
    GL_REPLACE,
    GL_INCR,
    GL_DECR,
    GL_FRONT,
    GL_BACK,
    GL_FRONT_AND_BACK,
    GL_CW,
    GL_CCW,
    GL_FLAT,
    GL_SMOOTH,
    GL_DONT_CARE,
    GL_FASTEST,
    GL_NICEST,
    GL_PERSPECTIVE_CORRECTION_HINT,
    GL_POINT_SMOOTH_HINT,
    GL_LINE_SMOOTH_HINT,
    GL_FOG_HINT,
    GL_GENERATE_MIPMAP_HINT,
    GL_EXP,
    GL_EXP2,
    GL_FOG_DENSITY,
    GL_FOG_START,
    GL_FOG_END,
    GL_FOG_MODE,
    GL_FOG_COLOR,
    GL_LIGHT_MODEL_TWO_SIDE,
    GL_LIGHT_MODEL_AMBIENT,
    GL_AMBIENT,
    GL_DIFFUSE,
    GL_SPECULAR,
    GL_POSITION,
    GL_SPOT_DIRECTION,
    GL_SPOT_EXPONENT,
    GL_SPOT_CUTOFF,
    GL_CONSTANT_ATTENUATION,
    GL_LINEAR_ATTENUATION,
    GL_QUADRATIC_ATTENUATION,
    GL_EMISSION,
    GL_SHININESS,
    GL_AMBIENT_AND_DIFFUSE,
    GL_POINT_SIZE_MIN,
    GL_POINT_SIZE_MAX,
    GL_POINT_FADE_THRESHOLD_SIZE,
    GL_POINT_DISTANCE_ATTENUATION,
    GL_MODELVIEW,
    GL_PROJECTION,
    GL_TEXTURE,
    GL_ALPHA,
    GL_RGB,
    GL_RGBA,
    GL_LUMINANCE,
    GL_LUMINANCE_ALPHA,
    GL_UNSIGNED_SHORT_4_4_4_4,
    GL_UNSIGNED_SHORT_5_5_5_1,
    GL_UNSIGNED_SHORT_5_6_5,
    GL_UNPACK_ALIGNMENT,
    GL_PACK_ALIGNMENT,
    GL_NEAREST,
    GL_LINEAR,
    GL_NEAREST_MIPMAP_NEAREST,
    GL_LINEAR_MIPMAP_NEAREST,
    GL_NEAREST_MIPMAP_LINEAR,
    GL_LINEAR_MIPMAP_LINEAR,
    GL_TEXTURE_MAG_FILTER,
    GL_TEXTURE_MIN_FILTER,
    GL_TEXTURE_WRAP_S,
    GL_TEXTURE_WRAP_T,
    GL_REPEAT,
    GL_CLAMP_TO_EDGE,
    GL_GENERATE_MIPMAP,
    GL_TEXTURE0,
    GL_TEXTURE1,
    GL_TEXTURE2,
    GL_TEXTURE3,
    GL_TEXTURE4,
    GL_TEXTURE5,
    GL_TEXTURE6,
    GL_TEXTURE7,
    GL_TEXTURE8,
    GL_TEXTURE9,
    GL_TEXTURE10,
    GL_TEXTURE11,
    GL_TEXTURE12,
    GL_TEXTURE13,
    GL_TEXTURE14,
    GL_TEXTURE15,
    GL_TEXTURE16,
    GL_TEXTURE17,
    GL_TEXTURE18,
    GL_TEXTURE19,
    GL_TEXTURE20,
    GL_TEXTURE21,
    GL_TEXTURE22,
    GL_TEXTURE23,
    GL_TEXTURE24,
    GL_TEXTURE25,
    GL_TEXTURE26,
    GL_TEXTURE27,
    GL_TEXTURE28,
    GL_TEXTURE29,
    GL_TEXTURE30,
    GL_TEXTURE31,
    GL_TEXTURE_ENV,
    GL_TEXTURE_ENV_MODE,
    GL_TEXTURE_ENV_COLOR,
    GL_ADD,
    GL_MODULATE,
    GL_DECAL,
    GL_COMBINE,
    GL_COMBINE_RGB,
    GL_COMBINE_ALPHA,
    GL_RGB_SCALE,
    GL_ALPHA_SCALE,
    GL_ADD_SIGNED,
    GL_INTERPOLATE,
    GL_SUBTRACT,
    GL_DOT3_RGB,
    GL_DOT3_RGBA,
    GL_CONSTANT,
    GL_PRIMARY_COLOR,
    GL_PREVIOUS,
    GL_SRC0_RGB,
    GL_SRC1_RGB,
    GL_SRC2_RGB,
    GL_SRC0_ALPHA,
    GL_SRC1_ALPHA,
    GL_SRC2_ALPHA,
    GL_OPERAND0_RGB,
    GL_OPERAND1_RGB,
    GL_OPERAND2_RGB,
    GL_OPERAND0_ALPHA,
    GL_OPERAND1_ALPHA,
    GL_OPERAND2_ALPHA,
    GL_ARRAY_BUFFER,
    GL_ELEMENT_ARRAY_BUFFER,
    GL_STATIC_DRAW,
    GL_DYNAMIC_DRAW,
    GL_BUFFER_SIZE,
    GL_BUFFER_USAGE,
    GL_CURRENT_COLOR,
    GL_CURRENT_NORMAL,
    GL_CURRENT_TEXTURE_COORDS,
    GL_POINT_SIZE,
    GL_SMOOTH_POINT_SIZE_RANGE,
    GL_LINE_WIDTH,
    GL_SMOOTH_LINE_WIDTH_RANGE,
    GL_ALIASED_POINT_SIZE_RANGE,
    GL_ALIASED_LINE_WIDTH_RANGE,
    GL_CULL_FACE_MODE,
    GL_FRONT_FACE,
    GL_SHADE_MODEL,
    GL_POLYGON_OFFSET_UNITS,
    GL_POLYGON_OFFSET_FACTOR,
    GL_DEPTH_RANGE,
    GL_DEPTH_WRITEMASK,
    GL_DEPTH_CLEAR_VALUE,
    GL_DEPTH_FUNC,
    GL_STENCIL_CLEAR_VALUE,
    GL_STENCIL_FUNC,
    GL_STENCIL_VALUE_MASK,
    GL_STENCIL_FAIL,
    GL_STENCIL_PASS_DEPTH_FAIL,
    GL_STENCIL_PASS_DEPTH_PASS,
    GL_STENCIL_REF,
    GL_STENCIL_WRITEMASK,
    GL_ALPHA_TEST_FUNC,
    GL_ALPHA_TEST_REF,
    GL_BLEND_DST,
    GL_BLEND_SRC,
    GL_LOGIC_OP_MODE,
    GL_COLOR_CLEAR_VALUE,
    GL_COLOR_WRITEMASK,
    GL_SAMPLE_BUFFERS,
    GL_SAMPLES,
    GL_SAMPLE_COVERAGE_VALUE,
    GL_SAMPLE_COVERAGE_INVERT,
    GL_VIEWPORT,
    GL_SCISSOR_BOX,
    GL_MATRIX_MODE,
    GL_MODELVIEW_STACK_DEPTH,
    GL_PROJECTION_STACK_DEPTH,
    GL_TEXTURE_STACK_DEPTH,
    GL_MODELVIEW_MATRIX,
    GL_PROJECTION_MATRIX,
    GL_TEXTURE_MATRIX,
    GL_MAX_LIGHTS,
    GL_MAX_CLIP_PLANES,
    GL_MAX_TEXTURE_SIZE,
    GL_MAX_MODELVIEW_STACK_DEPTH,
    GL_MAX_PROJECTION_STACK_DEPTH,
    GL_MAX_TEXTURE_STACK_DEPTH,
    GL_MAX_VIEWPORT_DIMS,
    GL_MAX_TEXTURE_UNITS,
    GL_SUBPIXEL_BITS,
    GL_RED_BITS,
    GL_GREEN_BITS,
    GL_BLUE_BITS,
    GL_ALPHA_BITS,
    GL_DEPTH_BITS,
    GL_STENCIL_BITS,
    GL_NUM_COMPRESSED_TEXTURE_FORMATS,
    GL_COMPRESSED_TEXTURE_FORMATS,
    GL_TEXTURE_BINDING_2D,
    GL_ACTIVE_TEXTURE,
    GL_CLIENT_ACTIVE_TEXTURE,
    GL_ARRAY_BUFFER_BINDING,
    GL_ELEMENT_ARRAY_BUFFER_BINDING,
    GL_VERTEX_ARRAY_BUFFER_BINDING,
    GL_NORMAL_ARRAY_BUFFER_BINDING,
    GL_COLOR_ARRAY_BUFFER_BINDING,
    GL_TEXTURE_COORD_ARRAY_BUFFER_BINDING,
    GL_VERTEX_ARRAY_SIZE,
    GL_VERTEX_ARRAY_TYPE,
    GL_VERTEX_ARRAY_STRIDE,
    GL_NORMAL_ARRAY_TYPE,
    GL_NORMAL_ARRAY_STRIDE,
    GL_COLOR_ARRAY_SIZE,
    GL_COLOR_ARRAY_TYPE,
    GL_COLOR_ARRAY_STRIDE,
    GL_TEXTURE_COORD_ARRAY_SIZE,
    GL_TEXTURE_COORD_ARRAY_TYPE,
    GL_TEXTURE_COORD_ARRAY_STRIDE,
    GL_VERTEX_ARRAY_POINTER,
    GL_NORMAL_ARRAY_POINTER,
    GL_COLOR_ARRAY_POINTER,
    GL_TEXTURE_COORD_ARRAY_POINTER,
    GL_IMPLEMENTATION_COLOR_READ_TYPE_OES,
    GL_IMPLEMENTATION_COLOR_READ_FORMAT_OES,
    GL_PALETTE4_RGB8_OES,
    GL_PALETTE4_RGBA8_OES,
    GL_PALETTE4_R5_G6_B5_OES,
    GL_PALETTE4_RGBA4_OES,
    GL_PALETTE4_RGB5_A1_OES,
    GL_PALETTE8_RGB8_OES,
    GL_PALETTE8_RGBA8_OES,
    GL_PALETTE8_R5_G6_B5_OES,
    GL_PALETTE8_RGBA4_OES,
    GL_PALETTE8_RGB5_A1_OES,
    GL_POINT_SPRITE_OES,
    GL_COORD_REPLACE_OES,
    GL_POINT_SIZE_ARRAY_TYPE_OES,
    GL_POINT_SIZE_ARRAY_STRIDE_OES,
    GL_POINT_SIZE_ARRAY_POINTER_OES,
    GL_POINT_SIZE_ARRAY_OES,
    GL_POINT_SIZE_ARRAY_BUFFER_BINDING_OES,
};

// Client memory: what the pointers of the calls point into.
constexpr size_t CLIENT_BYTES = 8u << 20;   // the largest read: a 1024x1024 RGBA image
constexpr size_t INPUT_WINDOW = 64u << 10;  // the first bytes, refreshed with each input

class Arguments {
 public:
  Arguments(ByteReader& reader, uint8_t* client, uint8_t* output) : r(reader), m_client(client), m_output(output) {}

  GLenum e() { return r.pick(8) == 0 ? r.u32() : ENUMS[r.u16() % std::size(ENUMS)]; }
  GLfloat f() {
    static constexpr float EDGES[] = {0.0f,
                                      1.0f,
                                      -1.0f,
                                      0.5f,
                                      2.0f,
                                      255.0f,
                                      1e-3f,
                                      1e10f,
                                      -1e10f,
                                      1e30f,
                                      std::numeric_limits<float>::max(),
                                      std::numeric_limits<float>::denorm_min(),
                                      std::numeric_limits<float>::infinity(),
                                      -std::numeric_limits<float>::infinity(),
                                      std::numeric_limits<float>::quiet_NaN()};
    return r.pick(4) == 0 ? r.f32() : EDGES[r.pick(std::size(EDGES))];
  }
  GLfixed x() {
    static constexpr GLfixed EDGES[] = {0,
                                        1 << 16,
                                        -(1 << 16),
                                        1 << 15,
                                        2 << 16,
                                        255 << 16,
                                        1,
                                        -1,
                                        std::numeric_limits<GLfixed>::max(),
                                        std::numeric_limits<GLfixed>::min()};
    return r.pick(4) == 0 ? r.i32() : EDGES[r.pick(std::size(EDGES))];
  }
  // Any integer, edge values likely.
  GLint i() {
    static constexpr GLint EDGES[] = {0,
                                      1,
                                      -1,
                                      2,
                                      3,
                                      4,
                                      7,
                                      8,
                                      16,
                                      32,
                                      64,
                                      255,
                                      256,
                                      257,
                                      1024,
                                      65535,
                                      65536,
                                      std::numeric_limits<GLint>::max(),
                                      std::numeric_limits<GLint>::min()};
    return r.pick(4) == 0 ? r.i32() : EDGES[r.pick(std::size(EDGES))];
  }
  // A small integer, sometimes negative: a count or size of client memory.
  GLint small(GLint limit) { return r.pick(16) == 0 ? -1 - r.u8() : static_cast<GLint>(r.u16() % (limit + 1)); }
  GLboolean b() { return r.u8(); }
  // A stride the client buffer holds for every vertex an index can reach.
  GLsizei stride() { return r.pick(16) == 0 ? -4 : static_cast<GLsizei>(r.u8() % 65); }
  // Client memory to read: 4-byte aligned, in the window the input fills.
  // Never null: a null vector of parameters is the application's fault.
  const void* in() { return m_client + (r.u16() % INPUT_WINDOW & ~size_t{3}); }
  // Where the GL takes null (no data yet): texture images, buffer data.
  const void* in_or_null() { return r.pick(16) == 0 ? nullptr : in(); }
  const GLfloat* fv() { return static_cast<const GLfloat*>(in()); }
  const GLfixed* xv() { return static_cast<const GLfixed*>(in()); }
  const GLint* iv() { return static_cast<const GLint*>(in()); }
  const GLuint* uv() { return static_cast<const GLuint*>(in()); }
  // Client memory to write: room for any query.
  template <typename T>
  T* out() {
    return reinterpret_cast<T*>(m_output);
  }
  // Pointers of vertex arrays and indices: an offset into the buffer object
  // bound to `binding` (the driver must check it against the buffer's
  // size), or client memory when none is (where an offset would be the
  // application's fault).
  const void* array_pointer(GLenum binding) {
    GLint buffer = 0;
    glGetIntegerv(binding, &buffer);
    if (buffer == 0) return in();
    const uintptr_t bytes = r.pick(4) == 0 ? r.u32() : r.u16();
    return reinterpret_cast<const void*>(bytes);  // NOLINT(performance-no-int-to-ptr): GL's buffer offsets
  }

  ByteReader& r;

 private:
  uint8_t* m_client;
  uint8_t* m_output;
};

// Values the GL reads as enums: a valid enum half the time, any float or
// integer (NaN, 1e30, INT_MIN) the other half; every glTexParameter*,
// glTexEnv* and glFog* must refuse a value that is no exact enum (issue 14
// item 6, regression inputs fuzz/corpus/gl/regress-*).
GLfloat enum_float(Arguments& a) {
  if (a.r.boolean()) return static_cast<GLfloat>(a.e() & 0xffff);
  return a.f();
}
GLint enum_int(Arguments& a) {
  if (a.r.boolean()) return static_cast<GLint>(a.e() & 0xffff);
  return a.i();
}
template <typename T>
const T* enum_vector(Arguments& a) {
  static std::array<T, 16> values;
  for (T& v : values) v = a.r.boolean() ? static_cast<T>(a.e() & 0xffff) : static_cast<T>(a.i());
  return values.data();
}
// Texture offsets: any integer (glTexSubImage2D at INT_MAX used to overflow).
GLint offset(Arguments& a) {
  return a.i();
}

// Longer than 150 lines: one case per GL ES entry point the fuzzer calls,
// each a line; the switch is the list of what is fuzzed.
void call(Arguments& a) {
  ByteReader& r = a.r;
  switch (r.u8() % 150) {
    case 0: glActiveTexture(r.boolean() ? GL_TEXTURE0 + r.u8() % 4 : a.e()); break;
    case 1: glAlphaFunc(a.e(), a.f()); break;
    case 2: glAlphaFuncx(a.e(), a.x()); break;
    case 3: glBindBuffer(a.e(), r.u8() % 8); break;
    case 4: glBindTexture(a.e(), r.u8() % 8); break;
    case 5: glBlendFunc(a.e(), a.e()); break;
    case 6: {
      const GLenum target = a.e();
      const GLsizeiptr size = r.boolean() ? a.small(4096) : a.i();
      // The client holds `size` bytes only up to the window's end.
      const void* data = size >= 0 && size <= static_cast<GLsizeiptr>(INPUT_WINDOW) ? a.in_or_null() : nullptr;
      glBufferData(target, size, data, a.e());
      break;
    }
    case 7: {
      const GLenum target = a.e();
      const GLintptr offset_bytes = a.i();
      const GLsizeiptr size = a.small(4096);
      glBufferSubData(target, offset_bytes, size, a.in());
      break;
    }
    case 8: glClear(r.u32()); break;
    case 9: glClearColor(a.f(), a.f(), a.f(), a.f()); break;
    case 10: glClearColorx(a.x(), a.x(), a.x(), a.x()); break;
    case 11: glClearDepthf(a.f()); break;
    case 12: glClearDepthx(a.x()); break;
    case 13: glClearStencil(a.i()); break;
    case 14: glClientActiveTexture(r.boolean() ? GL_TEXTURE0 + r.u8() % 4 : a.e()); break;
    case 15: glClipPlanef(a.e(), a.fv()); break;
    case 16: glClipPlanex(a.e(), a.xv()); break;
    case 17: glColor4f(a.f(), a.f(), a.f(), a.f()); break;
    case 18: glColor4ub(r.u8(), r.u8(), r.u8(), r.u8()); break;
    case 19: glColor4x(a.x(), a.x(), a.x(), a.x()); break;
    case 20: glColorMask(a.b(), a.b(), a.b(), a.b()); break;
    case 21: glColorPointer(a.i(), a.e(), a.stride(), a.array_pointer(GL_ARRAY_BUFFER_BINDING)); break;
    case 22: {
      const GLenum target = a.e();
      const GLint level = a.i();
      const GLenum format = a.e();
      const GLsizei w = a.i(), h = a.i();
      const GLint border = a.i();
      glCompressedTexImage2D(target, level, format, w, h, border, a.small(4096), a.in());
      break;
    }
    case 23: {
      const GLenum target = a.e();
      const GLint level = a.i(), x = offset(a), y = offset(a);
      const GLsizei w = a.i(), h = a.i();
      const GLenum format = a.e();
      glCompressedTexSubImage2D(target, level, x, y, w, h, format, a.small(4096), a.in());
      break;
    }
    case 24: {
      const GLenum target = a.e();
      const GLint level = a.i();
      const GLenum format = a.e();
      const GLint x = a.i(), y = a.i();
      const GLsizei w = a.i(), h = a.i();
      glCopyTexImage2D(target, level, format, x, y, w, h, a.i());
      break;
    }
    case 25: {
      const GLenum target = a.e();
      const GLint level = a.i(), xo = offset(a), yo = offset(a), x = a.i(), y = a.i();
      glCopyTexSubImage2D(target, level, xo, yo, x, y, a.i(), a.i());
      break;
    }
    case 26: glCullFace(a.e()); break;
    case 27: glDeleteBuffers(a.small(16), a.uv()); break;
    case 28: glDeleteTextures(a.small(16), a.uv()); break;
    case 29: glDepthFunc(a.e()); break;
    case 30: glDepthMask(a.b()); break;
    case 31: glDepthRangef(a.f(), a.f()); break;
    case 32: glDepthRangex(a.x(), a.x()); break;
    case 33: glDisable(a.e()); break;
    case 34: glDisableClientState(a.e()); break;
    case 35: {
      const GLenum mode = r.boolean() ? GL_POINTS + r.u8() % 7 : a.e();
      const GLint first = a.small(1024);
      glDrawArrays(mode, first, a.small(300));
      break;
    }
    case 36: {
      const GLenum mode = r.boolean() ? GL_POINTS + r.u8() % 7 : a.e();
      const GLsizei count = a.small(300);
      const GLenum type = r.boolean() ? (r.boolean() ? GL_UNSIGNED_SHORT : GL_UNSIGNED_BYTE) : a.e();
      glDrawElements(mode, count, type, a.array_pointer(GL_ELEMENT_ARRAY_BUFFER_BINDING));
      break;
    }
    case 37: glEnable(a.e()); break;
    case 38: glEnableClientState(a.e()); break;
    case 39: glFinish(); break;
    case 40: glFlush(); break;
    case 41: glFogf(a.e(), enum_float(a)); break;
    case 42: glFogfv(a.e(), enum_vector<GLfloat>(a)); break;
    case 43: glFogx(a.e(), enum_int(a)); break;
    case 44: glFogxv(a.e(), enum_vector<GLfixed>(a)); break;
    case 45: glFrontFace(a.e()); break;
    case 46: glFrustumf(a.f(), a.f(), a.f(), a.f(), a.f(), a.f()); break;
    case 47: glFrustumx(a.x(), a.x(), a.x(), a.x(), a.x(), a.x()); break;
    case 48: glGenBuffers(a.small(16), a.out<GLuint>()); break;
    case 49: glGenTextures(a.small(16), a.out<GLuint>()); break;
    case 50: glGetBooleanv(a.e(), a.out<GLboolean>()); break;
    case 51: glGetBufferParameteriv(a.e(), a.e(), a.out<GLint>()); break;
    case 52: glGetClipPlanef(a.e(), a.out<GLfloat>()); break;
    case 53: glGetClipPlanex(a.e(), a.out<GLfixed>()); break;
    case 54: {
      const GLenum error = glGetError();
      if (error != GL_NO_ERROR && error != GL_INVALID_ENUM && error != GL_INVALID_VALUE &&
          error != GL_INVALID_OPERATION && error != GL_STACK_OVERFLOW && error != GL_STACK_UNDERFLOW &&
          error != GL_OUT_OF_MEMORY)
        fail("glGetError returned " + std::to_string(error) + ", which is not an error code");
      break;
    }
    case 55: glGetFixedv(a.e(), a.out<GLfixed>()); break;
    case 56: glGetFloatv(a.e(), a.out<GLfloat>()); break;
    case 57: glGetIntegerv(a.e(), a.out<GLint>()); break;
    case 58: glGetLightfv(a.e(), a.e(), a.out<GLfloat>()); break;
    case 59: glGetLightxv(a.e(), a.e(), a.out<GLfixed>()); break;
    case 60: glGetMaterialfv(a.e(), a.e(), a.out<GLfloat>()); break;
    case 61: glGetMaterialxv(a.e(), a.e(), a.out<GLfixed>()); break;
    case 62: glGetPointerv(a.e(), a.out<void*>()); break;
    case 63: {
      const GLubyte* text = glGetString(a.e());
      if (text) (void)std::strlen(reinterpret_cast<const char*>(text));
      break;
    }
    case 64: glGetTexEnvfv(a.e(), a.e(), a.out<GLfloat>()); break;
    case 65: glGetTexEnviv(a.e(), a.e(), a.out<GLint>()); break;
    case 66: glGetTexEnvxv(a.e(), a.e(), a.out<GLfixed>()); break;
    case 67: glGetTexParameterfv(a.e(), a.e(), a.out<GLfloat>()); break;
    case 68: glGetTexParameteriv(a.e(), a.e(), a.out<GLint>()); break;
    case 69: glGetTexParameterxv(a.e(), a.e(), a.out<GLfixed>()); break;
    case 70: glHint(a.e(), a.e()); break;
    case 71: (void)glIsBuffer(r.u8() % 8); break;
    case 72: (void)glIsEnabled(a.e()); break;
    case 73: (void)glIsTexture(r.u8() % 8); break;
    case 74: glLightModelf(a.e(), a.f()); break;
    case 75: glLightModelfv(a.e(), a.fv()); break;
    case 76: glLightModelx(a.e(), a.x()); break;
    case 77: glLightModelxv(a.e(), a.xv()); break;
    case 78: glLightf(a.e(), a.e(), a.f()); break;
    case 79: glLightfv(a.e(), a.e(), a.fv()); break;
    case 80: glLightx(a.e(), a.e(), a.x()); break;
    case 81: glLightxv(a.e(), a.e(), a.xv()); break;
    case 82: glLineWidth(a.f()); break;
    case 83: glLineWidthx(a.x()); break;
    case 84: glLoadIdentity(); break;
    case 85: glLoadMatrixf(a.fv()); break;
    case 86: glLoadMatrixx(a.xv()); break;
    case 87: glLogicOp(a.e()); break;
    case 88: glMaterialf(a.e(), a.e(), a.f()); break;
    case 89: glMaterialfv(a.e(), a.e(), a.fv()); break;
    case 90: glMaterialx(a.e(), a.e(), a.x()); break;
    case 91: glMaterialxv(a.e(), a.e(), a.xv()); break;
    case 92: glMatrixMode(a.e()); break;
    case 93: glMultMatrixf(a.fv()); break;
    case 94: glMultMatrixx(a.xv()); break;
    case 95: glMultiTexCoord4f(a.e(), a.f(), a.f(), a.f(), a.f()); break;
    case 96: glMultiTexCoord4x(a.e(), a.x(), a.x(), a.x(), a.x()); break;
    case 97: glNormal3f(a.f(), a.f(), a.f()); break;
    case 98: glNormal3x(a.x(), a.x(), a.x()); break;
    case 99: glNormalPointer(a.e(), a.stride(), a.array_pointer(GL_ARRAY_BUFFER_BINDING)); break;
    case 100: glOrthof(a.f(), a.f(), a.f(), a.f(), a.f(), a.f()); break;
    case 101: glOrthox(a.x(), a.x(), a.x(), a.x(), a.x(), a.x()); break;
    case 102: glPixelStorei(a.e(), a.i()); break;
    case 103: glPointParameterf(a.e(), a.f()); break;
    case 104: glPointParameterfv(a.e(), a.fv()); break;
    case 105: glPointParameterx(a.e(), a.x()); break;
    case 106: glPointParameterxv(a.e(), a.xv()); break;
    case 107: glPointSize(a.f()); break;
    case 108: glPointSizex(a.x()); break;
    case 109: glPolygonOffset(a.f(), a.f()); break;
    case 110: glPolygonOffsetx(a.x(), a.x()); break;
    case 111: glPopMatrix(); break;
    case 112: glPushMatrix(); break;
    case 113: {
      const GLint x = a.i(), y = a.i();
      const GLsizei w = a.small(1024), h = a.small(1024);
      const GLenum format = a.e();
      glReadPixels(x, y, w, h, format, a.e(), a.out<uint8_t>());
      break;
    }
    case 114: glRotatef(a.f(), a.f(), a.f(), a.f()); break;
    case 115: glRotatex(a.x(), a.x(), a.x(), a.x()); break;
    case 116: glSampleCoverage(a.f(), a.b()); break;
    case 117: glSampleCoveragex(a.x(), a.b()); break;
    case 118: glScalef(a.f(), a.f(), a.f()); break;
    case 119: glScalex(a.x(), a.x(), a.x()); break;
    case 120: glScissor(a.i(), a.i(), a.i(), a.i()); break;
    case 121: glShadeModel(a.e()); break;
    case 122: glStencilFunc(a.e(), a.i(), r.u32()); break;
    case 123: glStencilMask(r.u32()); break;
    case 124: glStencilOp(a.e(), a.e(), a.e()); break;
    case 125: glTexCoordPointer(a.i(), a.e(), a.stride(), a.array_pointer(GL_ARRAY_BUFFER_BINDING)); break;
    case 126: glTexEnvf(a.e(), a.e(), enum_float(a)); break;
    case 127: glTexEnvfv(a.e(), a.e(), enum_vector<GLfloat>(a)); break;
    case 128: glTexEnvi(a.e(), a.e(), enum_int(a)); break;
    case 129: glTexEnviv(a.e(), a.e(), enum_vector<GLint>(a)); break;
    case 130: glTexEnvx(a.e(), a.e(), enum_int(a)); break;
    case 131: glTexEnvxv(a.e(), a.e(), enum_vector<GLfixed>(a)); break;
    case 132:
    case 133: {
      const GLenum target = r.boolean() ? GL_TEXTURE_2D : a.e();
      const GLint level = a.small(10);
      const GLint internal = r.boolean() ? GL_RGBA : static_cast<GLint>(a.e());
      // Sizes: powers of two likely; anything else, too (MAX_TEXTURE_SIZE is the driver's check).
      const GLsizei w = r.boolean() ? 1 << (r.u8() % 11) : a.i();
      const GLsizei h = r.boolean() ? 1 << (r.u8() % 11) : a.i();
      const GLint border = r.pick(8) == 0 ? a.i() : 0;
      const GLenum format = r.boolean() ? GL_RGBA : a.e();
      const GLenum type = r.boolean() ? GL_UNSIGNED_BYTE : a.e();
      // Pixels: the client holds 1024x1024 RGBA past the window.
      glTexImage2D(target, level, internal, w, h, border, format, type, a.in_or_null());
      break;
    }
    case 134: glTexParameterf(a.e(), a.e(), enum_float(a)); break;
    case 135: glTexParameterfv(a.e(), a.e(), enum_vector<GLfloat>(a)); break;
    case 136: glTexParameteri(a.e(), a.e(), enum_int(a)); break;
    case 137: glTexParameteriv(a.e(), a.e(), enum_vector<GLint>(a)); break;
    case 138: glTexParameterx(a.e(), a.e(), enum_int(a)); break;
    case 139: glTexParameterxv(a.e(), a.e(), enum_vector<GLfixed>(a)); break;
    case 140: {
      const GLenum target = r.boolean() ? GL_TEXTURE_2D : a.e();
      const GLint level = a.small(10), x = offset(a), y = offset(a);
      const GLsizei w = a.small(1024), h = a.small(1024);
      const GLenum format = r.boolean() ? GL_RGBA : a.e();
      const GLenum type = r.boolean() ? GL_UNSIGNED_BYTE : a.e();
      glTexSubImage2D(target, level, x, y, w, h, format, type, a.in());
      break;
    }
    case 141: glTranslatef(a.f(), a.f(), a.f()); break;
    case 142: glTranslatex(a.x(), a.x(), a.x()); break;
    case 143: glVertexPointer(a.i(), a.e(), a.stride(), a.array_pointer(GL_ARRAY_BUFFER_BINDING)); break;
    case 144: glViewport(a.i(), a.i(), a.i(), a.i()); break;
    // Common states, to reach deeper than random enums do.
    case 145: glEnableClientState(GL_VERTEX_ARRAY + r.u8() % 4); break;
    case 146: glEnable(r.boolean() ? GL_TEXTURE_2D : r.boolean() ? GL_LIGHTING : GL_LIGHT0 + r.u8() % 8); break;
    case 147:
      glVertexPointer(2 + r.u8() % 3, r.boolean() ? GL_FLOAT : GL_FIXED, 0, a.array_pointer(GL_ARRAY_BUFFER_BINDING));
      break;
    case 148: glTexParameteri(GL_TEXTURE_2D, a.e(), enum_int(a)); break;
    default: glDrawArrays(GL_TRIANGLES, 0, a.small(64)); break;
  }
}

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static FuzzHost host;
  static CountingRenderer renderer;
  static std::vector<uint8_t> client(CLIENT_BYTES, 0);
  static std::vector<uint8_t> output(CLIENT_BYTES, 0);
  // The input is also the client's data (vertices, matrices, images).
  if (size == 0) {
    std::memset(client.data(), 0, INPUT_WINDOW);
  } else {
    size_t filled = std::min(size, INPUT_WINDOW);
    std::memcpy(client.data(), data, filled);
    for (; filled < INPUT_WINDOW; filled *= 2)
      std::memcpy(client.data() + filled, client.data(), std::min(filled, INPUT_WINDOW - filled));
  }

  tessera::AppEnvironment env;
  env.host = &host;
  env.memory_bytes = host.memory_bytes();
  env.heap_base = 4u << 20;
  env.heap_end = 15u << 20;
  env.frames = 1000;
  tessera::gl::set_environment(&env);
  auto context = std::make_unique<tessera::gl::Context>(host, renderer);
  tessera::gl::set_current_context(context.get());

  ByteReader reader(data, size);
  Arguments arguments(reader, client.data(), output.data());
  try {
    while (!reader.empty()) call(arguments);
  } catch (const std::runtime_error& e) {
    if (std::string(e.what()).rfind("GL driver: out of system memory", 0) != 0)
      fail(std::string("an exception escaped a GL call: ") + e.what());
  } catch (const std::exception& e) {
    fail(std::string("an exception escaped a GL call: ") + e.what());
  }

  tessera::gl::set_current_context(nullptr);
  context.reset();
  tessera::gl::set_environment(nullptr);
  return 0;
}
