// Mesa is made deterministic through its environment, which it reads once,
// when the first context is created:
//  - GALLIUM_DRIVER=softpipe: llvmpipe splits the frame over threads and
//    generates code for the host CPU; softpipe is single-threaded scalar C,
//    so the same build gives the same bytes on every machine we use.
//  - MESA_NO_DITHER=1: dithering would make the 8-bit result depend on the
//    pixel position; our display quantises without it.
//  - mesa_glthread=false: no GL command thread.
//  - MESA_SHADER_CACHE_DISABLE=true: nothing is written to the user's home
//    directory, and a stale cache cannot change what runs.
// These are overwritten, not defaulted: a reference that silently changes
// driver with the caller's environment is no reference.
#include "reference/mesa_reference.h"

#include <GL/osmesa.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <mutex>
#include <stdexcept>

namespace tessera::reference {

namespace {

void pin_mesa_configuration() {
  static std::once_flag once;
  std::call_once(once, [] {
    setenv("GALLIUM_DRIVER", "softpipe", 1);
    setenv("MESA_NO_DITHER", "1", 1);
    setenv("mesa_glthread", "false", 1);
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
  });
}

struct ContextDeleter {
  void operator()(osmesa_context* context) const {
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(context);
  }
};
using ContextPtr = std::unique_ptr<osmesa_context, ContextDeleter>;

}  // namespace

ReferenceFrame render_with_mesa(const scenes::Scene& scene, const ReferenceRequest& request) {
  if (request.width == 0 || request.height == 0) throw std::runtime_error("reference: empty image size");
  pin_mesa_configuration();

  // RGBA8 colour with 24-bit depth and 8-bit stencil: at least what tessera
  // offers, so no scene is limited by the reference.
  const int attributes[] = {OSMESA_FORMAT,
                            OSMESA_RGBA,
                            OSMESA_DEPTH_BITS,
                            24,
                            OSMESA_STENCIL_BITS,
                            8,
                            OSMESA_ACCUM_BITS,
                            0,
                            OSMESA_PROFILE,
                            OSMESA_COMPAT_PROFILE,
                            0};
  // Declared before the context: OSMesa writes to it until the context is
  // released, so it must be destroyed after the context.
  std::vector<uint8_t> colour_buffer(size_t{request.width} * request.height * 4);
  ContextPtr context(OSMesaCreateContextAttribs(attributes, nullptr));
  if (!context) throw std::runtime_error("reference: OSMesaCreateContextAttribs failed");

  const auto width = static_cast<GLsizei>(request.width);
  const auto height = static_cast<GLsizei>(request.height);
  if (!OSMesaMakeCurrent(context.get(), colour_buffer.data(), GL_UNSIGNED_BYTE, width, height))
    throw std::runtime_error("reference: OSMesaMakeCurrent failed");
  ReferenceFrame result;
  result.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));

  std::string error;
  if (!scene.init(static_cast<int>(request.width), static_cast<int>(request.height), request.args, &error))
    throw std::runtime_error(std::string("reference: scene ") + scene.name + ": " + error);
  for (int frame = 0; frame <= request.frame; ++frame) {
    scene.draw(frame);
    if (request.after_frame) {
      glFinish();
      request.after_frame(frame);
    }
  }
  glFinish();

  // Read through GL rather than from colour_buffer, so the result does not
  // depend on when OSMesa brings the caller's buffer up to date.
  std::vector<uint8_t> bottom_up(colour_buffer.size());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());

  Image& image = result.image;
  image.width = request.width;
  image.height = request.height;
  image.rgba.resize(bottom_up.size());
  const size_t row_bytes = size_t{request.width} * 4;
  for (unsigned row = 0; row < request.height; ++row)
    std::memcpy(&image.rgba[row * row_bytes], &bottom_up[(request.height - 1 - row) * row_bytes], row_bytes);

  // As GL converts a float colour to an 8-bit unsigned normalised channel.
  GLfloat clear[4] = {};
  glGetFloatv(GL_COLOR_CLEAR_VALUE, clear);
  for (int c = 0; c < 4; ++c)
    result.clear_colour[c] = static_cast<uint8_t>(std::lround(std::clamp(clear[c], 0.0f, 1.0f) * 255.0f));
  return result;
}

}  // namespace tessera::reference
