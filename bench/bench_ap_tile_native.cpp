// bench_ap_tile_native: runs a built-in scene through tessera's GL ES driver
// with the ap-tile ALGORITHM run natively, on a NativeHost (no SystemC,
// nothing charged), and prints the wall time per frame as one line of JSON.
// bench_ap_tile runs it as a child process; it may be run by hand:
//
//   bench_ap_tile_native --scene teapot --frames 20 [--columns 24 --rows 4
//                        --format rgb565 --dma false --mem-mib 16]
//                        [--idle-cus skip] [--png-frame K --png FILE] [-- scene args]
//   bench_ap_tile_native --list
//
// The renderer is the ap-tile back end with the array replaced by its
// functional code: the same host side (the GL state's record flags, the
// texture numbers, TriangleSetup, the tiles, the per-CU queues run in
// passes, the records; tessera_ap_tile_core), and for each pass, instead of
// CIU writes and the array program's stages, the record encoded straight
// into the CU's CMEM image in memory and tile_reference's stages run on it;
// at present the colour (and texture coordinates) read from the images, the
// texturing of renderers/common/texturing.h, and the frame written out
// through DisplayDriver, as ApTileRenderer does. The array runs every stage
// on every CU, so by default so does this (--idle-cus skip: only the CUs
// with a triangle in the pass; the picture is the same).
//
// The scene draws 2N frames; the time reported is that of frames N..2N-1
// (from the N-th present to the 2N-th, divided by N), the frames bench_ap_tile
// times on soc_sim.

#include <cstdio>
#include <cstring>
#include <exception>
#include <iostream>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "ap_programs/ap_tile.h"
#include "device/display_driver.h"
#include "frame_writer.h"
#include "guarded_main.h"
#include "host/native_host.h"
#include "native_scene.h"
#include "renderers/ap_tile/tile_host.h"
#include "renderers/ap_tile/tile_reference.h"
#include "renderers/ap_tile/tile_setup.h"
#include "renderers/backends.h"
#include "scenes/scene.h"

namespace {

using namespace tessera;
using namespace tessera::ap_tile;

struct NativeOptions {
  unsigned columns = 24, rows = 4, cmem_bytes = 4096;
  bool skip_idle = false;
  unsigned png_frame = 0;  // the frame --png writes (0-based)
  std::string png;
};

// The depth a clear stores (ApTileRenderer, tile_setup.cpp: z24 * 65535 /
// 65536 / 256, rounded).
uint16_t clear_depth16(uint32_t z24) {
  return static_cast<uint16_t>((uint64_t{z24} * 65535 + 65536 * 128) / (65536 * 256));
}

class NativeApTileRenderer : public gl::Renderer {
 public:
  NativeApTileRenderer(AppEnvironment& env, const NativeOptions& options)
      : m_host(*env.host),
        m_display(env),
        m_layout(CmemLayout::of(ap::programs::ap_tile())),
        m_options(options),
        m_bins(options.columns * options.rows) {
    m_frame.columns = options.columns;
    m_frame.rows = options.rows;
    m_frame.tile_width = m_layout.tile_width;
    m_frame.tile_height = m_layout.tile_height;
    if (m_display.width() != m_frame.width() || m_display.height() != m_frame.height())
      throw std::invalid_argument("bench_ap_tile_native: the array's frame is " + std::to_string(m_frame.width()) +
                                  " x " + std::to_string(m_frame.height()) + ", the display " +
                                  std::to_string(m_display.width()) + " x " + std::to_string(m_display.height()));
    m_cmem.assign(size_t{m_frame.cus()} * options.cmem_bytes, 0);
    for (unsigned cu = 0; cu < m_frame.cus(); ++cu) {
      uint8_t* cmem = cmem_of(cu);
      for (unsigned l = 0; l < m_frame.tile_height; ++l)
        cmem[m_layout.yc + l] = static_cast<uint8_t>(m_frame.tile_height - 1 - l);
    }
    m_rgba.assign(size_t{m_frame.width()} * m_frame.height(), 0xff000000u);
  }

  const char* name() const override { return "ap-tile's functional code, natively (bench_ap_tile_native)"; }
  gl::RendererCapabilities capabilities() const override { return backends::ap_tile::CAPABILITIES; }
  unsigned width() const override { return m_frame.width(); }
  unsigned height() const override { return m_frame.height(); }
  PixelFormat color_format() const override { return m_display.format(); }

  void clear(const gl::ClearRequest& request) override {
    flush();
    switch (scissor_cover(request.scissor_test, request.scissor_x, request.scissor_y, request.scissor_width,
                          request.scissor_height, m_frame.width(), m_frame.height())) {
      case ScissorCover::none: return;
      case ScissorCover::part: unsupported("scissored clears: the whole frame is cleared"); break;
      case ScissorCover::whole: break;
    }
    if (request.color && (!request.color_mask[0] || !request.color_mask[1] || !request.color_mask[2]))
      unsupported("masked colour clears: every channel is cleared");
    if (request.color) {
      const uint32_t rgba = uint32_t{request.rgba[0]} | uint32_t{request.rgba[1]} << 8 |
                            uint32_t{request.rgba[2]} << 16 | uint32_t{request.rgba[3]} << 24;
      const auto packed = static_cast<uint16_t>(pack_pixel(PixelFormat::rgb565, rgba));
      for (unsigned cu = 0; cu < m_frame.cus(); ++cu) {
        uint8_t* cmem = cmem_of(cu);
        cmem[m_layout.clear_c] = static_cast<uint8_t>(packed >> 8);
        cmem[m_layout.clear_c + 1] = static_cast<uint8_t>(packed);
        run_reference(TileStage::clear_colour, m_layout, cmem);
      }
      m_textures.clear();
      m_frame_textured = false;
    }
    if (request.depth && request.depth_write) {
      const uint16_t z = clear_depth16(request.depth_value);
      for (unsigned cu = 0; cu < m_frame.cus(); ++cu) {
        uint8_t* cmem = cmem_of(cu);
        cmem[m_layout.clear_z] = static_cast<uint8_t>(z >> 8);
        cmem[m_layout.clear_z + 1] = static_cast<uint8_t>(z);
        run_reference(TileStage::clear_depth, m_layout, cmem);
      }
    }
  }

  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) override {
    const std::optional<DrawFlags> flags = draw_flags(state, m_frame.width(), m_frame.height(), m_textures,
                                                      [this](const std::string& what) { unsupported(what); });
    if (!flags) return;
    if (flags->tex != 0) m_frame_textured = true;
    for (size_t t = 0; t < count; ++t) {
      TriangleSetup setup(triangles[t], *flags, m_frame);
      if (!setup.valid()) continue;
      const std::vector<unsigned> tiles = setup.tiles();
      if (!tiles.empty()) m_bins.add(setup, tiles);
    }
  }

  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override {
    read_back();
    read_frame_pixels(m_rgba, m_frame.width(), m_frame.height(), m_display.format(), x, y, width, height, rgba);
  }

  void finish() override { flush(); }

  void present() override {
    read_back();
    const PixelFormat format = m_display.format();
    const unsigned bytes = bytes_per_pixel(format), width = m_frame.width();
    for (unsigned row = 0; row < m_frame.height(); ++row) {
      uint8_t* out = m_host.store_span(m_display.back_buffer() + row * m_display.stride(), bytes, width);
      for (unsigned column = 0; column < width; ++column)
        store_pixel(format, out + column * bytes, pack_pixel(format, m_rgba[size_t{row} * width + column]));
    }
    if (!m_options.png.empty() && m_presented == m_options.png_frame) write_frame();
    m_display.present();
    ++m_presented;
    m_unsupported.clear();
  }

 private:
  uint8_t* cmem_of(unsigned cu) { return m_cmem.data() + size_t{cu} * m_options.cmem_bytes; }

  void unsupported(const std::string& what) {
    if (m_unsupported.insert(what).second)
      std::cerr << "warning: ap-tile does not support " << what << " (reported once per frame)\n";
  }

  // The passes: every CU gets its pass-th triangle's record (or goes idle),
  // then runs the stages the pass needs, as ApTileRenderer::flush has the
  // array do.
  void flush() {
    const size_t passes = m_bins.passes();
    for (size_t pass = 0; pass < passes; ++pass) {
      bool depth = false;
      m_live.assign(m_frame.cus(), false);
      for (unsigned r = 0; r < m_frame.rows; ++r)
        for (unsigned c = 0; c < m_frame.columns; ++c) {
          const unsigned cu = r * m_frame.columns + c;
          uint8_t* cmem = cmem_of(cu);
          const TriangleSetup* setup = m_bins.at(cu, pass);
          if (setup == nullptr) {
            cmem[m_layout.live] = 0;
            continue;
          }
          const TileRecord record = setup->record(c, r);
          encode_record(record, m_layout, cmem + m_layout.record_first);
          depth = depth || !record.zoff;
          m_live[cu] = true;
        }
      for (unsigned cu = 0; cu < m_frame.cus(); ++cu) {
        if (m_options.skip_idle && !m_live[cu]) continue;
        uint8_t* cmem = cmem_of(cu);
        run_reference(TileStage::fill, m_layout, cmem);
        if (depth) run_reference(TileStage::depth, m_layout, cmem);
        run_reference(TileStage::colour, m_layout, cmem);
        if (m_frame_textured) run_reference(TileStage::texcoord, m_layout, cmem);
      }
    }
    m_bins.clear();
  }

  // The colour of every pixel from the CMEM images, textured where the
  // pixel carries a texture number, into m_rgba (row 0 at the top).
  void read_back() {
    flush();
    const unsigned width = m_frame.width();
    for (unsigned r = 0; r < m_frame.rows; ++r)
      for (unsigned c = 0; c < m_frame.columns; ++c) {
        const uint8_t* cmem = cmem_of(r * m_frame.columns + c);
        for (unsigned x = 0; x < m_frame.tile_width; ++x)
          for (unsigned l = 0; l < m_frame.tile_height; ++l) {
            const uint32_t packed =
                uint32_t{cmem[m_layout.pixel(m_layout.chi, x, l)]} << 8 | cmem[m_layout.pixel(m_layout.clo, x, l)];
            uint32_t rgba = unpack_pixel(PixelFormat::rgb565, packed);
            if (m_frame_textured)
              if (const TextureEntry* entry = m_textures.find(cmem[m_layout.pixel(m_layout.tid, x, l)])) {
                auto value16 = [&](uint16_t hi, uint16_t lo) {
                  return static_cast<int16_t>(cmem[m_layout.pixel(hi, x, l)] << 8 | cmem[m_layout.pixel(lo, x, l)]);
                };
                rgba = texture_pixel(*entry, rgba, value16(m_layout.shi, m_layout.slo),
                                     value16(m_layout.thi, m_layout.tlo),
                                     [this](uint32_t address) { return m_host.load_span(address, 4, 1); });
              }
            m_rgba[size_t{r * m_frame.tile_height + l} * width + c * m_frame.tile_width + x] = rgba;
          }
      }
  }

  // The back buffer as the display shows it, as PNG (the manual check
  // against soc_sim's frames; README.md).
  void write_frame() {
    const PixelFormat format = m_display.format();
    const unsigned bytes = bytes_per_pixel(format), width = m_frame.width(), height = m_frame.height();
    std::vector<uint8_t> rgba(size_t{width} * height * 4);
    for (unsigned row = 0; row < height; ++row) {
      const uint8_t* in = m_host.load_span(m_display.back_buffer() + row * m_display.stride(), bytes, width);
      for (unsigned column = 0; column < width; ++column) {
        const uint32_t value = unpack_pixel(format, load_pixel(format, in + column * bytes));
        std::memcpy(&rgba[(size_t{row} * width + column) * 4], &value, 4);
      }
    }
    write_png(m_options.png, width, height, rgba);
  }

  HostApi& m_host;
  DisplayDriver m_display;
  CmemLayout m_layout;
  NativeOptions m_options;
  FrameGeometry m_frame;
  TileBins m_bins;
  std::vector<uint8_t> m_cmem;  // the CUs' CMEM images, CU r * columns + c at (r * columns + c) * cmem_bytes
  std::vector<bool> m_live;     // per CU: a triangle in the current pass
  TextureTable m_textures;
  bool m_frame_textured = false;
  std::vector<uint32_t> m_rgba;
  std::set<std::string> m_unsupported;
  unsigned m_presented = 0;
};

// The boot loader's layout on the SoC (as bench_arm_native): the two frame
// buffers, page-aligned, at the top of memory, and the driver's heap from
// 4 MiB up to them.
int run(int argc, char** argv) {
  std::string scene_name;
  unsigned frames = 10;
  NativeOptions options;
  std::string format = "rgb565", idle_cus = "run";
  unsigned memory_mib = 16;
  bench::NativeDisplay display;
  bool list = false;
  std::vector<std::string> scene_args;
  CLI::App cli{"bench_ap_tile_native: a built-in scene on the ap-tile algorithm's functional code, natively, timed"};
  cli.add_option("--scene", scene_name, "built-in scene");
  cli.add_option("--frames", frames, "N: 2N frames are drawn, frames N..2N-1 are timed")
      ->check(CLI::Range(1, 50000))
      ->capture_default_str();
  cli.add_option("--columns", options.columns, "array.columns")->check(CLI::Range(4, 1024))->capture_default_str();
  cli.add_option("--rows", options.rows, "array.rows")->check(CLI::Range(1, 1024))->capture_default_str();
  cli.add_option("--cmem-bytes", options.cmem_bytes, "array.cmem_bytes")
      ->check(CLI::Range(1024, 65536))
      ->capture_default_str();
  cli.add_option("--format", format, "display.format")
      ->check([](const std::string& name) {
        return pixel_format_from_name(name) ? "" : "expects one of " + pixel_format_names();
      })
      ->capture_default_str();
  cli.add_option("--dma", display.dma, "display.dma")->capture_default_str();
  cli.add_option("--mem-mib", memory_mib, "mem.size_mib")->check(CLI::Range(1, 256))->capture_default_str();
  cli.add_option("--idle-cus", idle_cus, "run: every CU runs every stage, as on the array; skip: only CUs with work")
      ->check(CLI::IsMember({"run", "skip"}))
      ->capture_default_str();
  cli.add_option("--png", options.png, "write frame --png-frame, as the display shows it, to this PNG file");
  cli.add_option("--png-frame", options.png_frame, "the frame --png writes (0-based)")->capture_default_str();
  cli.add_flag("--list", list, "print the built-in scenes' names and exit");
  cli.add_option("scene_args", scene_args, "arguments passed to the scene (after --)");
  CLI11_PARSE(cli, argc, argv);

  if (list) {
    for (const auto& scene : scenes::all_scenes()) std::printf("%s\n", scene.name);
    return 0;
  }
  const scenes::Scene* scene = scenes::find_scene(scene_name);
  if (!scene) {
    std::cerr << "bench_ap_tile_native: no built-in scene '" << scene_name << "' (see --list)\n";
    return 2;
  }
  if (options.columns % 4 != 0) {
    std::cerr << "bench_ap_tile_native: --columns must be a multiple of 4\n";
    return 2;
  }
  options.skip_idle = idle_cus == "skip";
  const CmemLayout layout = CmemLayout::of(ap::programs::ap_tile());
  display.width = options.columns * layout.tile_width;
  display.height = options.rows * layout.tile_height;
  display.format = *pixel_format_from_name(format);

  bench::NativeHost host(memory_mib << 20, display);
  AppEnvironment env;
  env.host = &host;
  env.frames = 2 * frames;
  env.memory_bytes = memory_mib << 20;
  env.args = scene_args;
  backends::hand_over(backends::backend("ap-tile"), env);
  env.make_renderer = [&options](AppEnvironment& e) -> std::unique_ptr<gl::Renderer> {
    return std::make_unique<NativeApTileRenderer>(e, options);
  };
  bench::lay_out_memory(env, display);

  return bench::run_timed_scene("bench_ap_tile_native", env, host, *scene, scene_name, frames,
                                nlohmann::json::object({{"idle_cus", idle_cus}}));
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::guarded_main("bench_ap_tile_native", [&] { return run(argc, argv); });
}
