// Unit tests of the back-end registry (sw_driver/renderers/backends.def and
// backends.h): every line of the table registered with its entry points,
// finding a back end by name, driver.backend's choices and the chosen back
// end's configuration check, and the handover of the factory to the GL
// front end (EGL builds its surface's renderer with the launcher's factory).
#include <EGL/egl.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <iterator>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "gl/renderer.h"
#include "gl/runtime.h"
#include "renderers/backend_parameters.h"
#include "renderers/backends.h"

using namespace tessera;

namespace {

std::vector<std::string> table_names() {
  return {
#define TESSERA_BACKEND(id, name, depth_bits, stencil_bits, description) name,
#include "renderers/backends.def"
#undef TESSERA_BACKEND
  };
}

std::string what_of(const std::function<void()>& action) {
  try {
    action();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Backends, EveryLineOfTheTableIsRegisteredInOrder) {
  const std::vector<std::string> names = table_names();
  ASSERT_EQ(std::size(backends::BACKENDS), names.size());
  std::set<std::string> ids, unique_names;
  for (size_t i = 0; i < names.size(); ++i) {
    const backends::Backend& entry = backends::BACKENDS[i];
    SCOPED_TRACE(entry.name);
    EXPECT_EQ(entry.name, names[i]);
    EXPECT_TRUE(ids.insert(entry.id).second) << "id listed twice";
    EXPECT_TRUE(unique_names.insert(entry.name).second) << "name listed twice";
    EXPECT_NE(entry.make_renderer, nullptr);
    EXPECT_NE(entry.check_configuration, nullptr);
    EXPECT_NE(entry.parameters, nullptr);
    EXPECT_FALSE(std::string(entry.description).empty());
    EXPECT_GE(entry.capabilities.depth_bits, 1u);
    EXPECT_LE(entry.capabilities.depth_bits, 32u);
    EXPECT_LE(entry.capabilities.stencil_bits, 8u);
  }
}

TEST(Backends, EveryBackEndHasItsFolderWithAReadme) {
  const char* source = std::getenv("TESSERA_SOURCE_DIR");
  ASSERT_NE(source, nullptr) << "run through ctest (TESSERA_SOURCE_DIR)";
  for (const backends::Backend& entry : backends::BACKENDS) {
    const std::filesystem::path folder = std::filesystem::path(source) / "sw_driver/renderers" / entry.id;
    EXPECT_TRUE(std::filesystem::is_regular_file(folder / "CMakeLists.txt")) << folder;
    EXPECT_TRUE(std::filesystem::is_regular_file(folder / "README.md")) << folder;
  }
}

// The facts EGL reports before a surface exists: arm keeps 16-bit depth and
// 8-bit stencil buffers (renderers/arm/README.md), raster one 32-bit word
// per pixel, depth 24 | stencil 8 (raster_regs.def, DEPTH_BASE).
TEST(Backends, BuiltInCapabilities) {
  EXPECT_EQ(backends::backend("arm").capabilities.depth_bits, 16u);
  EXPECT_EQ(backends::backend("arm").capabilities.stencil_bits, 8u);
  EXPECT_EQ(backends::backend("raster").capabilities.depth_bits, 24u);
  EXPECT_EQ(backends::backend("raster").capabilities.stencil_bits, 8u);
}

TEST(Backends, FoundByName) {
  for (const backends::Backend& entry : backends::BACKENDS) {
    EXPECT_EQ(backends::find_backend(entry.name), &entry);
    EXPECT_EQ(&backends::backend(entry.name), &entry);
  }
  EXPECT_EQ(backends::find_backend("no-such-backend"), nullptr);
  EXPECT_EQ(backends::find_backend(""), nullptr);
}

TEST(Backends, UnknownNameIsAnErrorListingTheKnownOnes) {
  EXPECT_THROW(backends::backend("ARM"), std::invalid_argument);
  const std::string message = what_of([] { backends::backend("no-such-backend"); });
  EXPECT_NE(message.find("'no-such-backend'"), std::string::npos) << message;
  for (const std::string& name : table_names()) EXPECT_NE(message.find(name), std::string::npos) << message;
}

TEST(Backends, NamesAreJoinedInTheTablesOrder) {
  std::string commas, with_or;
  const std::vector<std::string> names = table_names();
  for (size_t i = 0; i < names.size(); ++i) {
    commas += (i ? ", " : "") + names[i];
    with_or += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
  }
  EXPECT_EQ(backends::backend_names(), commas);
  EXPECT_EQ(backends::backend_names(", ", " or "), with_or);
  EXPECT_EQ(backends::backend_names(" | "), [&] {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i) s += (i ? " | " : "") + names[i];
    return s;
  }());
}

TEST(DriverParameters, BackendChoicesAndDescriptionComeFromTheTable) {
  const ParamGroup group = driver_parameters();
  ASSERT_FALSE(group.specs.empty());
  const ParamSpec& spec = group.specs[0];
  EXPECT_EQ(spec.key, "driver.backend");
  EXPECT_EQ(spec.type, ParamType::choice);
  EXPECT_EQ(spec.choices, table_names());
  EXPECT_NE(backends::find_backend(spec.default_value.get<std::string>()), nullptr);
  for (const backends::Backend& entry : backends::BACKENDS) {
    const std::string part = std::string(entry.name) + " (" + entry.description + ")";
    EXPECT_NE(spec.description.find(part), std::string::npos) << spec.description;
  }
}

// ap-pixel's own key: the block size, 1 to 5 (its program has an entry per
// size).
TEST(DriverParameters, ApPixelBlockIsOneToFive) {
  Config config(driver_parameter_groups());
  EXPECT_EQ(config.get_uint("ap.pixel.block"), 1u);
  config.set("ap.pixel.block", 5, "test");
  EXPECT_EQ(config.get_uint("ap.pixel.block"), 5u);
  for (int bad : {0, 6}) {
    try {
      config.set("ap.pixel.block", bad, "test");
      ADD_FAILURE() << "accepted ap.pixel.block=" << bad;
    } catch (const ConfigError& e) {
      EXPECT_NE(std::string(e.what()).find("ap.pixel.block"), std::string::npos) << e.what();
    }
  }
}

namespace {

// The keys the back ends' configuration checks read, with the SoC's
// defaults (the real groups live with SystemC modules, out of a unit test).
ParamGroup screen_parameters() {
  return {"test",
          {
              param::integer("display.width", 320, 16, 2048, "pixels", "display width"),
              param::integer("display.height", 240, 16, 2048, "lines", "display height"),
              param::integer("array.columns", 24, 4, 64, "CUs", "array columns"),
              param::integer("array.rows", 4, 1, 64, "CUs", "array rows"),
          },
          {}};
}

// As soc_sim builds it: the user's settings, then what the chosen back end
// fills in where the user set nothing.
Config configuration(const std::string& backend, const std::vector<std::string>& overrides) {
  Config config({driver_parameters(), screen_parameters()});
  config.set("driver.backend", backend, "test");
  for (const std::string& assignment : overrides) config.apply_override(assignment);
  backends::backend(backend).adjust_configuration(config);
  return config;
}

}  // namespace

// A back end's own keys live under its name, a dash read as a dot
// (ap-tile: ap.tile.*), so that no two back ends (and no block) share one.
TEST(DriverParameters, EachBackEndsKeysAreUnderItsName) {
  for (const backends::Backend& entry : backends::BACKENDS) {
    SCOPED_TRACE(entry.name);
    std::string prefix = entry.name;
    std::replace(prefix.begin(), prefix.end(), '-', '.');
    prefix += '.';
    for (const ParamSpec& spec : entry.parameters().specs) EXPECT_EQ(spec.key.rfind(prefix, 0), 0u) << spec.key;
  }
}

TEST(DriverParameters, GroupsAreTheDriversAndEveryBackEndsWithKeys) {
  const std::vector<ParamGroup> groups = driver_parameter_groups();
  ASSERT_FALSE(groups.empty());
  ASSERT_EQ(groups[0].specs.size(), 2u);
  EXPECT_EQ(groups[0].specs[0].key, "driver.backend");
  // The texture units: 1 to the driver's maximum, 2 (the ES 1.1 minimum) by default.
  EXPECT_EQ(groups[0].specs[1].key, "driver.texture_units");
  EXPECT_EQ(groups[0].specs[1].type, ParamType::integer);
  EXPECT_EQ(groups[0].specs[1].min, 1);
  EXPECT_EQ(groups[0].specs[1].max, gl::MAX_TEXTURE_UNITS);
  EXPECT_EQ(groups[0].specs[1].default_value.get<int64_t>(), 2);
  size_t with_keys = 0;
  for (const backends::Backend& entry : backends::BACKENDS) with_keys += entry.parameters().specs.empty() ? 0 : 1;
  EXPECT_EQ(groups.size(), 1 + with_keys);
  for (const ParamGroup& group : groups) EXPECT_FALSE(group.specs.empty()) << group.owner;
  // No key is declared twice (Config throws std::logic_error if one is).
  EXPECT_NO_THROW(Config(groups).specs());
}

TEST(DriverParameters, ApTileTexcoordsIsAChoiceOfTexturedOrAlways) {
  Config config(driver_parameter_groups());
  EXPECT_EQ(config.get_string("ap.tile.texcoords"), "textured");
  config.apply_override("ap.tile.texcoords=always");
  EXPECT_EQ(config.get_string("ap.tile.texcoords"), "always");
  const std::string message = what_of([&] { config.apply_override("ap.tile.texcoords=sometimes"); });
  for (const char* part : {"ap.tile.texcoords", "sometimes", "textured", "always"})
    EXPECT_NE(message.find(part), std::string::npos) << part << ": " << message;
  EXPECT_EQ(config.get_string("ap.tile.texcoords"), "always");
}

TEST(DriverParameters, EveryBackEndAcceptsTheDefaults) {
  for (const backends::Backend& entry : backends::BACKENDS) {
    SCOPED_TRACE(entry.name);
    EXPECT_NO_THROW(configuration(entry.name, {}).validate());
  }
}

TEST(DriverParameters, UnknownBackEndIsRejectedListingTheKnownOnes) {
  Config config({driver_parameters(), screen_parameters()});
  const std::string message = what_of([&] { config.set("driver.backend", "no-such-backend", "test"); });
  EXPECT_NE(message.find("no-such-backend"), std::string::npos) << message;
  for (const std::string& name : table_names()) EXPECT_NE(message.find(name), std::string::npos) << message;
}

TEST(DriverParameters, TheChosenBackEndChecksTheConfiguration) {
  // ap-tile draws the array's frame (24 x 8 by 4 x 36 pixels): the display's size must be it.
  for (const char* mismatch : {"display.width=256", "display.height=200"}) {
    SCOPED_TRACE(mismatch);
    const Config ap_tile = configuration("ap-tile", {mismatch});
    EXPECT_THROW(ap_tile.validate(), ConfigError);
    const std::string message = what_of([&] { ap_tile.validate(); });
    EXPECT_NE(message.find("impossible combination"), std::string::npos) << message;
    EXPECT_NE(message.find("display.width x display.height"), std::string::npos) << message;
    // The arm and raster back ends draw any size.
    EXPECT_NO_THROW(configuration("arm", {mismatch}).validate());
    EXPECT_NO_THROW(configuration("raster", {mismatch}).validate());
  }
  EXPECT_NO_THROW(configuration("ap-tile", {"display.width=192", "display.height=144"}).validate());
}

namespace {

class StubRenderer : public gl::Renderer {
 public:
  const char* name() const override { return "stub"; }
  gl::RendererCapabilities capabilities() const override { return {16, 8}; }
  unsigned width() const override { return 40; }
  unsigned height() const override { return 30; }
  PixelFormat color_format() const override { return PixelFormat::rgb565; }
  void clear(const gl::ClearRequest&) override {}
  void draw(const gl::RasterState&, const gl::Triangle*, size_t) override {}
  void read_pixels(int, int, int, int, uint8_t*) override {}
  void finish() override {}
  void present() override {}
};

EGLConfig the_config(EGLDisplay display) {
  EGLConfig config = nullptr;
  EGLint count = 0;
  EXPECT_EQ(eglGetConfigs(display, &config, 1, &count), EGL_TRUE);
  EXPECT_EQ(count, 1);
  return config;
}

}  // namespace

TEST(BackendHandover, EglBuildsTheSurfaceWithTheLaunchersFactory) {
  AppEnvironment env;
  std::vector<AppEnvironment*> calls;
  env.make_renderer = [&calls](AppEnvironment& given) {
    calls.push_back(&given);
    return std::make_unique<StubRenderer>();
  };
  gl::set_environment(&env);
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  ASSERT_EQ(eglInitialize(display, nullptr, nullptr), EGL_TRUE);
  EGLSurface surface =
      eglCreateWindowSurface(display, the_config(display), static_cast<EGLNativeWindowType>(0), nullptr);
  ASSERT_NE(surface, EGL_NO_SURFACE);
  ASSERT_EQ(calls.size(), 1u);
  EXPECT_EQ(calls[0], &env);
  EGLint width = 0, height = 0;
  EXPECT_EQ(eglQuerySurface(display, surface, EGL_WIDTH, &width), EGL_TRUE);
  EXPECT_EQ(eglQuerySurface(display, surface, EGL_HEIGHT, &height), EGL_TRUE);
  EXPECT_EQ(width, 40);
  EXPECT_EQ(height, 30);
  EXPECT_EQ(eglDestroySurface(display, surface), EGL_TRUE);
  EXPECT_EQ(eglTerminate(display), EGL_TRUE);
  gl::set_environment(nullptr);
}

TEST(BackendHandover, NoFactoryIsAClearError) {
  AppEnvironment env;
  gl::set_environment(&env);
  EGLDisplay display = eglGetDisplay(EGL_DEFAULT_DISPLAY);
  ASSERT_EQ(eglInitialize(display, nullptr, nullptr), EGL_TRUE);
  const EGLConfig config = the_config(display);
  const std::string message =
      what_of([&] { eglCreateWindowSurface(display, config, static_cast<EGLNativeWindowType>(0), nullptr); });
  EXPECT_NE(message.find("make_renderer"), std::string::npos) << message;
  EXPECT_EQ(eglTerminate(display), EGL_TRUE);
  gl::set_environment(nullptr);
}
