// The GL ES 1.1 rendering context: all GL state, the vertex pipeline
// (fetch, transform, lighting, primitive assembly, clipping, viewport,
// culling) and the hand-over of triangles to the back end. The C entry
// points in gl_api.cpp forward to the current context. Every call charges
// the host's cost model (soft-float for the geometry), so the driver's time
// on the ARM is part of the simulation.
#pragma once

#include <GLES/gl.h>

#include <array>
#include <map>
#include <memory>
#include <vector>

#include <glm/glm.hpp>

#include "common/activity_counters.h"
#include "costs/host_cost.h"
#include "gl/geometry.h"
#include "gl/renderer.h"
#include "gl/vertex_cache.h"
#include "host/host_api.h"

namespace tessera::gl {

struct ArrayPointer {
  bool enabled = false;
  GLint size = 4;
  GLenum type = GL_FLOAT;
  GLsizei stride = 0;
  const void* pointer = nullptr;
  GLuint buffer = 0;  // bound GL_ARRAY_BUFFER when the pointer was set
};

// One mipmap level as the application defined it: RGBA8 in system memory.
struct TextureImage {
  uint32_t address = 0;
  unsigned width = 0, height = 0;
  GLenum format = 0;  // the internal format it was given; 0: not defined
};

// The state of one texture unit (ES 1.1 section 3.7.12 and 2.10.2): the
// server side (enable, binding, environment, texture matrix stack) selected
// by glActiveTexture, the client side (coordinate array, current
// coordinates) by glClientActiveTexture and glMultiTexCoord. Environment
// values are kept as the GL enums glGetTexEnv returns.
struct TextureUnitState {
  bool enabled = false;  // GL_TEXTURE_2D
  GLuint bound = 0;      // GL_TEXTURE_BINDING_2D
  GLenum env_mode = GL_MODULATE;
  float env_color[4] = {0, 0, 0, 0};
  GLenum combine_rgb = GL_MODULATE, combine_alpha = GL_MODULATE;
  GLenum source_rgb[3] = {GL_TEXTURE, GL_PREVIOUS, GL_CONSTANT};
  GLenum source_alpha[3] = {GL_TEXTURE, GL_PREVIOUS, GL_CONSTANT};
  GLenum operand_rgb[3] = {GL_SRC_COLOR, GL_SRC_COLOR, GL_SRC_ALPHA};
  GLenum operand_alpha[3] = {GL_SRC_ALPHA, GL_SRC_ALPHA, GL_SRC_ALPHA};
  float rgb_scale = 1, alpha_scale = 1;
  std::vector<glm::mat4> matrix{glm::mat4(1)};
  glm::vec4 texcoord{0, 0, 0, 1};
  ArrayPointer texcoord_array;
  bool coord_replace = false;  // GL_COORD_REPLACE_OES (glTexEnv GL_POINT_SPRITE_OES)
};

struct TextureObject {
  // Sampling parameters (filters, wraps); the level chain is filled in for
  // drawing (drawn_texture, textures.cpp). A new object has GL's default
  // minification filter, GL_NEAREST_MIPMAP_LINEAR.
  Texture texture = mipmapped_default();
  bool defined = false;  // level 0 has texels
  bool generate_mipmap = false;
  TextureImage image[MAX_TEXTURE_LEVELS];

  static Texture mipmapped_default() {
    Texture t;
    t.min_mipmap = MipmapFilter::linear;
    return t;
  }
};

// Whether `object` may be sampled (OpenGL ES 1.1 section 3.8.10): level 0
// defined and, for a mipmap minification filter, every level down to 1 x 1
// defined with half the size of the one before and level 0's format. An
// incomplete texture disables texturing for its unit.
bool texture_complete(const TextureObject& object);
// The texture as the back ends draw it: parameters and levels (one level
// unless the minification filter uses mipmaps). `object` is complete.
Texture drawn_texture(const TextureObject& object);

struct BufferObject {
  std::vector<uint8_t> data;
  GLenum usage = GL_STATIC_DRAW;
};

class Context {
 public:
  // The renderer belongs to the EGL surface the context is current on. The
  // driver's statistics (vertex cache) go to `counters` if there are any.
  // `texture_units` (driver.texture_units, 1 .. MAX_TEXTURE_UNITS) is what
  // GL_MAX_TEXTURE_UNITS answers.
  Context(HostApi& host, Renderer& renderer, ActivityCounters* counters = nullptr,
          unsigned texture_units = DEFAULT_TEXTURE_UNITS);

  HostApi& host() { return m_host; }
  Renderer& renderer() { return *m_renderer; }

  // Errors: the first one sticks until glGetError reads it.
  void error(GLenum code);
  GLenum get_error();

  // Charges one GL call (argument checks, state update) to the host.
  void charge_call() { charge(costs::HostCost::gl_call); }
  // Charges `units` of a row of the measured cost table (sw_driver/costs).
  void charge(costs::HostCost cost, uint64_t units = 1) { costs::charge(m_host, cost, units); }

  // State commands
  void enable(GLenum cap, bool on);
  bool is_enabled(GLenum cap);
  void enable_client_state(GLenum array, bool on);
  void clear_color(float r, float g, float b, float a);
  void clear_depth(float d);
  void clear_stencil(GLint s);
  void clear(GLbitfield mask);
  void viewport(GLint x, GLint y, GLsizei w, GLsizei h);
  void depth_range(float n, float f);
  void scissor(GLint x, GLint y, GLsizei w, GLsizei h);
  void depth_func(GLenum func);
  void depth_mask(bool flag);
  void alpha_func(GLenum func, float ref);
  void stencil_func(GLenum func, GLint ref, GLuint mask);
  void stencil_op(GLenum fail, GLenum zfail, GLenum zpass);
  void stencil_mask(GLuint mask);
  void blend_func(GLenum src, GLenum dst);
  void logic_op(GLenum op);
  void color_mask(bool r, bool g, bool b, bool a);
  void shade_model(GLenum mode);
  void cull_face(GLenum mode);
  void front_face(GLenum mode);
  void hint(GLenum target, GLenum mode);
  void point_size(float size);
  void line_width(float width);
  void polygon_offset(float factor, float units);
  void pixel_store(GLenum name, GLint value);
  void sample_coverage(float value, bool invert);
  void fog(GLenum name, const float* values, int count);
  void clip_plane(GLenum plane, const float* equation);
  void get_clip_plane(GLenum plane, float* equation);
  // glPointParameterf/fv: `count` values (3 for GL_POINT_DISTANCE_ATTENUATION).
  void point_parameter(GLenum name, const float* values, int count);
  // glTexEnv / glGetTexEnv with target GL_POINT_SPRITE_OES (GL_COORD_REPLACE_OES
  // of the active texture unit).
  void point_sprite_env(GLenum name, const float* values);
  void get_point_sprite_env(GLenum name, float* values);

  // Matrices
  void matrix_mode(GLenum mode);
  void load_matrix(const glm::mat4& m);
  void mult_matrix(const glm::mat4& m);
  void push_matrix();
  void pop_matrix();
  void frustum(float l, float r, float b, float t, float n, float f);
  void ortho(float l, float r, float b, float t, float n, float f);
  glm::mat4& current_matrix();

  // Current attributes and arrays
  void color(float r, float g, float b, float a);
  void normal(float x, float y, float z);
  void tex_coord(GLenum unit, float s, float t, float r, float q);
  void array_pointer(ArrayPointer& array, GLint size, GLenum type, GLsizei stride, const void* pointer, bool size_ok,
                     bool type_ok);
  ArrayPointer& vertex_array() { return m_attributes.vertex_array; }
  ArrayPointer& color_array() { return m_attributes.color_array; }
  ArrayPointer& normal_array() { return m_attributes.normal_array; }
  ArrayPointer& texcoord_array() { return client_unit().texcoord_array; }
  ArrayPointer& point_size_array() { return m_attributes.point_size_array; }
  void active_texture(GLenum unit, bool client);

  // Lighting
  void light(GLenum light, GLenum name, const float* values, int count);
  void get_light(GLenum light, GLenum name, float* values);
  void light_model(GLenum name, const float* values, int count);
  void material(GLenum face, GLenum name, const float* values, int count);
  void get_material(GLenum face, GLenum name, float* values);

  // Textures
  void gen_textures(GLsizei n, GLuint* names);
  void delete_textures(GLsizei n, const GLuint* names);
  void bind_texture(GLenum target, GLuint name);
  bool is_texture(GLuint name);
  void tex_image(GLenum target, GLint level, GLint internal_format, GLsizei width, GLsizei height, GLint border,
                 GLenum format, GLenum type, const void* pixels);
  void tex_sub_image(GLenum target, GLint level, GLint x, GLint y, GLsizei width, GLsizei height, GLenum format,
                     GLenum type, const void* pixels);
  // A level of OES_compressed_paletted_texture; level <= 0 gives 1 - level levels.
  void compressed_tex_image(GLenum target, GLint level, GLenum internal_format, GLsizei width, GLsizei height,
                            GLint border, GLsizei image_size, const void* data);
  void tex_parameter(GLenum target, GLenum name, float value);
  void get_tex_parameter(GLenum target, GLenum name, float* value);
  void tex_env(GLenum target, GLenum name, const float* values, int count);
  void get_tex_env(GLenum target, GLenum name, float* values);

  // Buffer objects
  void gen_buffers(GLsizei n, GLuint* names);
  void delete_buffers(GLsizei n, const GLuint* names);
  void bind_buffer(GLenum target, GLuint name);
  bool is_buffer(GLuint name);
  void buffer_data(GLenum target, GLsizeiptr size, const void* data, GLenum usage);
  void buffer_sub_data(GLenum target, GLintptr offset, GLsizeiptr size, const void* data);
  void get_buffer_parameter(GLenum target, GLenum name, GLint* value);

  // Drawing
  void draw_arrays(GLenum mode, GLint first, GLsizei count);
  void draw_elements(GLenum mode, GLsizei count, GLenum type, const void* indices);
  void read_pixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum format, GLenum type, void* pixels);
  void flush();
  void finish();

  // Queries
  void get_floats(GLenum name, float* values);  // also used for integers and booleans
  int query_count(GLenum name);                 // number of values of `name`, 0 if unknown
  const GLubyte* get_string(GLenum name);
  void get_pointer(GLenum name, void** value);

 private:
  struct Vertex {
    ClipVertex clip;
    glm::vec4 eye;
    bool valid;
  };
  // What emit_triangle is given: a polygon (culled, offset, two-sided lit)
  // or the two triangles of a point or a line (none of these).
  enum class Primitive { polygon, point_or_line };
  // `indexed`: the indices come from glDrawElements and may repeat, so
  // they go through the vertex cache; glDrawArrays' never repeat.
  void fetch_and_transform(const std::vector<uint32_t>& indices, bool indexed, std::vector<Vertex>& out);
  void draw(GLenum mode, const std::vector<uint32_t>& indices, bool indexed);
  // `flat_back_color`: the provoking vertex's back colour (two-sided lighting, flat shading).
  void emit_triangle(const Vertex& a, const Vertex& b, const Vertex& c, const glm::vec4* flat_color,
                     Primitive primitive = Primitive::polygon, const glm::vec4* flat_back_color = nullptr);
  // The user clip planes enabled, in eye coordinates.
  const std::vector<glm::vec4>& enabled_user_planes();
  // The point's size after the point-size array or glPointSize, distance
  // attenuation and clamping (GL ES 1.1 section 3.3).
  float derived_point_size(uint32_t index, const glm::vec4& eye);
  bool two_sided_lighting() const { return m_enabled.lighting && m_lighting.two_side; }
  void emit_quad(const glm::vec2 corners[4], const Vertex& source, const glm::vec2* tex);
  // Adds the polygon offset to the window depth of `screen` (the clipped
  // `polygon`'s vertices); false if a vertex cannot be placed.
  bool apply_polygon_offset(const std::vector<ClipVertex>& polygon, std::vector<ScreenVertex>& screen);
  void flush_triangles();
  RasterState raster_state() const;
  const uint8_t* array_element(const ArrayPointer& array, uint32_t index, size_t element_size);
  // One element of `array` (`defaults` for the components it lacks);
  // `normalized`: signed integer components as normal components.
  glm::vec4 read_attribute(const ArrayPointer& array, uint32_t index, const glm::vec4& defaults,
                           bool normalized = false);
  TextureObject* bound_texture();
  TextureUnitState& active_unit() { return m_texture.units[m_attributes.active_texture - GL_TEXTURE0]; }
  TextureUnitState& client_unit() { return m_texture.units[m_attributes.client_active_texture - GL_TEXTURE0]; }
  // Whether unit u draws: enabled, with a defined texture bound.
  bool unit_textured(unsigned u) const;
  // Level `level` of the bound texture as `width` x `height` RGBA8 words
  // (re)allocated in system memory, with `rows` written if not null.
  void store_level(TextureObject* object, unsigned level, unsigned width, unsigned height, GLenum format,
                   const uint32_t* rows);
  // GL_GENERATE_MIPMAP: levels 1.. from level 0 by the box filter.
  void generate_mipmaps(TextureObject* object);

  // The state, grouped by area. Each group is written by the file named
  // beside it (the others read it). The groups, and the fields in each, lie
  // in the order the flat fields had before they were grouped, so that a
  // context's layout in the ARM program stayed the same
  // (sw_driver/gl/README.md, "The context's state").

  // glEnable / glDisable switches, GL_CLIP_PLANEi included (state.cpp).
  struct EnableState {
    bool depth_test = false, blend = false, alpha_test = false, stencil_test = false;
    bool scissor_test = false, logic_op = false, dither = true;
    bool cull = false, lighting = false, normalize = false, rescale_normal = false;
    bool color_material = false, fog = false, multisample = true, polygon_offset_fill = false;
    bool sample_alpha_to_coverage = false, sample_alpha_to_one = false, sample_coverage = false;
    bool point_smooth = false, line_smooth = false, polygon_smooth = false;
    std::array<bool, MAX_USER_CLIP_PLANES> clip_plane{};
  };
  // User clip planes in eye coordinates (glClipPlane: state.cpp), and the
  // enabled ones gathered for a draw (primitives.cpp).
  struct ClipPlaneState {
    std::array<glm::vec4, MAX_USER_CLIP_PLANES> planes{};
    std::vector<glm::vec4> enabled_user_planes;  // scratch of enabled_user_planes()
  };
  // Face culling and shading (glCullFace, glFrontFace, glShadeModel: state.cpp).
  struct PrimitiveState {
    GLenum cull_mode = GL_BACK, front_face = GL_CCW, shade_model = GL_SMOOTH;
  };
  // glClearColor, glClearDepth, glClearStencil (state.cpp).
  struct ClearState {
    float color[4] = {0, 0, 0, 0};
    float depth = 1;
    GLint stencil = 0;
  };
  // The stencil and alpha tests' reference values as the application gave
  // them (glStencilFunc, glAlphaFunc: state.cpp); RasterState holds them as
  // the renderers use them.
  struct ReferenceState {
    GLint stencil = 0;
    float alpha = 0;
  };
  // Points, lines and polygon offset (glPointSize, glLineWidth,
  // glPointParameter, OES_point_sprite, glPolygonOffset: state.cpp).
  struct RasterizationState {
    float point_size = 1, line_width = 1;
    // Points: OES_point_sprite, glPointParameter (ES 1.1 table 6.10's initial values).
    bool point_sprite = false;
    float point_size_min = 0, point_size_max = MAX_POINT_SIZE, point_fade_threshold = 1;
    glm::vec3 point_distance_attenuation{1, 0, 0};
    float polygon_offset[2] = {0, 0};
  };
  // glPixelStorei (state.cpp).
  struct PixelStoreState {
    GLint pack_alignment = 4, unpack_alignment = 4;
  };
  // glSampleCoverage (state.cpp).
  struct CoverageState {
    float value = 1;
    bool invert = false;
  };
  // glFog (state.cpp).
  struct FogState {
    GLenum mode = GL_EXP;
    float density = 1, start = 0, end = 1, color[4] = {0, 0, 0, 0};
  };
  // The matrix stacks (matrices.cpp).
  struct TransformState {
    GLenum matrix_mode = GL_MODELVIEW;
    std::vector<glm::mat4> modelview{glm::mat4(1)}, projection{glm::mat4(1)};
  };
  // Current vertex attributes (glColor, glNormal), the vertex arrays and
  // the active units (glActiveTexture, glClientActiveTexture):
  // vertex_arrays.cpp; the arrays' switches (glEnableClientState): state.cpp.
  struct AttributeState {
    glm::vec4 color{1, 1, 1, 1};
    glm::vec3 normal{0, 0, 1};
    ArrayPointer vertex_array, color_array, normal_array;
    ArrayPointer point_size_array{false, 1, GL_FLOAT, 0, nullptr, 0};  // OES_point_size_array
    GLenum active_texture = GL_TEXTURE0, client_active_texture = GL_TEXTURE0;
  };
  // glLight, glLightModel, glMaterial (lighting.cpp).
  struct LightingState {
    LightingModel model;
    Material front_material;
    bool two_side = false;
  };
  // Texture objects and units (textures.cpp; a unit's current coordinates,
  // glMultiTexCoord: vertex_arrays.cpp).
  struct TextureState {
    explicit TextureState(unsigned units) : offered_units(units) {}
    std::map<GLuint, TextureObject> objects;
    GLuint next_name = 1;
    // Texture units: offered_units of them are offered, the rest stay off.
    unsigned offered_units;
    std::array<TextureUnitState, MAX_TEXTURE_UNITS> units;
  };
  // Buffer objects and their bindings (buffers.cpp).
  struct BufferState {
    std::map<GLuint, BufferObject> objects;
    GLuint next_name = 1;
    GLuint array = 0, element = 0;
  };
  // Driver statistics, null without counters (context.cpp).
  struct DriverCounters {
    ActivityCounter* cache_hits = nullptr;
    ActivityCounter* cache_misses = nullptr;
    ActivityCounter* vertices_transformed = nullptr;
  };

  HostApi& m_host;
  Renderer* m_renderer;
  GLenum m_error = GL_NO_ERROR;

  RasterState m_raster;  // fragment and framebuffer state as the renderers take it (state.cpp)
  EnableState m_enabled;
  ClipPlaneState m_clip;
  PrimitiveState m_primitive;
  ClearState m_clear;
  Viewport m_viewport;
  ReferenceState m_references;
  RasterizationState m_rasterization;
  PixelStoreState m_pixel_store;
  std::map<GLenum, GLenum> m_hints;
  CoverageState m_coverage;
  FogState m_fog;
  TransformState m_transform;
  AttributeState m_attributes;
  LightingState m_lighting;
  TextureState m_texture;
  BufferState m_buffer;
  // Not state: a draw's working space, kept so that a triangle allocates
  // nothing (the batch for the renderer, emit_triangle's polygon before and
  // after clipping and in screen space: primitives.cpp; the transformed
  // vertices and their cache: vertex_fetch.cpp).
  std::vector<Triangle> m_batch;
  std::vector<ClipVertex> m_scratch_polygon;
  std::vector<ScreenVertex> m_scratch_screen;
  std::vector<Vertex> m_vertices;
  VertexCache<Vertex> m_vertex_cache;
  DriverCounters m_counters;
};

// The current context (eglMakeCurrent), or nullptr.
Context* current_context();
void set_current_context(Context* context);

}  // namespace tessera::gl
