#include "renderers/ap_tile/tile_dma.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "costs/host_cost.h"
#include "gl/runtime.h"

namespace tessera::ap_tile {

namespace {

// The bytes of one send_constants, per CU: at most the renderer's largest
// set (the study's constants at construction: 50 bytes).
constexpr unsigned MAX_CONSTANT_BYTES = 64;

}  // namespace

DmaLayout DmaLayout::of(const CmemLayout& m) {
  DmaLayout layout;
  layout.tile_height = m.tile_height;
  layout.record_first = m.record_first;
  layout.record_bytes = m.record_bytes;
  layout.live = m.live - m.record_first;
  layout.dead = {{static_cast<uint16_t>(m.live - m.record_first), 0}};
  layout.read_planes = {m.tid, m.shi, m.slo, m.thi, m.tlo, m.chi, m.clo};
  layout.colour_planes = 2;
  layout.max_constants = 4;  // yc, zero and live at construction
  return layout;
}

DmaLayout DmaLayout::of(const StudyLayout& m) {
  DmaLayout layout;
  layout.tile_height = m.tile_height;
  layout.record_first = m.record_first;
  layout.record_bytes = m.record_bytes;
  // Line 0 = 0 x + 0 y - 1: no pixel inside (encode_study_record's dead record).
  const auto at = [&](unsigned address) { return static_cast<uint16_t>(address - m.record_first); };
  layout.dead = {{at(m.line_a), 0},      {at(m.line_a + 1u), 0}, {at(m.line_b), 0},
                 {at(m.line_b + 1u), 0}, {at(m.line_c), 0xff},   {at(m.line_c + 1u), 0xff}};
  layout.read_planes = {m.tid, m.s_hi, m.s_lo, m.t_hi, m.t_lo, m.rg_hi, m.rg_lo, m.b};
  layout.colour_planes = 3;
  layout.max_constants = 8;  // one, ff, the counter tables, line 0, XPOS and YPOS at construction
  return layout;
}

TileDma::TileDma(AppEnvironment& env, DmaDriver& dma, const DmaLayout& layout, const FrameGeometry& frame,
                 bool broadcast)
    : m_host(*env.host),
      m_dma(dma),
      m_layout(layout),
      m_frame(frame),
      m_broadcast(broadcast),
      m_cus(frame.cus()),
      m_read_planes(static_cast<unsigned>(layout.read_planes.size())) {
  const uint32_t record_bytes = uint32_t{m_cus} * layout.record_bytes;
  const uint32_t plane_bytes = uint32_t{m_cus} * frame.tile_width * frame.tile_height;
  for (unsigned b = 0; b < 2; ++b) {
    m_records[b] = gl::allocate(record_bytes);
    // Zero, so that no slot starts live: STM of zero words.
    std::memset(m_host.store_span(m_records[b], 4, (record_bytes + 3) / 4), 0, (record_bytes + 3) / 4 * 4);
    // A program without a live byte: every slot starts dead, byte by byte.
    if (layout.live < 0)
      for (unsigned lane = 0; lane < m_cus; ++lane)
        for (const auto& [offset, value] : layout.dead)
          *m_host.store_span(m_records[b] + offset * m_cus + lane, 1, 1) = value;
    m_staged_live[b].assign(m_cus, false);
  }
  m_frame_staging = gl::allocate(plane_bytes * m_read_planes);
  m_constants = gl::allocate(m_cus * MAX_CONSTANT_BYTES);
  m_constant_chain = gl::allocate(layout.max_constants * dma::DESCRIPTOR_BYTES);

  for (unsigned b = 0; b < 2; ++b) {
    m_record_chains[b] = gl::allocate(dma::DESCRIPTOR_BYTES);
    m_dma.write_chain(m_record_chains[b], {DmaDriver::to_cmem(m_records[b], layout.record_first, record_bytes, 1)});
  }
  // Chunk x: rows tile_height x .. tile_height (x + 1) - 1 of each plane.
  const unsigned rows = frame.tile_height;
  m_chunk_chains = gl::allocate(frame.tile_width * m_read_planes * dma::DESCRIPTOR_BYTES);
  for (unsigned x = 0; x < frame.tile_width; ++x) {
    std::vector<dma::Descriptor> chain;
    for (uint16_t plane : layout.read_planes)
      chain.push_back(DmaDriver::from_cmem(plane + layout.tile_height * x, staged_row(plane, x, 0), m_cus * rows, 1));
    m_dma.write_chain(m_chunk_chains + x * m_read_planes * dma::DESCRIPTOR_BYTES, chain);
  }
}

void TileDma::wait(unsigned channel) {
  try {
    m_dma.wait(channel);
  } catch (const DmaError& e) {
    throw DmaError(std::string("ap-tile: ") + e.what(), e.code(), e.descriptor(), e.address());
  }
}

void TileDma::send_constants(const std::vector<Constant>& constants, const std::vector<Constant>& per_cu) {
  if (constants.empty() && per_cu.empty()) return;
  unsigned total = static_cast<unsigned>(per_cu.size());
  for (const Constant& c : constants) total += static_cast<unsigned>(c.bytes.size());
  if (constants.size() + per_cu.size() > m_layout.max_constants || total > MAX_CONSTANT_BYTES)
    throw std::logic_error("ap-tile: more constants at once than the DMA's staging holds");
  std::vector<dma::Descriptor> chain;
  uint32_t at = m_constants;
  for (const Constant& c : constants) {
    const auto n = static_cast<uint32_t>(c.bytes.size());
    if (m_broadcast) {
      // Each byte once: the DMA puts it on the data lines once for every CU.
      std::memcpy(m_host.store_span(at, 1, n), c.bytes.data(), n);
      chain.push_back(DmaDriver::broadcast(at, c.cmem, n));
      m_traffic.values_written += n;
      at += n;
    } else {
      // Row r of the reshuffle is byte r, once per CU: the byte replicated
      // into a word (two ORRs with shifts), stored as words.
      for (uint32_t r = 0; r < n; ++r) {
        costs::charge(m_host, costs::HostCost::ap_tile_dma_constant_byte);
        std::memset(m_host.store_span(at + r * m_cus, 4, m_cus / 4), c.bytes[r], m_cus);
      }
      chain.push_back(DmaDriver::to_cmem(at, c.cmem, m_cus * n, 1));
      m_traffic.values_written += uint64_t{m_cus} * n;
      at += m_cus * n;
    }
  }
  for (const Constant& c : per_cu) {
    // Each CU its own byte: a row of the reshuffle, stored as words.
    std::memcpy(m_host.store_span(at, 4, m_cus / 4), c.bytes.data(), m_cus);
    chain.push_back(DmaDriver::to_cmem(at, c.cmem, m_cus, 1));
    m_traffic.values_written += m_cus;
    at += m_cus;
  }
  m_dma.write_chain(m_constant_chain, chain);
  m_dma.start_chain(INPUT, m_constant_chain);
  m_traffic.dma_descriptors += chain.size();
  wait(INPUT);
}

void TileDma::stage_records(unsigned buffer, const std::vector<uint8_t>& bytes, const std::vector<bool>& has_record) {
  const unsigned record_bytes = m_layout.record_bytes;
  const uint32_t base = m_records[buffer];
  std::vector<bool>& staged_live = m_staged_live[buffer];
  costs::charge(m_host, costs::HostCost::ap_tile_dma_lane, m_cus);
  for (unsigned lane = 0; lane < m_cus; ++lane) {
    if (has_record[lane]) {
      // One STRB per byte, a row apart: no packing.
      for (unsigned r = 0; r < record_bytes; ++r)
        *m_host.store_span(base + r * m_cus + lane, 1, 1) = bytes[size_t{lane} * record_bytes + r];
      staged_live[lane] = m_layout.live < 0 || bytes[size_t{lane} * record_bytes + m_layout.live] != 0;
    } else if (staged_live[lane]) {
      for (const auto& [offset, value] : m_layout.dead) *m_host.store_span(base + offset * m_cus + lane, 1, 1) = value;
      staged_live[lane] = false;
    }
  }
}

void TileDma::start_records(unsigned buffer) {
  m_dma.start_chain(INPUT, m_record_chains[buffer]);
  ++m_traffic.dma_descriptors;
  m_traffic.values_written += uint64_t{m_cus} * m_layout.record_bytes;
}

uint32_t TileDma::chunk_chain(unsigned x, bool textured) const {
  const unsigned first = textured ? 0 : m_read_planes - m_layout.colour_planes;
  return m_chunk_chains + (x * m_read_planes + first) * dma::DESCRIPTOR_BYTES;
}

void TileDma::start_chunk(unsigned x, bool textured) {
  const unsigned planes = textured ? m_read_planes : m_layout.colour_planes;
  m_dma.start_chain(x % 2, chunk_chain(x, textured));
  m_traffic.dma_descriptors += planes;
  m_traffic.values_read += uint64_t{planes} * m_cus * m_frame.tile_height;
}

uint32_t TileDma::staged_row(uint16_t plane, unsigned x, unsigned l) const {
  unsigned index = 0;
  while (index < m_read_planes && m_layout.read_planes[index] != plane) ++index;
  if (index == m_read_planes)
    throw std::invalid_argument("ap-tile: CMEM plane " + std::to_string(plane) + " is not read back");
  const uint32_t plane_bytes = uint32_t{m_cus} * m_frame.tile_width * m_frame.tile_height;
  return m_frame_staging + index * plane_bytes + (m_layout.tile_height * x + l) * m_cus;
}

}  // namespace tessera::ap_tile
