#include "renderers/ap_tile/ap_tile_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <iostream>
#include <optional>
#include <stdexcept>

#include "ap_programs/ap_tile.h"
#include "ap_programs/ap_tile_study.h"
#include "common/little_endian.h"
#include "common/pixel_format.h"
#include "costs/host_cost.h"
#include "gl/runtime.h"
#include "renderers/common/host_time.h"

namespace tessera::ap_tile {

namespace {

using Timed = renderers::TimedScope;
using costs::HostCost;

// The depth a clear stores: the value the depth plane gives that depth
// (tile_setup.cpp: z24 * 65535 / 65536 / 256, rounded).
uint16_t clear_depth16(uint32_t z24) {
  return static_cast<uint16_t>((uint64_t{z24} * 65535 + 65536 * 128) / (65536 * 256));
}

constexpr TileStage PASS_STAGES[] = {TileStage::fill, TileStage::depth, TileStage::colour, TileStage::texcoord};

// The planes read back, per row of a chunk: colour (two planes, or the
// study's three), tid, shi, slo, thi, tlo.
constexpr unsigned READ_PLANES = 8;

}  // namespace

ApTileRenderer::ApTileRenderer(AppEnvironment& env, Settings settings)
    : m_env(env),
      m_settings(settings),
      m_host(*env.host),
      m_display(env),
      m_array(env),
      m_dma(env),
      m_layout(CmemLayout::of(ap::programs::ap_tile())),
      m_bins(m_array.cus()) {
  m_frame.columns = m_array.columns();
  m_frame.rows = m_array.rows();
  m_frame.tile_width = m_layout.tile_width;
  m_frame.tile_height = m_layout.tile_height;
  if (m_display.width() != m_frame.width() || m_display.height() != m_frame.height())
    throw std::invalid_argument(
        "ap-tile: the array's " + std::to_string(m_frame.columns) + " x " + std::to_string(m_frame.rows) +
        " tiles of " + std::to_string(m_frame.tile_width) + " x " + std::to_string(m_frame.tile_height) +
        " pixels cover " + std::to_string(m_frame.width()) + " x " + std::to_string(m_frame.height()) +
        ", but the display is " + std::to_string(m_display.width()) + " x " + std::to_string(m_display.height()));
  const ap::Program& program = settings.study_program ? ap::programs::ap_tile_study() : ap::programs::ap_tile();
  m_cmem_bytes = cmem_extent(program);
  if (settings.study_program) {
    costs::charge(m_host, HostCost::ap_tile_study_start);
    m_study_layout = StudyLayout::of(program);
    m_read = {m_study_layout.rg_hi, m_study_layout.rg_lo, m_study_layout.b,    m_study_layout.tid,
              m_study_layout.s_hi,  m_study_layout.s_lo,  m_study_layout.t_hi, m_study_layout.t_lo};
  } else {
    m_read = {m_layout.chi, m_layout.clo, 0, m_layout.tid, m_layout.shi, m_layout.slo, m_layout.thi, m_layout.tlo};
  }
  m_array.load(program, m_program_base);
  for (TileStage stage : {TileStage::fill, TileStage::depth, TileStage::colour, TileStage::texcoord,
                          TileStage::clear_colour, TileStage::clear_depth})
    m_entry[static_cast<int>(stage)] = m_program_base + program.entries.at(stage_entry(stage));
  const renderers::DmaUse use = renderers::dma_use(env, m_dma);
  if (use.enabled) {
    m_tile_dma = std::make_unique<TileDma>(
        env, m_dma, settings.study_program ? DmaLayout::of(m_study_layout) : DmaLayout::of(m_layout), m_frame,
        use.broadcast);
    m_has_record.assign(m_frame.cus(), false);
    m_record_bytes.resize(size_t{settings.study_program ? m_study_layout.record_bytes : m_layout.record_bytes} *
                          m_frame.cus());
    m_rows.resize(size_t{m_frame.cus()} * READ_PLANES);
  }
  send_constants();
  m_live.assign(m_frame.cus(), false);
  m_rgba.assign(size_t{m_frame.width()} * m_frame.height(), 0xff000000u);
  if (settings.texture_warp) {
    // The resampler's DMA staging: lines as long as its program takes.
    const uint32_t bytes = use.enabled ? forward_texture::ArrayResampler::largest_staging(m_array.cus()) : 0;
    const uint32_t staging = bytes > 0 ? gl::allocate(bytes) : 0;
    m_resampler = std::make_unique<forward_texture::ArrayResampler>(env, m_time, staging, staging + bytes);
  }
}

// The constants: the tuned program's row heights yc[l] = TILE_H - 1 - l,
// 0 and `live` cleared, or the study's (write_study_constants_by_ciu).
void ApTileRenderer::send_constants() {
  if (m_tile_dma && m_settings.study_program) {
    send_study_constants_by_dma();
  } else if (m_settings.study_program) {
    write_study_constants_by_ciu();
  } else if (m_tile_dma) {
    std::vector<uint8_t> yc(m_frame.tile_height);
    for (unsigned l = 0; l < m_frame.tile_height; ++l) yc[l] = static_cast<uint8_t>(m_frame.tile_height - 1 - l);
    m_tile_dma->send_constants({{m_layout.yc, yc}, {m_layout.zero, {0}}, {m_layout.live, {0}}});
  } else {
    for (unsigned l = 0; l < m_frame.tile_height; ++l)
      m_array.fill8(m_layout.yc + l, static_cast<uint8_t>(m_frame.tile_height - 1 - l));
    m_array.fill8(m_layout.zero, 0);
    m_array.fill8(m_layout.live, 0);
    m_ciu_traffic.values_written += uint64_t{m_frame.cus()} * (m_frame.tile_height + 2);
  }
}

// The study's constants: the CU's grid position, 1, 0xff and the counter
// tables, once, as the study wrote them; and line 0 of every CU's record
// as 0 x + 0 y - 1, no pixel inside, because CMEM starts at 0, which puts
// every pixel inside every line (the study's program has no live flag).
void ApTileRenderer::write_study_constants_by_ciu() {
  const StudyLayout& m = m_study_layout;
  ArrayDriver::Constants constants;
  constants.xpos = m.xpos;
  constants.ypos = m.ypos;
  constants.one = m.one;
  constants.ones = m.ff;
  constants.x_counter = m.xcounter;
  constants.x_counter_length = m.tile_width;
  constants.y_counter = m.ycounter;
  constants.y_counter_length = m.tile_height;
  m_array.write_constants(constants);
  m_array.fill8(m.line_c, 0xff);
  m_array.fill8(m.line_c + 1, 0xff);
  m_ciu_traffic.values_written += uint64_t{m_frame.cus()} * (4 + m.tile_width + m.tile_height + 2);
}

// The study's constants through the DMA, as write_study_constants_by_ciu sends
// them through the CIU: XPOS and YPOS (each CU its own byte), 1, 0xff,
// the counter tables and line 0 of every CU's record (no pixel inside).
void ApTileRenderer::send_study_constants_by_dma() {
  const StudyLayout& m = m_study_layout;
  std::vector<uint8_t> xcounter(m.tile_width), ycounter(m.tile_height), xpos(m_frame.cus()), ypos(m_frame.cus());
  for (unsigned x = 0; x < m.tile_width; ++x) xcounter[x] = static_cast<uint8_t>(x);
  for (unsigned y = 0; y < m.tile_height; ++y) ycounter[y] = static_cast<uint8_t>(y);
  for (unsigned lane = 0; lane < m_frame.cus(); ++lane) {
    xpos[lane] = static_cast<uint8_t>(lane % m_frame.columns);
    ypos[lane] = static_cast<uint8_t>(lane / m_frame.columns);
  }
  m_tile_dma->send_constants(
      {{m.one, {1}}, {m.ff, {0xff}}, {m.xcounter, xcounter}, {m.ycounter, ycounter}, {m.line_c, {0xff, 0xff}}},
      {{m.xpos, xpos}, {m.ypos, ypos}});
}

void ApTileRenderer::unsupported(const std::string& what) {
  m_unsupported.report(m_env, what);
}

void ApTileRenderer::draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) {
  Timed timed(m_host, m_time, renderers::HostSplit::compute);
  costs::charge(m_host, HostCost::ap_tile_draw);
  const std::optional<DrawFlags> flags = draw_flags(state, m_frame.width(), m_frame.height(), m_textures,
                                                    [this](const std::string& what) { unsupported(what); });
  if (!flags) return;
  if (m_tiles_overwritten)
    unsupported(
        "drawing on a frame whose tiles a texture warp overwrote (ap.tile.texture_warp=array; clear the "
        "colour buffer after a present or glReadPixels): drawn on what the warp left");
  if (flags->tex != 0) m_frame_textured = true;
  if (m_settings.study_program && flags->depth_test) {
    if (flags->depth_lequal) unsupported("GL_LEQUAL with ap.tile.program=study: drawn as GL_LESS (z < buffer)");
    if (!flags->depth_write)
      unsupported("depth writes off with ap.tile.program=study: the depth of every pixel that passes is stored");
  }
  costs::charge(m_host, HostCost::ap_tile_triangle, count);
  if (flags->tex != 0) costs::charge(m_host, HostCost::ap_tile_textured_triangle, count);
  for (size_t t = 0; t < count; ++t) {
    TriangleSetup setup(triangles[t], *flags, m_frame);
    if (!setup.valid()) continue;
    const std::vector<unsigned> tiles = setup.tiles();
    costs::charge(m_host, HostCost::ap_tile_tile, tiles.size());
    if (tiles.empty()) continue;
    m_bins.add(setup, tiles);
    ++m_triangles_drawn;
    if (m_settings.texture_warp && flags->tex != 0) {
      costs::charge(m_host, HostCost::ap_tile_warp_triangle);
      m_warp_plan.add(flags->tex, triangles[t], m_textures.find(flags->tex)->texture);
    }
  }
}

void ApTileRenderer::write_group(unsigned i, unsigned j, const TileRecord* records) {
  std::vector<uint8_t>& bytes = m_record_bytes;
  bytes.resize(size_t{m_layout.record_bytes} * 4);
  for (unsigned k = 0; k < 4; ++k) encode_record(records[k], m_layout, bytes.data() + k * m_layout.record_bytes);
  costs::charge(m_host, HostCost::ap_tile_record_group);
  costs::charge(m_host, HostCost::ap_tile_record_word, m_layout.record_bytes);
  for (unsigned b = 0; b < m_layout.record_bytes; ++b) {
    uint32_t word = 0;
    for (unsigned k = 0; k < 4; ++k) word |= uint32_t{bytes[k * m_layout.record_bytes + b]} << (8 * k);
    m_array.write32(i, j, m_layout.record_first + b, word);
    ++m_words_written;
    m_ciu_traffic.values_written += 4;
  }
}

void ApTileRenderer::write_study_group(unsigned i, unsigned j, const StudyRecord* records) {
  const unsigned bytes_per_record = m_study_layout.record_bytes;
  std::vector<uint8_t>& bytes = m_record_bytes;
  bytes.resize(size_t{bytes_per_record} * 4);
  for (unsigned k = 0; k < 4; ++k) encode_study_record(records[k], m_study_layout, bytes.data() + k * bytes_per_record);
  costs::charge(m_host, HostCost::ap_tile_record_group);
  costs::charge(m_host, HostCost::ap_tile_record_word, bytes_per_record);
  for (unsigned b = 0; b < bytes_per_record; ++b) {
    uint32_t word = 0;
    for (unsigned k = 0; k < 4; ++k) word |= uint32_t{bytes[k * bytes_per_record + b]} << (8 * k);
    m_array.write32(i, j, m_study_layout.record_first + b, word);
    ++m_words_written;
    m_ciu_traffic.values_written += 4;
  }
}

void ApTileRenderer::run_stage(TileStage stage) {
  Timed timed(m_host, m_time, renderers::HostSplit::array_wait);
  costs::charge(m_host, HostCost::ap_tile_stage);
  m_stage_cycles[static_cast<int>(stage)] += m_array.run(m_entry[static_cast<int>(stage)]);
}

void ApTileRenderer::run_pass(bool depth) {
  const bool texcoords = m_frame_textured || m_settings.texcoords_always;
  for (TileStage stage : PASS_STAGES) {
    if (stage == TileStage::depth && !depth) continue;
    if (stage == TileStage::texcoord && !texcoords) continue;
    run_stage(stage);
  }
  costs::charge(m_host, HostCost::ap_tile_pass);
  ++m_passes;
}

void ApTileRenderer::flush() {
  const size_t passes = m_bins.passes();
  if (passes == 0) {
    m_bins.clear();
    return;
  }
  if (m_tile_dma)
    flush_by_dma(passes);
  else
    flush_by_ciu(passes);
  m_busiest = std::max<uint64_t>(m_busiest, passes);
  m_frame_busiest = std::max<uint64_t>(m_frame_busiest, passes);
  m_bins.clear();
  publish_statistics();
}

void ApTileRenderer::flush_by_ciu(size_t passes) {
  const unsigned groups = m_frame.columns / 4;
  for (size_t pass = 0; pass < passes; ++pass) {
    bool depth = false, untested = false;
    for (unsigned j = 0; j < m_frame.rows; ++j)
      for (unsigned i = 0; i < groups; ++i) {
        TileRecord records[4];
        StudyRecord study[4];
        bool any = false, was_live = false;
        {
          Timed timed(m_host, m_time, renderers::HostSplit::compute);
          costs::charge(m_host, HostCost::ap_tile_group);
          for (unsigned k = 0; k < 4; ++k) {
            const unsigned c = 4 * i + k, lane = j * m_frame.columns + c;
            was_live = was_live || m_live[lane];
            const TriangleSetup* setup = m_bins.at(lane, pass);
            if (setup == nullptr) continue;
            if (m_settings.study_program) {
              study[k] = setup->study_record(c, j);
              costs::charge(m_host, HostCost::ap_tile_study_record);
              records[k].live = study[k].live;
              records[k].zoff = !study[k].depth_test;
            } else {
              records[k] = setup->record(c, j);
            }
            costs::charge(m_host, HostCost::ap_tile_record);
            any = true;
            ++m_cu_triangles;
            depth = depth || !records[k].zoff;
            untested = untested || records[k].zoff;
          }
        }
        if (!any && !was_live) continue;
        Timed timed(m_host, m_time, renderers::HostSplit::array_write);
        if (any && m_settings.study_program) {
          write_study_group(i, j, study);
        } else if (any) {
          write_group(i, j, records);
        } else if (m_settings.study_program) {
          // Line 0 = 0 x + 0 y - 1 in the four CUs: no pixel inside.
          const StudyLayout& m = m_study_layout;
          for (unsigned a : {unsigned{m.line_a}, m.line_a + 1u, unsigned{m.line_b}, m.line_b + 1u})
            m_array.write32(i, j, a, 0);
          for (unsigned a : {unsigned{m.line_c}, m.line_c + 1u}) m_array.write32(i, j, a, 0xffffffffu);
          m_words_written += 6;
          m_ciu_traffic.values_written += 24;
        } else {
          m_array.write32(i, j, m_layout.live, 0);
          ++m_words_written;
          m_ciu_traffic.values_written += 4;
        }
        for (unsigned k = 0; k < 4; ++k) m_live[j * m_frame.columns + 4 * i + k] = records[k].live;
      }
    // The study's program tests depth in every CU of a pass that runs the
    // stage: it has no flag for a triangle drawn without the test.
    if (m_settings.study_program && depth && untested)
      unsupported("depth test off beside depth-tested triangles in one pass with ap.tile.program=study: tested");
    run_pass(depth);
  }
}

// Pass p's records are staged in buffer p % 2 while the DMA moves pass
// p - 1's out of the other; a buffer is staged again only after the DMA
// that read it has finished (its pass's stages ran after that DMA's
// interrupt), and a pass's stages start only after its records' DMA has.
void ApTileRenderer::flush_by_dma(size_t passes) {
  bool depth[2] = {stage_pass(0, 0), false};
  {
    Timed timed(m_host, m_time, renderers::HostSplit::array_write);
    m_tile_dma->start_records(0);
  }
  for (size_t pass = 0; pass < passes; ++pass) {
    const unsigned buffer = pass % 2, next = 1 - buffer;
    if (pass + 1 < passes) depth[next] = stage_pass(pass + 1, next);
    {
      Timed timed(m_host, m_time, renderers::HostSplit::array_write);
      m_tile_dma->wait_input();
    }
    run_pass(depth[buffer]);
    if (pass + 1 < passes) {
      Timed timed(m_host, m_time, renderers::HostSplit::array_write);
      m_tile_dma->start_records(next);
    }
  }
}

// Every CU's record of pass `pass` computed (as on the CIU path) and staged
// in buffer `buffer`; whether a record tests depth.
bool ApTileRenderer::stage_pass(size_t pass, unsigned buffer) {
  bool depth = false, untested = false;
  {
    Timed timed(m_host, m_time, renderers::HostSplit::compute);
    for (unsigned j = 0; j < m_frame.rows; ++j)
      for (unsigned c = 0; c < m_frame.columns; ++c) {
        const unsigned lane = j * m_frame.columns + c;
        const TriangleSetup* setup = m_bins.at(lane, pass);
        m_has_record[lane] = setup != nullptr;
        if (setup == nullptr) continue;
        bool tested = false;
        if (m_settings.study_program) {
          const StudyRecord record = setup->study_record(c, j);
          costs::charge(m_host, HostCost::ap_tile_record);
          costs::charge(m_host, HostCost::ap_tile_study_record);
          encode_study_record(record, m_study_layout,
                              m_record_bytes.data() + size_t{lane} * m_study_layout.record_bytes);
          tested = record.depth_test;
        } else {
          const TileRecord record = setup->record(c, j);
          costs::charge(m_host, HostCost::ap_tile_record);
          encode_record(record, m_layout, m_record_bytes.data() + size_t{lane} * m_layout.record_bytes);
          tested = !record.zoff;
        }
        costs::charge(m_host, HostCost::ap_tile_dma_record);
        ++m_cu_triangles;
        untested = untested || !tested;
        depth = depth || tested;
      }
  }
  if (m_settings.study_program && depth && untested)
    unsupported("depth test off beside depth-tested triangles in one pass with ap.tile.program=study: tested");
  Timed timed(m_host, m_time, renderers::HostSplit::array_write);
  m_tile_dma->stage_records(buffer, m_record_bytes, m_has_record);
  return depth;
}

void ApTileRenderer::clear(const gl::ClearRequest& request) {
  flush();
  costs::charge(m_host, HostCost::ap_tile_clear);
  switch (scissor_cover(request.scissor_test, request.scissor_x, request.scissor_y, request.scissor_width,
                        request.scissor_height, m_frame.width(), m_frame.height())) {
    case ScissorCover::none: return;
    case ScissorCover::part: unsupported("scissored clears: the whole frame is cleared"); break;
    case ScissorCover::whole: break;
  }
  if (request.color && (!request.color_mask[0] || !request.color_mask[1] || !request.color_mask[2]))
    unsupported("masked colour clears: every channel is cleared");
  if (request.color) {
    const uint32_t rgba = uint32_t{request.rgba[0]} | uint32_t{request.rgba[1]} << 8 | uint32_t{request.rgba[2]} << 16 |
                          uint32_t{request.rgba[3]} << 24;
    const auto packed = static_cast<uint16_t>(pack_pixel(PixelFormat::rgb565, rgba));
    {
      Timed timed(m_host, m_time, renderers::HostSplit::array_write);
      if (m_tile_dma && m_settings.study_program) {
        m_tile_dma->send_constants({{m_study_layout.clear_rg, {request.rgba[0], request.rgba[1]}},
                                    {m_study_layout.clear_b, {request.rgba[2]}}});
      } else if (m_tile_dma) {
        m_tile_dma->send_constants(
            {{m_layout.clear_c, {static_cast<uint8_t>(packed >> 8), static_cast<uint8_t>(packed)}}});
      } else if (m_settings.study_program) {
        m_array.fill8(m_study_layout.clear_rg, request.rgba[0]);
        m_array.fill8(m_study_layout.clear_rg + 1, request.rgba[1]);
        m_array.fill8(m_study_layout.clear_b, request.rgba[2]);
        m_words_written += 3 * m_frame.cus() / 4;
        m_ciu_traffic.values_written += 3 * m_frame.cus();
      } else {
        m_array.fill8(m_layout.clear_c, static_cast<uint8_t>(packed >> 8));
        m_array.fill8(m_layout.clear_c + 1, static_cast<uint8_t>(packed));
        m_words_written += 2 * m_frame.cus() / 4;
        m_ciu_traffic.values_written += 2 * m_frame.cus();
      }
    }
    run_stage(TileStage::clear_colour);
    m_textures.clear();
    m_warp_plan.clear();
    m_tiles_overwritten = false;
    m_frame_textured = false;
  }
  if (request.depth && request.depth_write) {
    const uint16_t z = clear_depth16(request.depth_value);
    {
      Timed timed(m_host, m_time, renderers::HostSplit::array_write);
      const uint16_t at = m_settings.study_program ? m_study_layout.clear_z : m_layout.clear_z;
      if (m_tile_dma) {
        m_tile_dma->send_constants({{at, {static_cast<uint8_t>(z >> 8), static_cast<uint8_t>(z)}}});
      } else {
        m_array.fill8(at, static_cast<uint8_t>(z >> 8));
        m_array.fill8(at + 1, static_cast<uint8_t>(z));
        m_words_written += 2 * m_frame.cus() / 4;
        m_ciu_traffic.values_written += 2 * m_frame.cus();
      }
    }
    run_stage(TileStage::clear_depth);
  }
}

uint32_t ApTileRenderer::shade_pixel(uint32_t rgba, unsigned tid, int16_t s, int16_t t, size_t index) {
  costs::charge(m_host, HostCost::ap_tile_pixel);
  if (m_settings.texture_warp && m_warp_plan.warped(tid)) {
    m_warp_pending.push_back({static_cast<uint32_t>(index), static_cast<uint8_t>(tid), s, t});
    return rgba;
  }
  if (const TextureEntry* entry = m_textures.find(tid)) {
    rgba = texture_pixel(*entry, rgba, s, t, [this](uint32_t address) { return m_host.load_span(address, 4, 1); });
    costs::charge(m_host, entry->texture.mag_filter == gl::TexFilter::nearest ? HostCost::ap_tile_texel_nearest
                                                                              : HostCost::ap_tile_texel_linear);
    costs::charge(m_host, HostCost::ap_tile_texture_environment);
  }
  return rgba;
}

void ApTileRenderer::read_back() {
  flush();
  if (m_tile_dma)
    read_back_by_dma();
  else
    read_back_by_ciu();
  if (!m_warp_pending.empty()) shade_warped();
}

void ApTileRenderer::read_back_by_ciu() {
  const unsigned groups = m_frame.columns / 4, width = m_frame.width();
  for (unsigned j = 0; j < m_frame.rows; ++j)
    for (unsigned i = 0; i < groups; ++i)
      for (unsigned x = 0; x < m_frame.tile_width; ++x)
        for (unsigned l = 0; l < m_frame.tile_height; ++l) {
          uint32_t hi, lo, blue = 0, tid = 0, s_hi = 0, s_lo = 0, t_hi = 0, t_lo = 0;
          {
            Timed timed(m_host, m_time, renderers::HostSplit::array_read);
            hi = m_array.read32(i, j, m_layout.pixel(m_read.hi, x, l));
            lo = m_array.read32(i, j, m_layout.pixel(m_read.lo, x, l));
            m_words_read += 2;
            m_ciu_traffic.values_read += 8;
            if (m_settings.study_program) {
              blue = m_array.read32(i, j, m_layout.pixel(m_read.blue, x, l));
              ++m_words_read;
              m_ciu_traffic.values_read += 4;
            }
            if (m_frame_textured) {
              tid = m_array.read32(i, j, m_layout.pixel(m_read.tid, x, l));
              if (tid != 0) {
                s_hi = m_array.read32(i, j, m_layout.pixel(m_read.s_hi, x, l));
                s_lo = m_array.read32(i, j, m_layout.pixel(m_read.s_lo, x, l));
                t_hi = m_array.read32(i, j, m_layout.pixel(m_read.t_hi, x, l));
                t_lo = m_array.read32(i, j, m_layout.pixel(m_read.t_lo, x, l));
                m_words_read += 4;
                m_ciu_traffic.values_read += 16;
              }
              ++m_words_read;
              m_ciu_traffic.values_read += 4;
            }
          }
          Timed timed(m_host, m_time, renderers::HostSplit::compute);
          costs::charge(m_host, HostCost::ap_tile_read_position);
          for (unsigned b = 0; b < 4; ++b) {
            const unsigned shift = 8 * b;
            // The study's program keeps 8 bits a channel (red, green, blue
            // bytes); the tuned one RGB565 in two.
            const uint32_t colour =
                m_settings.study_program
                    ? ((hi >> shift) & 0xff) | ((lo >> shift) & 0xff) << 8 | ((blue >> shift) & 0xff) << 16 |
                          0xff000000u
                    : unpack_pixel(PixelFormat::rgb565, ((hi >> shift) & 0xff) << 8 | ((lo >> shift) & 0xff));
            const auto s16 = static_cast<int16_t>(((s_hi >> shift) & 0xff) << 8 | ((s_lo >> shift) & 0xff));
            const auto t16 = static_cast<int16_t>(((t_hi >> shift) & 0xff) << 8 | ((t_lo >> shift) & 0xff));
            const unsigned column = (4 * i + b) * m_frame.tile_width + x;
            const unsigned row = j * m_frame.tile_height + l;
            const size_t index = size_t{row} * width + column;
            m_rgba[index] = shade_pixel(colour, (tid >> shift) & 0xff, s16, t16, index);
          }
        }
}

// Chunk x + 1 (and x + 2) on the DMA while the host converts chunk x:
// two chunks in flight, one per channel.
void ApTileRenderer::read_back_by_dma() {
  const unsigned chunks = m_tile_dma->chunks();
  {
    Timed timed(m_host, m_time, renderers::HostSplit::array_read);
    for (unsigned x = 0; x < std::min(chunks, 2u); ++x) m_tile_dma->start_chunk(x, m_frame_textured);
  }
  for (unsigned x = 0; x < chunks; ++x) {
    {
      Timed timed(m_host, m_time, renderers::HostSplit::array_read);
      m_tile_dma->wait_chunk(x);
    }
    convert_chunk(x);
    if (x + 2 < chunks) {
      Timed timed(m_host, m_time, renderers::HostSplit::array_read);
      m_tile_dma->start_chunk(x + 2, m_frame_textured);
    }
  }
}

// Tile column x of every tile from the staging frame: per row of the tile
// the bytes of every CU (LDRB each, no unpacking of CIU words), then the
// pixels shaded as on the CIU path. s and t are loaded only for rows with
// a textured pixel, as the CIU path reads them only for such groups.
void ApTileRenderer::convert_chunk(unsigned x) {
  const unsigned cus = m_frame.cus(), width = m_frame.width();
  uint8_t* hi = m_rows.data();
  uint8_t* lo = hi + cus;
  uint8_t* tid = lo + cus;
  uint8_t* s_hi = tid + cus;
  uint8_t* s_lo = s_hi + cus;
  uint8_t* t_hi = s_lo + cus;
  uint8_t* t_lo = t_hi + cus;
  uint8_t* blue = t_lo + cus;
  std::fill(tid, hi + READ_PLANES * cus, 0);
  auto load = [&](uint16_t plane, unsigned l, uint8_t* out) {
    std::memcpy(out, m_host.load_span(m_tile_dma->staged_row(plane, x, l), 1, cus), cus);
  };
  for (unsigned l = 0; l < m_frame.tile_height; ++l) {
    {
      Timed timed(m_host, m_time, renderers::HostSplit::array_read);
      load(m_read.hi, l, hi);
      load(m_read.lo, l, lo);
      if (m_settings.study_program) load(m_read.blue, l, blue);
      if (m_frame_textured) {
        load(m_read.tid, l, tid);
        if (std::any_of(tid, tid + cus, [](uint8_t t) { return t != 0; })) {
          load(m_read.s_hi, l, s_hi);
          load(m_read.s_lo, l, s_lo);
          load(m_read.t_hi, l, t_hi);
          load(m_read.t_lo, l, t_lo);
        }
      }
    }
    Timed timed(m_host, m_time, renderers::HostSplit::compute);
    costs::charge(m_host, HostCost::ap_tile_dma_chunk_row);
    for (unsigned lane = 0; lane < cus; ++lane) {
      const auto s16 = static_cast<int16_t>(s_hi[lane] << 8 | s_lo[lane]);
      const auto t16 = static_cast<int16_t>(t_hi[lane] << 8 | t_lo[lane]);
      const uint32_t colour =
          m_settings.study_program
              ? uint32_t{hi[lane]} | uint32_t{lo[lane]} << 8 | uint32_t{blue[lane]} << 16 | 0xff000000u
              : unpack_pixel(PixelFormat::rgb565, uint32_t{hi[lane]} << 8 | lo[lane]);
      const unsigned column = (lane % m_frame.columns) * m_frame.tile_width + x;
      const unsigned row = (lane / m_frame.columns) * m_frame.tile_height + l;
      const size_t index = size_t{row} * width + column;
      m_rgba[index] = shade_pixel(colour, tid[lane], s16, t16, index);
    }
  }
}

void ApTileRenderer::warp_refused(unsigned tid, const std::string& why) {
  m_warp_plan.refuse(tid, why);
  ++m_warp_refusals;
  const std::string message = "ap.tile.texture_warp=array: texture " + std::to_string(tid) +
                              " of this frame textured by look-ups on the host: " + why;
  if (m_env.warn)
    m_env.warn("ap-tile", message);
  else
    std::cerr << "warning: " << message << "\n";
}

// Each texture with waiting pixels warped once (its three colour channels),
// its pixels textured from the warped image by the texture environment;
// then the tiles' program gets its constants back (the warp's program
// overwrote CMEM: the frame was read back before, and the next frame
// starts with a clear, as after a present).
void ApTileRenderer::shade_warped() {
  std::vector<uint8_t> done(256, 0);  // 1: warped, 2: refused
  std::vector<WarpedTexture> warped(256);
  bool ran = false;
  const auto width = static_cast<int>(m_frame.width()), height = static_cast<int>(m_frame.height());
  for (const WarpPixel& pixel : m_warp_pending) {
    if (done[pixel.tid] != 0) continue;
    const TextureEntry& entry = *m_textures.find(pixel.tid);
    // The resampler times its own parts (writes, waits, reads) into m_time;
    // the rest is compute.
    const uint64_t parts_before = m_time.array_write + m_time.array_wait + m_time.array_read;
    renderers::HostTime whole;
    std::optional<Timed> timed(std::in_place, m_host, whole, renderers::HostSplit::compute);
    costs::charge(m_host, HostCost::ap_tile_warp_setup);
    WarpJob job(warp_filter(m_settings.texture_warp_width));
    std::string error = entry.texture.has_color
                            ? m_warp_plan.job(pixel.tid, entry.texture, width, height, m_resampler->max_texels(), job)
                            : "an alpha texture (its colour is the fragment's)";
    if (error.empty()) {
      int longest = 0;
      for (const WarpBand& band : job.bands())
        longest = std::max(longest, std::max(band.width, band.height) * band.upscale);
      error = m_resampler->check(warp_filter(m_settings.texture_warp_width), longest);
    }
    if (error.empty()) {
      ran = true;
      const gl::Texture& tex = entry.texture;
      uint64_t texels = 0;
      // The texture's own levels when GL would use them (levels > 1 only
      // with a mipmapped minification filter); else the job averages.
      const WarpJob::TexelSource source = [&](int level, int i, int j, uint8_t out[4]) {
        if (level >= static_cast<int>(tex.levels)) return false;
        const gl::TextureLevel& at = tex.level[level];
        const auto u = static_cast<uint32_t>(wrap_texel(i, static_cast<int>(at.width), tex.wrap_s));
        const auto v = static_cast<uint32_t>(wrap_texel(j, static_cast<int>(at.height), tex.wrap_t));
        copy_word(m_host.load_span(at.address + (v * at.width + u) * 4, 4, 1), out);
        return true;
      };
      WarpedTexture& out = warped[pixel.tid];
      error = job.run(source, m_resampler.get(), out, texels);
      costs::charge(m_host, HostCost::ap_tile_warp_texel, texels);
      costs::charge(m_host, HostCost::forward_texture_line, out.lines);
      uint64_t band_texels = 0;
      for (const WarpBand& band : job.bands())
        band_texels += uint64_t{static_cast<unsigned>(band.width * band.upscale)} *
                       static_cast<unsigned>(band.height * band.upscale);
      costs::charge(m_host, HostCost::forward_texture_texel_load, 3 * band_texels);
      costs::charge(m_host, HostCost::forward_texture_output_pixel,
                    uint64_t{3} * job.bands().size() * m_frame.width() * m_frame.height());
      m_warp_lines += out.lines;
      m_warp_borders += out.borders;
    }
    timed.reset();
    m_time.compute += whole.compute - (m_time.array_write + m_time.array_wait + m_time.array_read - parts_before);
    if (error.empty()) {
      done[pixel.tid] = 1;
      ++m_warps;
    } else {
      done[pixel.tid] = 2;
      warp_refused(pixel.tid, error);
    }
  }
  Timed timed(m_host, m_time, renderers::HostSplit::compute);
  for (const WarpPixel& pixel : m_warp_pending) {
    const TextureEntry& entry = *m_textures.find(pixel.tid);
    uint32_t& rgba = m_rgba[pixel.index];
    if (done[pixel.tid] == 1) {
      const auto x = static_cast<int>(pixel.index % m_frame.width());
      const int y = height - 1 - static_cast<int>(pixel.index / m_frame.width());
      uint8_t texel[4];
      warped[pixel.tid].texel(x, y, texel);
      rgba = renderers::apply_tex_env(entry.env, rgba, texel);
      costs::charge(m_host, HostCost::ap_tile_warp_pixel);
      ++m_warp_pixels;
    } else {
      rgba = texture_pixel(entry, rgba, pixel.s, pixel.t,
                           [this](uint32_t address) { return m_host.load_span(address, 4, 1); });
      costs::charge(m_host, entry.texture.mag_filter == gl::TexFilter::nearest ? HostCost::ap_tile_texel_nearest
                                                                               : HostCost::ap_tile_texel_linear);
    }
    costs::charge(m_host, HostCost::ap_tile_texture_environment);
  }
  m_warp_pending.clear();
  if (ran) {
    Timed write(m_host, m_time, renderers::HostSplit::array_write);
    m_array.load(m_settings.study_program ? ap::programs::ap_tile_study() : ap::programs::ap_tile(), m_program_base);
    send_constants();
    m_live.assign(m_frame.cus(), false);
    m_resampler->forget_loaded();
    m_tiles_overwritten = true;
  }
}

void ApTileRenderer::read_pixels(int x, int y, int width, int height, uint8_t* rgba) {
  read_back();
  read_frame_pixels(m_rgba, m_frame.width(), m_frame.height(), m_display.format(), x, y, width, height, rgba);
}

void ApTileRenderer::present() {
  read_back();
  {
    Timed timed(m_host, m_time, renderers::HostSplit::frame_out);
    const PixelFormat format = m_display.format();
    const unsigned bytes = bytes_per_pixel(format), width = m_frame.width();
    for (unsigned row = 0; row < m_frame.height(); ++row) {
      uint8_t* out = m_host.store_span(m_display.back_buffer() + row * m_display.stride(), bytes, width);
      for (unsigned column = 0; column < width; ++column)
        store_pixel(format, out + column * bytes, pack_pixel(format, m_rgba[size_t{row} * width + column]));
      costs::charge(m_host, HostCost::ap_tile_frame_out_pixel, width);
    }
    m_display.present();
  }
  m_unsupported.new_frame();
  publish_statistics();
  // This frame's figures: the totals' changes, and the busiest CU and the
  // CUs' occupancy (CUs with a triangle per pass) of this frame.
  const renderers::ArrayTraffic traffic = this->traffic();
  renderers::FrameFigures::Figures totals = {{"triangles", static_cast<double>(m_triangles_drawn)},
                                             {"cu_triangles", static_cast<double>(m_cu_triangles)},
                                             {"passes", static_cast<double>(m_passes)},
                                             {"ciu_words_written", static_cast<double>(m_words_written)},
                                             {"ciu_words_read", static_cast<double>(m_words_read)}};
  renderers::add_traffic(totals, traffic);
  for (TileStage stage : {TileStage::fill, TileStage::depth, TileStage::colour, TileStage::texcoord,
                          TileStage::clear_colour, TileStage::clear_depth})
    totals.emplace_back(std::string("cycles.") + stage_entry(stage),
                        static_cast<double>(m_stage_cycles[static_cast<int>(stage)]));
  renderers::add_host_time(totals, m_host, m_time);
  const double passes = m_frame_figures.change("passes", static_cast<double>(m_passes));
  const double cu_triangles = m_frame_figures.change("cu_triangles", static_cast<double>(m_cu_triangles));
  const double per_triangle = renderers::values_written_per_triangle(m_frame_figures, m_triangles_drawn, traffic);
  m_frame_figures.emit(m_env, totals,
                       {{"busiest_cu_triangles", static_cast<double>(m_frame_busiest)},
                        {"triangles_per_pass", passes > 0 ? cu_triangles / passes : 0.0},
                        {"cu_occupancy", passes > 0 ? cu_triangles / (passes * m_frame.cus()) : 0.0},
                        {"values_written_per_triangle", per_triangle}});
  m_frame_busiest = 0;
}

renderers::ArrayTraffic ApTileRenderer::traffic() const {
  renderers::ArrayTraffic traffic = m_ciu_traffic;
  if (m_tile_dma) traffic += m_tile_dma->traffic();
  if (m_resampler) traffic += m_resampler->figures().traffic;
  return traffic;
}

void ApTileRenderer::publish_statistics() {
  if (m_env.counters == nullptr) return;
  ActivityCounters& c = *m_env.counters;
  auto set = [&](const char* name, const char* description, uint64_t value) {
    c.counter(std::string("ap_tile.") + name, description).value = value;
  };
  renderers::publish_host_time(c, "ap_tile", m_host, m_time, "host time setting up, binning, packing and texturing");
  set("triangles", "triangles binned to at least one CU", m_triangles_drawn);
  set("cu_triangles", "triangle records written (one per CU per triangle)", m_cu_triangles);
  set("passes", "passes run (every CU at most one triangle per pass)", m_passes);
  set("busiest_cu_triangles", "most triangles one CU drew in one flush (the passes that flush needed)", m_busiest);
  set("ciu_words_written", "CMEM words the host wrote", m_words_written);
  set("ciu_words_read", "CMEM words the host read", m_words_read);
  set("cmem_bytes_per_cu", "CMEM bytes per CU the array program declares (ap.tile.program)", m_cmem_bytes);
  renderers::publish_traffic(c, "ap_tile", traffic());
  for (TileStage stage : {TileStage::fill, TileStage::depth, TileStage::colour, TileStage::texcoord,
                          TileStage::clear_colour, TileStage::clear_depth})
    c.counter(std::string("ap_tile.cycles.") + stage_entry(stage), "array cycles of the program's stage").value =
        m_stage_cycles[static_cast<int>(stage)];
  if (m_resampler) {
    const forward_texture::ArrayResampler::Figures& f = m_resampler->figures();
    set("warp.textures", "textures warped on the array (each once a frame, three colour channels)", m_warps);
    set("warp.refused", "textures of a frame textured by look-ups instead (each warned)", m_warp_refusals);
    set("warp.pixels", "pixels textured from a warped image", m_warp_pixels);
    set("warp.lines", "lines of the warps' two passes (every channel)", m_warp_lines);
    set("warp.borders", "texel borders of the warps' two passes (every channel)", m_warp_borders);
    set("warp.array_runs", "runs of the warp's array program (a batch of one line per CU each)", f.runs);
    set("warp.array_cycles", "array cycles of the warp's program runs", f.cycles);
  }
}

}  // namespace tessera::ap_tile
