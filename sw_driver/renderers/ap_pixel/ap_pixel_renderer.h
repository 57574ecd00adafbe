// The `ap-pixel` back end: the study's pixel algorithm with the array
// processor as a 96-wide ALU (README.md). The host scan-converts each
// triangle and depth-tests it against the depth buffer in system memory,
// writes the triangle's 21 values into every CU, and then, batch by batch,
// gives each CU the position of one k x k block of visible pixels, runs the
// program, reads the attributes back, textures, and writes the pixels into
// the frame buffer in system memory. Clears, read-back and the buffers'
// formats are the arm back end's (its rasterizer does them).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/app_environment.h"
#include "device/array_driver.h"
#include "device/display_driver.h"
#include "device/dma_driver.h"
#include "gl/renderer.h"
#include "renderers/ap_pixel/pixel_setup.h"
#include "renderers/arm/arm_rasterizer.h"
#include "renderers/arm/arm_renderer.h"
#include "renderers/backend_entry_points.h"
#include "renderers/common/array_dma.h"
#include "renderers/common/host_time.h"
#include "renderers/common/texture_units.h"
#include "renderers/common/unsupported_state.h"

namespace tessera::ap_pixel {

class ApPixelRenderer : public gl::Renderer {
 public:
  // block: the side of the block each CU shades (ap.pixel.block), 1 to 5;
  // program: the array program (ap.pixel.program).
  ApPixelRenderer(AppEnvironment& env, unsigned block, ProgramVariant program = ProgramVariant::tuned);

  const char* name() const override { return "tessera ap-pixel (array processor as a 96-wide ALU)"; }
  gl::RendererCapabilities capabilities() const override { return backends::ap_pixel::CAPABILITIES; }
  unsigned width() const override { return m_frame.buffers.width; }
  unsigned height() const override { return m_frame.buffers.height; }
  PixelFormat color_format() const override { return m_frame.buffers.color_format; }
  void clear(const gl::ClearRequest& request) override;
  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) override;
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override;
  void finish() override {}
  void present() override;

  unsigned block() const { return m_block; }
  ProgramVariant program() const { return m_layout.variant; }

 private:
  // A pixel the host found visible: its place, depth, and where its block
  // went in the batch.
  struct Pixel {
    int x = 0, y = 0;
    uint16_t z = 0;
    uint32_t block = 0;  // index into m_blocks
  };
  struct Block {
    int x = 0, y = 0;  // its bottom-left pixel
  };
  // What the host needs back per pixel (README.md, "What the host reads").
  struct Reads {
    bool colour = false, alpha = false, texcoords = false;
    bool any() const { return colour || texcoords; }
  };
  // An attribute read back and how many of its bytes (high first).
  struct Needed {
    Attribute attribute;
    unsigned bytes;
  };
  // A batch whose results the DMA brings out of CMEM: its blocks, the
  // staging buffer, and per slot v * k + u its first row there (-1: none).
  struct DmaBatch {
    size_t first_block = 0, blocks = 0;
    unsigned buffer = 0;
    std::vector<int32_t> slot_row;
  };

  void draw_triangle(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads);
  void run_batch(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads, size_t first_block,
                 size_t blocks, int ox, int oy);
  void draw_batches_dma(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads,
                        const TriangleValues& values, int ox, int oy);
  void collect_dma_batch(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads,
                         const DmaBatch& batch);
  unsigned needed_reads(const Reads& reads, Needed needed[6]) const;
  int32_t result_value(const gl::RasterState& state, Attribute attribute, uint32_t code) const;
  void write_shaded(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads, const Pixel& pixel,
                    const std::array<int32_t, ATTRIBUTES>& values);
  void write_pixel(const gl::RasterState& state, const Pixel& pixel, uint32_t rgba, const int st[2], bool textured);
  void unsupported(const std::string& what);
  void publish_statistics();

  AppEnvironment& m_env;
  HostApi& m_host;
  arm::HostFrame m_frame;  // its core clears and reads back
  ArrayDriver m_array;
  DmaDriver m_dma;
  renderers::DmaUse m_dma_use;
  PixelLayout m_layout;
  unsigned m_block = 1;
  unsigned m_program_base = 0;

  // The triangle being drawn: its visible pixels in scan order, its blocks
  // in first-seen order, and per block of the frame its index (or -1).
  std::vector<Pixel> m_pixels;
  std::vector<Block> m_blocks;
  std::vector<int32_t> m_block_index;
  std::vector<uint16_t> m_depth_row;                  // the depth buffer's values under the current span
  std::vector<std::vector<uint32_t>> m_block_pixels;  // per block in the batch: its pixels
  // Per pixel of a batch, the attribute values read back (16.8).
  std::vector<std::array<int32_t, ATTRIBUTES>> m_results;
  renderers::UnsupportedState m_unsupported{"ap-pixel"};
  // The one texture unit the current draw textures with (texture_units.h).
  renderers::SingleTextureUnit m_unit;

  // With the DMA: the CMEM ranges of the 21 values (with the gradients'
  // sign bytes, which the program overwrites), the staging buffers in
  // system memory, the chains, and the channel of the results.
  struct Range {
    unsigned cmem = 0, bytes = 0;
  };
  std::vector<Range> m_value_ranges;
  unsigned m_value_bytes = 0;
  uint32_t m_stage_values = 0, m_stage_offsets[2] = {0, 0}, m_stage_results[2] = {0, 0};
  uint32_t m_chain_in = 0, m_chain_out = 0;
  unsigned m_out_channel = 0;
  renderers::ArrayTraffic m_traffic;

  renderers::HostTime m_time;
  renderers::FrameFigures m_frame_figures;
  uint64_t m_host_shaded = 0;
  uint64_t m_triangles = 0, m_batches = 0, m_visible = 0, m_blocks_sent = 0, m_cycles = 0;
  uint64_t m_words_written = 0, m_words_read = 0;
};

}  // namespace tessera::ap_pixel
