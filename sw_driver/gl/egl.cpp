// EGL 1.4 on the simulated SoC: one display (the SoC's), one configuration
// matching the display controller's pixel format and the back end's depth
// and stencil buffers, one window surface (the screen) owning the back
// end's renderer, and GL ES 1.x contexts.
// eglSwapBuffers presents through the back end and ends the application
// once the run's frame count has been shown.
#include <EGL/egl.h>

#include <cstring>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "common/pixel_format.h"
#include "config/config.h"
#include "display/display_regs.h"
#include "gl/context.h"
#include "gl/frame_phases.h"
#include "gl/runtime.h"
#include "soc/memory_map.h"

namespace {

using tessera::gl::Context;

struct Display {
  bool initialized = false;
};

struct Surface {
  std::unique_ptr<tessera::gl::Renderer> renderer;
  EGLConfig config;
};

struct ContextObject {
  EGLConfig config;
  std::unique_ptr<Context> gl;  // made at the first eglMakeCurrent
  Surface* surface = nullptr;
};

Display g_display;
EGLint g_error = EGL_SUCCESS;
EGLenum g_api = EGL_OPENGL_ES_API;
std::set<Surface*> g_surfaces;
std::set<ContextObject*> g_contexts;
ContextObject* g_current = nullptr;
Surface* g_current_surface = nullptr;
unsigned g_swaps = 0;
// AppEnvironment::frame_statistics as the launcher gave it, and the back
// end's figures of the frame being presented (eglCreateWindowSurface).
std::function<void(const std::vector<std::pair<std::string, double>>&)> g_frame_statistics;
std::vector<std::pair<std::string, double>> g_backend_figures;

// The one configuration: its id is 1.
EGLConfig const CONFIG = reinterpret_cast<EGLConfig>(1);

EGLDisplay display_handle() {
  return reinterpret_cast<EGLDisplay>(&g_display);
}

template <typename T>
T fail(EGLint code, T value) {
  g_error = code;
  return value;
}

EGLBoolean ok() {
  g_error = EGL_SUCCESS;
  return EGL_TRUE;
}

// Checks the display handle and its initialisation; sets the error.
bool valid_display(EGLDisplay dpy) {
  if (dpy != display_handle()) return fail(EGL_BAD_DISPLAY, false);
  if (!g_display.initialized) return fail(EGL_NOT_INITIALIZED, false);
  return true;
}

// The display's frame-buffer format, from its FORMAT register.
const tessera::PixelFormatInfo& display_format() {
  const uint32_t format = tessera::memory_map::display_regs.base + tessera::display_regs::FORMAT;
  const uint32_t code = tessera::gl::environment().host->read32(format);
  const std::optional<tessera::PixelFormat> known = tessera::pixel_format_from_code(code);
  if (!known) throw std::runtime_error("EGL: the display reports an unknown pixel format code " + std::to_string(code));
  return tessera::pixel_format_info(*known);
}

// What the run's back end stores: the configuration is offered before the
// surface that makes the renderer exists.
tessera::gl::RendererCapabilities back_end_capabilities() {
  return tessera::gl::environment().capabilities;
}

EGLint config_attribute(EGLint attribute, bool* known) {
  *known = true;
  const tessera::PixelFormatInfo& format = display_format();
  switch (attribute) {
    case EGL_BUFFER_SIZE: return static_cast<EGLint>(8 * format.bytes);
    case EGL_RED_SIZE: return static_cast<EGLint>(format.red_bits);
    case EGL_GREEN_SIZE: return static_cast<EGLint>(format.green_bits);
    case EGL_BLUE_SIZE: return static_cast<EGLint>(format.blue_bits);
    case EGL_ALPHA_SIZE: return static_cast<EGLint>(format.alpha_bits);
    case EGL_LUMINANCE_SIZE:
    case EGL_ALPHA_MASK_SIZE:
    case EGL_SAMPLES:
    case EGL_SAMPLE_BUFFERS:
    case EGL_MAX_SWAP_INTERVAL:
    case EGL_MIN_SWAP_INTERVAL:
    case EGL_TRANSPARENT_RED_VALUE:
    case EGL_TRANSPARENT_GREEN_VALUE:
    case EGL_TRANSPARENT_BLUE_VALUE:
    case EGL_LEVEL:
    case EGL_BIND_TO_TEXTURE_RGB:
    case EGL_BIND_TO_TEXTURE_RGBA:
    case EGL_NATIVE_VISUAL_ID:
    case EGL_NATIVE_VISUAL_TYPE:
    case EGL_MAX_PBUFFER_WIDTH:
    case EGL_MAX_PBUFFER_HEIGHT:
    case EGL_MAX_PBUFFER_PIXELS:
      return attribute == EGL_MAX_SWAP_INTERVAL || attribute == EGL_MIN_SWAP_INTERVAL ? 1 : 0;
    case EGL_DEPTH_SIZE: return static_cast<EGLint>(back_end_capabilities().depth_bits);
    case EGL_STENCIL_SIZE: return static_cast<EGLint>(back_end_capabilities().stencil_bits);
    case EGL_CONFIG_ID: return 1;
    case EGL_CONFIG_CAVEAT: return EGL_NONE;
    case EGL_COLOR_BUFFER_TYPE: return EGL_RGB_BUFFER;
    case EGL_NATIVE_RENDERABLE: return EGL_TRUE;
    case EGL_RENDERABLE_TYPE:
    case EGL_CONFORMANT: return EGL_OPENGL_ES_BIT;
    case EGL_SURFACE_TYPE: return EGL_WINDOW_BIT;
    case EGL_TRANSPARENT_TYPE: return EGL_NONE;
    default: *known = false; return 0;
  }
}

// Whether the configuration satisfies one requested attribute (EGL 1.4
// table 3.4: sizes are minimums, masks must be contained, ids exact).
bool satisfies(EGLint attribute, EGLint value, bool* known) {
  const EGLint have = config_attribute(attribute, known);
  if (!*known) return false;
  if (value == EGL_DONT_CARE) return true;
  switch (attribute) {
    case EGL_BUFFER_SIZE:
    case EGL_RED_SIZE:
    case EGL_GREEN_SIZE:
    case EGL_BLUE_SIZE:
    case EGL_ALPHA_SIZE:
    case EGL_LUMINANCE_SIZE:
    case EGL_ALPHA_MASK_SIZE:
    case EGL_DEPTH_SIZE:
    case EGL_STENCIL_SIZE:
    case EGL_SAMPLES:
    case EGL_SAMPLE_BUFFERS:
    case EGL_LEVEL: return have >= value;
    case EGL_RENDERABLE_TYPE:
    case EGL_SURFACE_TYPE:
    case EGL_CONFORMANT: return (have & value) == value;
    default: return have == value;
  }
}

}  // namespace

extern "C" {

EGLAPI EGLint EGLAPIENTRY eglGetError(void) {
  const EGLint e = g_error;
  g_error = EGL_SUCCESS;
  return e;
}

EGLAPI EGLDisplay EGLAPIENTRY eglGetDisplay(EGLNativeDisplayType display_id) {
  if (display_id != EGL_DEFAULT_DISPLAY) return fail(EGL_BAD_PARAMETER, EGL_NO_DISPLAY);
  g_error = EGL_SUCCESS;
  return display_handle();
}

EGLAPI EGLBoolean EGLAPIENTRY eglInitialize(EGLDisplay dpy, EGLint* major, EGLint* minor) {
  if (dpy != display_handle()) return fail(EGL_BAD_DISPLAY, EGL_FALSE);
  g_display.initialized = true;
  if (major) *major = 1;
  if (minor) *minor = 4;
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglTerminate(EGLDisplay dpy) {
  if (dpy != display_handle()) return fail(EGL_BAD_DISPLAY, EGL_FALSE);
  // Resources still current stay alive until released (EGL 1.4, 3.2).
  for (auto it = g_contexts.begin(); it != g_contexts.end();) {
    if (*it != g_current)
      delete *it, it = g_contexts.erase(it);
    else
      ++it;
  }
  for (auto it = g_surfaces.begin(); it != g_surfaces.end();) {
    if (*it != g_current_surface)
      delete *it, it = g_surfaces.erase(it);
    else
      ++it;
  }
  g_display.initialized = false;
  return ok();
}

EGLAPI const char* EGLAPIENTRY eglQueryString(EGLDisplay dpy, EGLint name) {
  if (!valid_display(dpy)) return nullptr;
  g_error = EGL_SUCCESS;
  switch (name) {
    case EGL_VENDOR: return "tessera";
    case EGL_VERSION: return "1.4 tessera";
    case EGL_EXTENSIONS: return "";
    case EGL_CLIENT_APIS: return "OpenGL_ES";
    default: return fail(EGL_BAD_PARAMETER, static_cast<const char*>(nullptr));
  }
}

EGLAPI __eglMustCastToProperFunctionPointerType EGLAPIENTRY eglGetProcAddress(const char*) {
  return nullptr;
}

EGLAPI EGLBoolean EGLAPIENTRY eglGetConfigs(EGLDisplay dpy, EGLConfig* configs, EGLint config_size,
                                            EGLint* num_config) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (!num_config) return fail(EGL_BAD_PARAMETER, EGL_FALSE);
  *num_config = configs ? (config_size > 0 ? 1 : 0) : 1;
  if (configs && config_size > 0) configs[0] = CONFIG;
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglChooseConfig(EGLDisplay dpy, const EGLint* attrib_list, EGLConfig* configs,
                                              EGLint config_size, EGLint* num_config) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (!num_config) return fail(EGL_BAD_PARAMETER, EGL_FALSE);
  bool match = true;
  for (const EGLint* a = attrib_list; a && *a != EGL_NONE; a += 2) {
    bool known = false;
    if (a[0] == EGL_MATCH_NATIVE_PIXMAP || a[0] == EGL_CONFIG_ID) {
      if (a[0] == EGL_CONFIG_ID && a[1] != EGL_DONT_CARE && a[1] != 1) match = false;
      continue;
    }
    if (!satisfies(a[0], a[1], &known)) {
      if (!known) return fail(EGL_BAD_ATTRIBUTE, EGL_FALSE);
      match = false;
    }
  }
  *num_config = match ? (configs ? (config_size > 0 ? 1 : 0) : 1) : 0;
  if (match && configs && config_size > 0) configs[0] = CONFIG;
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglGetConfigAttrib(EGLDisplay dpy, EGLConfig config, EGLint attribute, EGLint* value) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (config != CONFIG) return fail(EGL_BAD_CONFIG, EGL_FALSE);
  bool known = false;
  const EGLint v = config_attribute(attribute, &known);
  if (!known) return fail(EGL_BAD_ATTRIBUTE, EGL_FALSE);
  if (value) *value = v;
  return ok();
}

EGLAPI EGLSurface EGLAPIENTRY eglCreateWindowSurface(EGLDisplay dpy, EGLConfig config, EGLNativeWindowType,
                                                     const EGLint* attrib_list) {
  if (!valid_display(dpy)) return EGL_NO_SURFACE;
  if (config != CONFIG) return fail(EGL_BAD_CONFIG, EGL_NO_SURFACE);
  for (const EGLint* a = attrib_list; a && *a != EGL_NONE; a += 2)
    if (a[0] != EGL_RENDER_BUFFER || (a[1] != EGL_BACK_BUFFER && a[1] != EGL_SINGLE_BUFFER))
      return fail(EGL_BAD_ATTRIBUTE, EGL_NO_SURFACE);
  // The SoC has one screen: a second window surface on it is refused.
  if (!g_surfaces.empty()) return fail(EGL_BAD_ALLOC, EGL_NO_SURFACE);
  auto& env = tessera::gl::environment();
  auto surface = std::make_unique<Surface>();
  // The launcher hands the back end over (AppEnvironment::make_renderer);
  // the front end knows none by name.
  if (!env.make_renderer)
    throw std::logic_error("EGL: no renderer back end was handed to the driver (AppEnvironment::make_renderer)");
  // The back end's figures for a frame (it gives them in present()) go
  // out with the front end's phases, one record per frame, at the swap.
  if (env.frame_statistics && !g_frame_statistics) {
    g_frame_statistics = std::move(env.frame_statistics);
    env.frame_statistics = [](const std::vector<std::pair<std::string, double>>& figures) {
      g_backend_figures.insert(g_backend_figures.end(), figures.begin(), figures.end());
    };
  }
  surface->renderer = env.make_renderer(env);
  surface->config = config;
  Surface* handle = surface.release();
  g_surfaces.insert(handle);
  g_error = EGL_SUCCESS;
  return handle;
}

EGLAPI EGLSurface EGLAPIENTRY eglCreatePbufferSurface(EGLDisplay dpy, EGLConfig, const EGLint*) {
  if (!valid_display(dpy)) return EGL_NO_SURFACE;
  return fail(EGL_BAD_MATCH, EGL_NO_SURFACE);  // the configuration supports window surfaces only
}
EGLAPI EGLSurface EGLAPIENTRY eglCreatePixmapSurface(EGLDisplay dpy, EGLConfig, EGLNativePixmapType, const EGLint*) {
  if (!valid_display(dpy)) return EGL_NO_SURFACE;
  return fail(EGL_BAD_MATCH, EGL_NO_SURFACE);
}
EGLAPI EGLSurface EGLAPIENTRY eglCreatePbufferFromClientBuffer(EGLDisplay dpy, EGLenum, EGLClientBuffer, EGLConfig,
                                                               const EGLint*) {
  if (!valid_display(dpy)) return EGL_NO_SURFACE;
  return fail(EGL_BAD_PARAMETER, EGL_NO_SURFACE);
}

EGLAPI EGLBoolean EGLAPIENTRY eglDestroySurface(EGLDisplay dpy, EGLSurface surface) {
  if (!valid_display(dpy)) return EGL_FALSE;
  auto* s = static_cast<Surface*>(surface);
  if (!g_surfaces.count(s)) return fail(EGL_BAD_SURFACE, EGL_FALSE);
  if (s == g_current_surface) return ok();  // destroyed when no longer current
  g_surfaces.erase(s);
  delete s;
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglQuerySurface(EGLDisplay dpy, EGLSurface surface, EGLint attribute, EGLint* value) {
  if (!valid_display(dpy)) return EGL_FALSE;
  auto* s = static_cast<Surface*>(surface);
  if (!g_surfaces.count(s)) return fail(EGL_BAD_SURFACE, EGL_FALSE);
  switch (attribute) {
    case EGL_WIDTH: *value = static_cast<EGLint>(s->renderer->width()); break;
    case EGL_HEIGHT: *value = static_cast<EGLint>(s->renderer->height()); break;
    case EGL_CONFIG_ID: *value = 1; break;
    case EGL_RENDER_BUFFER: *value = EGL_BACK_BUFFER; break;
    case EGL_SWAP_BEHAVIOR: *value = EGL_BUFFER_DESTROYED; break;
    default: return fail(EGL_BAD_ATTRIBUTE, EGL_FALSE);
  }
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglSurfaceAttrib(EGLDisplay dpy, EGLSurface surface, EGLint attribute, EGLint) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (!g_surfaces.count(static_cast<Surface*>(surface))) return fail(EGL_BAD_SURFACE, EGL_FALSE);
  if (attribute != EGL_SWAP_BEHAVIOR && attribute != EGL_MIPMAP_LEVEL && attribute != EGL_MULTISAMPLE_RESOLVE)
    return fail(EGL_BAD_ATTRIBUTE, EGL_FALSE);
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglBindTexImage(EGLDisplay dpy, EGLSurface, EGLint) {
  if (!valid_display(dpy)) return EGL_FALSE;
  return fail(EGL_BAD_SURFACE, EGL_FALSE);
}
EGLAPI EGLBoolean EGLAPIENTRY eglReleaseTexImage(EGLDisplay dpy, EGLSurface, EGLint) {
  if (!valid_display(dpy)) return EGL_FALSE;
  return fail(EGL_BAD_SURFACE, EGL_FALSE);
}

EGLAPI EGLBoolean EGLAPIENTRY eglBindAPI(EGLenum api) {
  if (api != EGL_OPENGL_ES_API) return fail(EGL_BAD_PARAMETER, EGL_FALSE);
  g_api = api;
  return ok();
}
EGLAPI EGLenum EGLAPIENTRY eglQueryAPI(void) {
  return g_api;
}

EGLAPI EGLContext EGLAPIENTRY eglCreateContext(EGLDisplay dpy, EGLConfig config, EGLContext share_context,
                                               const EGLint* attrib_list) {
  if (!valid_display(dpy)) return EGL_NO_CONTEXT;
  if (config != CONFIG) return fail(EGL_BAD_CONFIG, EGL_NO_CONTEXT);
  if (share_context != EGL_NO_CONTEXT) return fail(EGL_BAD_MATCH, EGL_NO_CONTEXT);  // no sharing
  for (const EGLint* a = attrib_list; a && *a != EGL_NONE; a += 2) {
    if (a[0] != EGL_CONTEXT_CLIENT_VERSION) return fail(EGL_BAD_ATTRIBUTE, EGL_NO_CONTEXT);
    if (a[1] != 1) return fail(EGL_BAD_MATCH, EGL_NO_CONTEXT);  // GL ES 1.x only
  }
  auto* context = new ContextObject{config, nullptr, nullptr};
  g_contexts.insert(context);
  g_error = EGL_SUCCESS;
  return context;
}

EGLAPI EGLBoolean EGLAPIENTRY eglDestroyContext(EGLDisplay dpy, EGLContext ctx) {
  if (!valid_display(dpy)) return EGL_FALSE;
  auto* c = static_cast<ContextObject*>(ctx);
  if (!g_contexts.count(c)) return fail(EGL_BAD_CONTEXT, EGL_FALSE);
  if (c == g_current) return ok();
  g_contexts.erase(c);
  delete c;
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglMakeCurrent(EGLDisplay dpy, EGLSurface draw, EGLSurface read, EGLContext ctx) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (ctx == EGL_NO_CONTEXT) {
    if (draw != EGL_NO_SURFACE || read != EGL_NO_SURFACE) return fail(EGL_BAD_MATCH, EGL_FALSE);
    g_current = nullptr;
    g_current_surface = nullptr;
    tessera::gl::set_current_context(nullptr);
    return ok();
  }
  auto* c = static_cast<ContextObject*>(ctx);
  auto* d = static_cast<Surface*>(draw);
  if (!g_contexts.count(c)) return fail(EGL_BAD_CONTEXT, EGL_FALSE);
  if (!g_surfaces.count(d) || read != draw) return fail(EGL_BAD_SURFACE, EGL_FALSE);
  if (c->surface && c->surface != d) return fail(EGL_BAD_MATCH, EGL_FALSE);
  if (!c->gl) {
    auto& env = tessera::gl::environment();
    // driver.texture_units where the launcher has a configuration that
    // declares it (driver_parameters), the default elsewhere.
    const unsigned units = env.config != nullptr && env.config->has("driver.texture_units")
                               ? static_cast<unsigned>(env.config->get_uint("driver.texture_units"))
                               : tessera::gl::DEFAULT_TEXTURE_UNITS;
    c->gl = std::make_unique<Context>(*env.host, *d->renderer, env.counters, units);
  }
  c->surface = d;
  g_current = c;
  g_current_surface = d;
  tessera::gl::set_current_context(c->gl.get());
  return ok();
}

EGLAPI EGLContext EGLAPIENTRY eglGetCurrentContext(void) {
  return g_current ? g_current : EGL_NO_CONTEXT;
}
EGLAPI EGLSurface EGLAPIENTRY eglGetCurrentSurface(EGLint readdraw) {
  if (readdraw != EGL_READ && readdraw != EGL_DRAW) return fail(EGL_BAD_PARAMETER, EGL_NO_SURFACE);
  return g_current_surface ? g_current_surface : EGL_NO_SURFACE;
}
EGLAPI EGLDisplay EGLAPIENTRY eglGetCurrentDisplay(void) {
  return g_current ? display_handle() : EGL_NO_DISPLAY;
}

EGLAPI EGLBoolean EGLAPIENTRY eglQueryContext(EGLDisplay dpy, EGLContext ctx, EGLint attribute, EGLint* value) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (!g_contexts.count(static_cast<ContextObject*>(ctx))) return fail(EGL_BAD_CONTEXT, EGL_FALSE);
  switch (attribute) {
    case EGL_CONFIG_ID: *value = 1; break;
    case EGL_CONTEXT_CLIENT_TYPE: *value = EGL_OPENGL_ES_API; break;
    case EGL_CONTEXT_CLIENT_VERSION: *value = 1; break;
    case EGL_RENDER_BUFFER: *value = EGL_BACK_BUFFER; break;
    default: return fail(EGL_BAD_ATTRIBUTE, EGL_FALSE);
  }
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglReleaseThread(void) {
  g_current = nullptr;
  g_current_surface = nullptr;
  tessera::gl::set_current_context(nullptr);
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglWaitClient(void) {
  if (g_current && g_current->gl) g_current->gl->finish();
  return ok();
}
EGLAPI EGLBoolean EGLAPIENTRY eglWaitGL(void) {
  return eglWaitClient();
}
EGLAPI EGLBoolean EGLAPIENTRY eglWaitNative(EGLint engine) {
  if (engine != EGL_CORE_NATIVE_ENGINE) return fail(EGL_BAD_PARAMETER, EGL_FALSE);
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglSwapBuffers(EGLDisplay dpy, EGLSurface surface) {
  if (!valid_display(dpy)) return EGL_FALSE;
  auto* s = static_cast<Surface*>(surface);
  if (!g_surfaces.count(s)) return fail(EGL_BAD_SURFACE, EGL_FALSE);
  if (!g_current || g_current_surface != s) return fail(EGL_BAD_SURFACE, EGL_FALSE);
  {
    const tessera::gl::PhaseScope phase(tessera::gl::Phase::presenting);
    g_current->gl->flush();
    s->renderer->present();
  }
  if (g_frame_statistics) {
    std::vector<std::pair<std::string, double>> figures = tessera::gl::phase_clock().take_frame();
    figures.insert(figures.end(), g_backend_figures.begin(), g_backend_figures.end());
    g_backend_figures.clear();
    g_frame_statistics(figures);
    // Handing the record over is the program's own work on the ISS (in the
    // next frame's application phase): a row of the measured cost table
    // per figure (the native model's units_ figures are not the ISS's).
    uint64_t handed = 0;
    for (const auto& figure : figures) handed += figure.first.compare(0, 6, "units_") != 0 ? 1 : 0;
    if (tessera::HostApi* host = tessera::gl::environment().host)
      tessera::costs::charge(*host, tessera::costs::HostCost::frame_record_figure, handed);
  }
  ++g_swaps;
  if (g_swaps >= tessera::gl::environment().frames) throw tessera::gl::FramesComplete{};
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglSwapInterval(EGLDisplay dpy, EGLint) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (!g_current) return fail(EGL_BAD_CONTEXT, EGL_FALSE);
  return ok();
}

EGLAPI EGLBoolean EGLAPIENTRY eglCopyBuffers(EGLDisplay dpy, EGLSurface surface, EGLNativePixmapType) {
  if (!valid_display(dpy)) return EGL_FALSE;
  if (!g_surfaces.count(static_cast<Surface*>(surface))) return fail(EGL_BAD_SURFACE, EGL_FALSE);
  return fail(EGL_BAD_NATIVE_PIXMAP, EGL_FALSE);
}

}  // extern "C"
