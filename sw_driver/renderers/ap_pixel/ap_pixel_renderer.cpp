#include "renderers/ap_pixel/ap_pixel_renderer.h"

#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "common/fixed_function.h"
#include "common/pixel_format.h"
#include "costs/host_cost.h"
#include "gl/runtime.h"
#include "renderers/common/fragment_ops.h"
#include "renderers/common/texture_units.h"
#include "renderers/common/texturing.h"

namespace tessera::ap_pixel {

namespace {

using costs::HostCost;
using renderers::TimedScope;

// The offsets a CU multiplies by are signed bytes, so every block of a
// triangle lies within 128 pixels of its origin: frames up to this size.
constexpr unsigned MAX_FRAME = 256;

}  // namespace

ApPixelRenderer::ApPixelRenderer(AppEnvironment& env, unsigned block, ProgramVariant program)
    : m_env(env),
      m_host(*env.host),
      m_frame(env),
      m_array(env),
      m_dma(env),
      m_layout(PixelLayout::of(program)),
      m_block(block) {
  if (m_frame.buffers.width > MAX_FRAME || m_frame.buffers.height > MAX_FRAME)
    throw std::invalid_argument("ap-pixel: the display is " + std::to_string(m_frame.buffers.width) + " x " +
                                std::to_string(m_frame.buffers.height) +
                                ", but a CU's block offsets are signed bytes, so " +
                                "the back end draws frames of at most " + std::to_string(MAX_FRAME) + " x " +
                                std::to_string(MAX_FRAME) + " pixels");
  if (m_block < 1 || m_block > m_layout.max_block)
    throw std::invalid_argument("ap-pixel: block size " + std::to_string(m_block) + " is outside 1.." +
                                std::to_string(m_layout.max_block));
  m_array.load(program_of(program), m_program_base);
  const unsigned across = (m_frame.buffers.width + m_block - 1) / m_block,
                 up = (m_frame.buffers.height + m_block - 1) / m_block;
  m_block_index.assign(size_t{across} * up, -1);

  m_dma_use = renderers::dma_use(env, m_dma);
  if (m_dma_use.enabled) {
    // The values' ranges, merged where the program's variables touch.
    const unsigned values = m_layout.value_bytes * ATTRIBUTES;
    for (unsigned start : {unsigned{m_layout.c0}, unsigned{m_layout.gx}, unsigned{m_layout.gy}}) {
      if (!m_value_ranges.empty() && m_value_ranges.back().cmem + m_value_ranges.back().bytes == start)
        m_value_ranges.back().bytes += values;
      else
        m_value_ranges.push_back({start, values});
      m_value_bytes += values;
    }
    const unsigned cus = m_array.cus(), slots = m_layout.max_block * m_layout.max_block;
    m_stage_values = gl::allocate(m_value_bytes * cus);
    for (unsigned buffer = 0; buffer < 2; ++buffer) {
      m_stage_offsets[buffer] = gl::allocate(2 * cus);
      m_stage_results[buffer] = gl::allocate(slots * m_layout.value_bytes * ATTRIBUTES * cus);
    }
    m_chain_in = gl::allocate(static_cast<uint32_t>((m_value_ranges.size() + 2) * dma::DESCRIPTOR_BYTES));
    m_chain_out = gl::allocate(slots * dma::DESCRIPTOR_BYTES);
    m_out_channel = m_dma.channels() >= 2 ? 1 : 0;
  }
}

void ApPixelRenderer::unsupported(const std::string& what) {
  m_unsupported.report(m_env, what);
}

void ApPixelRenderer::clear(const gl::ClearRequest& request) {
  TimedScope timed(m_host, m_time, renderers::HostSplit::compute);
  m_frame.core->clear(request);
}

void ApPixelRenderer::read_pixels(int x, int y, int width, int height, uint8_t* rgba) {
  TimedScope timed(m_host, m_time, renderers::HostSplit::compute);
  m_frame.core->read_pixels(x, y, width, height, rgba);
}

void ApPixelRenderer::present() {
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::frame_out);
    m_frame.present();
  }
  m_unsupported.new_frame();
  publish_statistics();
  renderers::FrameFigures::Figures totals = {{"triangles", static_cast<double>(m_triangles)},
                                             {"visible_pixels", static_cast<double>(m_visible)},
                                             {"blocks", static_cast<double>(m_blocks_sent)},
                                             {"passes", static_cast<double>(m_batches)},
                                             {"cycles", static_cast<double>(m_cycles)},
                                             {"host_shaded_triangles", static_cast<double>(m_host_shaded)},
                                             {"ciu_words_written", static_cast<double>(m_words_written)},
                                             {"ciu_words_read", static_cast<double>(m_words_read)}};
  renderers::add_traffic(totals, m_traffic);
  renderers::add_host_time(totals, m_host, m_time);
  m_frame_figures.emit(m_env, totals,
                       {{"values_written_per_triangle",
                         renderers::values_written_per_triangle(m_frame_figures, m_triangles, m_traffic)}});
}

void ApPixelRenderer::draw(const gl::RasterState& state, const gl::Triangle* triangles, size_t count) {
  // Everything the host does here is computing except the array's own
  // parts, which their scopes charge.
  const uint64_t start = m_host.now_cycles();
  const renderers::HostTime before = m_time;
  const renderers::CostSplit split(renderers::HostSplit::compute);
  if (state.stencil_test) unsupported("the stencil test (GL_STENCIL_TEST): drawn without it");
  if (state.fog) unsupported("fog (GL_FOG): drawn without it");
  m_unit = renderers::single_texture_unit(state, [this](const std::string& what) { unsupported(what); });
  const gl::Texture tex = m_unit.index >= 0 ? state.unit[m_unit.index].tex : gl::Texture{};
  const bool textured = m_unit.index >= 0 && tex.width > 0 && tex.height > 0 && tex.width <= 256 && tex.height <= 256 &&
                        (tex.width & (tex.width - 1)) == 0 && (tex.height & (tex.height - 1)) == 0;
  if (m_unit.index >= 0 && !textured)
    unsupported("textures that are not a power of two up to 256 texels: drawn untextured");
  if (textured && renderers::env_needs_base_format(tex, m_unit.env))
    unsupported(
        "textures without alpha under GL_REPLACE and GL_ALPHA textures under GL_MODULATE or GL_REPLACE (ES 1.1 table "
        "3.15): drawn with the texel expanded to RGBA");
  if (textured && renderers::texture_needs_lod(tex))
    unsupported(
        "mipmaps and a minification filter other than the magnification filter (GL_TEXTURE_MIN_FILTER): level 0 "
        "sampled with the magnification filter");
  Reads reads;
  reads.colour = !state.flat_shading;
  reads.alpha =
      reads.colour && (state.alpha_test || state.blend || m_frame.buffers.color_format != PixelFormat::rgb565 ||
                       (textured && m_unit.env != gl::TexEnv::replace));
  reads.texcoords = textured;
  for (size_t t = 0; t < count; ++t) draw_triangle(state, triangles[t], reads);
  const uint64_t elsewhere = (m_time.array_write - before.array_write) + (m_time.array_read - before.array_read) +
                             (m_time.array_wait - before.array_wait);
  m_time.compute += m_host.now_cycles() - start - elsewhere;
}

void ApPixelRenderer::draw_triangle(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads) {
  costs::charge(m_host, HostCost::ap_pixel_triangle);
  PixelBox box{0, 0, static_cast<int>(m_frame.buffers.width) - 1, static_cast<int>(m_frame.buffers.height) - 1};
  if (state.scissor_test) {
    box.x0 = std::max(box.x0, state.scissor_x);
    box.y0 = std::max(box.y0, state.scissor_y);
    box.x1 = static_cast<int>(std::min<int64_t>(box.x1, int64_t{state.scissor_x} + state.scissor_width - 1));
    box.y1 = static_cast<int>(std::min<int64_t>(box.y1, int64_t{state.scissor_y} + state.scissor_height - 1));
  }
  const gl::Texture* tex = reads.texcoords ? &state.unit[m_unit.index].tex : nullptr;
  const PixelTriangle setup(triangle, state.flat_shading, tex ? tex->width : 0, tex ? tex->height : 0, box,
                            tex ? static_cast<unsigned>(m_unit.index) : 0);
  if (!setup.valid()) return;

  // Scan conversion and the depth test, on the host.
  m_pixels.clear();
  m_blocks.clear();
  const unsigned b = m_block, across = (m_frame.buffers.width + b - 1) / b;
  std::vector<uint16_t>& depth_row = m_depth_row;
  for (int j = setup.y_first(); j <= setup.y_last(); ++j) {
    costs::charge(m_host, HostCost::ap_pixel_row);
    int first = 0, last = -1;
    if (!setup.span(j, first, last)) continue;
    const auto n = static_cast<unsigned>(last - first + 1);
    costs::charge(m_host, HostCost::ap_pixel_span_pixel, n);
    const uint32_t row = (m_frame.buffers.height - 1 - static_cast<uint32_t>(j)) * m_frame.buffers.width;
    if (state.depth_test) {
      const uint8_t* p =
          m_host.load_span(m_frame.buffers.depth_address + (row + static_cast<uint32_t>(first)) * 2, 2, n);
      depth_row.resize(n);
      for (unsigned i = 0; i < n; ++i) depth_row[i] = static_cast<uint16_t>(p[2 * i] | p[2 * i + 1] << 8);
    }
    for (unsigned i = 0; i < n; ++i) {
      const int x = first + static_cast<int>(i);
      const uint16_t z = setup.depth16(x, j);
      if (state.depth_test && !compare_passes(state.depth_func, z, depth_row[i])) continue;
      const size_t key = size_t{static_cast<unsigned>(j) / b} * across + static_cast<unsigned>(x) / b;
      if (m_block_index[key] < 0) {
        m_block_index[key] = static_cast<int32_t>(m_blocks.size());
        m_blocks.push_back(
            {x / static_cast<int>(b) * static_cast<int>(b), j / static_cast<int>(b) * static_cast<int>(b)});
      }
      m_pixels.push_back({x, j, z, static_cast<uint32_t>(m_block_index[key])});
    }
  }
  for (const Block& block : m_blocks)
    m_block_index[size_t{static_cast<unsigned>(block.y) / b} * across + static_cast<unsigned>(block.x) / b] = -1;
  costs::charge(m_host, HostCost::ap_pixel_visible, m_pixels.size());
  if (m_pixels.empty()) return;
  ++m_triangles;
  m_visible += m_pixels.size();

  if (!reads.any()) {
    // Flat and untextured: the host knows every pixel's colour.
    const gl::ScreenVertex& v = triangle.v[2];
    const uint32_t rgba = uint32_t{v.r} | uint32_t{v.g} << 8 | uint32_t{v.b} << 16 | uint32_t{v.a} << 24;
    for (const Pixel& pixel : m_pixels) write_pixel(state, pixel, rgba, nullptr, false);
    return;
  }

  // Each block's pixels.
  costs::charge(m_host, HostCost::ap_pixel_array_triangle);
  costs::charge(m_host, HostCost::ap_pixel_block, m_blocks.size());
  m_block_pixels.assign(m_blocks.size(), {});
  for (size_t p = 0; p < m_pixels.size(); ++p) m_block_pixels[m_pixels[p].block].push_back(static_cast<uint32_t>(p));

  // The origin: the middle of the blocks, so that every offset fits a
  // signed byte.
  int x_lo = m_blocks[0].x, x_hi = x_lo, y_lo = m_blocks[0].y, y_hi = y_lo;
  for (const Block& block : m_blocks) {
    x_lo = std::min(x_lo, block.x);
    x_hi = std::max(x_hi, block.x);
    y_lo = std::min(y_lo, block.y);
    y_hi = std::max(y_hi, block.y);
  }
  const int ox = (x_lo + x_hi + 1) / 2, oy = (y_lo + y_hi + 1) / 2;
  const TriangleValues values = setup.values(ox, oy);
  bool representable = true;
  for (Attribute a : {Attribute::red, Attribute::green, Attribute::blue, Attribute::alpha})
    representable = representable && (!reads.colour || !values.clamped[static_cast<unsigned>(a)]);
  for (Attribute a : {Attribute::s, Attribute::t})
    representable = representable && (!reads.texcoords || !values.clamped[static_cast<unsigned>(a)]);
  if (!representable) {
    // A sliver whose gradients 8.8 cannot hold: the host evaluates the
    // planes at each pixel itself (README.md, "Slivers").
    ++m_host_shaded;
    for (const Pixel& pixel : m_pixels) {
      const TriangleValues at = setup.values(pixel.x, pixel.y);
      costs::charge(m_host, HostCost::ap_pixel_sliver_pixel);
      std::array<int32_t, ATTRIBUTES> r{};
      for (unsigned a = 0; a < ATTRIBUTES; ++a) r[a] = static_cast<int32_t>(at.c0[a] << 8) >> 8;
      write_shaded(state, triangle, reads, pixel, r);
    }
    return;
  }
  if (m_dma_use.enabled) {
    draw_batches_dma(state, triangle, reads, values, ox, oy);
    return;
  }
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
    for_each_value_byte(values, m_layout, [&](unsigned address, uint8_t byte) {
      costs::charge(m_host, HostCost::ap_pixel_value_byte);
      m_array.fill8(address, byte);
      m_words_written += m_array.cus() / 4;
      m_traffic.values_written += m_array.cus();
    });
  }
  for (size_t first = 0; first < m_blocks.size(); first += m_array.cus())
    run_batch(state, triangle, reads, first, std::min<size_t>(m_array.cus(), m_blocks.size() - first), ox, oy);
}

void ApPixelRenderer::run_batch(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads,
                                size_t first_block, size_t blocks, int ox, int oy) {
  const unsigned columns = m_array.columns(), b = m_block;
  costs::charge(m_host, HostCost::ap_pixel_batch);
  const unsigned groups = static_cast<unsigned>((blocks + 3) / 4);  // groups holding a block, in CU order
  auto lane_block = [&](unsigned group, unsigned byte) -> const Block* {
    const size_t lane = size_t{group} * 4 + byte;
    return lane < blocks ? &m_blocks[first_block + lane] : nullptr;
  };
  // The blocks' offsets: one word of dx and one of dy per group of four CUs.
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
    for (unsigned g = 0; g < groups; ++g) {
      uint32_t dx = 0, dy = 0;
      for (unsigned byte = 0; byte < 4; ++byte)
        if (const Block* block = lane_block(g, byte)) {
          dx |= uint32_t{static_cast<uint8_t>(block->x - ox)} << (8 * byte);
          dy |= uint32_t{static_cast<uint8_t>(block->y - oy)} << (8 * byte);
        }
      const unsigned i = g % (columns / 4), j = g / (columns / 4);
      costs::charge(m_host, HostCost::ap_pixel_offset_group);
      m_array.write32(i, j, m_layout.dx, dx);
      m_array.write32(i, j, m_layout.dy, dy);
      m_words_written += 2;
      m_traffic.values_written += 8;
    }
  }
  {
    TimedScope timed(m_host, m_time, renderers::HostSplit::array_wait);
    m_cycles += m_array.run(m_program_base + m_layout.entry[b]);
  }
  ++m_batches;
  m_blocks_sent += blocks;

  // What comes back: per pixel of the block that the host drew, the
  // attributes it needs, byte by byte (README.md, "What the host reads").
  Needed needed[6];
  const unsigned needs = needed_reads(reads, needed);
  m_results.resize(m_pixels.size());
  for (unsigned g = 0; g < groups; ++g) {
    const unsigned i = g % (columns / 4), j = g / (columns / 4);
    // The group's pixels by place: slot v * b + u of each of its four CUs.
    int32_t slot_pixel[4][25];
    std::fill(&slot_pixel[0][0], &slot_pixel[0][0] + 4 * 25, -1);
    uint32_t used = 0;
    for (unsigned byte = 0; byte < 4; ++byte) {
      if (lane_block(g, byte) == nullptr) continue;
      const size_t index = first_block + size_t{g} * 4 + byte;
      const Block& block = m_blocks[index];
      for (uint32_t p : m_block_pixels[index]) {
        const unsigned slot =
            static_cast<unsigned>(m_pixels[p].y - block.y) * b + static_cast<unsigned>(m_pixels[p].x - block.x);
        slot_pixel[byte][slot] = static_cast<int32_t>(p);
        used |= 1u << slot;
      }
    }
    for (unsigned v = 0; v < b; ++v)
      for (unsigned u = 0; u < b; ++u) {
        if ((used & (1u << (v * b + u))) == 0) continue;
        costs::charge(m_host, HostCost::ap_pixel_result_place);
        for (unsigned n = 0; n < needs; ++n) {
          const Needed& need = needed[n];
          uint32_t word[3] = {0, 0, 0};
          {
            TimedScope timed(m_host, m_time, renderers::HostSplit::array_read);
            for (unsigned byte = 0; byte < need.bytes; ++byte)
              word[byte] = m_array.read32(i, j, m_layout.result(u, v, need.attribute) + byte);
            m_words_read += need.bytes;
            m_traffic.values_read += 4 * need.bytes;
          }
          for (unsigned lane = 0; lane < 4; ++lane) {
            const int32_t p = slot_pixel[lane][v * b + u];
            if (p < 0) continue;
            uint32_t value = 0;
            for (unsigned byte = 0; byte < m_layout.value_bytes; ++byte)
              value = value << 8 | (byte < need.bytes ? (word[byte] >> (8 * lane)) & 0xff : 0);
            m_results[static_cast<size_t>(p)][static_cast<unsigned>(need.attribute)] =
                result_value(state, need.attribute, value);
            costs::charge(m_host, HostCost::ap_pixel_result_byte, need.bytes);
          }
        }
      }
  }

  // The pixels, into the frame buffer.
  for (size_t index = first_block; index < first_block + blocks; ++index)
    for (uint32_t p : m_block_pixels[index]) write_shaded(state, triangle, reads, m_pixels[p], m_results[p]);
}

unsigned ApPixelRenderer::needed_reads(const Reads& reads, Needed needed[6]) const {
  unsigned needs = 0;
  if (reads.colour)
    for (Attribute a : {Attribute::red, Attribute::green, Attribute::blue}) needed[needs++] = {a, 2};
  if (reads.alpha) needed[needs++] = {Attribute::alpha, 2};
  if (reads.texcoords) {
    needed[needs++] = {Attribute::s, m_layout.value_bytes};
    needed[needs++] = {Attribute::t, m_layout.value_bytes};
  }
  return needs;
}

// A result's code (big-endian, value_bytes of it, the bytes not read 0) as
// 16.8. tuned: sign-extended from 24 bits. study: 8.8 modulo 2^16, so the
// host picks the window of 256 units the value lies in: colour and alpha
// in 0..255, S and T within 128 texels of the texture's middle (exact for
// a texture of up to 256 texels under GL_REPEAT, which wraps at its size
// anyway; README.md, "The study program").
int32_t ApPixelRenderer::result_value(const gl::RasterState& state, Attribute attribute, uint32_t code) const {
  if (m_layout.value_bytes == 3) return static_cast<int32_t>(code << 8) >> 8;
  if (attribute != Attribute::s && attribute != Attribute::t) return static_cast<int32_t>(code);
  const gl::Texture& tex = state.unit[m_unit.index].tex;
  const uint32_t size = attribute == Attribute::s ? tex.width : tex.height;
  const uint32_t window_end = (size / 2 + 128) * 256;
  return static_cast<int32_t>(code) - (code >= window_end ? 0x10000 : 0);
}

// The batches of one triangle through the DMA (README.md, "With the DMA"):
// the host stages batch n's offsets while the array runs batch n - 1, the
// DMA brings batch n - 1's results out as soon as the array has finished,
// the host starts batch n and then unpacks and writes batch n - 1's pixels
// while batch n runs. A triangle's batches drain before the next triangle
// is scan-converted, whose depth test needs this one's depths.
void ApPixelRenderer::draw_batches_dma(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads,
                                       const TriangleValues& values, int ox, int oy) {
  const unsigned cus = m_array.cus(), b = m_block;
  Needed needed[6];
  const unsigned needs = needed_reads(reads, needed);
  unsigned first_byte = m_layout.value_bytes * ATTRIBUTES, last_byte = 0;
  for (unsigned n = 0; n < needs; ++n) {
    const unsigned at = m_layout.value_bytes * static_cast<unsigned>(needed[n].attribute);
    first_byte = std::min(first_byte, at);
    last_byte = std::max(last_byte, at + needed[n].bytes - 1);
  }
  const unsigned rows = last_byte - first_byte + 1;  // bytes of a slot brought out per CU

  std::vector<dma::Descriptor> in;
  {
    // The 21 values, once per triangle: by broadcast, or replicated for
    // every CU and reshuffled.
    TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
    std::vector<uint8_t> bytes(m_value_bytes, 0);
    for_each_value_byte(values, m_layout, [&](unsigned address, uint8_t byte) {
      costs::charge(m_host, HostCost::ap_pixel_dma_value_byte);
      unsigned offset = 0;
      for (const Range& range : m_value_ranges) {
        if (address >= range.cmem && address < range.cmem + range.bytes) bytes[offset + address - range.cmem] = byte;
        offset += range.bytes;
      }
    });
    unsigned offset = 0;
    if (m_dma_use.broadcast) {
      std::memcpy(m_host.store_span(m_stage_values, 1, m_value_bytes), bytes.data(), m_value_bytes);
      for (const Range& range : m_value_ranges) {
        in.push_back(DmaDriver::broadcast(m_stage_values + offset, range.cmem, range.bytes));
        offset += range.bytes;
        m_traffic.values_written += range.bytes;
      }
    } else {
      uint8_t* out = m_host.store_span(m_stage_values, 4, m_value_bytes * cus / 4);
      for (unsigned row = 0; row < m_value_bytes; ++row) std::memset(out + size_t{row} * cus, bytes[row], cus);
      costs::charge(m_host, HostCost::ap_pixel_dma_value_word_replicated, uint64_t{m_value_bytes} * cus / 4);
      for (const Range& range : m_value_ranges) {
        in.push_back(DmaDriver::to_cmem(m_stage_values + offset * cus, range.cmem, range.bytes * cus, 1));
        offset += range.bytes;
        m_traffic.values_written += uint64_t{range.bytes} * cus;
      }
    }
  }

  DmaBatch running;  // the batch on the array, its results on their way out
  bool pending = false;
  auto finish = [&](const DmaBatch& batch) {
    {
      TimedScope timed(m_host, m_time, renderers::HostSplit::array_wait);
      m_cycles += m_array.wait();
    }
    if (batch.slot_row.empty()) return;
    {
      TimedScope timed(m_host, m_time, renderers::HostSplit::array_read);
      m_dma.wait(m_out_channel);
    }
    collect_dma_batch(state, triangle, reads, batch);
  };
  for (size_t first = 0, n = 0; first < m_blocks.size(); first += cus, ++n) {
    DmaBatch batch;
    batch.first_block = first;
    batch.blocks = std::min<size_t>(cus, m_blocks.size() - first);
    batch.buffer = static_cast<unsigned>(n % 2);
    {
      // The blocks' offsets, dx of every CU and then dy, in CU order.
      TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
      uint8_t* p = m_host.store_span(m_stage_offsets[batch.buffer], 1, 2 * cus);
      std::memset(p, 0, 2 * cus);
      for (size_t lane = 0; lane < batch.blocks; ++lane) {
        const Block& block = m_blocks[first + lane];
        p[lane] = static_cast<uint8_t>(block.x - ox);
        p[cus + lane] = static_cast<uint8_t>(block.y - oy);
      }
      costs::charge(m_host, HostCost::ap_pixel_batch);
      costs::charge(m_host, HostCost::ap_pixel_dma_block, batch.blocks);
      if (m_layout.dy == m_layout.dx + 1) {
        in.push_back(DmaDriver::to_cmem(m_stage_offsets[batch.buffer], m_layout.dx, 2 * cus, 1));
      } else {
        in.push_back(DmaDriver::to_cmem(m_stage_offsets[batch.buffer], m_layout.dx, cus, 1));
        in.push_back(DmaDriver::to_cmem(m_stage_offsets[batch.buffer] + cus, m_layout.dy, cus, 1));
      }
      m_traffic.values_written += 2 * cus;
    }
    if (pending) {
      // The previous batch's results must be out of CMEM before this
      // batch's program overwrites them (the host then unpacks them while
      // this batch runs).
      {
        TimedScope timed(m_host, m_time, renderers::HostSplit::array_wait);
        m_cycles += m_array.wait();
      }
      if (!running.slot_row.empty()) {
        TimedScope timed(m_host, m_time, renderers::HostSplit::array_read);
        m_dma.wait(m_out_channel);
      }
    }
    {
      TimedScope timed(m_host, m_time, renderers::HostSplit::array_write);
      costs::charge(m_host, HostCost::ap_pixel_dma_descriptor, in.size());
      m_traffic.dma_descriptors += in.size();
      m_dma.write_chain(m_chain_in, in);
      m_dma.start_chain(0, m_chain_in);
      m_dma.wait(0);
      in.clear();
    }
    m_array.start(m_program_base + m_layout.entry[b]);
    ++m_batches;
    m_blocks_sent += batch.blocks;

    // The results of the slots some block of the batch uses, one
    // descriptor per slot: its bytes of every CU, row by row.
    std::vector<bool> used(size_t{b} * b, false);
    for (size_t index = first; index < first + batch.blocks; ++index)
      for (uint32_t p : m_block_pixels[index]) {
        const Pixel& pixel = m_pixels[p];
        used[static_cast<size_t>(pixel.y - m_blocks[index].y) * b + static_cast<size_t>(pixel.x - m_blocks[index].x)] =
            true;
      }
    if (needs > 0) {
      TimedScope timed(m_host, m_time, renderers::HostSplit::array_read);
      std::vector<dma::Descriptor> out;
      batch.slot_row.assign(size_t{b} * b, -1);
      for (unsigned v = 0; v < b; ++v)
        for (unsigned u = 0; u < b; ++u) {
          if (!used[size_t{v} * b + u]) continue;
          const auto row = static_cast<int32_t>(out.size() * rows);
          batch.slot_row[size_t{v} * b + u] = row;
          out.push_back(DmaDriver::from_cmem(m_layout.result(u, v, Attribute::red) + first_byte,
                                             m_stage_results[batch.buffer] + static_cast<uint32_t>(row) * cus,
                                             rows * cus, 1));
          m_traffic.values_read += uint64_t{rows} * cus;
        }
      costs::charge(m_host, HostCost::ap_pixel_dma_descriptor, out.size());
      m_traffic.dma_descriptors += out.size();
      m_dma.write_chain(m_chain_out, out);
      m_dma.start_chain(m_out_channel, m_chain_out);
    }
    if (pending) collect_dma_batch(state, triangle, reads, running);
    running = std::move(batch);
    pending = true;
  }
  if (pending) finish(running);
}

// Unpacks a batch's results from the staging buffer (one byte per CU per
// row, README.md) and writes its pixels.
void ApPixelRenderer::collect_dma_batch(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads,
                                        const DmaBatch& batch) {
  const unsigned cus = m_array.cus(), b = m_block;
  Needed needed[6];
  const unsigned needs = needed_reads(reads, needed);
  unsigned first_byte = m_layout.value_bytes * ATTRIBUTES;
  for (unsigned n = 0; n < needs; ++n)
    first_byte = std::min(first_byte, m_layout.value_bytes * static_cast<unsigned>(needed[n].attribute));
  const uint32_t base = m_stage_results[batch.buffer];
  m_results.resize(m_pixels.size());
  for (size_t lane = 0; lane < batch.blocks; ++lane) {
    const size_t index = batch.first_block + lane;
    const Block& block = m_blocks[index];
    for (uint32_t p : m_block_pixels[index]) {
      const Pixel& pixel = m_pixels[p];
      const unsigned slot = static_cast<unsigned>(pixel.y - block.y) * b + static_cast<unsigned>(pixel.x - block.x);
      const auto row0 = static_cast<uint32_t>(batch.slot_row[slot]);
      for (unsigned n = 0; n < needs; ++n) {
        const Needed& need = needed[n];
        const unsigned at = m_layout.value_bytes * static_cast<unsigned>(need.attribute) - first_byte;
        uint32_t value = 0;
        for (unsigned byte = 0; byte < m_layout.value_bytes; ++byte) {
          uint32_t got = 0;
          if (byte < need.bytes)
            got = *m_host.load_span(base + (row0 + at + byte) * cus + static_cast<uint32_t>(lane), 1, 1);
          value = value << 8 | got;
        }
        m_results[p][static_cast<unsigned>(need.attribute)] = result_value(state, need.attribute, value);
        costs::charge(m_host, HostCost::ap_pixel_dma_result_byte, need.bytes);
      }
    }
  }
  for (size_t index = batch.first_block; index < batch.first_block + batch.blocks; ++index)
    for (uint32_t p : m_block_pixels[index]) write_shaded(state, triangle, reads, m_pixels[p], m_results[p]);
}

void ApPixelRenderer::write_shaded(const gl::RasterState& state, const gl::Triangle& triangle, const Reads& reads,
                                   const Pixel& pixel, const std::array<int32_t, ATTRIBUTES>& r) {
  costs::charge(m_host, HostCost::ap_pixel_shaded_pixel);
  uint32_t rgba;
  if (reads.colour) {
    // The integer part of 16.8, clamped.
    auto channel = [&](Attribute a) {
      return static_cast<uint32_t>(std::clamp<int32_t>(r[static_cast<unsigned>(a)] >> 8, 0, 255));
    };
    rgba = channel(Attribute::red) | channel(Attribute::green) << 8 | channel(Attribute::blue) << 16 |
           (reads.alpha ? channel(Attribute::alpha) : 255u) << 24;
  } else {
    const gl::ScreenVertex& provoking = triangle.v[2];
    rgba =
        uint32_t{provoking.r} | uint32_t{provoking.g} << 8 | uint32_t{provoking.b} << 16 | uint32_t{provoking.a} << 24;
  }
  const int st[2] = {r[static_cast<unsigned>(Attribute::s)], r[static_cast<unsigned>(Attribute::t)]};
  write_pixel(state, pixel, rgba, st, reads.texcoords);
}

void ApPixelRenderer::write_pixel(const gl::RasterState& state, const Pixel& pixel, uint32_t rgba, const int st[2],
                                  bool textured) {
  if (textured) {
    const gl::Texture& tex = state.unit[m_unit.index].tex;
    auto texel_at = [&](int ti, int tj, uint8_t out[4]) {
      copy_word(m_host.load_span(renderers::texel_address(tex, ti, tj), 4, 1), out);
    };
    uint8_t texel[4];
    costs::charge(m_host, renderers::sample_texture(tex, st[0], st[1], texel_at, texel)
                              ? HostCost::ap_pixel_texel_linear
                              : HostCost::ap_pixel_texel_nearest);
    rgba = renderers::apply_tex_env(m_unit.env, rgba, texel);
    costs::charge(m_host, HostCost::ap_pixel_texture_environment);
  }
  if (state.alpha_test && !compare_passes<uint32_t>(state.alpha_func, rgba >> 24, state.alpha_ref)) return;
  costs::charge(m_host, HostCost::ap_pixel_pixel);
  const uint32_t offset = (m_frame.buffers.height - 1 - static_cast<uint32_t>(pixel.y)) * m_frame.buffers.width +
                          static_cast<uint32_t>(pixel.x);
  if (state.depth_test && state.depth_write) {
    uint8_t* p = m_host.store_span(m_frame.buffers.depth_address + offset * 2, 2, 1);
    p[0] = static_cast<uint8_t>(pixel.z);
    p[1] = static_cast<uint8_t>(pixel.z >> 8);
  }
  renderers::write_color(m_host, state, m_frame.buffers.color_format, m_frame.buffers.color_address, offset, rgba,
                         {HostCost::ap_pixel_color_read_back, HostCost::ap_pixel_blend});
}

void ApPixelRenderer::publish_statistics() {
  if (m_env.counters == nullptr) return;
  ActivityCounters& c = *m_env.counters;
  auto set = [&](const char* name, const char* description, uint64_t value) {
    c.counter(std::string("ap_pixel.") + name, description).value = value;
  };
  renderers::publish_host_time(c, "ap_pixel", m_host, m_time,
                               "host time setting up, scan converting, depth testing, packing, texturing and writing "
                               "the pixels");
  set("triangles", "triangles with at least one visible pixel", m_triangles);
  set("visible_pixels", "pixels the host found inside and passing the depth test", m_visible);
  set("blocks", "blocks sent to a CU (each k x k pixels)", m_blocks_sent);
  set("passes", "array program runs (one block per CU each)", m_batches);
  set("cycles", "array cycles of the shading program", m_cycles);
  set("host_shaded_triangles", "slivers whose gradients 8.8 cannot hold, shaded by the host", m_host_shaded);
  set("ciu_words_written", "CMEM words the host wrote", m_words_written);
  set("ciu_words_read", "CMEM words the host read", m_words_read);
  set("cmem_bytes_per_cu", "CMEM bytes a CU uses for the array program's variables (ap.pixel.program)",
      m_layout.cmem_bytes);
  renderers::publish_traffic(c, "ap_pixel", m_traffic);
}

}  // namespace tessera::ap_pixel
