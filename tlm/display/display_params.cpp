// The display's parameters: display.*.
#include <string>
#include <vector>

#include "common/screen_size.h"
#include "display/display_controller.h"

namespace tessera {

namespace {

std::vector<std::string> pixel_format_name_list() {
  std::vector<std::string> names;
  for (const PixelFormatInfo& info : PIXEL_FORMATS) names.emplace_back(info.name);
  return names;
}

}  // namespace

ParamGroup DisplayParams::parameters() {
  using param::integer;
  return {"display",
          {
              integer("display.width", 320, 16, MAX_SCREEN_SIZE, "pixels",
                      "visible pixels per line (at most 512: screen x is 9.4 fixed point)"),
              integer("display.height", 240, 16, MAX_SCREEN_SIZE, "lines",
                      "visible lines (at most 512: screen y is 9.4 fixed point)"),
              param::choice("display.format", "rgb565", pixel_format_name_list(), "frame-buffer pixel format"),
              param::boolean("display.dma", false,
                             "true: a display DMA scans the front buffer out over the bus; false: the host copies "
                             "each frame to the display port"),
              param::real("display.refresh_hz", 60.0, 1, 240, "Hz", "refresh rate of the display DMA"),
              integer("display.vblank_lines", 20, 1, 1000, "lines", "vertical blanking interval, in line times"),
              integer("display.port_cycles", 248, 0, 100000, "bus cycles",
                      "time the display port takes to accept one 32-bit word: the data phase of a port write, "
                      "at least the bus's one cycle per beat (host copy mode; calibrated, see docs/calibration.md)"),
          },
          {}};
}

DisplayParams DisplayParams::from_config(const Config& config) {
  DisplayParams p;
  p.width = static_cast<unsigned>(config.get_uint("display.width"));
  p.height = static_cast<unsigned>(config.get_uint("display.height"));
  p.format = *pixel_format_from_name(config.get_string("display.format"));
  p.dma = config.get_bool("display.dma");
  p.refresh_hz = config.get_real("display.refresh_hz");
  p.vblank_lines = static_cast<unsigned>(config.get_uint("display.vblank_lines"));
  p.port_cycles = static_cast<unsigned>(config.get_uint("display.port_cycles"));
  return p;
}

DisplayParams DisplayParams::defaults() {
  return from_config(Config({parameters()}));
}

}  // namespace tessera
