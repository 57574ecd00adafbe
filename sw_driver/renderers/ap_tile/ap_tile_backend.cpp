// The ap-tile back end's entry points for the registry (backends.def).
#include <string>

#include "ap_programs/ap_tile.h"
#include "common/screen_size.h"
#include "renderers/ap_tile/ap_tile_renderer.h"
#include "renderers/backend_entry_points.h"

namespace tessera::backends::ap_tile {

namespace {

// The frame the array holds: one tile of the program's TILE_W x TILE_H
// pixels per CU.
unsigned frame_width_per_column() {
  return static_cast<unsigned>(ap::programs::ap_tile().constants.at("TILE_W"));
}
unsigned frame_height_per_row() {
  return static_cast<unsigned>(ap::programs::ap_tile().constants.at("TILE_H"));
}
unsigned frame_width(const Config& config) {
  return static_cast<unsigned>(config.get_uint("array.columns")) * frame_width_per_column();
}
unsigned frame_height(const Config& config) {
  return static_cast<unsigned>(config.get_uint("array.rows")) * frame_height_per_row();
}

}  // namespace

// The back end's keys, with their defaults: the one place they are declared.
ParamGroup parameters() {
  return {"ap-tile",
          {
              param::choice("ap.tile.texcoords", "textured", {"textured", "always"},
                            "when ap-tile runs its texcoord stage: textured (in the passes after a textured triangle "
                            "since the last colour clear) or always (in every pass, as the study measured it: "
                            "texture coordinates computed even where no texture is applied)"),
              param::choice("ap.tile.program", "tuned", {"tuned", "study"},
                            "ap-tile's array program: tuned (ap_tile.s: values in registers across a row, RGB565) "
                            "or study (ap_tile_study.s: the study's program as its compiler wrote it, every variable "
                            "in CMEM, 24-bit colour)"),
              param::choice("ap.tile.texture_warp", "off", {"off", "array"},
                            "how ap-tile textures a planar textured primitive: off (the host looks its texels up at "
                            "the s and t the array interpolated) or array (the array maps the texture onto the frame "
                            "by two-pass forward texture mapping, resample_lines.s, and the host reads the warped "
                            "image; other textured primitives keep the look-ups)"),
              param::integer("ap.tile.texture_warp_width", 1, 1, 8, "pixels",
                             "with ap.tile.texture_warp=array: the width F of the warp's box prefilter"),
          },
          {}};
}

std::unique_ptr<gl::Renderer> make_renderer(AppEnvironment& env) {
  const Config defaults({parameters()});
  const Config& config = env.config != nullptr ? *env.config : defaults;
  tessera::ap_tile::Settings settings;
  settings.texcoords_always = config.get_string("ap.tile.texcoords") == "always";
  settings.study_program = config.get_string("ap.tile.program") == "study";
  settings.texture_warp = config.get_string("ap.tile.texture_warp") == "array";
  settings.texture_warp_width = static_cast<int>(config.get_uint("ap.tile.texture_warp_width"));
  return std::make_unique<tessera::ap_tile::ApTileRenderer>(env, settings);
}

// The display shows the array's frame (192 x 144 for the 24 x 4 array)
// unless the user chose its size. A frame larger than the largest screen
// (array.rows 15 and 16: 540 and 576 lines) is refused here, naming the
// array's keys, before it reaches display.height's range.
void adjust_configuration(Config& config) {
  if (frame_width(config) > MAX_SCREEN_SIZE || frame_height(config) > MAX_SCREEN_SIZE)
    throw ConfigError("configuration: impossible combination: driver.backend=ap-tile draws the array's frame of " +
                      std::to_string(frame_width(config)) + " x " + std::to_string(frame_height(config)) +
                      " pixels (array.columns x array.rows tiles of 8 x 36), larger than the largest screen, " +
                      std::to_string(MAX_SCREEN_SIZE) + " x " + std::to_string(MAX_SCREEN_SIZE) +
                      " (screen x and y are 9.4 fixed point); use at most array.rows=" +
                      std::to_string(MAX_SCREEN_SIZE / frame_height_per_row()) +
                      " and array.columns=" + std::to_string(MAX_SCREEN_SIZE / frame_width_per_column()));
  if (!config.is_set("display.width")) config.set("display.width", frame_width(config), "driver.backend=ap-tile");
  if (!config.is_set("display.height")) config.set("display.height", frame_height(config), "driver.backend=ap-tile");
}

// The array holds exactly its tiles: the display must show that frame.
// With the DMA, the read-back keeps two chunks in flight, one per channel
// (tile_dma.h): one channel is refused here rather than failing at the
// first frame with a bus error on the missing channel's registers.
void check_configuration(const Config& config) {
  if (config.has("dma.enabled") && config.get_bool("dma.enabled") && config.get_uint("dma.channels") < 2)
    throw ConfigError(
        "configuration: impossible combination: driver.backend=ap-tile with dma.enabled=true reads "
        "the frame back on two DMA channels at once, but dma.channels=" +
        std::to_string(config.get_uint("dma.channels")) + "; set dma.channels=2 or more");
  if (config.get_uint("display.width") != frame_width(config) ||
      config.get_uint("display.height") != frame_height(config))
    throw ConfigError("configuration: impossible combination: driver.backend=ap-tile draws the array's frame of " +
                      std::to_string(frame_width(config)) + " x " + std::to_string(frame_height(config)) +
                      " pixels (array.columns x array.rows tiles of 8 x 36), but display.width x display.height = " +
                      std::to_string(config.get_uint("display.width")) + " x " +
                      std::to_string(config.get_uint("display.height")) +
                      "; leave the display's size unset or change the array's grid");
}

}  // namespace tessera::backends::ap_tile
