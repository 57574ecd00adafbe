#include "array/ciu.h"

#include <algorithm>
#include <cstring>

#include "array/array_regs.h"
#include "common/log.h"
#include "common/loosely_timed.h"
#include "common/schedule_untouched.h"
#include "common/ticks_time.h"

namespace tessera {

using sc_core::sc_time;

Ciu::Ciu(sc_core::sc_module_name name, const CiuParams& params, ArrayProcessor& array)
    : Block(name),
      in("in"),
      m_params(params),
      m_array(array),
      m_writes(counter("writes", "32-bit words written into CMEM (one byte in each of 4 CUs)")),
      m_reads(counter("reads", "32-bit words read from CMEM")),
      m_bytes_written(counter("bytes_written", "bytes written into CMEM")),
      m_bytes_read(counter("bytes_read", "bytes read from CMEM")),
      m_stalled(counter("stalled_accesses", "accesses that waited for a running program to finish")),
      m_errors(counter("errors", "accesses answered with an error (outside CMEM, not whole aligned words)")),
      m_access_trace("access") {
  sleeps_until_used();
  // Where each group of four CUs starts among the lanes, and CMEM's size
  // as a shift when it is a power of two: place_of() and move_words()
  // divide by neither.
  const ap::ArrayGeometry& g = m_array.params().geometry;
  m_cmem_bytes = g.cmem_bytes;
  m_window_bytes = uint64_t{g.lanes()} * g.cmem_bytes;
  if ((g.cmem_bytes & (g.cmem_bytes - 1)) == 0)
    while ((1u << m_cmem_shift) < g.cmem_bytes) ++m_cmem_shift;
  const unsigned groups_per_row = g.columns / array_regs::CUS_PER_GROUP;
  for (unsigned group = 0; group < g.lanes() / array_regs::CUS_PER_GROUP; ++group)
    m_group_lane.push_back((group / groups_per_row) * g.columns + (group % groups_per_row) * array_regs::CUS_PER_GROUP);
  m_groups_in_lane_order = true;
  for (size_t group = 0; group < m_group_lane.size(); ++group)
    m_groups_in_lane_order = m_groups_in_lane_order && m_group_lane[group] == group * array_regs::CUS_PER_GROUP;
  in.bind(static_cast<tlm::tlm_fw_transport_if<>&>(*this));
}

Ciu::WordPlace Ciu::place_of(uint64_t offset) const {
  // The window is the groups one after another, each cmem_bytes words.
  const uint64_t word = offset / 4;
  const uint64_t group = m_cmem_shift ? word >> m_cmem_shift : word / m_cmem_bytes;
  return {group, static_cast<unsigned>(word - group * m_cmem_bytes)};
}

void Ciu::move_words(uint64_t offset, uint64_t words, uint8_t* data, bool write, bool read) {
  // A word's four bytes go to four neighbouring CUs of a row (a group), at
  // one CMEM address: four neighbouring bytes of that address's row of
  // lanes (CMEM address a is the array's state row a). The next word is the
  // next address of the same group, until CMEM's end takes it to the next
  // group.
  ap::CuArray& cus = m_array.core().array();
  WordPlace place = place_of(offset);
  for (uint64_t w = 0; w < words; ++w) {
    uint8_t* cmem = cus.state_row(place.address) + m_group_lane[place.group];
    if (write)
      std::memcpy(cmem, data + 4 * w, 4);
    else if (read)
      std::memcpy(data + 4 * w, cmem, 4);
    if (++place.address == m_cmem_bytes) {
      place.address = 0;
      ++place.group;
    }
  }
}

bool Ciu::transport(tlm::tlm_generic_payload& gp, sc_time& delay) {
  // The CIU's access reaches CMEM: both are in use from here.
  mark_used(delay);
  m_array.mark_used(delay);
  const uint64_t offset = gp.get_address();
  const uint64_t length = gp.get_data_length();
  const uint64_t size = window_bytes();
  if (offset % 4 != 0 || length == 0 || length % 4 != 0 || offset >= size || length > size - offset) {
    ++m_errors;
    gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    log::warning(name(), "access of " + std::to_string(length) + " bytes at offset " + log::hex(offset) +
                             ": the CIU takes whole aligned 32-bit words within the " + std::to_string(size) +
                             "-byte CMEM window");
    return false;
  }
  if (gp.get_byte_enable_ptr() || gp.get_streaming_width() < length) {
    ++m_errors;
    gp.set_response_status(tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE);
    log::warning(name(), "access at offset " + log::hex(offset) + " with byte enables: the CIU takes whole words");
    return false;
  }
  // The CUs own CMEM while a program runs: wait for its end.
  const sc_time arrival = sc_core::sc_time_stamp() + delay;
  if (m_array.busy_at(arrival)) {
    const sc_time wait = m_array.busy_until() - arrival;
    ++m_stalled;
    m_stall_time += wait;
    delay += wait;
  }
  const uint64_t words = length / 4;
  move_words(offset, words, gp.get_data_ptr(), gp.is_write(), gp.is_read());
  const sc_time latency = ticks_time(latency_ticks(gp.is_write(), words));
  if (m_tracing) {
    const sc_time start = sc_core::sc_time_stamp() + delay;
    m_access_trace.set_at(true, start);
    m_access_trace.set_at(false, start + latency);
  }
  if (m_timeline) record_access(sc_core::sc_time_stamp() + delay, latency);
  delay += latency;
  count_access(gp.is_write(), words, latency);
  // Bytes moved, counters and time added: nothing notified (a traced
  // edge is counted apart).
  gp.set_response_status(tlm::TLM_OK_RESPONSE);
  return true;
}

void Ciu::count_access(bool write, uint64_t words, const sc_time& latency) {
  m_access_time += latency;
  if (write) {
    m_writes += words;
    m_bytes_written += 4 * words;
  } else {
    m_reads += words;
    m_bytes_read += 4 * words;
  }
}

bool Ciu::quote_train(const WordTrain& train, uint64_t first_ticks, TrainQuote& quote) {
  // As transport() would take each word: whole aligned words in the
  // window, the AC idle when the first arrives (the host, the only one
  // that starts it, is the one sending the train), and nothing traced.
  if (m_tracing || m_timeline != nullptr || train.count == 0 || train.address % 4 != 0 || train.stride % 4 != 0)
    return false;
  if (train.address > m_window_bytes - 4 ||
      (train.stride != 0 && train.count - 1 > (m_window_bytes - 4 - train.address) / train.stride))
    return false;
  if (m_array.busy_at(ticks_time(first_ticks))) return false;
  quote.edge_ticks = 1;
  quote.latency_ticks = latency_ticks(true, 1);
  quote.untouched = true;
  return true;
}

void Ciu::direct_train(const WordTrain& train, const uint64_t* arrivals) {
  if (train.count == 0) return;
  const sc_time first = ticks_time(arrivals[0]) - sc_core::sc_time_stamp();
  mark_used(first);
  m_array.mark_used(first);
  // Word k's place from word k - 1's: the stride in groups and addresses,
  // one division for the train.
  ap::CuArray& cus = m_array.core().array();
  WordPlace place = place_of(train.address);
  const WordPlace step = place_of(train.stride);
  // A word at one CMEM address in each of consecutive groups (a fill):
  // one run of the address's row.
  const bool one_run = m_groups_in_lane_order && step.group == 1 && step.address == 0;
  if (one_run) std::memcpy(cus.state_row(place.address) + m_group_lane[place.group], train.values, 4 * train.count);
  for (size_t k = 0; k < train.count && !one_run; ++k) {
    std::memcpy(cus.state_row(place.address) + m_group_lane[place.group], &train.values[k], 4);
    place.group += step.group;
    place.address += step.address;
    if (place.address >= m_cmem_bytes) {
      place.address -= m_cmem_bytes;
      ++place.group;
    }
  }
  count_access(true, train.count, ticks_time(latency_ticks(true, 1) * train.count));
}

bool Ciu::get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) {
  (void)gp;
  dmi.allow_read_write();
  dmi.set_start_address(0);
  dmi.set_end_address(~sc_dt::uint64(0));
  return false;
}

tlm::tlm_sync_enum Ciu::nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& /*phase*/, sc_time& /*delay*/) {
  ++m_errors;
  return refuse_non_blocking(name(), gp);
}

unsigned Ciu::transport_dbg(tlm::tlm_generic_payload& gp) {
  const uint64_t offset = gp.get_address();
  const uint64_t size = window_bytes();
  if (offset >= size) return 0;
  const uint64_t length = std::min<uint64_t>(gp.get_data_length(), size - offset);
  ap::CuArray& cus = m_array.core().array();
  for (uint64_t i = 0; i < length; ++i) {
    const WordPlace place = place_of(offset + i);
    const unsigned lane = m_group_lane[place.group] + static_cast<unsigned>((offset + i) % 4);
    if (gp.is_write())
      cus.set_cmem(lane, place.address, gp.get_data_ptr()[i]);
    else
      gp.get_data_ptr()[i] = cus.cmem(lane, place.address);
  }
  return static_cast<unsigned>(length);
}

void Ciu::trace_signals(sc_core::sc_trace_file* file) {
  m_tracing = true;
  sc_core::sc_trace(file, m_access_trace.signal, std::string(name()) + ".access");
}

void Ciu::timeline_to(TimelineSink& sink) {
  if (!sink.records(TimelineDetail::blocks)) return;
  m_timeline = &sink;
  m_timeline_track = sink.track(name(), "accesses");
}

void Ciu::record_access(const sc_time& start, const sc_time& latency) {
  if (m_timeline->records(TimelineDetail::all)) {
    m_timeline->slice(m_timeline_track, "access", start, start + latency);
    return;
  }
  if (m_burst.accesses > 0 && start <= m_burst.end + sc_time(BURST_GAP_NS, sc_core::SC_NS)) {
    m_burst.end = start + latency;
    m_burst.latency += latency;
    ++m_burst.accesses;
    return;
  }
  finish_timeline();
  m_burst = {start, start + latency, latency, 1};
}

void Ciu::finish_timeline() {
  if (!m_timeline || m_burst.accesses == 0) return;
  m_timeline->slice(
      m_timeline_track, "burst", m_burst.begin, m_burst.end,
      {{"accesses", static_cast<double>(m_burst.accesses)}, {"access_ns", m_burst.latency.to_seconds() * 1e9}});
  m_burst.accesses = 0;
}

nlohmann::json Ciu::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Block::stats_json(elapsed);
  stats["write_cycles"] = m_params.write_cycles;
  stats["read_cycles"] = m_params.read_cycles;
  stats["access_ns"] = m_access_time.to_seconds() * 1e9;
  stats["stall_ns"] = m_stall_time.to_seconds() * 1e9;
  // What the initiators waited on the CIU: its latency and the stalls.
  stats["host_wait_ns"] = (m_access_time + m_stall_time).to_seconds() * 1e9;
  stats["elapsed_ns"] = elapsed.to_seconds() * 1e9;
  return stats;
}

void Ciu::describe_stats(StatsSchema& schema) const {
  Block::describe_stats(schema);
  schema.add_setting("write_cycles", "cycles", "array cycles of a CIU write (ciu.write_cycles)");
  schema.add_setting("read_cycles", "cycles", "array cycles of a CIU read (ciu.read_cycles)");
  schema.add("access_ns", "ns", "latency of every CIU access, summed");
  schema.add("stall_ns", "ns", "time accesses stalled while the array held the CIU");
  schema.add("host_wait_ns", "ns", "what the initiators waited on the CIU: access_ns + stall_ns");
  schema.add("elapsed_ns", "ns", "simulated time of the run");
}

SummaryRow Ciu::summary_row(const sc_time& elapsed) const {
  return busy_row(m_access_time, elapsed,
                  std::to_string(m_writes.value) + " words written, " + std::to_string(m_reads.value) + " read, " +
                      std::to_string(m_stalled.value) + " waited for the array (" +
                      format_duration(m_stall_time.to_seconds()) + ")");
}

EnergyActivity Ciu::energy_activity(const sc_time& now) const {
  (void)now;
  return {{"ciu", {{"words", static_cast<double>(m_reads.value + m_writes.value)}}}};
}

}  // namespace tessera
