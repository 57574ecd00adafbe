// The `ap-object` back end: object-parallel rasterization on the array as on
// MorphoSys (README.md). The host sets each triangle up and splits it at its
// middle vertex; batch by batch, each CU gets one half (ap.object.unit=half)
// or one whole triangle (=triangle) as pieces that fit its slots, walks the
// rows and spans and emits every covered pixel's depth and colour into CMEM;
// the host reads them back through the CIU, textures them, z-tests them
// against its depth buffer and writes the frame buffer in system memory. Clears, read-back and
// the buffers' formats are the arm back end's (its rasterizer does them).
// With ap.object.zpath=unit the CUs send their pixels to the z-buffer unit
// instead; a frame is kept until it is shown or read, then drawn on the
// unit and its colour copied into the back buffer, or drawn on the host
// path when a clear or draw call needs what the unit does not do (README.md,
// "The z path through the unit").
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <vector>

#include "device/app_environment.h"
#include "device/array_driver.h"
#include "device/display_driver.h"
#include "device/dma_driver.h"
#include "gl/renderer.h"
#include "renderers/ap_object/object_setup.h"
#include "renderers/arm/arm_rasterizer.h"
#include "renderers/arm/arm_renderer.h"
#include "renderers/backend_entry_points.h"
#include "renderers/common/array_dma.h"
#include "renderers/common/host_time.h"
#include "renderers/common/texture_units.h"
#include "renderers/common/unsupported_state.h"

namespace tessera::ap_object {

class ApObjectRenderer : public gl::Renderer {
 public:
  ApObjectRenderer(AppEnvironment& env, Unit unit, ZPath zpath = ZPath::host);

  const char* name() const override { return "tessera ap-object (array processor, a triangle or half per CU)"; }
  gl::RendererCapabilities capabilities() const override { return backends::ap_object::CAPABILITIES; }
  unsigned width() const override { return m_frame.buffers.width; }
  unsigned height() const override { return m_frame.buffers.height; }
  PixelFormat color_format() const override { return m_frame.buffers.color_format; }
  void clear(const gl::ClearRequest& request) override;
  void draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) override;
  void read_pixels(int x, int y, int width, int height, uint8_t* rgba) override;
  void finish() override {}
  void present() override;

  Unit unit() const { return m_unit; }
  ZPath zpath() const { return m_zpath; }

 private:
  // A piece of a half: its rows [row, row + rows) and the walk's offset
  // from each row's left end (a multiple of the span class's W).
  struct Piece {
    uint32_t triangle = 0;  // index into m_triangles
    unsigned half = 0;
    int row = 0;
    unsigned rows = 0;  // 0: no piece
    int offset = 0;
  };
  // What one CU walks in one run: a piece per record.
  struct Job {
    std::array<Piece, 2> pieces{};
  };
  struct Fragment {
    int x, y;
    uint16_t z;
    uint32_t rgba;
    int32_t st[2];  // texels, 16.8
  };

  // A clear or a draw call of the frame being kept for the unit.
  struct FrameOp {
    bool clear = false;
    gl::ClearRequest request;
    gl::RasterState state;
    std::vector<gl::Triangle> triangles;
  };
  // Why the unit cannot do it: a short key (the statistic's name) and the
  // feature; an empty key when it can.
  struct Misfit {
    std::string key, feature;
  };

  void draw_now(const gl::RasterState& state, const gl::Triangle* triangles, size_t count);
  void load_programs(ZPath path);
  Misfit unit_cannot_draw(const gl::RasterState& state) const;
  Misfit unit_cannot_clear(const gl::ClearRequest& request) const;
  void fall_back(const Misfit& why);
  void flush_unit();
  void clear_unit(const gl::ClearRequest& request);
  void copy_band(unsigned first_row, unsigned rows);
  UnitRecord piece_record(const Piece& piece) const;
  void run_units(const gl::RasterState& state);
  void run_jobs(const gl::RasterState& state, const Job* jobs, size_t count, unsigned span_class);
  void write_records_ciu(const Job* jobs, size_t count, const ObjectLayout& layout);
  void write_records_dma(const Job* jobs, size_t count, const ObjectLayout& layout);
  void read_back_ciu(const Job* jobs, size_t count, const ObjectLayout& layout, const std::array<unsigned, 2>& rows);
  void read_back_dma(const Job* jobs, size_t count, const ObjectLayout& layout, const std::array<unsigned, 2>& rows);
  // The fragment of a covered pixel from its slot's bytes (b 0..12).
  template <typename Byte>
  Fragment fragment_of(int x, int y, Byte&& byte) const;
  // Runs a chain of descriptors on `channel` and waits for it.
  void run_chain(unsigned channel, uint32_t chain, std::vector<dma::Descriptor>& descriptors);
  void patch_loop(unsigned span_class, unsigned h, unsigned rows);
  void write_fragment(const gl::RasterState& state, const Fragment& fragment);
  void unsupported(const std::string& what);
  void publish_statistics();

  AppEnvironment& m_env;
  HostApi& m_host;
  arm::HostFrame m_frame;  // its core clears and reads back
  ArrayDriver m_array;
  DmaDriver m_dma;
  renderers::DmaUse m_dma_use;
  // With the DMA: the records, the rows' ends and the slots staged in
  // system memory (one byte per CU per CMEM address), the chains.
  uint32_t m_stage_records = 0, m_stage_ends = 0, m_stage_slots = 0, m_chain = 0;
  unsigned m_out_channel = 0;
  renderers::ArrayTraffic m_traffic;
  Unit m_unit;
  ZPath m_zpath;
  ZPath m_loaded = ZPath::host;  // the programs in program memory
  // The loaded programs' layouts, entries, row-loop counts and words.
  std::array<ObjectLayout, SPAN_CLASSES> m_layouts;
  std::array<unsigned, SPAN_CLASSES> m_program_base{};
  std::array<std::array<unsigned, 2>, SPAN_CLASSES> m_loop_rows{};  // each row loop's current count
  std::array<std::vector<uint64_t>, SPAN_CLASSES> m_words;          // the programs as loaded

  // The draw being drawn: its triangles' set-ups and its units (a half:
  // triangle index and half; a triangle: half 2).
  PixelBox m_box;
  std::vector<ObjectTriangle> m_triangles;
  std::vector<std::pair<uint32_t, unsigned>> m_units;
  std::vector<Job> m_jobs;
  std::vector<std::vector<Fragment>> m_fragments;  // per CU of a run
  std::vector<uint8_t> m_record_bytes;
  renderers::UnsupportedState m_unsupported{"ap-object"};
  // The one texture unit the current draw textures with (texture_units.h).
  renderers::SingleTextureUnit m_tex_unit;
  bool m_textured = false;

  renderers::HostTime m_time;
  renderers::FrameFigures m_frame_figures;
  uint64_t m_triangles_drawn = 0, m_units_drawn = 0, m_pieces = 0, m_runs = 0, m_cycles = 0;
  uint64_t m_busy_lanes = 0, m_lane_rows = 0, m_walked_rows = 0, m_emitted = 0, m_written = 0;
  uint64_t m_words_written = 0, m_words_read = 0, m_loop_patches = 0;
  std::array<uint64_t, SPAN_CLASSES> m_class_runs{};

  // ap.object.zpath=unit: the frame's clears and draw calls kept for the
  // unit (m_ops_done of them drawn on it already, when the screen is one
  // band), or the frame fallen back to the host path.
  std::vector<FrameOp> m_frame_ops;
  size_t m_ops_done = 0;
  bool m_frame_cleared = false, m_frame_on_host = false, m_frame_on_unit = false;
  unsigned m_band_rows = 0;  // frame rows the unit's window holds (zbuf.entries / width)
  std::set<std::string> m_warned;
  uint64_t m_unit_frames = 0, m_host_frames = 0, m_bands = 0, m_unit_clears = 0, m_pixels_sent = 0;
  uint64_t m_copied_bytes = 0, m_kept_triangles = 0;
  std::map<std::string, uint64_t> m_fallbacks;
};

}  // namespace tessera::ap_object
