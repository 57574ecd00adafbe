#include "dma/dma.h"

#include <algorithm>
#include <stdexcept>

#include "common/log.h"
#include "dma/dma_regs.h"

namespace tessera {

using sc_core::sc_time;
namespace regs = dma_regs;

// The engine's two sides for the core: memory over the bus master (the
// engine waits for each transfer, so its bursts are timed at the kernel's
// time), CMEM through the array's direct path at dma.cmem_bytes_per_cycle.
class Dma::Port : public dma::DmaPort {
 public:
  Port(Dma& dma, Channel& channel) : m_dma(dma), m_channel(channel) {}

  bool read_memory(uint32_t address, uint8_t* data, unsigned bytes) override {
    return transfer(tlm::TLM_READ_COMMAND, address, data, bytes);
  }
  bool write_memory(uint32_t address, const uint8_t* data, unsigned bytes) override {
    return transfer(tlm::TLM_WRITE_COMMAND, address, const_cast<uint8_t*>(data), bytes);
  }
  void write_cmem_row(unsigned count, uint32_t address, unsigned element, const uint8_t* data) override {
    pass(count * element);
    for (unsigned lane = 0; lane < count; ++lane)
      for (unsigned b = 0; b < element; ++b)  // little-endian in memory, high byte first in CMEM
        m_dma.m_cmem->write_cmem(lane, address + element - 1 - b, data[lane * element + b]);
    m_dma.m_cmem_written += uint64_t{count} * element;
  }
  void read_cmem_row(unsigned count, uint32_t address, unsigned element, uint8_t* data) override {
    pass(count * element);
    for (unsigned lane = 0; lane < count; ++lane)
      for (unsigned b = 0; b < element; ++b)
        data[lane * element + b] = m_dma.m_cmem->read_cmem(lane, address + element - 1 - b);
    m_dma.m_cmem_read += uint64_t{count} * element;
  }
  void broadcast_cmem(const std::vector<uint8_t>& mask, uint32_t address, uint32_t step, const uint8_t* data,
                      unsigned bytes) override {
    // Every CU latches the shared data lines: one pass whatever the CUs.
    pass(bytes);
    const unsigned lanes = m_dma.m_cmem->cmem_geometry().lanes();
    for (unsigned lane = 0; lane < lanes; ++lane) {
      if (!mask.empty() && ((mask[lane / 8] >> (lane % 8)) & 1u) == 0) continue;
      for (unsigned j = 0; j < bytes; ++j) m_dma.m_cmem->write_cmem(lane, address + j * step, data[j]);
      m_dma.m_cmem_written += bytes;
    }
  }

 private:
  bool transfer(tlm::tlm_command command, uint32_t address, uint8_t* data, unsigned bytes) {
    const uint64_t wait_before = m_dma.m_bus_wait_probe ? m_dma.m_bus_wait_probe() : 0;
    sc_time local = sc_core::SC_ZERO_TIME;
    const bool ok = m_dma.out.transfer(command, address, data, bytes, local);
    if (m_dma.m_bus_wait_probe)
      m_channel.bus_wait += m_dma.m_params.clock_period * static_cast<double>(m_dma.m_bus_wait_probe() - wait_before);
    sc_core::wait(local);
    return ok;
  }
  // A CMEM pass of `line_bytes` on the data lines, once the CUs let go of CMEM.
  void pass(unsigned line_bytes) {
    const sc_time now = sc_core::sc_time_stamp();
    const sc_time free = m_dma.m_cmem->cmem_free_from(now);
    if (free > now) {
      ++m_dma.m_cmem_stalls;
      m_dma.m_cmem_stall += free - now;
      sc_core::wait(free - now);
    }
    const unsigned rate = m_dma.m_params.cmem_bytes_per_cycle;
    const unsigned cycles = (line_bytes + rate - 1) / rate;
    ++m_dma.m_cmem_passes;
    m_dma.m_cmem_cycles += cycles;
    sc_core::wait(m_dma.m_params.cmem_clock_period * static_cast<double>(cycles));
  }

  Dma& m_dma;
  Channel& m_channel;
};

Dma::Dma(sc_core::sc_module_name name, const DmaParams& params)
    : Peripheral(name, params.clock_period),
      out("out", activity()),
      m_params(params),
      m_cmem_written(counter("cmem.bytes_written", "bytes stored into CMEM, all CUs together")),
      m_cmem_read(counter("cmem.bytes_read", "bytes read from CMEM, all CUs together")),
      m_cmem_passes(counter("cmem.passes",
                            "passes over the CUs' shared data lines (one reshuffle row or broadcast "
                            "chunk each)")),
      m_cmem_cycles(counter("cmem.cycles", "array cycles of the CMEM passes")),
      m_cmem_stalls(counter("cmem_stalls", "CMEM passes that waited for a running program")),
      m_descriptor_fetches(counter("descriptor_fetches", "descriptors read from system memory")) {
  sleeps_until_used();
  if (params.channels == 0 || params.channels > regs::MAX_CHANNELS)
    throw std::invalid_argument(std::string(this->name()) + ": channels must be 1.." +
                                std::to_string(regs::MAX_CHANNELS));
  if (params.cmem_bytes_per_cycle == 0 || params.burst_bytes == 0 || params.row_buffer_bytes == 0)
    throw std::invalid_argument(std::string(this->name()) + ": zero rate, burst or row buffer");
  out.configure(params.burst_bytes, BusMaster::OnError::stop);
  m_channels.resize(params.channels);

  CHANNELS.set_reset(params.channels);
  bind_irq_registers(IRQ_STATUS, IRQ_ENABLE);
  CMEM_BYTES_PER_CYCLE.set_reset(params.cmem_bytes_per_cycle);

  for (unsigned c = 0; c < params.channels; ++c) {
    Channel& ch = m_channels[c];
    const std::string prefix = "ch" + std::to_string(c) + ".";
    ch.descriptors = &counter(prefix + "descriptors", "descriptors completed by channel " + std::to_string(c));
    ch.bytes = &counter(prefix + "bytes", "bytes delivered by channel " + std::to_string(c));
    ch.errors = &counter(prefix + "errors", "starts of channel " + std::to_string(c) + " stopped by an error");
    ch.busy_trace = std::make_unique<TimedTrace>(("ch" + std::to_string(c) + "_busy").c_str());
    ch.registers = std::make_unique<ChannelRegisters>(m_regs, regs::channel_base(c));
    ChannelRegisters& r = *ch.registers;
    r.START.on_write([this, c](uint32_t value) { write_START(c, value); });
    r.STATUS.on_read([this, c] { return read_STATUS(c); });
    r.ERROR_CODE.on_read([this, c] { return read_ERROR_CODE(c); });
    r.ERROR_DESC.on_read([this, c] { return read_ERROR_DESC(c); });
    r.ERROR_ADDR.on_read([this, c] { return read_ERROR_ADDR(c); });
    r.ERROR_ADDR_HI.on_read([this, c] { return read_ERROR_ADDR_HI(c); });
    r.DESCRIPTORS.on_read([this, c] { return read_DESCRIPTORS(c); });
    r.BYTES.on_read([this, c] { return read_BYTES(c); });
  }
  SC_THREAD(engine);
}

Dma::~Dma() = default;

void Dma::connect_cmem(CmemAccess& cmem) {
  m_cmem = &cmem;
}

dma::Limits Dma::limits() const {
  dma::Limits l;
  l.memory_base = m_params.memory_base;
  l.memory_bytes = m_params.memory_bytes;
  l.readable_base = m_params.readable_base;
  l.readable_bytes = m_params.readable_bytes;
  if (m_cmem) {
    l.lanes = m_cmem->cmem_geometry().lanes();
    l.cmem_bytes = m_cmem->cmem_geometry().cmem_bytes;
  }
  return l;
}

dma::Descriptor Dma::register_descriptor(unsigned channel) const {
  const ChannelRegisters& r = *m_channels[channel].registers;
  return dma::decode({r.D_CTRL.get(), r.D_SRC.get(), r.D_DST.get(), r.D_LENGTH.get(), r.D_SRC_STRIDE.get(),
                      r.D_DST_STRIDE.get(), r.D_NEXT.get(), r.D_MASK.get()});
}

uint32_t Dma::read_STATUS(unsigned channel) const {
  const Channel& s = m_channels[channel];
  return (s.busy ? regs::STATUS_BUSY : 0u) | (s.done ? regs::STATUS_DONE : 0u) | (s.error ? regs::STATUS_ERROR : 0u) |
         (s.refused ? regs::STATUS_REFUSED : 0u);
}

uint32_t Dma::read_ERROR_ADDR(unsigned channel) const {
  return static_cast<uint32_t>(m_channels[channel].error_addr);
}

uint32_t Dma::read_ERROR_ADDR_HI(unsigned channel) const {
  return static_cast<uint32_t>(m_channels[channel].error_addr >> 32);
}

uint32_t Dma::read_DESCRIPTORS(unsigned channel) const {
  return static_cast<uint32_t>(m_channels[channel].descriptors->value);
}

uint32_t Dma::read_BYTES(unsigned channel) const {
  return static_cast<uint32_t>(m_channels[channel].bytes->value);
}

const char* Dma::write_refusal(const tlm::tlm_generic_payload& gp) const {
  if (!gp.is_write() || gp.get_address() < regs::CHANNEL_BASE) return nullptr;
  const uint64_t channel = (gp.get_address() - regs::CHANNEL_BASE) / regs::CHANNEL_STRIDE;
  if (channel >= m_channels.size() || !m_channels[channel].busy) return nullptr;
  // The bus calls this through a const path; the flag is the channel's state.
  const_cast<Channel&>(m_channels[channel]).refused = true;
  return "written while the channel runs";
}

void Dma::write_START(unsigned channel, uint32_t value) {
  if ((value & regs::START_GO) == 0) return;
  Channel& ch = m_channels[channel];
  ch.busy = true;
  ch.queued = true;
  ch.done = ch.error = ch.refused = false;
  ch.error_code = ch.error_desc = ch.error_addr = 0;
  ch.registers_first = (value & regs::START_CHAIN_ONLY) == 0;
  ch.next = ch.registers_first ? 0 : ch.registers->D_NEXT.get();
  ch.visited.clear();
  ch.ready_at = access_time();
  if (m_tracing) ch.busy_trace->set_at(true, ch.ready_at);
  m_wake.notify(m_regs.access_delay());
}

void Dma::engine() {
  for (;;) {
    const sc_time now = sc_core::sc_time_stamp();
    int chosen = -1;
    sc_time earliest = sc_core::SC_ZERO_TIME;
    bool any = false;
    for (unsigned i = 0; i < m_channels.size(); ++i) {
      const unsigned c = (m_round_robin + i) % m_channels.size();
      const Channel& ch = m_channels[c];
      if (!ch.queued) continue;
      if (ch.ready_at <= now) {
        chosen = static_cast<int>(c);
        break;
      }
      if (!any || ch.ready_at < earliest) earliest = ch.ready_at;
      any = true;
    }
    if (chosen < 0) {
      if (any)
        wait(earliest - now, m_wake);
      else
        wait(m_wake);
      continue;
    }
    m_round_robin = (static_cast<unsigned>(chosen) + 1) % m_channels.size();
    const sc_time begin = sc_core::sc_time_stamp();
    step(static_cast<unsigned>(chosen));
    m_engine_busy += sc_core::sc_time_stamp() - begin;
  }
}

void Dma::step(unsigned channel) {
  Channel& ch = m_channels[channel];
  const sc_time begin = sc_core::sc_time_stamp();
  const dma::Limits lim = limits();
  dma::Descriptor d;
  uint32_t where = regs::ERROR_DESC_REGISTERS;
  if (ch.registers_first) {
    ch.registers_first = false;
    d = register_descriptor(channel);
  } else {
    where = ch.next;
    dma::Fault fault = dma::validate_descriptor_address(where, lim);
    if (!fault.ok()) return fail(channel, where, fault);
    if (!ch.visited.insert(where).second) return fail(channel, where, {dma::Error::chain_loop, where});
    uint8_t bytes[dma::DESCRIPTOR_BYTES] = {};
    Port port(*this, ch);
    ++m_descriptor_fetches;
    if (!port.read_memory(where, bytes, dma::DESCRIPTOR_BYTES))
      return fail(channel, where, {dma::Error::bus_error, where});
    d = dma::decode_bytes(bytes);
  }
  ch.next = d.next;
  dma::Fault fault = dma::validate(d, lim);
  if (fault.ok() && !m_cmem && d.kind() != dma::Kind::mem_to_mem) fault = {dma::Error::no_array, d.dst};
  if (!fault.ok()) return fail(channel, where, fault);
  Port port(*this, ch);
  uint64_t moved = 0;
  fault = dma::execute(d, lim, m_params.row_buffer_bytes, port, moved);
  *ch.bytes += moved;
  if (m_timeline && m_timeline->records(TimelineDetail::blocks)) {
    m_timeline->slice(ch.timeline_track, dma::kind_name(d.kind()), begin, sc_core::sc_time_stamp(),
                      {{"bytes", static_cast<double>(moved)},
                       {"src", static_cast<double>(d.src)},
                       {"dst", static_cast<double>(d.dst)}});
    if (d.kind() == dma::Kind::mem_to_cmem || d.kind() == dma::Kind::broadcast)
      m_timeline->flow_from(m_cmem_flow_key, ch.timeline_track, begin);
  }
  if (!fault.ok()) return fail(channel, where, fault);
  ++*ch.descriptors;
  m_descriptor_bytes.sample(d.length);
  if (log::enabled(log::Level::debug))
    log::debug(name(), "channel " + std::to_string(channel) + ": " + dma::kind_name(d.kind()) + " of " +
                           std::to_string(d.length) + " bytes from " + log::hex(d.src) + " to " + log::hex(d.dst));
  if (ch.next == 0) finish(channel);
}

void Dma::finish(unsigned channel) {
  Channel& ch = m_channels[channel];
  const sc_time now = sc_core::sc_time_stamp();
  ch.queued = false;
  ch.busy = false;
  ch.done = !ch.error;
  ch.busy_time += now - ch.ready_at;
  if (m_tracing) ch.busy_trace->set_at(false, now);
  if (m_timeline && m_timeline->records(TimelineDetail::blocks))
    m_timeline->slice(ch.timeline_track, ch.error ? "chain (failed)" : "chain", ch.ready_at, now);
  raise_irq(ch.error ? regs::irq_error(channel) : regs::irq_done(channel));
  m_finished.notify(sc_core::SC_ZERO_TIME);
}

void Dma::fail(unsigned channel, uint32_t descriptor, const dma::Fault& fault) {
  Channel& ch = m_channels[channel];
  ch.error = true;
  ch.error_code = static_cast<uint32_t>(fault.error);
  ch.error_desc = descriptor;
  ch.error_addr = fault.address;
  ++*ch.errors;
  const std::string at =
      descriptor == regs::ERROR_DESC_REGISTERS ? std::string("in registers") : "at " + log::hex(descriptor);
  log::warning(name(), "channel " + std::to_string(channel) + ": descriptor " + at + ": " +
                           dma::error_text(fault.error) + " at " + log::hex(fault.address) + "; channel stopped");
  finish(channel);
}

void Dma::trace_signals(sc_core::sc_trace_file* file) {
  m_tracing = true;
  const std::string prefix = std::string(name()) + ".";
  for (unsigned c = 0; c < m_channels.size(); ++c)
    sc_core::sc_trace(file, m_channels[c].busy_trace->signal, prefix + "ch" + std::to_string(c) + ".busy");
  sc_core::sc_trace(file, irq, prefix + "irq");
}

void Dma::timeline_to(TimelineSink& sink) {
  m_timeline = &sink;
  for (unsigned c = 0; c < m_channels.size(); ++c)
    m_channels[c].timeline_track = sink.track(name(), "ch" + std::to_string(c));
  if (const auto* array = dynamic_cast<const sc_core::sc_object*>(m_cmem)) m_cmem_flow_key = cmem_flow_key(*array);
}

nlohmann::json Dma::stats_json(const sc_time& elapsed) const {
  nlohmann::json stats = Peripheral::stats_json(elapsed);
  stats["channels"] = m_params.channels;
  stats["burst_bytes"] = m_params.burst_bytes;
  stats["cmem_bytes_per_cycle"] = m_params.cmem_bytes_per_cycle;
  stats["cmem_stall_ns"] = m_cmem_stall.to_seconds() * 1e9;
  for (unsigned c = 0; c < m_channels.size(); ++c) {
    nlohmann::json& ch = stats["ch" + std::to_string(c)];
    ch["busy_ns"] = m_channels[c].busy_time.to_seconds() * 1e9;
    ch["bus_wait_ns"] = m_channels[c].bus_wait.to_seconds() * 1e9;
  }
  add_busy_stats(stats, m_engine_busy, elapsed);
  stats["histograms"]["descriptor_bytes"] = histogram_json(m_descriptor_bytes);
  return stats;
}

void Dma::describe_stats(StatsSchema& schema) const {
  Peripheral::describe_stats(schema);
  schema.add_setting("channels", "count", "channels of the DMA (dma.channels)");
  schema.add_setting("burst_bytes", "bytes", "length of the DMA's bus bursts (dma.burst_bytes)");
  schema.add_setting("cmem_bytes_per_cycle", "bytes",
                     "bytes the DMA moves to or from CMEM per array cycle (dma.cmem_bytes_per_cycle)");
  schema.add("cmem_stall_ns", "ns", "time the DMA waited for the CUs to let go of CMEM");
  schema.add("ch*.busy_ns", "ns", "time the channel ran descriptors");
  schema.add("ch*.bus_wait_ns", "ns", "time the channel's bus transfers took");
  describe_busy_stats(schema, "time the DMA engine ran descriptors (any channel)");
  schema.add_histogram("histograms.descriptor_bytes", "bytes", "the length of each descriptor completed");
}

SummaryRow Dma::summary_row(const sc_time& elapsed) const {
  uint64_t descriptors = 0, bytes = 0, errors = 0;
  for (const Channel& ch : m_channels) {
    descriptors += ch.descriptors->value;
    bytes += ch.bytes->value;
    errors += ch.errors->value;
  }
  return busy_row(m_engine_busy, elapsed,
                  std::to_string(descriptors) + " descriptors, " + std::to_string(bytes) + " bytes, " +
                      std::to_string(errors) + " errors");
}

EnergyActivity Dma::energy_activity(const sc_time& now) const {
  (void)now;
  return {{"dma", {{"bytes", static_cast<double>(m_cmem_written.value + m_cmem_read.value)}}}};
}

}  // namespace tessera
