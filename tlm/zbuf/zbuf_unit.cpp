#include "zbuf/zbuf_unit.h"

#include <algorithm>
#include <cstring>

#include "common/log.h"
#include "zbuf/zbuf_regs.h"

namespace tessera {

using sc_core::sc_time;
namespace regs = zbuf_regs;

namespace {

uint32_t low32(uint64_t value) {
  return static_cast<uint32_t>(value);
}

}  // namespace

ZbufUnit::ZbufUnit(sc_core::sc_module_name name, const ZbufParams& params, const ArrayProcessor& array)
    : Peripheral(name, params.clock_period),
      colour_in("colour_in"),
      m_params(params),
      m_array(array),
      m_core(params.core),
      m_sends(counter("sends", "zsend instructions that reached the unit")),
      m_pixels(counter("pixels", "pixels received: CUs whose mask was set, per zsend")),
      m_written(counter("written", "pixels that passed the depth test (depth and colour written)")),
      m_failed(counter("failed", "pixels that failed the depth test")),
      m_clipped(counter("clipped", "pixels outside the frame's window")),
      m_conflicts(counter("conflicts", "pixels that met a lower lane's pixel at the same entry in one cycle")),
      m_port_cycles(counter("port_cycles", "array cycles the ports were busy taking pixels")),
      m_clears(counter("clears", "CONTROL.CLEAR commands")),
      m_cleared_entries(counter("cleared_entries", "entries the clears wrote")),
      m_window_words(counter("colour_window.words", "32-bit words read or written through the colour window")),
      m_window_waits(counter("colour_window.waits", "colour window accesses that waited for the array or a clear")) {
  sleeps_until_used();
  irq.bind(m_no_irq);
  ENTRIES.set_reset(params.core.entries);
  PORTS.set_reset(std::min(params.core.ports, 255u) |
                  (params.core.pair_halves_only ? regs::PORTS_PAIR_HALVES_ONLY : 0u));
  FRAME_ORIGIN.on_write([this](uint32_t value) {
    FRAME_ORIGIN.set(value);
    write_FRAME(value);
  });
  FRAME_SIZE.on_write([this](uint32_t value) {
    FRAME_SIZE.set(value);
    write_FRAME(value);
  });
  CONTROL.on_write(this, &ZbufUnit::write_CONTROL);
  STATUS.on_read(this, &ZbufUnit::read_STATUS);
  PIXELS.on_read([this] { return low32(m_core.counts().pixels); });
  WRITTEN.on_read([this] { return low32(m_core.counts().written); });
  CLIPPED.on_read([this] { return low32(m_core.counts().clipped); });
  PORT_CYCLES.on_read([this] { return low32(m_core.counts().port_cycles); });
  colour_in.register_b_transport(this, &ZbufUnit::colour_b_transport);
  colour_in.register_transport_dbg(this, &ZbufUnit::colour_transport_dbg);
}

ap::SendTimes ZbufUnit::send(const std::vector<ap::SentPixel>& pixels, const ap::SendArrival& arrival) {
  mark_used();
  ap::SendTimes times = m_core.send(pixels, arrival);
  const zbuf::ZbufCounts& c = m_core.counts();
  m_sends.value = c.sends;
  m_pixels.value = c.pixels;
  m_written.value = c.written;
  m_failed.value = c.failed;
  m_clipped.value = c.clipped;
  m_conflicts.value = c.conflicts;
  m_port_cycles.value = c.port_cycles;
  return times;
}

sc_time ZbufUnit::free_from(const sc_time& when) const {
  return std::max({when, m_array.busy_until(), m_clear_until});
}

uint32_t ZbufUnit::read_STATUS() const {
  const sc_time now = access_time();
  return (free_from(now) > now ? regs::STATUS_BUSY : 0u) | (m_refused ? regs::STATUS_REFUSED : 0u);
}

void ZbufUnit::write_FRAME(uint32_t unused) {
  (void)unused;
  // write_refusal() has checked that the window fits.
  const uint32_t origin = FRAME_ORIGIN.get(), size = FRAME_SIZE.get();
  m_core.set_frame(origin & regs::FRAME_ORIGIN_X, origin >> 16, size & regs::FRAME_SIZE_WIDTH, size >> 16);
}

void ZbufUnit::write_CONTROL(uint32_t value) {
  if ((value & regs::CONTROL_CLEAR) == 0) return;
  m_core.clear(static_cast<uint16_t>(CLEAR_DEPTH.get()), static_cast<uint16_t>(CLEAR_COLOUR.get()));
  m_clear_until = access_time() + clock_period() * static_cast<double>(m_core.clear_cycles());
  m_clears.value = m_core.counts().clears;
  m_cleared_entries.value = m_core.counts().cleared_entries;
}

const char* ZbufUnit::write_refusal(const tlm::tlm_generic_payload& gp) const {
  if (!gp.is_write()) return nullptr;
  const uint64_t offset = gp.get_address();
  if (offset != regs::FRAME_ORIGIN && offset != regs::FRAME_SIZE && offset != regs::CONTROL) return nullptr;
  const sc_time now = access_time();
  if (free_from(now) > now) {
    m_refused = true;
    return "written while the array's program or a clear runs (the planes are the unit's then)";
  }
  if (offset == regs::FRAME_SIZE && gp.get_data_length() == 4) {
    uint32_t size = 0;
    std::memcpy(&size, gp.get_data_ptr(), 4);
    const uint64_t entries = uint64_t{size & regs::FRAME_SIZE_WIDTH} * (size >> 16);
    if (entries > m_params.core.entries) {
      m_refused = true;
      m_refusal = "FRAME_SIZE " + std::to_string(size & regs::FRAME_SIZE_WIDTH) + " x " + std::to_string(size >> 16) +
                  " is beyond the unit's " + std::to_string(m_params.core.entries) + " entries (zbuf.entries)";
      return m_refusal.c_str();
    }
  }
  return nullptr;
}

void ZbufUnit::copy_colour(uint64_t offset, uint8_t* data, uint64_t length, bool write) {
  for (uint64_t i = 0; i < length; ++i) {
    const auto entry = static_cast<unsigned>((offset + i) / regs::COLOUR_ENTRY_BYTES);
    const unsigned shift = 8 * static_cast<unsigned>((offset + i) % regs::COLOUR_ENTRY_BYTES);
    uint16_t colour = m_core.colour(entry);
    if (write) {
      colour = static_cast<uint16_t>((colour & ~(0xffu << shift)) | (unsigned{data[i]} << shift));
      m_core.set_entry(entry, m_core.depth(entry), colour);
    } else {
      data[i] = static_cast<uint8_t>(colour >> shift);
    }
  }
}

void ZbufUnit::colour_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) {
  mark_used(delay);
  const uint64_t offset = gp.get_address();
  const uint64_t length = gp.get_data_length();
  const uint64_t size = uint64_t{m_params.core.entries} * regs::COLOUR_ENTRY_BYTES;
  if (offset % 2 != 0 || length == 0 || length % 2 != 0 || offset >= size || length > size - offset) {
    gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    log::warning(name(), "colour window access of " + std::to_string(length) + " bytes at offset " + log::hex(offset) +
                             ": whole 16-bit entries within the " + std::to_string(size) + "-byte plane");
    return;
  }
  if (gp.get_byte_enable_ptr() || gp.get_streaming_width() < length) {
    gp.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    return;
  }
  // The planes are final once the array's program and any clear are done.
  const sc_time arrival = sc_core::sc_time_stamp() + delay;
  const sc_time free = free_from(arrival);
  if (free > arrival) {
    ++m_window_waits;
    delay += free - arrival;
  }
  copy_colour(offset, gp.get_data_ptr(), length, gp.is_write());
  const uint64_t words = (length + 3) / 4;
  m_window_words += words;
  delay += clock_period() * static_cast<double>(words);
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
}

unsigned ZbufUnit::colour_transport_dbg(tlm::tlm_generic_payload& gp) {
  const uint64_t offset = gp.get_address();
  const uint64_t size = uint64_t{m_params.core.entries} * regs::COLOUR_ENTRY_BYTES;
  if (offset >= size) return 0;
  const uint64_t length = std::min<uint64_t>(gp.get_data_length(), size - offset);
  copy_colour(offset, gp.get_data_ptr(), length, gp.is_write());
  return static_cast<unsigned>(length);
}

nlohmann::json ZbufUnit::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Peripheral::stats_json(elapsed);
  stats["entries"] = m_params.core.entries;
  stats["ports"] = m_params.core.ports;
  stats["pair_halves_only"] = m_params.core.pair_halves_only;
  return stats;
}

void ZbufUnit::describe_stats(StatsSchema& schema) const {
  Peripheral::describe_stats(schema);
  schema.add_setting("entries", "count", "depth entries of the unit (zbuf.entries)");
  schema.add_setting("ports", "count", "ports of the unit (zbuf.ports)");
}

SummaryRow ZbufUnit::summary_row(const sc_time& elapsed) const {
  return busy_row(clock_period() * static_cast<double>(m_core.counts().port_cycles), elapsed,
                  std::to_string(m_core.counts().pixels) + " pixels, " + std::to_string(m_core.counts().written) +
                      " written, " + std::to_string(m_core.counts().clipped) + " clipped");
}

EnergyActivity ZbufUnit::energy_activity(const sc_time& now) const {
  (void)now;
  const zbuf::ZbufCounts& c = m_core.counts();
  return {{"zbuf",
           {{"pixels", static_cast<double>(c.pixels)},
            {"writes", static_cast<double>(c.written)},
            {"cleared_entries", static_cast<double>(c.cleared_entries)},
            {"window_words", static_cast<double>(m_window_words.value)}}}};
}

}  // namespace tessera
