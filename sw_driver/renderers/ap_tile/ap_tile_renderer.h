// The `ap-tile` back end: the study's tile algorithm with the array
// processor as an intelligent frame buffer (README.md). The host sets up
// each triangle (tile_setup.h), bins it to the CUs whose tiles it overlaps,
// and at a flush (clear, finish, read-back, present) writes the triangle
// records through the CIU and runs the array program's stages pass by
// pass; at present it reads the colour (and texture coordinates) back,
// textures on the host and writes the frame out through the display driver.
// When the SoC has the system/array DMA, the records, the constants and the
// read-back go through it instead of the CIU (tile_dma.h, README.md "With
// the DMA").
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "device/app_environment.h"
#include "device/array_driver.h"
#include "device/display_driver.h"
#include "device/dma_driver.h"
#include "forward_texture/array_resampler.h"
#include "gl/renderer.h"
#include "renderers/ap_tile/tile_dma.h"
#include "renderers/ap_tile/tile_host.h"
#include "renderers/ap_tile/tile_reference.h"
#include "renderers/ap_tile/tile_setup.h"
#include "renderers/ap_tile/tile_study.h"
#include "renderers/ap_tile/tile_warp.h"
#include "renderers/backend_entry_points.h"
#include "renderers/common/array_dma.h"
#include "renderers/common/host_time.h"
#include "renderers/common/unsupported_state.h"

namespace tessera::ap_tile {

// The back end's configuration (ap.tile.*, declared in ap_tile_backend.cpp).
struct Settings {
  bool texcoords_always = false;  // the texcoord stage in every pass, textured or not
  bool study_program = false;     // ap_tile_study.s (the study's program) instead of ap_tile.s (tuned)
  bool texture_warp = false;      // planar textured primitives warped on the array (tile_warp.h)
  int texture_warp_width = 1;     // the warp's box filter width F
};

class ApTileRenderer : public gl::Renderer {
 public:
  explicit ApTileRenderer(AppEnvironment& env, Settings settings = {});

  const char* name() const override { return "tessera ap-tile (array processor, one tile per CU)"; }
  gl::RendererCapabilities capabilities() const override { return backends::ap_tile::CAPABILITIES; }
  unsigned width() const override { return m_frame.width(); }
  unsigned height() const override { return m_frame.height(); }
  PixelFormat color_format() const override { return m_display.format(); }
  void clear(const gl::ClearRequest& request) override;
  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) override;
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override;
  void finish() override { flush(); }
  void present() override;

 private:
  // The program's constants into CMEM (at construction, and after a
  // texture warp ran its own program there).
  void send_constants();
  void flush();
  void flush_by_ciu(size_t passes);
  void run_pass(bool depth);
  void run_stage(TileStage stage);
  void write_group(unsigned i, unsigned j, const TileRecord* records);
  void write_study_group(unsigned i, unsigned j, const StudyRecord* records);
  void write_study_constants_by_ciu();
  void send_study_constants_by_dma();
  void read_back();
  // A pixel read back: its colour (RGBA, from the program's colour
  // format), textured on the host when `tid` names a texture of the frame.
  // A pixel whose texture is warped on the array (ap.tile.texture_warp)
  // waits, untextured, until the read-back's end (shade_warped): `index` is
  // its place in m_rgba.
  uint32_t shade_pixel(uint32_t rgba, unsigned tid, int16_t s, int16_t t, size_t index);
  void read_back_by_ciu();
  // The warps of the frame's planar textures on the array, then their
  // waiting pixels textured from the warped images (or by look-ups where a
  // warp is refused).
  void shade_warped();
  void warp_refused(unsigned tid, const std::string& why);
  // With the DMA: the passes' records double-buffered in system memory, the
  // frame read back in chunks on two channels.
  void flush_by_dma(size_t passes);
  bool stage_pass(size_t pass, unsigned buffer);
  void read_back_by_dma();
  void convert_chunk(unsigned x);
  renderers::ArrayTraffic traffic() const;
  void unsupported(const std::string& what);
  void publish_statistics();

  AppEnvironment& m_env;
  Settings m_settings;
  HostApi& m_host;
  DisplayDriver m_display;
  ArrayDriver m_array;
  DmaDriver m_dma;
  CmemLayout m_layout;         // the tuned program's (the DMA's staging follows it)
  StudyLayout m_study_layout;  // the study's program's, when it runs
  // The planes the read-back reads, of the program that runs: colour
  // (RGB565 in hi, lo; or red, green and, in `blue`, blue), texture number
  // and coordinates.
  struct ReadPlanes {
    uint16_t hi = 0, lo = 0, blue = 0, tid = 0, s_hi = 0, s_lo = 0, t_hi = 0, t_lo = 0;
  };
  ReadPlanes m_read;
  unsigned m_cmem_bytes = 0;  // CMEM bytes per CU the program declares
  FrameGeometry m_frame;
  unsigned m_entry[6]{};
  unsigned m_program_base = 0;

  TileBins m_bins;                // drawn since the last flush
  std::vector<bool> m_live;       // per CU: the live byte last written
  TextureTable m_textures;        // since the last colour clear
  bool m_frame_textured = false;  // some pixel may carry a texture number
  std::vector<uint32_t> m_rgba;   // the frame read back, row 0 at the top
  renderers::UnsupportedState m_unsupported{"ap-tile"};
  std::vector<uint8_t> m_record_bytes;  // four CUs' records, packed into words (with the DMA: every CU's)

  std::unique_ptr<TileDma> m_tile_dma;  // null: the CIU carries everything
  std::vector<bool> m_has_record;       // per CU: a record in the pass being staged
  std::vector<uint8_t> m_rows;          // a chunk row of every read-back plane, copied from the staging

  renderers::HostTime m_time;
  renderers::FrameFigures m_frame_figures;
  uint64_t m_frame_busiest = 0;  // the most passes one flush of this frame needed
  uint64_t m_passes = 0, m_cu_triangles = 0, m_busiest = 0;
  uint64_t m_stage_cycles[6]{}, m_words_written = 0, m_words_read = 0, m_triangles_drawn = 0;
  renderers::ArrayTraffic m_ciu_traffic;  // the CIU's share (the DMA's: m_tile_dma)

  // ap.tile.texture_warp=array (tile_warp.h): the frame's texture planes,
  // the pixels waiting for their warp, the resampler and its figures.
  struct WarpPixel {
    uint32_t index;
    uint8_t tid;
    int16_t s, t;
  };
  WarpPlan m_warp_plan;
  std::vector<WarpPixel> m_warp_pending;
  std::unique_ptr<forward_texture::ArrayResampler> m_resampler;
  bool m_tiles_overwritten = false;  // a warp ran since the last colour clear
  uint64_t m_warps = 0, m_warp_refusals = 0, m_warp_pixels = 0, m_warp_lines = 0, m_warp_borders = 0;
};

}  // namespace tessera::ap_tile
