// A diagnostic application without the GL driver: the host draws a moving test
// pattern -- eight colour bars, a grey ramp and a white square that moves
// with the frame number -- into the back buffer over the bus, and presents it.
#include <vector>

#include "apps/apps.h"
#include "costs/host_cost.h"
#include "device/display_driver.h"

namespace tessera {

namespace {

struct Rgb {
  unsigned r, g, b;
};

Rgb pattern_pixel(unsigned x, unsigned y, unsigned width, unsigned height, unsigned frame) {
  static const Rgb bars[8] = {{255, 255, 255}, {255, 255, 0}, {0, 255, 255}, {0, 255, 0},
                              {255, 0, 255},   {255, 0, 0},   {0, 0, 255},   {0, 0, 0}};
  const unsigned square = height / 4;
  const unsigned square_x = (frame * 16) % (width - square);
  const unsigned square_y = height / 2 - square / 2;
  if (x >= square_x && x < square_x + square && y >= square_y && y < square_y + square) return {255, 255, 255};
  if (y < height * 3 / 4) return bars[x * 8 / width];
  const unsigned grey = x * 255 / (width - 1);
  return {grey, grey, grey};
}

}  // namespace

int pattern_app(AppEnvironment& env) {
  HostApi& host = *env.host;
  DisplayDriver display(env);
  const unsigned width = display.width();
  const unsigned height = display.height();
  std::vector<uint32_t> row((width * display.bytes_per_pixel() + 3) / 4);
  for (unsigned frame = 0; frame < env.frames; ++frame) {
    const uint32_t buffer = display.back_buffer();
    for (unsigned y = 0; y < height; ++y) {
      uint8_t* bytes = reinterpret_cast<uint8_t*>(row.data());
      for (unsigned x = 0; x < width; ++x) {
        const Rgb c = pattern_pixel(x, y, width, height, frame);
        const uint32_t rgba = c.r | c.g << 8 | c.b << 16 | 0xffu << 24;
        store_pixel(display.format(), bytes + x * display.bytes_per_pixel(), pack_pixel(display.format(), rgba));
      }
      costs::charge(host, costs::HostCost::pattern_pixel, width);
      const uint32_t line = buffer + y * display.stride();
      const unsigned words = static_cast<unsigned>(row.size());
      for (unsigned w = 0; w < words; w += 8) host.write_words(line + 4 * w, &row[w], std::min(8u, words - w));
    }
    display.present();
  }
  return 0;
}

}  // namespace tessera
