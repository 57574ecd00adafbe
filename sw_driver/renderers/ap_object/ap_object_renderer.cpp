#include "renderers/ap_object/ap_object_renderer.h"

#include <algorithm>
#include <cstring>
#include <iostream>
#include <iterator>
#include <stdexcept>

#include "array/isa/ap_isa.h"
#include "common/fixed_function.h"
#include "common/pixel_format.h"
#include "costs/host_cost.h"
#include "gl/runtime.h"
#include "renderers/common/fragment_ops.h"
#include "renderers/common/texturing.h"
#include "soc/memory_map.h"
#include "zbuf/zbuf_regs.h"

namespace tessera::ap_object {

namespace {

using costs::HostCost;
using renderers::TimedScope;

// A pixel's x and a row's ends are signed 16-bit, the set-up's vertices
// within +-2^14 sixteenths (1024 pixels): frames up to this size.
constexpr unsigned MAX_FRAME = 1024;

int floor_div(int n, int d) {
  return n >= 0 ? n / d : -((-n + d - 1) / d);
}

}  // namespace

ApObjectRenderer::ApObjectRenderer(AppEnvironment& env, Unit unit, ZPath zpath)
    : m_env(env), m_host(*env.host), m_frame(env), m_array(env), m_dma(env), m_unit(unit), m_zpath(zpath) {
  if (m_frame.buffers.width > MAX_FRAME || m_frame.buffers.height > MAX_FRAME)
    throw std::invalid_argument("ap-object: the display is " + std::to_string(m_frame.buffers.width) + " x " +
                                std::to_string(m_frame.buffers.height) + ", but the back end draws frames of at most " +
                                std::to_string(MAX_FRAME) + " x " + std::to_string(MAX_FRAME) + " pixels");
  if (zpath == ZPath::unit) {
    // The window holds whole frame rows: bands of this many (README.md).
    const uint32_t entries = m_host.read32(memory_map::zbuf_regs.base + zbuf_regs::ENTRIES);
    m_band_rows = std::min<unsigned>(m_frame.buffers.height, entries / m_frame.buffers.width);
    if (m_band_rows == 0 || m_frame.buffers.color_format != PixelFormat::rgb565)
      throw std::invalid_argument("ap-object: ap.object.zpath=unit needs an RGB565 display at most zbuf.entries (" +
                                  std::to_string(entries) + ") pixels wide");
  }
  load_programs(zpath);
  m_dma_use = renderers::dma_use(env, m_dma);
  if (m_dma_use.enabled) {
    const unsigned cus = m_array.cus();
    unsigned ends = 0, slots = 0, descriptors = 0, record = 0;
    for (unsigned k = 0; k < SPAN_CLASSES; ++k)
      for (ZPath path : {ZPath::host, zpath}) {
        const ObjectLayout layout = ObjectLayout::of(program_of(unit, k, path));
        record = std::max(record, layout.rec_bytes);
        if (layout.zsend) continue;
        ends = std::max(ends, layout.row_bytes * layout.rows * cus);
        slots = std::max(slots, layout.slot_bytes * layout.span * layout.rows * cus);
        descriptors = std::max(descriptors, layout.slot_bytes * layout.span + layout.row_bytes + 2);
      }
    m_stage_records = gl::allocate(2 * record * cus);
    m_stage_ends = gl::allocate(ends);
    m_stage_slots = gl::allocate(slots);
    m_chain = gl::allocate(descriptors * dma::DESCRIPTOR_BYTES);
    m_out_channel = m_dma.channels() >= 2 ? 1 : 0;
  }
}

// The unit's three span classes of one z path, one after the other in
// program memory (both paths' six do not fit with unit=triangle).
void ApObjectRenderer::load_programs(ZPath path) {
  unsigned base = 0;
  for (unsigned k = 0; k < SPAN_CLASSES; ++k) {
    const ap::Program& program = program_of(m_unit, k, path);
    m_layouts[k] = ObjectLayout::of(program);
    m_program_base[k] = base;
    m_array.load(program, base);
    m_words[k] = program.words;
    for (unsigned h = 0; h < m_layouts[k].units; ++h) {
      const ap::Decoded decoded = ap::decode(program.words[m_layouts[k].loop_word[h]]);
      m_loop_rows[k][h] = decoded.instruction.a.value + 1u;
    }
    base += static_cast<unsigned>(program.words.size());
  }
  m_loaded = path;
  if (path == ZPath::unit) {
    // The programs' constants, and no rows left in any CU's records: a CU
    // whose group gets no record in a run walks the rows its last record
    // left, which the host path's runs overwrote.
    const ObjectLayout& layout = m_layouts[0];
    for (unsigned k = 0; k < std::size(ZSEND_KONST); ++k) m_array.fill8(layout.konst + k, ZSEND_KONST[k]);
    for (unsigned h = 0; h < layout.units; ++h) m_array.fill8(layout.record(h) + layout.nrows, 0);
  }
}

void ApObjectRenderer::unsupported(const std::string& what) {
  m_unsupported.report(m_env, what);
}

void ApObjectRenderer::clear(const gl::ClearRequest& request) {
  if (m_zpath == ZPath::unit && !m_frame_on_host) {
    const Misfit why = unit_cannot_clear(request);
    if (why.key.empty()) {
      FrameOp op;
      op.clear = true;
      op.request = request;
      m_frame_ops.push_back(std::move(op));
      m_frame_cleared = true;
      return;
    }
    fall_back(why);  // outside the scope below: the draw calls time themselves
  }
  TimedScope timed(m_host, m_time, renderers::HostSplit::compute);
  m_frame.core->clear(request);
}

void ApObjectRenderer::read_pixels(int x, int y, int width, int height, uint8_t* rgba) {
  flush_unit();
  TimedScope timed(m_host, m_time, renderers::HostSplit::compute);
  m_frame.core->read_pixels(x, y, width, height, rgba);
}

// What the unit does: GL_LESS on 16-bit depth, depth and RGB565 colour
// written, over a window of whole frame rows; a draw call needing anything
// else is drawn on the host path.
ApObjectRenderer::Misfit ApObjectRenderer::unit_cannot_draw(const gl::RasterState& state) const {
  if (!state.depth_test) return {"depth_test_off", "drawing without the depth test (GL_DEPTH_TEST disabled)"};
  if (state.depth_func != CompareFunc::less) return {"depth_func", "a depth function other than GL_LESS"};
  if (!state.depth_write) return {"depth_mask", "glDepthMask(GL_FALSE)"};
  for (const gl::TextureUnit& unit : state.unit)
    if (unit.enabled) return {"texturing", "texturing"};
  if (state.blend) return {"blend", "blending (GL_BLEND)"};
  if (state.alpha_test) return {"alpha_test", "the alpha test (GL_ALPHA_TEST)"};
  if (state.logic_op) return {"logic_op", "a logic op (GL_COLOR_LOGIC_OP)"};
  if (!state.color_mask[0] || !state.color_mask[1] || !state.color_mask[2]) return {"color_mask", "glColorMask"};
  if (state.stencil_test) return {"stencil", "the stencil test (GL_STENCIL_TEST)"};
  if (state.fog) return {"fog", "fog (GL_FOG)"};
  const auto width = static_cast<int64_t>(m_frame.buffers.width), height = static_cast<int64_t>(m_frame.buffers.height);
  if (state.scissor_test &&
      (state.scissor_x > 0 || state.scissor_y > 0 || state.scissor_x + int64_t{state.scissor_width} < width ||
       state.scissor_y + int64_t{state.scissor_height} < height))
    return {"scissor", "a scissor box smaller than the frame (GL_SCISSOR_TEST)"};
  return {};
}

// The unit's clear writes depth and colour into the whole window.
ApObjectRenderer::Misfit ApObjectRenderer::unit_cannot_clear(const gl::ClearRequest& request) const {
  const auto width = static_cast<int64_t>(m_frame.buffers.width), height = static_cast<int64_t>(m_frame.buffers.height);
  if (!request.color || !request.depth || !request.depth_write || !request.color_mask[0] || !request.color_mask[1] ||
      !request.color_mask[2] ||
      (request.scissor_test &&
       (request.scissor_x > 0 || request.scissor_y > 0 || request.scissor_x + int64_t{request.scissor_width} < width ||
        request.scissor_y + int64_t{request.scissor_height} < height)))
    return {"clear", "a glClear other than of the whole colour and depth buffers"};
  return {};
}

// The frame so far is drawn again on the host path, and the rest of it
// goes there directly; one warning per reason.
void ApObjectRenderer::fall_back(const Misfit& why) {
  ++m_fallbacks[why.key];
  if (m_warned.insert(why.key).second) {
    const std::string message = "ap.object.zpath=unit: " + why.feature +
                                " is not what the z-buffer unit does (GL_LESS on 16-bit depth, RGB565 colour): frames "
                                "with it are drawn on the host path (reported once)";
    if (m_env.warn)
      m_env.warn("ap-object", message);
    else
      std::cerr << "warning: ap-object: " << message << "\n";
  }
  m_frame_on_host = true;
  std::vector<FrameOp> ops = std::move(m_frame_ops);
  m_frame_ops.clear();
  m_ops_done = 0;
  for (const FrameOp& op : ops) {
    if (op.clear)
      m_frame.core->clear(op.request);
    else
      draw_now(op.state, op.triangles.data(), op.triangles.size());
  }
}

// The frame's clears and draw calls not yet on the unit, band by band (all
// of them again per band when the window holds less than the frame), each
// band's colour copied into the back buffer.
void ApObjectRenderer::flush_unit() {
  if (m_zpath != ZPath::unit || m_frame_on_host || m_ops_done == m_frame_ops.size()) return;
  if (m_loaded != ZPath::unit) load_programs(ZPath::unit);
  m_frame_on_unit = true;
  const uint32_t regs = memory_map::zbuf_regs.base;
  const unsigned width = m_frame.buffers.width, height = m_frame.buffers.height;
  const bool one_band = m_band_rows >= height;
  const uint32_t pixels_before = m_host.read32(regs + zbuf_regs::PIXELS);
  for (unsigned first = 0; first < height; first += m_band_rows) {
    const unsigned rows = std::min(m_band_rows, height - first);
    if (!one_band || m_ops_done == 0) {
      TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
      costs::charge(m_host, HostCost::ap_object_zunit_window);
      m_host.write32(regs + zbuf_regs::FRAME_ORIGIN, first << 16);
      m_host.write32(regs + zbuf_regs::FRAME_SIZE, width | rows << 16);
    }
    for (size_t i = one_band ? m_ops_done : 0; i < m_frame_ops.size(); ++i) {
      const FrameOp& op = m_frame_ops[i];
      if (op.clear)
        clear_unit(op.request);
      else
        draw_now(op.state, op.triangles.data(), op.triangles.size());
    }
    copy_band(first, rows);
    ++m_bands;
  }
  m_ops_done = m_frame_ops.size();
  m_pixels_sent += m_host.read32(regs + zbuf_regs::PIXELS) - pixels_before;
}

void ApObjectRenderer::clear_unit(const gl::ClearRequest& request) {
  TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
  costs::charge(m_host, HostCost::ap_object_zunit_clear);
  const uint32_t regs = memory_map::zbuf_regs.base;
  uint32_t rgba = 0;
  for (unsigned ch = 0; ch < 4; ++ch) rgba |= uint32_t{request.rgba[ch]} << (8 * ch);
  // As the arm back end's clear converts them.
  m_host.write32(regs + zbuf_regs::CLEAR_DEPTH, std::min<uint32_t>(request.depth_value, 0xffffff) >> 8);
  m_host.write32(regs + zbuf_regs::CLEAR_COLOUR, pack_pixel(m_frame.buffers.color_format, rgba));
  m_host.write32(regs + zbuf_regs::CONTROL, zbuf_regs::CONTROL_CLEAR);
  // The array's next program starts after the clear.
  while ((m_host.read32(regs + zbuf_regs::STATUS) & zbuf_regs::STATUS_BUSY) != 0) m_host.compute_cycles(64);
  ++m_unit_clears;
}

// The window's colour into the back buffer's rows [first, first + rows)
// (memory rows, 0 at the top): one DMA copy, or the host's reads.
void ApObjectRenderer::copy_band(unsigned first, unsigned rows) {
  TimedScope timed(m_host, m_time, renderers::HostSplit::array_read);
  const uint32_t bytes = m_frame.buffers.width * rows * zbuf_regs::COLOUR_ENTRY_BYTES;
  const uint32_t destination =
      m_frame.buffers.color_address + first * m_frame.buffers.width * zbuf_regs::COLOUR_ENTRY_BYTES;
  if (m_dma_use.enabled) {
    std::vector<dma::Descriptor> copy{DmaDriver::copy(memory_map::zbuf_colour.base, destination, bytes)};
    run_chain(0, m_chain, copy);
  } else {
    const unsigned words = bytes / 4;
    std::vector<uint32_t> colour(words);
    costs::charge(m_host, HostCost::ap_object_zunit_copy_word, words);
    m_host.read_words(memory_map::zbuf_colour.base, colour.data(), words);
    std::memcpy(m_host.store_span(destination, 4, words), colour.data(), size_t{words} * 4);
    if (bytes % 4 != 0)
      m_host.write16(destination + bytes - 2, m_host.read16(memory_map::zbuf_colour.base + bytes - 2));
  }
  m_copied_bytes += bytes;
}

void ApObjectRenderer::present() {
  flush_unit();
  if (m_frame_on_host) ++m_host_frames;
  if (m_frame_on_unit && !m_frame_on_host) ++m_unit_frames;
  m_frame_ops.clear();
  m_ops_done = 0;
  m_frame_cleared = m_frame_on_host = m_frame_on_unit = false;
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::frame_out);
    m_frame.present();
  }
  m_unsupported.new_frame();
  publish_statistics();
  renderers::FrameFigures::Figures totals = {{"triangles", static_cast<double>(m_triangles_drawn)},
                                             {"units", static_cast<double>(m_units_drawn)},
                                             {"pieces", static_cast<double>(m_pieces)},
                                             {"runs", static_cast<double>(m_runs)},
                                             {"cycles", static_cast<double>(m_cycles)},
                                             {"pixels_emitted", static_cast<double>(m_emitted)},
                                             {"pixels_written", static_cast<double>(m_written)},
                                             {"ciu_words_written", static_cast<double>(m_words_written)},
                                             {"ciu_words_read", static_cast<double>(m_words_read)}};
  renderers::add_traffic(totals, m_traffic);
  renderers::add_host_time(totals, m_host, m_time);
  m_frame_figures.emit(m_env, totals, {});
}

void ApObjectRenderer::draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) {
  if (m_zpath == ZPath::unit && !m_frame_on_host) {
    Misfit why = unit_cannot_draw(state);
    if (why.key.empty() && !m_frame_cleared)
      why = {"no_clear", "a frame that does not begin with glClear of the colour and depth buffers"};
    if (why.key.empty()) {
      // Kept until the frame is shown or read (the bands draw it again).
      TimedScope timed(m_host, m_time, renderers::HostSplit::compute);
      costs::charge(m_host, HostCost::ap_object_zunit_keep_triangle, count);
      FrameOp op;
      op.state = state;
      op.triangles.assign(triangles, triangles + count);
      m_frame_ops.push_back(std::move(op));
      m_kept_triangles += count;
      return;
    }
    fall_back(why);
  }
  draw_now(state, triangles, count);
}

void ApObjectRenderer::draw_now(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) {
  if (m_frame_on_host && m_loaded != ZPath::host) load_programs(ZPath::host);
  const uint64_t start = m_host.now_cycles();
  const renderers::HostTime before = m_time;
  const renderers::CostSplit split(renderers::HostSplit::compute);
  if (state.stencil_test) unsupported("the stencil test (GL_STENCIL_TEST): drawn without it");
  if (state.fog) unsupported("fog (GL_FOG): drawn without it");
  // Texturing as ap-pixel's host does it (one unit, affine coordinates
  // from the array, the look-up and the environment on the host).
  m_tex_unit = renderers::single_texture_unit(state, [this](const std::string& what) { unsupported(what); });
  const gl::Texture tex = m_tex_unit.index >= 0 ? state.unit[m_tex_unit.index].tex : gl::Texture{};
  m_textured = m_tex_unit.index >= 0 && tex.width > 0 && tex.height > 0 && tex.width <= 256 && tex.height <= 256 &&
               (tex.width & (tex.width - 1)) == 0 && (tex.height & (tex.height - 1)) == 0;
  if (m_tex_unit.index >= 0 && !m_textured)
    unsupported("textures that are not a power of two up to 256 texels: drawn untextured");
  if (m_textured && renderers::env_needs_base_format(tex, m_tex_unit.env))
    unsupported(
        "textures without alpha under GL_REPLACE and GL_ALPHA textures under GL_MODULATE or GL_REPLACE (ES 1.1 table "
        "3.15): drawn with the texel expanded to RGBA");
  if (m_textured && renderers::texture_needs_lod(tex))
    unsupported(
        "mipmaps and a minification filter other than the magnification filter (GL_TEXTURE_MIN_FILTER): level 0 "
        "sampled with the magnification filter");
  m_box = PixelBox{0, 0, static_cast<int>(m_frame.buffers.width) - 1, static_cast<int>(m_frame.buffers.height) - 1};
  if (state.scissor_test) {
    m_box.x0 = std::max(m_box.x0, state.scissor_x);
    m_box.y0 = std::max(m_box.y0, state.scissor_y);
    m_box.x1 = static_cast<int>(std::min<int64_t>(m_box.x1, int64_t{state.scissor_x} + state.scissor_width - 1));
    m_box.y1 = static_cast<int>(std::min<int64_t>(m_box.y1, int64_t{state.scissor_y} + state.scissor_height - 1));
  }
  // Units in draw order, a batch of one per CU at a time.
  m_triangles.clear();
  m_units.clear();
  for (size_t t = 0; t < count; ++t) {
    costs::charge(m_host, HostCost::ap_object_triangle);
    const ObjectTriangle setup(triangles[t], state.flat_shading, m_box, m_textured ? tex.width : 0,
                               m_textured ? tex.height : 0, m_textured ? static_cast<unsigned>(m_tex_unit.index) : 0);
    if (!setup.valid()) continue;
    // Only a valid set-up reaches the texture coordinates (object_setup.cpp).
    if (m_textured) costs::charge(m_host, HostCost::ap_object_textured_triangle);
    const auto index = static_cast<uint32_t>(m_triangles.size());
    m_triangles.push_back(setup);
    ++m_triangles_drawn;
    // A batch is exactly one unit per CU (the last of a draw fewer).
    const auto add = [&](unsigned which) {
      m_units.emplace_back(index, which);
      if (m_units.size() == m_array.cus()) run_units(state);
    };
    if (m_unit == Unit::triangle) {
      add(2);
    } else {
      for (unsigned h = 0; h < 2; ++h)
        if (!setup.empty(h)) add(h);
    }
  }
  run_units(state);
  const uint64_t elsewhere = (m_time.array_write - before.array_write) + (m_time.array_read - before.array_read) +
                             (m_time.array_wait - before.array_wait);
  m_time.compute += m_host.now_cycles() - start - elsewhere;
}

// One batch of units: the span class from their widest span, their pieces
// (README.md, "Pieces"), and the runs, one job per CU.
void ApObjectRenderer::run_units(const gl::RasterState& state) {
  if (m_units.empty()) return;
  costs::charge(m_host, HostCost::ap_object_batch);
  m_units_drawn += m_units.size();
  int widest = 1;
  for (const auto& [index, which] : m_units)
    for (unsigned h = 0; h < 2; ++h) {
      const ObjectTriangle& t = m_triangles[index];
      if ((which != 2 && which != h) || t.empty(h)) continue;
      for (int j : {t.first_row(h), t.last_row(h)}) widest = std::max(widest, t.right(h, j) - t.left(h, j) + 1);
    }
  unsigned span_class = 0;
  while (span_class + 1 < SPAN_CLASSES && SPAN_WIDTHS[span_class] < static_cast<unsigned>(widest)) ++span_class;
  const ObjectLayout& layout = m_layouts[span_class];
  const int w = static_cast<int>(layout.span), rows_max = static_cast<int>(layout.rows);

  m_jobs.clear();
  std::array<std::vector<Piece>, 2> pieces;
  for (const auto& [index, which] : m_units) {
    costs::charge(m_host, HostCost::ap_object_unit);
    const ObjectTriangle& t = m_triangles[index];
    for (unsigned h = 0; h < 2; ++h) {
      pieces[h].clear();
      if ((which != 2 && which != h) || t.empty(h)) continue;
      for (int j0 = t.first_row(h); j0 <= t.last_row(h); j0 += rows_max) {
        const int j1 = std::min(t.last_row(h), j0 + rows_max - 1);
        const int l0 = t.left(h, j0), l1 = t.left(h, j1);
        const int r_max = std::max(t.right(h, j0), t.right(h, j1));
        const int k_first = std::max(0, floor_div(m_box.x0 - std::max(l0, l1), w));
        const int k_last = floor_div(std::min(r_max, m_box.x1) - std::min(l0, l1), w);
        for (int k = k_first; k <= k_last; ++k) {
          costs::charge(m_host, HostCost::ap_object_piece);
          pieces[h].push_back({index, h, j0, static_cast<unsigned>(j1 - j0 + 1), k * w});
        }
      }
    }
    if (m_unit == Unit::triangle) {
      // A CU walks the lower half's piece n and then the upper half's.
      for (size_t n = 0; n < std::max(pieces[0].size(), pieces[1].size()); ++n) {
        Job job;
        for (unsigned h = 0; h < 2; ++h)
          if (n < pieces[h].size()) job.pieces[h] = pieces[h][n];
        m_jobs.push_back(job);
      }
    } else {
      for (unsigned h = 0; h < 2; ++h)
        for (const Piece& piece : pieces[h]) {
          Job job;
          job.pieces[0] = piece;
          m_jobs.push_back(job);
        }
    }
  }
  m_units.clear();
  for (size_t first = 0; first < m_jobs.size(); first += m_array.cus())
    run_jobs(state, m_jobs.data() + first, std::min<size_t>(m_array.cus(), m_jobs.size() - first), span_class);
}

// A piece's record; a ZSEND program's also takes its first row's y in
// memory rows and its rows.
UnitRecord ApObjectRenderer::piece_record(const Piece& piece) const {
  UnitRecord r = m_triangles[piece.triangle].record(piece.half, piece.row, piece.offset);
  r.y_memory = static_cast<int16_t>(static_cast<int>(m_frame.buffers.height) - 1 - piece.row);
  r.rows = static_cast<uint8_t>(piece.rows);
  return r;
}

void ApObjectRenderer::patch_loop(unsigned span_class, unsigned h, unsigned rows) {
  if (m_loop_rows[span_class][h] == rows) return;
  const ObjectLayout& layout = m_layouts[span_class];
  ap::Decoded decoded = ap::decode(m_words[span_class][layout.loop_word[h]]);
  decoded.instruction.a.value = static_cast<uint16_t>(rows - 1);
  costs::charge(m_host, HostCost::ap_object_loop_patch);
  m_array.load(std::vector<uint64_t>{ap::encode(decoded.instruction)},
               m_program_base[span_class] + layout.loop_word[h]);
  m_loop_rows[span_class][h] = rows;
  ++m_loop_patches;
}

// One run: the row loops set, the records in (CIU or DMA), the program, the
// row ends and the covered pixels' slots back, and the fragments in job
// order (draw order).
void ApObjectRenderer::run_jobs(const gl::RasterState& state, const Job* jobs, size_t count, unsigned span_class) {
  const ObjectLayout& layout = m_layouts[span_class];
  std::array<unsigned, 2> rows{1, 1};
  for (size_t n = 0; n < count; ++n)
    for (unsigned h = 0; h < layout.units; ++h) rows[h] = std::max(rows[h], jobs[n].pieces[h].rows);
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
    for (unsigned h = 0; h < layout.units; ++h) patch_loop(span_class, h, rows[h]);
    if (m_dma_use.enabled)
      write_records_dma(jobs, count, layout);
    else
      write_records_ciu(jobs, count, layout);
  }
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::array_wait);
    m_cycles += m_array.run(m_program_base[span_class] + layout.entry);
  }
  ++m_runs;
  ++m_class_runs[span_class];
  m_busy_lanes += count;
  for (unsigned h = 0; h < layout.units; ++h) {
    m_lane_rows += uint64_t{rows[h]} * m_array.cus();
    for (size_t n = 0; n < count; ++n) m_walked_rows += jobs[n].pieces[h].rows;
  }

  if (layout.zsend) return;  // the pixels went to the z-buffer unit
  m_fragments.resize(m_array.cus());
  for (size_t n = 0; n < count; ++n) m_fragments[n].clear();
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::array_read);
    if (m_dma_use.enabled)
      read_back_dma(jobs, count, layout, rows);
    else
      read_back_ciu(jobs, count, layout, rows);
  }
  for (size_t n = 0; n < count; ++n) {
    m_emitted += m_fragments[n].size();
    for (const Fragment& fragment : m_fragments[n]) write_fragment(state, fragment);
  }
}

// The records through the CIU: one byte of four CUs' records per word, as
// ap-tile packs its records; groups without a job are not written.
void ApObjectRenderer::write_records_ciu(const Job* jobs, size_t count, const ObjectLayout& layout) {
  const unsigned columns = m_array.columns(), groups = static_cast<unsigned>((count + 3) / 4);
  m_record_bytes.resize(size_t{layout.rec_bytes} * 4);
  for (unsigned g = 0; g < groups; ++g) {
    const unsigned i = g % (columns / 4), j = g / (columns / 4);
    for (unsigned h = 0; h < layout.units; ++h) {
      bool any = false;
      for (unsigned k = 0; k < 4; ++k) {
        uint8_t* bytes = m_record_bytes.data() + k * layout.rec_bytes;
        const size_t n = size_t{g} * 4 + k;
        if (n < count && jobs[n].pieces[h].rows > 0) {
          const Piece& piece = jobs[n].pieces[h];
          costs::charge(m_host, HostCost::ap_object_record);
          encode_record(piece_record(piece), layout, bytes);
          any = true;
          ++m_pieces;
        } else {
          std::memset(bytes, 0, layout.rec_bytes);
        }
      }
      if (!any) continue;
      costs::charge(m_host, HostCost::ap_object_record_word, layout.rec_bytes);
      for (unsigned b = 0; b < layout.rec_bytes; ++b) {
        uint32_t word = 0;
        for (unsigned k = 0; k < 4; ++k) word |= uint32_t{m_record_bytes[k * layout.rec_bytes + b]} << (8 * k);
        m_array.write32(i, j, layout.record(h) + b, word);
        ++m_words_written;
        m_traffic.values_written += 4;
      }
    }
  }
}

// The read-back through the CIU, group by group: the rows' ends, then the
// slots any of the four CUs covers inside the box.
void ApObjectRenderer::read_back_ciu(const Job* jobs, size_t count, const ObjectLayout& layout,
                                     const std::array<unsigned, 2>& rows) {
  const unsigned columns = m_array.columns(), groups = static_cast<unsigned>((count + 3) / 4);
  std::vector<int16_t> ends(size_t{4} * 2 * layout.rows);
  std::vector<uint8_t> needed(size_t{layout.span} * layout.rows);
  for (unsigned g = 0; g < groups; ++g) {
    const unsigned i = g % (columns / 4), j = g / (columns / 4);
    for (unsigned h = 0; h < layout.units; ++h) {
      unsigned most = 0;
      for (unsigned k = 0; k < 4; ++k) {
        const size_t n = size_t{g} * 4 + k;
        if (n < count) most = std::max(most, jobs[n].pieces[h].rows);
      }
      if (most == 0) continue;
      // Rows r = 0 .. most - 1 are in row slot l = rows[h] - 1 - r.
      for (unsigned r = 0; r < most; ++r) {
        const unsigned l = rows[h] - 1 - r;
        uint32_t plane[4];
        for (unsigned b = 0; b < 4; ++b) plane[b] = m_array.read32(i, j, layout.row_plane(h, b, l));
        m_words_read += 4;
        m_traffic.values_read += 16;
        costs::charge(m_host, HostCost::ap_object_row_read);
        for (unsigned k = 0; k < 4; ++k) {
          const auto byte = [&](unsigned b) { return (plane[b] >> (8 * k)) & 0xff; };
          ends[(k * 2) * layout.rows + r] = static_cast<int16_t>(byte(0) << 8 | byte(1));
          ends[(k * 2 + 1) * layout.rows + r] = static_cast<int16_t>(byte(2) << 8 | byte(3));
        }
      }
      std::fill(needed.begin(), needed.end(), uint8_t{0});
      bool any = false;
      for (unsigned k = 0; k < 4; ++k) {
        const size_t n = size_t{g} * 4 + k;
        if (n >= count) continue;
        const Piece& piece = jobs[n].pieces[h];
        for (unsigned r = 0; r < piece.rows; ++r) {
          const int xl = ends[(k * 2) * layout.rows + r], xr = ends[(k * 2 + 1) * layout.rows + r];
          for (unsigned p = 0; p < layout.span; ++p) {
            const int x = xl + piece.offset + static_cast<int>(p);
            if (x > xr || x > m_box.x1) break;
            if (x < m_box.x0) continue;
            needed[size_t{p} * layout.rows + r] = 1;
            any = true;
          }
        }
      }
      if (!any) continue;
      for (unsigned p = 0; p < layout.span; ++p)
        for (unsigned r = 0; r < most; ++r) {
          if (!needed[size_t{p} * layout.rows + r]) continue;
          const unsigned l = rows[h] - 1 - r;
          // z and colour, and s and t when textured.
          uint32_t slot[13];
          const unsigned slot_words = m_textured ? 13 : 7;
          for (unsigned b = 0; b < slot_words; ++b) slot[b] = m_array.read32(i, j, layout.slot(h, p, b, l));
          m_words_read += slot_words;
          m_traffic.values_read += 4 * slot_words;
          costs::charge(m_host, HostCost::ap_object_slot_read);
          costs::charge(m_host, HostCost::ap_object_slot_word, slot_words);
          for (unsigned k = 0; k < 4; ++k) {
            const size_t n = size_t{g} * 4 + k;
            if (n >= count) continue;
            const Piece& piece = jobs[n].pieces[h];
            if (r >= piece.rows) continue;
            const int xl = ends[(k * 2) * layout.rows + r], xr = ends[(k * 2 + 1) * layout.rows + r];
            const int x = xl + piece.offset + static_cast<int>(p);
            if (x > xr || x < m_box.x0 || x > m_box.x1) continue;
            m_fragments[n].push_back(fragment_of(x, piece.row + static_cast<int>(r), [&](unsigned b) {
              return static_cast<uint32_t>((slot[b] >> (8 * k)) & 0xff);
            }));
            costs::charge(m_host, m_textured ? HostCost::ap_object_fragment_textured : HostCost::ap_object_fragment);
          }
        }
    }
  }
}

template <typename Byte>
ApObjectRenderer::Fragment ApObjectRenderer::fragment_of(int x, int y, Byte&& byte) const {
  // z's top byte catches rounding beyond 0 .. 2^24 - 1.
  const uint32_t top = byte(0);
  const auto z = static_cast<uint16_t>(top >= 0x80 ? 0 : top != 0 ? 0xffff : byte(1) << 8 | byte(2));
  Fragment fragment{x, y, z, byte(3) | byte(4) << 8 | byte(5) << 16 | byte(6) << 24, {0, 0}};
  if (m_textured)
    for (unsigned v = 0; v < 2; ++v) {
      const uint32_t code = byte(7 + 3 * v) << 16 | byte(8 + 3 * v) << 8 | byte(9 + 3 * v);
      fragment.st[v] = static_cast<int32_t>(code << 8) >> 8;  // 16.8, sign-extended
    }
  return fragment;
}

void ApObjectRenderer::run_chain(unsigned channel, uint32_t chain, std::vector<dma::Descriptor>& descriptors) {
  if (descriptors.empty()) return;
  costs::charge(m_host, HostCost::ap_object_dma_descriptor, descriptors.size());
  m_traffic.dma_descriptors += descriptors.size();
  m_dma.write_chain(chain, descriptors);
  m_dma.start_chain(channel, chain);
  m_dma.wait(channel);
  descriptors.clear();
}

// The records through the DMA: staged as one byte per CU per CMEM address
// (CU order), reshuffled into CMEM by one descriptor per record.
void ApObjectRenderer::write_records_dma(const Job* jobs, size_t count, const ObjectLayout& layout) {
  const unsigned cus = m_array.cus(), bytes = layout.rec_bytes * cus;
  std::vector<dma::Descriptor> in;
  m_record_bytes.resize(layout.rec_bytes);
  for (unsigned h = 0; h < layout.units; ++h) {
    const uint32_t stage = m_stage_records + h * bytes;
    uint8_t* out = m_host.store_span(stage, 4, bytes / 4);
    std::memset(out, 0, bytes);
    for (size_t n = 0; n < count; ++n) {
      const Piece& piece = jobs[n].pieces[h];
      if (piece.rows == 0) continue;
      costs::charge(m_host, HostCost::ap_object_record);
      costs::charge(m_host, HostCost::ap_object_dma_record);
      encode_record(piece_record(piece), layout, m_record_bytes.data());
      for (unsigned b = 0; b < layout.rec_bytes; ++b) out[size_t{b} * cus + n] = m_record_bytes[b];
      ++m_pieces;
    }
    in.push_back(DmaDriver::to_cmem(stage, layout.record(h), bytes, 1));
    m_traffic.values_written += bytes;
  }
  run_chain(0, m_chain, in);
}

// The read-back through the DMA: per record, the rows' ends of the rows the
// run walked (four planes), then, for every pixel position some CU covers
// inside the box, its slot's planes over those rows; each staged as one
// byte per CU per CMEM address and read by the host from system memory.
void ApObjectRenderer::read_back_dma(const Job* jobs, size_t count, const ObjectLayout& layout,
                                     const std::array<unsigned, 2>& rows) {
  const unsigned cus = m_array.cus(), slot_words = m_textured ? 13 : 7;
  std::vector<dma::Descriptor> out;
  std::vector<int32_t> slot_at(layout.span);
  for (unsigned h = 0; h < layout.units; ++h) {
    unsigned most = 0;
    for (size_t n = 0; n < count; ++n) most = std::max(most, jobs[n].pieces[h].rows);
    if (most == 0) continue;
    // Row r is in row slot l = rows[h] - 1 - r: the rows walked are the
    // slots rows[h] - most .. rows[h] - 1, at staging row l - first.
    const unsigned first = rows[h] - most, span = most * cus;
    for (unsigned b = 0; b < layout.row_bytes; ++b)
      out.push_back(DmaDriver::from_cmem(layout.row_plane(h, b, first), m_stage_ends + b * span, span, 1));
    m_traffic.values_read += uint64_t{layout.row_bytes} * span;
    run_chain(m_out_channel, m_chain, out);
    const uint8_t* ends = m_host.load_span(m_stage_ends, 4, layout.row_bytes * span / 4);
    costs::charge(m_host, HostCost::ap_object_dma_row, uint64_t{most} * count);
    const auto end = [&](unsigned b, unsigned r, size_t n) {
      const size_t at = size_t{b} * span + size_t{rows[h] - 1 - r - first} * cus + n;
      return static_cast<int16_t>(ends[at] << 8 | ends[at + span]);
    };
    std::fill(slot_at.begin(), slot_at.end(), -1);
    unsigned positions = 0;
    for (size_t n = 0; n < count; ++n) {
      const Piece& piece = jobs[n].pieces[h];
      for (unsigned r = 0; r < piece.rows; ++r) {
        const int xl = end(0, r, n), xr = end(2, r, n);
        for (unsigned p = 0; p < layout.span; ++p) {
          const int x = xl + piece.offset + static_cast<int>(p);
          if (x > xr || x > m_box.x1) break;
          if (x >= m_box.x0 && slot_at[p] < 0) slot_at[p] = static_cast<int32_t>(positions++);
        }
      }
    }
    if (positions == 0) continue;
    for (unsigned p = 0; p < layout.span; ++p) {
      if (slot_at[p] < 0) continue;
      for (unsigned b = 0; b < slot_words; ++b)
        out.push_back(DmaDriver::from_cmem(layout.slot(h, p, b, first),
                                           m_stage_slots + (static_cast<uint32_t>(slot_at[p]) * slot_words + b) * span,
                                           span, 1));
      m_traffic.values_read += uint64_t{slot_words} * span;
    }
    run_chain(m_out_channel, m_chain, out);
    const uint8_t* slots = m_host.load_span(m_stage_slots, 4, positions * slot_words * span / 4);
    for (size_t n = 0; n < count; ++n) {
      const Piece& piece = jobs[n].pieces[h];
      for (unsigned r = 0; r < piece.rows; ++r) {
        const int xl = end(0, r, n), xr = end(2, r, n);
        const size_t row_at = size_t{rows[h] - 1 - r - first} * cus + n;
        for (unsigned p = 0; p < layout.span; ++p) {
          const int x = xl + piece.offset + static_cast<int>(p);
          if (x > xr || x > m_box.x1) break;
          if (x < m_box.x0) continue;
          costs::charge(m_host, HostCost::ap_object_dma_slot);
          const size_t base = size_t{static_cast<uint32_t>(slot_at[p]) * slot_words} * span + row_at;
          m_fragments[n].push_back(fragment_of(x, piece.row + static_cast<int>(r), [&](unsigned b) {
            return static_cast<uint32_t>(slots[base + size_t{b} * span]);
          }));
        }
      }
    }
  }
}

// The fragment operations on the host, as ap-pixel's host does them: alpha
// and depth tests, then blending, logic op and masks into the frame.
void ApObjectRenderer::write_fragment(const gl::RasterState& state, const Fragment& f) {
  costs::charge(m_host, HostCost::ap_object_pixel);
  uint32_t rgba = f.rgba;
  if (m_textured) {
    const gl::Texture& tex = state.unit[m_tex_unit.index].tex;
    auto texel_at = [&](int ti, int tj, uint8_t out[4]) {
      copy_word(m_host.load_span(renderers::texel_address(tex, ti, tj), 4, 1), out);
    };
    uint8_t texel[4];
    costs::charge(m_host, renderers::sample_texture(tex, f.st[0], f.st[1], texel_at, texel)
                              ? HostCost::ap_object_texel_linear
                              : HostCost::ap_object_texel_nearest);
    rgba = renderers::apply_tex_env(m_tex_unit.env, rgba, texel);
    costs::charge(m_host, HostCost::ap_object_texture_environment);
  }
  if (state.alpha_test && !compare_passes<uint32_t>(state.alpha_func, rgba >> 24, state.alpha_ref)) return;
  const uint32_t offset =
      (m_frame.buffers.height - 1 - static_cast<uint32_t>(f.y)) * m_frame.buffers.width + static_cast<uint32_t>(f.x);
  if (state.depth_test) {
    const uint8_t* d = m_host.load_span(m_frame.buffers.depth_address + offset * 2, 2, 1);
    const auto old = static_cast<uint16_t>(d[0] | d[1] << 8);
    if (!compare_passes(state.depth_func, f.z, old)) return;
    if (state.depth_write) {
      uint8_t* p = m_host.store_span(m_frame.buffers.depth_address + offset * 2, 2, 1);
      p[0] = static_cast<uint8_t>(f.z);
      p[1] = static_cast<uint8_t>(f.z >> 8);
    }
  }
  ++m_written;
  renderers::write_color(m_host, state, m_frame.buffers.color_format, m_frame.buffers.color_address, offset, rgba,
                         {HostCost::ap_object_color_read_back, std::nullopt});
}

void ApObjectRenderer::publish_statistics() {
  if (m_env.counters == nullptr) return;
  ActivityCounters& c = *m_env.counters;
  auto set = [&](const char* name, const char* description, uint64_t value) {
    c.counter(std::string("ap_object.") + name, description).value = value;
  };
  renderers::publish_host_time(c, "ap_object", m_host, m_time,
                               "host time setting up, cutting into pieces, packing, depth testing and writing the "
                               "pixels");
  set("triangles", "triangles set up with at least one row in the box", m_triangles_drawn);
  set("units", "units given out (halves, or triangles with ap.object.unit=triangle)", m_units_drawn);
  set("pieces", "pieces of halves walked by a CU (rows and columns that fit its slots)", m_pieces);
  set("runs", "array program runs (one job per CU each)", m_runs);
  set("runs_w8", "runs of the 8-pixel span class", m_class_runs[0]);
  set("runs_w16", "runs of the 16-pixel span class", m_class_runs[1]);
  set("runs_w32", "runs of the 32-pixel span class", m_class_runs[2]);
  set("cycles", "array cycles of the walking program", m_cycles);
  set("busy_lanes", "CUs given a job, summed over the runs (of runs x CUs)", m_busy_lanes);
  set("lane_rows", "rows the row loops ran, times the CUs, summed over the runs", m_lane_rows);
  set("walked_rows", "rows of pieces the CUs walked (of lane_rows: the rest is idle)", m_walked_rows);
  set("cu_utilisation_permille", "walked_rows per thousand lane_rows: how much of the array's row walking was useful",
      m_lane_rows == 0
          ? 0
          : static_cast<uint64_t>(1000.0 * static_cast<double>(m_walked_rows) / static_cast<double>(m_lane_rows)));
  set("pixels_emitted", "covered pixels in the box read back from the array", m_emitted);
  set("pixels_written", "pixels that passed the alpha and depth tests", m_written);
  set("loop_patches", "row-loop words rewritten before a run", m_loop_patches);
  set("ciu_words_written", "CMEM words the host wrote", m_words_written);
  set("ciu_words_read", "CMEM words the host read", m_words_read);
  renderers::publish_traffic(c, "ap_object", m_traffic);
  if (m_zpath != ZPath::unit) return;
  set("zbuf.frames_unit", "frames drawn on the z-buffer unit (ap.object.zpath=unit)", m_unit_frames);
  set("zbuf.frames_host", "frames drawn on the host path because a clear or draw call needs what the unit does not do",
      m_host_frames);
  set("zbuf.bands", "windows of frame rows drawn on the unit and copied (one per frame when the frame fits)", m_bands);
  set("zbuf.clears", "clears done by the unit (CONTROL.CLEAR)", m_unit_clears);
  set("zbuf.pixels_sent", "pixels the CUs sent to the unit (its PIXELS counter)", m_pixels_sent);
  set("zbuf.copied_bytes", "bytes of the unit's colour window copied into the back buffer", m_copied_bytes);
  set("zbuf.kept_triangles", "triangles kept for the unit until the frame is shown or read", m_kept_triangles);
  for (const auto& [key, frames] : m_fallbacks)
    set(("zbuf.fallback." + key).c_str(), "frames fallen back to the host path for this reason (README.md)", frames);
}

}  // namespace tessera::ap_object
