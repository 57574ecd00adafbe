#include "zbuf/core/zbuf_core.h"

#include <algorithm>
#include <stdexcept>

namespace tessera::zbuf {

ZbufCore::ZbufCore(const ZbufCoreParams& params) : m_params(params) {
  if (params.entries == 0 || params.entries > MAX_ENTRIES)
    throw std::invalid_argument("z-buffer: " + std::to_string(params.entries) + " entries (zbuf.entries: 1.." +
                                std::to_string(MAX_ENTRIES) + ")");
  if (params.ports == 0) throw std::invalid_argument("z-buffer: 0 ports (zbuf.ports: at least 1)");
  m_depth.assign(params.entries, 0xffff);
  m_colour.assign(params.entries, 0);
}

std::string ZbufCore::set_frame(unsigned origin_x, unsigned origin_y, unsigned width, unsigned height) {
  if (uint64_t{width} * height > m_params.entries)
    return "a frame of " + std::to_string(width) + " x " + std::to_string(height) + " entries is beyond the unit's " +
           std::to_string(m_params.entries) + " (zbuf.entries)";
  m_origin_x = origin_x;
  m_origin_y = origin_y;
  m_width = width;
  m_height = height;
  return {};
}

void ZbufCore::clear(uint16_t depth, uint16_t colour) {
  std::fill_n(m_depth.begin(), frame_entries(), depth);
  std::fill_n(m_colour.begin(), frame_entries(), colour);
  ++m_counts.clears;
  m_counts.cleared_entries += frame_entries();
}

uint64_t ZbufCore::clear_cycles() const {
  return (uint64_t{frame_entries()} + m_params.ports - 1) / m_params.ports;
}

long ZbufCore::entry_of(uint16_t x, uint16_t y) const {
  if (x < m_origin_x || y < m_origin_y) return -1;
  const unsigned column = x - m_origin_x, row = y - m_origin_y;
  if (column >= m_width || row >= m_height) return -1;
  return static_cast<long>(row) * m_width + column;
}

std::vector<uint64_t> ZbufCore::schedule(const std::vector<ap::SentPixel>& pixels, unsigned ports,
                                         bool pair_halves_only, const ap::SendArrival& arrival) {
  std::vector<uint64_t> cycles(pixels.size());
  const unsigned per_cycle = pair_halves_only ? std::min(ports, 2u) : ports;
  uint64_t cycle = arrival.first;
  unsigned taken = 0;  // pixels in the current cycle
  for (size_t i = 0; i < pixels.size(); ++i) {
    const bool other_pair = pair_halves_only && taken > 0 && pixels[i].lane / 2 != pixels[i - 1].lane / 2;
    if (taken == per_cycle || other_pair) {
      ++cycle;
      taken = 0;
    }
    // A row that has not reached the port yet: the port waits for it.
    if (const uint64_t ready = arrival.arrival(pixels[i].lane); ready > cycle) {
      cycle = ready;
      taken = 0;
    }
    cycles[i] = cycle;
    ++taken;
  }
  return cycles;
}

// One cycle: every port reads its entry's depth, then the comparators
// decide, a port whose entry a lower lane's port also holds taking that
// port's result (the forwarding of the order rule), then the writes.
void ZbufCore::take_cycle(const ap::SentPixel* pixels, size_t count) {
  struct Port {
    long entry;
    uint16_t seen;  // the depth this port compares with
    bool writes;
  };
  std::vector<Port> ports(count);
  for (size_t i = 0; i < count; ++i) {
    ports[i].entry = entry_of(pixels[i].x, pixels[i].y);
    ports[i].seen = ports[i].entry >= 0 ? m_depth[static_cast<size_t>(ports[i].entry)] : 0;
  }
  for (size_t i = 0; i < count; ++i) {
    Port& port = ports[i];
    if (port.entry < 0) {
      ++m_counts.clipped;
      port.writes = false;
      continue;
    }
    // The nearest lower port at the same entry forwards its outcome.
    for (size_t j = i; j-- > 0;)
      if (ports[j].entry == port.entry) {
        ++m_counts.conflicts;
        port.seen = ports[j].writes ? pixels[j].z : ports[j].seen;
        break;
      }
    port.writes = pixels[i].z < port.seen;
    ++(port.writes ? m_counts.written : m_counts.failed);
  }
  // Writes in ascending ports: the last writer of an entry is the one whose
  // depth is the least, as forwarding decided.
  for (size_t i = 0; i < count; ++i)
    if (ports[i].writes) set_entry(static_cast<unsigned>(ports[i].entry), pixels[i].z, pixels[i].colour);
}

ap::SendTimes ZbufCore::send(const std::vector<ap::SentPixel>& pixels, const ap::SendArrival& arrival) {
  ++m_counts.sends;
  m_counts.pixels += pixels.size();
  ap::SendTimes times;
  if (pixels.empty()) return times;
  times.cycles = schedule(pixels, m_params.ports, m_params.pair_halves_only, arrival);
  size_t first = 0;
  for (size_t i = 1; i <= pixels.size(); ++i)
    if (i == pixels.size() || times.cycles[i] != times.cycles[first]) {
      take_cycle(pixels.data() + first, i - first);
      ++times.busy;
      first = i;
    }
  m_counts.port_cycles += times.busy;
  return times;
}

}  // namespace tessera::zbuf
