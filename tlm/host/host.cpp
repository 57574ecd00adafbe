#include "host/host.h"

#include <algorithm>
#include <cstring>

#include "common/log.h"
#include "common/ticks_time.h"

namespace tessera {

using sc_core::sc_time;

const char* op_name(Op op) {
  switch (op) {
    case Op::alu: return "alu";
    case Op::load_use: return "load_use";
    case Op::mul: return "mul";
    case Op::branch: return "branch";
    case Op::call: return "call";
    case Op::fadd: return "fadd";
    case Op::fmul: return "fmul";
    case Op::fdiv: return "fdiv";
    case Op::fsqrt: return "fsqrt";
    case Op::fcmp: return "fcmp";
    case Op::fconv: return "fconv";
    case Op::count_: break;
  }
  return "?";
}

Host::Host(sc_core::sc_module_name name, const HostParams& params)
    : Block(name),
      out("out"),
      irq("irq", params.irq_lines),
      core_irq("core_irq"),
      core_fiq("core_fiq"),
      m_params(params),
      m_context(sc_core::sc_get_curr_simcontext()),
      m_period_ticks(params.clock_period.value()),
      m_cacheable_end(uint64_t{params.cacheable_base} + params.cacheable_size),
      m_run_ahead_ticks(params.run_ahead.value()),
      m_run_aheads(counter("run_aheads", "quantum ends at which the host ran on (nothing else was scheduled)")),
      m_syncs(counter("synchronisations", "waits for the kernel to catch up with the host's local time")),
      m_dcache(params.dcache_bytes, params.dcache_line_bytes, params.dcache_ways, params.dcache_round_robin),
      m_write_buffer(std::max(1u, params.write_buffer_addresses)),
      m_busy_cycles(counter("busy_cycles", "host cycles charged")),
      m_measured_cycles(
          counter("measured_cycles", "cycles charged from the ISS-measured cost table (sw_driver/costs)")),
      m_write_buffer_stalls(counter("write_buffer_stalls", "waits for a write-buffer entry")),
      m_bus_errors(counter("bus_errors", "bus transactions that got an error response")),
      m_loads(counter("loads", "load instructions (an LDM counts once)")),
      m_stores(counter("stores", "store instructions (an STM counts once)")),
      m_busy_trace("busy") {
  for (size_t i = 0; i < m_op_counts.size(); ++i) {
    const Op op = static_cast<Op>(i);
    m_op_counts[i] = &counter(std::string("operations.") + op_name(op), "operations charged of this class");
  }
  out.register_invalidate_direct_mem_ptr(this, &Host::invalidate_direct_mem_ptr);
  m_train = new TransferTrain;
  m_payload.set_extension(m_train);
  m_untouched = new ScheduleUntouched;
  m_payload.set_extension(m_untouched);
  m_qk.reset();
  if (params.iss) {
    m_pc_trace = std::make_unique<TimedWord>("pc");
    m_function_trace = std::make_unique<TimedWord>("function");
    m_cpsr_trace = std::make_unique<TimedWord>("cpsr");
  }
  SC_THREAD(run);
}

void Host::trace_signals(sc_core::sc_trace_file* file) {
  m_tracing = true;
  sc_core::sc_trace(file, m_busy_trace.signal, std::string(name()) + ".busy");
  for (unsigned i = 0; i < irq.size(); ++i)
    sc_core::sc_trace(file, irq[i], std::string(name()) + ".irq_" + std::to_string(i));
  if (m_pc_trace) {
    sc_core::sc_trace(file, m_pc_trace->signal, std::string(name()) + ".pc");
    sc_core::sc_trace(file, m_function_trace->signal, std::string(name()) + ".function");
    sc_core::sc_trace(file, m_cpsr_trace->signal, std::string(name()) + ".cpsr");
  }
}

void Host::trace_program(uint32_t pc, uint32_t function, uint32_t cpsr) {
  if (!tracing_program()) return;
  const sc_time when = sc_time::from_value(local_ticks());
  m_pc_trace->set_at(pc, when);
  m_function_trace->set_at(function, when);
  m_cpsr_trace->set_at(cpsr, when);
}

void Host::end_of_elaboration() {
  Block::end_of_elaboration();
  if (out.size() == 1) m_direct_out = direct_transport_of(out.operator->());
}

void Host::restart_quantum() {
  m_qk.reset();
  m_local_ticks = 0;
  m_quantum_ticks = m_budget_ticks = m_qk.next_sync_ticks() - kernel_ticks();
  m_window_clear = false;
}

void Host::sync() {
  flush_train();
  ++m_syncs;
  m_qk.set(sc_time::from_value(m_local_ticks));
  m_qk.sync();
  m_local_ticks = 0;
  m_quantum_ticks = m_budget_ticks = m_qk.next_sync_ticks() - kernel_ticks();
  m_window_clear = false;
}

bool Host::nothing_scheduled_in_window() {
  // Asking the kernel (sc_time_to_pending_activity) is what a quantum end
  // costs while running ahead, and in port mode it comes after almost every
  // bus access. Its answer cannot change while the kernel's time stands
  // and nothing is scheduled, so it is kept until the host waits, accesses
  // anything but memory, or a traced edge is scheduled (the bus traces
  // every grant); the outcome, and so every count, is the kernel's.
  if (m_window_clear && m_traced_edges == timed_signal_edges()) return true;
  m_traced_edges = timed_signal_edges();
  m_window_clear = sc_core::sc_time_to_pending_activity().value() >= m_run_ahead_ticks;
  return m_window_clear;
}

void Host::quantum_used_up() {
  // Synchronising lets the other processes run up to the host's local time.
  // While none of them has anything at all scheduled within the run-ahead
  // window, the wait would only resume the host, so it runs on instead, to
  // the window's end. Any bus access ends the run-ahead (transact), since it
  // may have woken another process; the next check then sees that process.
  // When something is scheduled, the host synchronises at the quantum as a
  // plain quantum keeper does, so timing is exactly that of run_ahead = 0.
  if (m_local_ticks < m_run_ahead_ticks && nothing_scheduled_in_window()) {
    ++m_run_aheads;
    m_budget_ticks = m_run_ahead_ticks;
    return;
  }
  sync();
}

void Host::stall_until(uint64_t absolute_ticks) {
  const uint64_t local = local_ticks();
  if (absolute_ticks <= local) return;
  if (m_note_segments) note_segment(false, local, absolute_ticks);
  m_stall_ticks += absolute_ticks - local;
  m_local_ticks += absolute_ticks - local;
  if (m_local_ticks >= m_budget_ticks) quantum_used_up();
}

void Host::compute(Op op, uint64_t count) {
  const auto index = static_cast<size_t>(op);
  if (index >= m_op_counts.size()) throw std::invalid_argument("host: unknown operation class");
  *m_op_counts[index] += count;
  charge(m_params.op_cycles[index] * count);
}

void Host::compute_cycles(uint64_t cycles) {
  m_measured_cycles.value += cycles;
  charge(cycles);
}

double Host::now_seconds() const {
  return sc_time::from_value(local_ticks()).to_seconds();
}

uint64_t Host::transact(tlm::tlm_command command, uint32_t address, uint8_t* data, unsigned bytes,
                        uint64_t not_before_ticks) {
  const uint64_t now = kernel_ticks();
  const uint64_t issue = std::max(now + m_local_ticks, not_before_ticks);
  sc_time delay = ticks_time(issue - now);
  m_payload.set_command(command);
  m_payload.set_address(address);
  m_payload.set_data_ptr(data);
  m_payload.set_data_length(bytes);
  m_payload.set_streaming_width(bytes);
  m_payload.set_byte_enable_ptr(nullptr);
  m_payload.set_byte_enable_length(0);
  m_payload.set_dmi_allowed(false);
  m_payload.set_response_status(tlm::TLM_INCOMPLETE_RESPONSE);
  m_untouched->untouched = false;
  // Directly, the train's count and the target's "untouched" travel as
  // DirectExtras (common/direct_transport.h); the payload's extensions
  // carry the same for a target reached through a socket.
  DirectExtras extras;
  extras.transfers = m_train->transfers;
  if (m_direct_out)
    m_direct_out->direct_b_transport(m_payload, delay, extras);
  else
    out->b_transport(m_payload, delay);
  const bool untouched = extras.untouched || m_untouched->untouched;
  m_train->transfers = 1;
  m_budget_ticks = std::min(m_budget_ticks, std::max(m_quantum_ticks, m_local_ticks + 1));
  // Memory (a target that grants DMI may be bypassed, so its accesses can
  // wake no process) and a target that says so (ScheduleUntouched: the
  // CIU's CMEM) leave the kernel's schedule as it was; a request without
  // delay may have waited a delta cycle for others at the bus.
  m_window_clear = m_window_clear && (m_payload.is_dmi_allowed() || untouched) && issue > now;
  if (m_payload.is_response_error()) {
    ++m_bus_errors;
    const std::string message = std::string("bus error: ") + (command == tlm::TLM_WRITE_COMMAND ? "write" : "read") +
                                " of " + std::to_string(bytes) + " bytes at " + log::hex(address) + " (" +
                                log::response_text(m_payload.get_response_status()) + ")";
    throw BusError(message, address);
  }
  return kernel_ticks() + delay.value();
}

uint8_t* Host::dmi_pointer_or_null(uint32_t address, unsigned bytes) {
  if (!m_dmi_valid && !m_dmi_denied) {
    tlm::tlm_generic_payload request;
    request.set_command(tlm::TLM_READ_COMMAND);
    request.set_address(address);
    m_dmi.init();
    m_dmi_valid = out->get_direct_mem_ptr(request, m_dmi) && m_dmi.is_read_write_allowed();
    m_dmi_denied = !m_dmi_valid;
  }
  if (!m_dmi_valid || address < m_dmi.get_start_address() ||
      static_cast<uint64_t>(address) + bytes - 1 > m_dmi.get_end_address())
    return nullptr;
  return m_dmi.get_dmi_ptr() + (address - m_dmi.get_start_address());
}

void Host::invalidate_direct_mem_ptr(sc_dt::uint64 start, sc_dt::uint64 end) {
  if (m_dmi_valid && start <= m_dmi.get_end_address() && end >= m_dmi.get_start_address()) {
    m_dmi_valid = false;
    m_hit_lines.revoke_all();
    if (m_direct_memory_invalidated) m_direct_memory_invalidated();
  }
  m_dmi_denied = false;
}

HostCore::DirectMemory Host::direct_memory(uint32_t address) {
  if (dmi_pointer(address, 1) == nullptr) return {};
  return {m_dmi.get_dmi_ptr(), static_cast<uint32_t>(m_dmi.get_start_address()),
          m_dmi.get_end_address() - m_dmi.get_start_address() + 1};
}

namespace {
[[noreturn]] __attribute__((cold, noinline)) void misaligned(uint32_t address, unsigned bytes) {
  throw std::invalid_argument("host: misaligned " + std::to_string(bytes * 8) + "-bit access at " + log::hex(address));
}
// Inline, the message out of line: as a call it was 1.3 % of an ISS-hosted
// run (perf, compute_rounds_arm.elf).
inline void check_alignment(uint32_t address, unsigned bytes) {
  if (__builtin_expect(address % bytes != 0, 0)) misaligned(address, bytes);
}
// A load's or store's bytes (1, 2 or 4) copied by moves of their size, not a
// call of the C library's memcpy for a length it does not know (1.8 % of an
// ISS-hosted run).
inline void copy_access(void* to, const void* from, unsigned bytes) {
  switch (bytes) {
    case 4: std::memcpy(to, from, 4); break;
    case 2: std::memcpy(to, from, 2); break;
    case 1: std::memcpy(to, from, 1); break;
    default: std::memcpy(to, from, bytes); break;
  }
}
// The elements of `size` bytes that a span's piece of `bytes` touches,
// rounded up, at least one: a shift where the size is a power of two, as
// elements are (a division at each line of a span had an eighth to a sixth
// of the span functions' samples in an `arm` frame).
class PieceElements {
 public:
  explicit PieceElements(unsigned size)
      : m_size(size), m_shift(size != 0 && (size & (size - 1)) == 0 ? __builtin_ctz(size) : -1) {}
  unsigned operator()(uint32_t bytes) const {
    const uint32_t rounded = bytes + m_size - 1;
    return std::max(1u, m_shift >= 0 ? rounded >> m_shift : rounded / m_size);
  }

 private:
  unsigned m_size;
  int m_shift;
};
}  // namespace

void Host::read_data(uint32_t address, void* data, unsigned bytes, unsigned counted) {
  m_loads += counted;
  charge(m_params.load_cycles);
  if (cached(address, bytes)) {
    const DataCache::Result result = m_dcache.read(address);
    if (!result.hit) {
      const unsigned line = m_dcache.line_bytes();
      write_back(result.victim);
      uint8_t fill[256];
      stall_until(transact(tlm::TLM_READ_COMMAND, m_dcache.line_address(address), fill, line, 0));
      copy_access(data, fill + (address - m_dcache.line_address(address)), bytes);
      return;
    }
    if (const uint8_t* p = dmi_pointer(address, bytes)) {
      copy_access(data, p, bytes);
      grant_hit_line(address);
      return;
    }
    // No DMI: fetch the data without time (the cache hit has been charged).
    tlm::tlm_generic_payload request;
    request.set_command(tlm::TLM_READ_COMMAND);
    request.set_address(address);
    request.set_data_ptr(static_cast<uint8_t*>(data));
    request.set_data_length(bytes);
    request.set_streaming_width(bytes);
    out->transport_dbg(request);
    return;
  }
  // Uncached (a device, or the data cache off): the write buffer drains
  // before a read goes out, so it cannot overtake earlier writes.
  drain_write_buffer();
  stall_until(transact(tlm::TLM_READ_COMMAND, address, static_cast<uint8_t*>(data), bytes, 0));
}

void Host::write_data(uint32_t address, const void* data, unsigned bytes) {
  ++m_stores;
  charge(m_params.store_cycles);
  // A write-back hit stays in the cache; a write-through hit updates the
  // line (memory holds the data either way) and goes to the write buffer as
  // a miss does.
  if (cached(address, bytes) && m_dcache.write(address, !m_params.write_through) && !m_params.write_through) {
    if (uint8_t* p = dmi_pointer(address, bytes)) {
      copy_access(p, data, bytes);
      grant_hit_line(address);
      return;
    }
    tlm::tlm_generic_payload request;
    request.set_command(tlm::TLM_WRITE_COMMAND);
    request.set_address(address);
    request.set_data_ptr(const_cast<uint8_t*>(static_cast<const uint8_t*>(data)));
    request.set_data_length(bytes);
    request.set_streaming_width(bytes);
    out->transport_dbg(request);
    return;
  }
  post_write(address, static_cast<const uint8_t*>(data), bytes);
}

unsigned Host::transfers_per_request(unsigned bytes_each) const {
  const unsigned words_each = (bytes_each + 3) / 4;
  return std::max(1u, words_each <= 1 ? m_params.write_buffer_words : m_params.write_buffer_words / words_each);
}

void Host::post_write(uint32_t address, const uint8_t* data, unsigned bytes, unsigned transfers) {
  // One transfer always fits (the buffer holds at least one address).
  if (transfers == 1) {
    post_request(address, data, bytes, 1);
    return;
  }
  const unsigned each = bytes / transfers;
  // The buffer holds as many stores of a train as it has addresses for (each
  // store takes one) and data words: the core resumes when the train's last
  // stores of that number are in the buffer.
  const unsigned held = std::min(transfers_per_request(each), m_params.write_buffer_addresses);
  if (transfers <= held) {
    post_request(address, data, bytes, transfers);
    return;
  }
  // The buffer fills as the core stores and drains one entry at a time. The
  // bus sees the train as requests of at most a buffer's worth of data words
  // (one request a store would be faithful for arbitration and slow), each
  // issued when the one before has left the buffer; the last request is the
  // stores the buffer holds at the end, so that the core resumes when it is
  // posted, and the first takes the remainder of the others.
  const unsigned per_request = transfers_per_request(each);
  const unsigned before_last = transfers - held;
  const unsigned first = before_last % per_request ? before_last % per_request : per_request;
  const PostPlan plan{address, each, first, per_request, held, 2 + (before_last - first) / per_request};
  // The requests in closed form where posts_steady can take them, the
  // others by post_request.
  const bool unit = m_take_units && m_direct_out != nullptr && !m_note_segments && !m_store_train.running &&
                    m_params.write_buffer_addresses <= STEADY_BUFFER;
  for (size_t r = 0; r < plan.requests; ++r) {
    if (unit) r += posts_steady(plan, r, data);
    if (r == plan.requests) break;
    const uint64_t before = plan.before(r);
    const unsigned count = plan.transfers(r);
    post_request(static_cast<uint32_t>(address + before * each), data + before * each, count * each, count);
  }
}

size_t Host::posts_steady(const PostPlan& plan, size_t first, const uint8_t* data) {
  PostQuote quote;
  if (!m_direct_out->quote_posts(plan, quote) || m_write_buffer.size() > STEADY_BUFFER) return 0;
  // post_request's steps for each request, with the host's state in local
  // variables, kept only when every one is what the calls would do: the
  // finished requests retired, a stall for the oldest while the new one
  // does not fit (make_room), the request issued after the kernel's time
  // and granted as reserve() grants it, followed from the bus's last
  // reservation; every quantum end a run-ahead on the kernel's cached
  // answer.
  // The write buffer's requests, a ring from `head` (State's): a request
  // tried is entered at the tail only once it is taken, beyond the ones
  // held, so a request left to the calls leaves the ring as it was.
  PendingWrite ring[STEADY_BUFFER];
  for (size_t i = 0; i < m_write_buffer.size(); ++i) ring[i] = m_write_buffer.at(i);
  struct State : SteadyHost {
    size_t head = 0, size = 0;
    unsigned words = 0, addresses = 0;
    LastReservation last;
  } st;
  steady_host(st);
  st.size = m_write_buffer.size();
  st.words = m_write_buffer_words;
  st.addresses = m_write_buffer_addresses;
  st.last = quote.last;
  const uint64_t now = kernel_ticks();
  const bool edges_unchanged = m_traced_edges == timed_signal_edges();
  const uint64_t bus = quote.period_ticks, run_ahead = m_run_ahead_ticks, quantum = m_quantum_ticks;
  const unsigned buffer_words = m_params.write_buffer_words, buffer_addresses = m_params.write_buffer_addresses;
  // Each kind's words and addresses in the buffer (post_request's).
  unsigned kind_words[PostPlan::KINDS], kind_addresses[PostPlan::KINDS];
  for (unsigned k = 0; k < PostPlan::KINDS; ++k) {
    const unsigned transfers = plan.kind_transfers(k);
    kind_words[k] = std::max(transfers, (transfers * plan.each + 3) / 4);
    kind_addresses[k] = std::min(transfers, buffer_addresses);
  }
  const size_t left = plan.requests - first;
  if (m_copy_requests.size() < left) m_copy_requests.resize(left);
  CopyRequest* const requests = m_copy_requests.data();
  size_t taken = 0;
  const uint64_t between = quote.cycles[1] * bus;  // a request between's time on the bus
  const bool between_waits = 2 * kind_words[1] > buffer_words || 2 * kind_addresses[1] > buffer_addresses;
  for (size_t r = first; r < plan.requests; ++r) {
    const unsigned kind = plan.kind(r);
    const unsigned words = kind_words[kind], addresses = kind_addresses[kind];
    if (words > buffer_words) break;  // the stall for a burst longer than the buffer
    if (kind == 1 && between_waits && st.size == 1) {
      // The steady state of the requests between: each waits for the one
      // before, the buffer's only request (they do not fit together), to
      // complete, at the end of the bus's last reservation, which it
      // joins; the stall's end reaches the budget (the local time before
      // plus a tick) and runs ahead on the cached answer, and the request
      // sets the budget to its local time plus a tick again. The steps of
      // requests j = 0, 1, .. in closed form while their stalls end
      // before the run-ahead window's end: the stall to free + j H, the
      // completion at free + (j + 1) H.
      const PendingWrite& only = ring[st.head];
      const uint64_t until = st.free - now;
      if (only.done_ticks == st.free && st.free > now + st.local && st.free % bus == 0 && st.last.has &&
          st.last.end * bus == st.free &&
          (only.words + words > buffer_words || only.addresses + addresses > buffer_addresses) && st.window_clear &&
          edges_unchanged && quote.untouched && st.budget == st.local + 1 && st.local + 1 >= quantum &&
          until < run_ahead) {
        const size_t steps = std::min<size_t>(plan.requests - 1 - r, (run_ahead - 1 - until) / between + 1);
        const uint64_t at = st.free / bus;
        for (size_t j = 0; j < steps; ++j) requests[taken + j] = {at + j * quote.cycles[1], at + j * quote.cycles[1]};
        const uint64_t last_until = until + (steps - 1) * between;
        st.stalls += steps;
        st.run_aheads += steps;
        st.stall += last_until - st.local;
        st.local = last_until;
        st.budget = last_until + 1;
        st.free += steps * between;
        st.last.end = at + steps * quote.cycles[1];
        ring[st.head] = {st.free, words, addresses};
        st.words = words;
        st.addresses = addresses;
        taken += steps;
        r += steps - 1;
        continue;
      }
    }
    State s = st;
    // make_room: retire the finished requests; while the new one does not
    // fit, stall for the oldest (after the local time: retired otherwise),
    // each stall's end a quantum end where it reaches the budget.
    bool room = true;
    for (;;) {
      while (s.size != 0 && ring[s.head].done_ticks <= now + s.local) {
        s.words -= ring[s.head].words;
        s.addresses -= ring[s.head].addresses;
        s.head = s.head + 1 == STEADY_BUFFER ? 0 : s.head + 1;
        --s.size;
      }
      if (s.size == 0 || (s.words + words <= buffer_words && s.addresses + addresses <= buffer_addresses)) break;
      ++s.stalls;
      const uint64_t until = ring[s.head].done_ticks - now;
      s.stall += until - s.local;
      s.local = until;
      if (!s.reach(until, run_ahead, edges_unchanged)) {
        room = false;
        break;
      }
    }
    if (!room) break;
    const uint64_t issue = std::max(now + s.local, s.free);
    if (issue <= now) break;  // a request at the kernel's time may wait a delta cycle
    CopyRequest& request = requests[taken];
    request.request_cycle = (issue + bus - 1) / bus;
    const uint64_t hold = quote.cycles[kind];
    if (!s.last.grant(request.request_cycle, hold, request.start_cycle)) break;
    const uint64_t done = (request.start_cycle + hold) * bus;
    s.budget = std::min(s.budget, std::max(quantum, s.local + 1));
    s.window_clear = s.window_clear && quote.untouched;
    s.free = done;
    const size_t tail = s.head + s.size < STEADY_BUFFER ? s.head + s.size : s.head + s.size - STEADY_BUFFER;
    ring[tail] = {done, words, addresses};
    ++s.size;
    s.words += words;
    s.addresses += addresses;
    st = s;
    ++taken;
  }
  if (taken == 0) return 0;
  commit_steady(st);
  m_write_buffer.clear();
  for (size_t i = 0; i < st.size; ++i)
    m_write_buffer.push_back(ring[st.head + i < STEADY_BUFFER ? st.head + i : st.head + i - STEADY_BUFFER]);
  m_write_buffer_words = st.words;
  m_write_buffer_addresses = st.addresses;
  m_direct_out->direct_posts(plan, quote, first, taken, requests, data + plan.before(first) * plan.each);
  return taken;
}

inline void Host::make_room(unsigned held_words, unsigned held_addresses) {
  auto retire = [&] {
    const uint64_t local = local_ticks();
    while (!m_write_buffer.empty() && m_write_buffer.front().done_ticks <= local) {
      m_write_buffer_words -= m_write_buffer.front().words;
      m_write_buffer_addresses -= m_write_buffer.front().addresses;
      m_write_buffer.pop_front();
    }
  };
  retire();
  while (!m_write_buffer.empty() && (m_write_buffer_words + held_words > m_params.write_buffer_words ||
                                     m_write_buffer_addresses + held_addresses > m_params.write_buffer_addresses)) {
    ++m_write_buffer_stalls;
    stall_until(m_write_buffer.front().done_ticks);
    retire();
  }
}

inline void Host::enter_request(uint64_t done_ticks, unsigned held_words, unsigned held_addresses) {
  m_write_buffer.push_back({done_ticks, held_words, held_addresses});
  m_write_buffer_words += held_words;
  m_write_buffer_addresses += held_addresses;
}

void Host::post_request(uint32_t address, const uint8_t* data, unsigned bytes, unsigned transfers) {
  // The ARM922T's write buffer holds 16 data words and 4 addresses (TRM
  // 4.3): a burst (an STM, a victim or cleaned line) takes one address, each
  // single store of a train one; the core stalls while the new request's
  // words or addresses do not fit.
  const unsigned words = std::max(transfers, (bytes + 3) / 4);
  const unsigned held_words = std::min(words, m_params.write_buffer_words);
  const unsigned held_addresses = std::min(transfers, m_params.write_buffer_addresses);
  make_room(held_words, held_addresses);
  const uint64_t issue = std::max(local_ticks(), m_write_buffer_free_ticks);
  uint64_t done;
  if (m_store_train.running) {
    done = train_transact(address, data, bytes, m_write_buffer_free_ticks);
  } else {
    // The payload points at the caller's bytes (a write's target reads
    // them during the call). A span's are already in place in memory
    // through DMI: memory then moves its bytes onto themselves, which it
    // skips (tlm/mem/README.md).
    m_train->transfers = transfers;
    done = transact(tlm::TLM_WRITE_COMMAND, address, const_cast<uint8_t*>(data), bytes, m_write_buffer_free_ticks);
  }
  m_write_buffer_free_ticks = done;
  if (words > m_params.write_buffer_words) {
    // A burst longer than the buffer (a victim line of a buffer smaller
    // than a line): the core waits until all but the buffer's worth of its
    // words have left (they drain evenly).
    const uint64_t per_word = (done - issue) / words;
    ++m_write_buffer_stalls;
    stall_until(done - per_word * m_params.write_buffer_words);
  }
  enter_request(done, held_words, held_addresses);
}

void Host::write_back(const DataCache::WriteBack& dirty) {
  if (dirty.bytes == 0) return;
  // The line's bytes where DMI reaches them (post_request's payload points
  // at them), else zeros.
  if (const uint8_t* p = dmi_pointer(dirty.address, dirty.bytes)) {
    post_write(dirty.address, p, dirty.bytes);
    return;
  }
  const uint8_t zeros[256] = {};
  post_write(dirty.address, zeros, dirty.bytes);
}

DataHitLines* Host::data_hit_lines() {
  m_hit_lines = DataHitLines{};
  while ((1u << m_hit_lines.line_shift) < m_dcache.line_bytes()) ++m_hit_lines.line_shift;
  m_hit_lines.busy_cycles = &m_busy_cycles.value;
  m_hit_lines.measured_cycles = &m_measured_cycles.value;
  m_hit_lines.local_ticks = &m_local_ticks;
  m_hit_lines.budget_ticks = &m_budget_ticks;
  m_hit_lines.period_ticks = m_period_ticks;
  m_hit_lines.loads = &m_loads.value;
  m_hit_lines.stores = &m_stores.value;
  m_hit_lines.hits = m_dcache.hits_location();
  m_hit_lines.load_cycles = m_params.load_cycles;
  m_hit_lines.store_cycles = m_params.store_cycles;
  m_dcache.revoke_on_change(&m_hit_lines);
  return &m_hit_lines;
}

void Host::grant_line(uint32_t address) {
  // Not while busy intervals are noted (charge's note_segment), nor for a
  // line that is not all cacheable and in the direct window.
  const uint32_t line = m_dcache.line_address(address);
  const unsigned bytes = m_dcache.line_bytes();
  uint8_t* data = m_note_segments || !cacheable(line, bytes) ? nullptr : dmi_pointer(line, bytes);
  if (data != nullptr) m_hit_lines.grant(line, data, m_params.write_through ? nullptr : m_dcache.dirty_bits(line));
}

void Host::set_data_cache_control(bool enabled, bool round_robin) {
  m_hit_lines.revoke_all();
  m_dcache_on = enabled;
  m_dcache.set_round_robin(round_robin);
}

void Host::clean_data_line(uint32_t address, bool invalidate) {
  write_back(m_dcache.clean_line(address, invalidate));
}

void Host::clean_data_index(uint32_t index, bool invalidate) {
  write_back(m_dcache.clean_index(index, invalidate));
}

void Host::drain_write_buffer() {
  if (m_write_buffer.empty()) return;
  stall_until(m_write_buffer_free_ticks);
  m_write_buffer.clear();
  m_write_buffer_words = 0;
  m_write_buffer_addresses = 0;
}

uint32_t Host::read32(uint32_t address) {
  check_alignment(address, 4);
  uint32_t value = 0;
  read_data(address, &value, 4);
  return value;
}

uint16_t Host::read16(uint32_t address) {
  check_alignment(address, 2);
  uint16_t value = 0;
  read_data(address, &value, 2);
  return value;
}

uint8_t Host::read8(uint32_t address) {
  uint8_t value = 0;
  read_data(address, &value, 1);
  return value;
}

void Host::write32(uint32_t address, uint32_t value) {
  check_alignment(address, 4);
  write_data(address, &value, 4);
}

void Host::write16(uint32_t address, uint16_t value) {
  check_alignment(address, 2);
  write_data(address, &value, 2);
}

void Host::write8(uint32_t address, uint8_t value) {
  write_data(address, &value, 1);
}

void Host::read_words(uint32_t address, uint32_t* words, unsigned count) {
  check_alignment(address, 4);
  if (count == 0) return;
  if (cached(address, count * 4)) {
    // LDM through the cache: each word as a load (a line fill per missed
    // line), the instruction counted once.
    for (unsigned i = 0; i < count; ++i) read_data(address + 4 * i, &words[i], 4, i == 0 ? 1 : 0);
    return;
  }
  // LDM from an uncached address: one burst.
  ++m_loads;
  charge(m_params.load_cycles * count + 1);
  drain_write_buffer();
  stall_until(transact(tlm::TLM_READ_COMMAND, address, reinterpret_cast<uint8_t*>(words), count * 4, 0));
}

void Host::write_words(uint32_t address, const uint32_t* words, unsigned count) {
  check_alignment(address, 4);
  if (count == 0) return;
  ++m_stores;
  charge(m_params.store_cycles * count + 1);
  // STM: words hitting a write-back line are written there; the rest (all of
  // them, write-through) go out as one burst per contiguous run through the
  // write buffer.
  const bool write_through = m_params.write_through;
  unsigned run_start = 0;
  // The words from run_start up to `end` (missed), as bursts of at most a
  // buffer's worth.
  const auto post_run = [&](unsigned end) {
    while (run_start < end) {
      const unsigned length = std::min(end - run_start, m_params.write_buffer_words);
      post_write(address + 4 * run_start, reinterpret_cast<const uint8_t*>(&words[run_start]), length * 4);
      run_start += length;
    }
  };
  // No word looked up in the cache (a device's, as the frame copy's to the
  // display port; the words rise, so the last below the cacheable range's
  // base or the first beyond its end): one run, without the words' tests.
  const uint64_t last_word = uint64_t{address} + 4 * uint64_t{count - 1};
  if (!m_dcache_on || !m_dcache.enabled() || last_word < m_params.cacheable_base ||
      uint64_t{address} + 4 > m_cacheable_end) {
    post_run(count);
    return;
  }
  for (unsigned i = 0; i <= count; ++i) {
    const bool hit =
        i < count && cached(address + 4 * i, 4) && m_dcache.write(address + 4 * i, !write_through) && !write_through;
    if (hit) {
      if (uint8_t* p = dmi_pointer(address + 4 * i, 4)) {
        std::memcpy(p, &words[i], 4);
      } else {
        tlm::tlm_generic_payload request;
        request.set_command(tlm::TLM_WRITE_COMMAND);
        request.set_address(address + 4 * i);
        request.set_data_ptr(reinterpret_cast<uint8_t*>(const_cast<uint32_t*>(&words[i])));
        request.set_data_length(4);
        request.set_streaming_width(4);
        out->transport_dbg(request);
      }
    }
    if (i == count || hit) {
      post_run(i);
      run_start = i + 1;
    }
  }
}

void Host::write32_train(uint32_t address, uint32_t stride, const uint32_t* values, const uint64_t* cycles,
                         unsigned count) {
  // Every word aligned and below 2^32, nothing that notes the host's
  // intervals (timeline, power trace) and a bus that can quote: else the
  // calls one by one (which throw where the first bad word is).
  const bool trainable = count > 0 && m_take_units && m_direct_out != nullptr && !m_note_segments && address % 4 == 0 &&
                         stride % 4 == 0 && uint64_t{address} + uint64_t{count - 1} * stride <= 0xfffffffcu &&
                         m_params.write_buffer_words > 0 && m_params.write_buffer_addresses > 0;
  if (!trainable) {
    HostApi::write32_train(address, stride, values, cycles, count);
    return;
  }
  StoreTrain& t = m_store_train;
  t.running = true;
  t.words = {address, stride, values, count};
  t.quoted = false;
  t.cycles = cycles;
  t.arrived = 0;
  if (t.arrivals.size() < count) t.arrivals.resize(count);
  try {
    for (t.next = 0; t.next < count; ++t.next) {
      t.next = train_steady(t.next);
      if (t.next == count) break;
      if (cycles[t.next] != 0) Host::compute_cycles(cycles[t.next]);
      const uint32_t word = address + static_cast<uint32_t>(t.next) * stride;
      if (cached(word, 4)) {
        write_data(word, &values[t.next], 4);
        continue;
      }
      // write_data's path for an uncached word, in line: the store
      // charged, then a request of one transfer of one word (post_write,
      // post_request; a word fits the buffer, which holds at least one).
      ++m_stores;
      charge(m_params.store_cycles);
      make_room(1, 1);
      const auto* data = reinterpret_cast<const uint8_t*>(&values[t.next]);
      const uint64_t done = train_transact(word, data, 4, m_write_buffer_free_ticks);
      m_write_buffer_free_ticks = done;
      enter_request(done, 1, 1);
    }
    flush_train();
  } catch (...) {
    t.running = false;
    throw;
  }
  t.running = false;
}

void Host::commit_steady(const SteadyHost& s) {
  m_measured_cycles += s.measured;
  m_busy_cycles += s.busy;
  m_write_buffer_stalls += s.stalls;
  m_stall_ticks += s.stall;
  m_run_aheads += s.run_aheads;
  m_local_ticks = s.local;
  m_budget_ticks = s.budget;
  m_window_clear = s.window_clear;
  m_write_buffer_free_ticks = s.free;
}

size_t Host::train_steady(size_t from) {
  StoreTrain& t = m_store_train;
  const size_t held = m_write_buffer.size();
  const unsigned cap = std::min(m_params.write_buffer_words, m_params.write_buffer_addresses);
  if (!t.quoted || cap > STEADY_BUFFER || held > cap || m_write_buffer_words != held ||
      m_write_buffer_addresses != held)
    return from;
  SteadyTrain st;
  steady_host(st);
  st.cap = cap;
  for (size_t i = 0; i < held; ++i) st.done_at[i] = m_write_buffer.at(i).done_ticks;
  st.pending = held;
  st.now = kernel_ticks();
  st.edges_unchanged = m_traced_edges == timed_signal_edges();
  const uint64_t period = m_period_ticks;
  const uint64_t store_ticks = uint64_t{m_params.store_cycles} * period;
  size_t k = from;
  while (k < t.words.count) {
    if (const size_t run = steady_run(st, k)) {
      k += run;
      continue;
    }
    const uint32_t word = static_cast<uint32_t>(t.words.address + k * t.words.stride);
    if (cached(word, 4)) break;
    // A charge or a stall that reaches the budget: quantum_used_up, here
    // only where it runs ahead without asking the kernel (its cached
    // answer stands); anything else leaves the word to the loop.
    uint64_t at_budget = st.budget;
    unsigned more_run_aheads = 0;
    const auto reach = [&](uint64_t local_now) {
      if (local_now < at_budget) return true;
      if (local_now >= m_run_ahead_ticks || !st.window_clear || !st.edges_unchanged) return false;
      ++more_run_aheads;
      at_budget = m_run_ahead_ticks;
      return true;
    };
    const uint64_t c = t.cycles[k];
    uint64_t l = st.local + c * period;
    if (c != 0 && !reach(l)) break;
    l += store_ticks;
    if (!reach(l)) break;
    // make_room(1, 1): the finished requests retired, a stall for the
    // oldest while the buffer is full.
    size_t left = st.pending, first = st.head;
    const auto retire = [&] {
      while (left != 0 && st.done_at[first] <= st.now + l) {
        first = first + 1 == cap ? 0 : first + 1;
        --left;
      }
    };
    retire();
    uint64_t stalled = 0;
    if (left == cap) {
      stalled = st.done_at[first] - st.now - l;
      l += stalled;
      if (!reach(l)) break;
      retire();
    }
    // train_transact's deferral.
    const uint64_t issue = std::max(st.now + l, st.free);
    if (issue <= st.now) break;
    // Taken: the word's state is the host's from here.
    const uint64_t done = t.quote.done_after(issue, st.free);
    st.measured += c;
    st.busy += c + m_params.store_cycles;
    st.stalls += stalled != 0;
    st.stall += stalled;
    st.run_aheads += more_run_aheads;
    st.local = l;
    st.budget = std::min(at_budget, std::max(m_quantum_ticks, l + 1));
    st.window_clear = st.window_clear && t.quote.untouched;
    t.arrivals[t.arrived++] = issue;
    st.free = done;
    st.head = first;
    st.pending = left;
    st.done_at[st.slot(st.pending)] = done;
    ++st.pending;
    ++k;
  }
  if (k == from) return from;
  commit_steady(st);
  m_stores += k - from;
  m_write_buffer.clear();
  for (size_t i = 0; i < st.pending; ++i) m_write_buffer.push_back({st.done_at[st.slot(i)], 1, 1});
  m_write_buffer_words = m_write_buffer_addresses = static_cast<unsigned>(st.pending);
  return k;
}

size_t Host::steady_run(SteadyTrain& st, size_t from) {
  // The steady state the word-by-word steps reach when the bus is the
  // bottleneck: the buffer full, its words completing a latency L apart
  // (each issued at the completion of the one before), the host stalling
  // for the oldest at each store and past the quantum's end, so that each
  // word's first charge reaches the budget (the last word's local time
  // plus a tick) and runs ahead. Each word k of such a run then stalls to
  // the oldest word's completion, L after the last stall, and completes L
  // after the word before: its steps in closed form.
  StoreTrain& t = m_store_train;
  const uint64_t latency = t.quote.latency_ticks;
  const unsigned cap = st.cap;
  if (st.pending != cap || st.budget != st.local + 1 || st.local + 1 < m_quantum_ticks || !st.window_clear ||
      !st.edges_unchanged || !t.quote.untouched || latency == 0 || st.free <= st.now)
    return 0;
  // The buffer's completions a latency apart, the last the buffer's free time.
  const uint64_t front = st.done_at[st.head];
  for (unsigned i = 0; i < cap; ++i)
    if (st.done_at[st.slot(i)] != front + i * latency) return 0;
  if (front + uint64_t{cap - 1} * latency != st.free || front <= st.now + st.local) return 0;
  // The words: uncached, each with compute cycles (its first charge is then
  // what reaches the budget) and stalling (its cycles shorter than the gap
  // to the oldest completion: L, and for the first the gap there is now),
  // and every local time before the run-ahead window's end.
  const uint64_t period = m_period_ticks;
  const uint64_t store_ticks = uint64_t{m_params.store_cycles} * period;
  const uint64_t first_gap = front - st.now - st.local;
  // Word m's local time after its stall, the oldest completion then, is
  // start + m L: the words the run-ahead window admits.
  const uint64_t start = front - st.now, window_end = m_run_ahead_ticks;
  const size_t words = t.words.count - from;
  if (words == 0 || start >= window_end) return 0;
  const size_t in_window = static_cast<size_t>(std::min<uint64_t>(words, (window_end - start - 1) / latency + 1));
  const uint64_t* const word_cycles = t.cycles + from;
  const uint64_t stride = t.words.stride;
  const uint64_t first_address = t.words.address + from * stride;
  const auto fits = [&](uint64_t c, uint64_t gap) {
    uint64_t busy_ticks = 0;
    return c != 0 && !__builtin_mul_overflow(c, period, &busy_ticks) && busy_ticks < gap &&
           store_ticks < gap - busy_ticks;
  };
  // No word of the window cached (the addresses rise: the first above the
  // cacheable range's end or the last below its base): each later word's
  // test is then its cycles', the same for words with the same cycles.
  const uint64_t last_address = first_address + (in_window - 1) * stride;
  const bool none_cached = !m_dcache_on || !m_dcache.enabled() || last_address < m_params.cacheable_base ||
                           first_address + 4 > m_cacheable_end;
  const auto word_cached = [&](size_t m) {
    return !none_cached && cached(static_cast<uint32_t>(first_address + m * stride), 4);
  };
  if (!fits(word_cycles[0], first_gap) || word_cached(0)) return 0;
  uint64_t cycles = word_cycles[0];
  size_t m = 1;
  while (m < in_window) {
    const uint64_t c = word_cycles[m];
    if (!fits(c, latency) || word_cached(m)) break;
    // The words after it with the same cycles pass the same test.
    size_t end = m + 1;
    if (none_cached)
      while (end < in_window && word_cycles[end] == c) ++end;
    cycles += c * (end - m);
    m = end;
  }
  // The free time in a local: a store through `arrivals` could change
  // st.free as far as the compiler knows, which would load it again
  // at each word.
  uint64_t* const arrivals = t.arrivals.data() + t.arrived;
  const uint64_t free_ticks = st.free;
  for (size_t i = 0; i < m; ++i) arrivals[i] = free_ticks + i * latency;
  t.arrived += m;
  const uint64_t last_local = front - st.now + (m - 1) * latency;
  st.measured += cycles;
  st.busy += cycles + m * uint64_t{m_params.store_cycles};
  st.stalls += m;
  st.stall += last_local - st.local - cycles * period - m * store_ticks;
  st.run_aheads += m;
  st.local = last_local;
  st.budget = last_local + 1;
  st.free += m * latency;
  st.head = 0;
  for (unsigned i = 0; i < cap; ++i) st.done_at[i] = st.free - uint64_t{cap - 1 - i} * latency;
  return m;
}

uint64_t Host::train_transact(uint32_t address, const uint8_t* data, unsigned bytes, uint64_t not_before_ticks) {
  // A word of the train as transact() would send it: deferred when the
  // quote covers it (its issue after the kernel's time, as the bus's
  // quote requires of every word, and the quote taken at the first).
  StoreTrain& t = m_store_train;
  const uint64_t now = kernel_ticks();
  const uint64_t issue = std::max(now + m_local_ticks, not_before_ticks);
  if (bytes == 4 && issue > now && address == t.words.address + t.next * t.words.stride) {
    if (!t.quoted) {
      const WordTrain rest{address, t.words.stride, t.words.values + t.next, t.words.count - t.next};
      t.quoted = m_direct_out->quote_train(rest, issue, t.quote);
      t.first = t.next;
    }
    if (t.quoted) {
      t.arrivals[t.arrived++] = issue;
      // What transact() does to the host's quantum keeping.
      m_budget_ticks = std::min(m_budget_ticks, std::max(m_quantum_ticks, m_local_ticks + 1));
      m_window_clear = m_window_clear && t.quote.untouched;
      return t.quote.done_after(issue, not_before_ticks);
    }
  }
  // The words deferred so far go first (a store train makes no other
  // transaction while it runs).
  flush_train();
  if (m_post_data.size() < bytes) m_post_data.resize(bytes);
  copy_access(m_post_data.data(), data, bytes);
  m_train->transfers = 1;
  return transact(tlm::TLM_WRITE_COMMAND, address, m_post_data.data(), bytes, not_before_ticks);
}

void Host::hand_over_train() {
  StoreTrain& t = m_store_train;
  const WordTrain deferred{t.words.address + t.first * t.words.stride, t.words.stride, t.words.values + t.first,
                           t.arrived};
  t.quoted = false;
  m_direct_out->direct_train(deferred, t.arrivals.data());
  t.arrived = 0;
}

void Host::copy_words(uint32_t to, uint32_t from, uint32_t words, const uint64_t* cycles) {
  // Whole blocks in closed form only where each is copy_steady's steps:
  // lines of 32 bytes of system memory through the data cache and DMI,
  // bursts of eight words to a range none of which is cacheable, a write
  // buffer that holds a burst, nothing noting the host's intervals; else,
  // and for a last block short of eight words, the calls.
  const uint32_t blocks = words / 8;
  const uint64_t bytes = 32 * uint64_t{blocks};
  const bool unit = blocks > 0 && m_take_units && m_direct_out != nullptr && !m_note_segments && m_dcache_on &&
                    m_dcache.enabled() && m_dcache.line_bytes() == 32 && from % 32 == 0 && to % 4 == 0 &&
                    uint64_t{from} + bytes <= 1ull << 32 && uint64_t{to} + bytes <= 1ull << 32 &&
                    cacheable(from, static_cast<unsigned>(bytes)) &&
                    dmi_pointer(from, static_cast<unsigned>(bytes)) != nullptr &&
                    (uint64_t{to} + bytes <= m_params.cacheable_base || to >= m_cacheable_end) &&
                    m_params.write_buffer_words >= 8 && m_params.write_buffer_addresses >= 1;
  if (!unit) {
    HostApi::copy_words(to, from, words, cycles);
    return;
  }
  const CopyPlan plan{from, to, 32, blocks};
  for (uint32_t k = 0; k < blocks; ++k) {
    k += copy_steady(plan, k, cycles);
    if (k == blocks) break;
    const auto* data = reinterpret_cast<const uint32_t*>(load_span(from + 32 * k, 4, 8));
    write_words(to + 32 * k, data, 8);
    if (cycles[k] != 0) Host::compute_cycles(cycles[k]);
  }
  if (const unsigned count = words % 8) {
    const auto* data = reinterpret_cast<const uint32_t*>(load_span(from + 32 * blocks, 4, count));
    write_words(to + 32 * blocks, data, count);
    if (cycles[blocks] != 0) Host::compute_cycles(cycles[blocks]);
  }
}

uint32_t Host::copy_steady(const CopyPlan& plan, uint32_t first, const uint64_t* cycles) {
  CopyQuote quote;
  if (!m_direct_out->quote_copy(plan, quote)) return 0;
  // The host's state in local variables, a block at a time: a block's
  // steps are taken on a copy and kept only when every one is what the
  // calls would do here (load_span's charge and line fill, its stall,
  // write_words' charge and burst through an empty write buffer, the
  // block's cycles; a quantum's end that only runs ahead on the kernel's
  // cached answer). The bus grants each request as reserve() does,
  // followed from its last reservation (the bus is the host's alone until
  // it lets the kernel run).
  struct State : SteadyHost {
    LastReservation last;
    uint64_t last_done = 0;  // the latest completion the write buffer holds
  };
  const uint64_t now = kernel_ticks();
  State st;
  steady_host(st);
  st.last = quote.last;
  for (size_t i = 0; i < m_write_buffer.size(); ++i)
    st.last_done = std::max(st.last_done, m_write_buffer.at(i).done_ticks);
  const bool edges_unchanged = m_traced_edges == timed_signal_edges();
  const uint64_t period = m_period_ticks, bus = quote.period_ticks;
  const uint64_t load_cycles = uint64_t{m_params.load_cycles} * 8;
  const uint64_t store_cycles = uint64_t{m_params.store_cycles} * 8 + 1;
  const auto reach = [&](State& s, uint64_t local) { return s.reach(local, m_run_ahead_ticks, edges_unchanged); };
  // A request issued at `issue`, holding the bus `hold` cycles: reserve()'s grant.
  const auto grant = [&](State& s, uint64_t issue, uint64_t hold, CopyRequest& request) {
    if (issue <= now) return false;  // a request at the kernel's time may wait a delta cycle
    request.request_cycle = (issue + bus - 1) / bus;
    return s.last.grant(request.request_cycle, hold, request.start_cycle);
  };
  const size_t left = plan.blocks - first;
  if (m_copy_requests.size() < 2 * left) m_copy_requests.resize(2 * left);
  CopyRequest* const requests = m_copy_requests.data();
  uint32_t taken = 0;
  for (uint32_t k = first; k < plan.blocks; ++k) {
    const auto source = static_cast<uint32_t>(plan.from + 32 * uint64_t{k});
    if (!m_dcache.clean_miss(source)) break;
    State s = st;
    CopyRequest& fill = requests[2 * taken];
    CopyRequest& burst = requests[2 * taken + 1];
    // load_span: the loads' charge, the line's fill, the stall for it.
    uint64_t local = s.local + load_cycles * period;
    s.busy += load_cycles;
    if (!reach(s, local) || !grant(s, now + local, quote.fill_cycles, fill)) break;
    s.budget = std::min(s.budget, std::max(m_quantum_ticks, local + 1));
    s.window_clear = s.window_clear && quote.fill_untouched;
    const uint64_t filled = (fill.start_cycle + quote.fill_cycles) * bus;
    if (filled > now + local) {
      s.stall += filled - now - local;
      local = filled - now;
      if (!reach(s, local)) break;
    }
    // write_words: the STM's charge, then its burst through the write
    // buffer, every entry of which has left (make_room retires them all).
    local += store_cycles * period;
    s.busy += store_cycles;
    if (!reach(s, local) || s.last_done > now + local) break;
    if (!grant(s, std::max(now + local, s.free), quote.burst_cycles, burst)) break;
    s.free = s.last_done = (burst.start_cycle + quote.burst_cycles) * bus;
    s.budget = std::min(s.budget, std::max(m_quantum_ticks, local + 1));
    s.window_clear = s.window_clear && quote.burst_untouched;
    // The block's own cycles.
    if (const uint64_t c = cycles[k]) {
      s.measured += c;
      s.busy += c;
      local += c * period;
      if (!reach(s, local)) break;
    }
    s.local = local;
    st = s;
    m_dcache.read(source);  // the miss, its victim clean
    m_dcache.count_hits(7);
    ++taken;
  }
  if (taken == 0) return 0;
  m_loads += 8 * uint64_t{taken};
  m_stores += taken;
  commit_steady(st);
  // The last burst is all the write buffer holds.
  m_write_buffer.clear();
  m_write_buffer.push_back({st.last_done, 8, 1});
  m_write_buffer_words = 8;
  m_write_buffer_addresses = 1;
  const uint32_t source = static_cast<uint32_t>(plan.from + 32 * uint64_t{first});
  m_direct_out->direct_copy(plan, quote, first, taken, requests, dmi_pointer(source, 32 * taken));
  return taken;
}

uint8_t* Host::span_pointer(uint32_t address, unsigned bytes) {
  if (!cacheable(address, bytes))
    throw std::invalid_argument("host: span access of " + std::to_string(bytes) + " bytes at " + log::hex(address) +
                                " is not in system memory");
  uint8_t* p = dmi_pointer(address, bytes);
  if (!p) throw std::invalid_argument("host: span access at " + log::hex(address) + " without DMI to system memory");
  return p;
}

const uint8_t* Host::load_span(uint32_t address, unsigned size, unsigned count) {
  const unsigned bytes = size * count;
  uint8_t* data = span_pointer(address, std::max(bytes, 1u));
  if (count == 0) return data;
  m_loads += count;
  if (!m_dcache_on || !m_dcache.enabled()) {
    // No cache: one single transfer per element, back to back, as bus
    // requests of at most a buffer's worth (as posted stores are), each
    // issued when the one before has completed.
    charge(uint64_t{m_params.load_cycles} * count);
    drain_write_buffer();
    if (m_post_data.size() < bytes) m_post_data.resize(bytes);
    const unsigned per_request = transfers_per_request(size);
    for (unsigned done = 0; done < count; done += per_request) {
      const unsigned transfers = std::min(per_request, count - done);
      m_train->transfers = transfers;
      stall_until(transact(tlm::TLM_READ_COMMAND, address + done * size, m_post_data.data(), transfers * size, 0));
    }
    return data;
  }
  const unsigned line = m_dcache.line_bytes();
  const PieceElements piece_elements(size);
  uint32_t cursor = address;
  const uint32_t end = address + bytes;
  while (cursor < end) {
    const uint32_t line_end = m_dcache.line_address(cursor) + line;
    const uint32_t piece_end = std::min(end, line_end);
    const unsigned elements = piece_elements(piece_end - cursor);
    charge(uint64_t{m_params.load_cycles} * elements);
    const DataCache::Result result = m_dcache.read(cursor);
    if (!result.hit) {
      write_back(result.victim);
      // The line's bytes are the span's, already read through DMI: the
      // fill's payload is the line itself where DMI reaches it (memory
      // skips moving its bytes onto themselves), else a buffer.
      const uint32_t line_address = m_dcache.line_address(cursor);
      uint8_t fill[256];
      uint8_t* into = dmi_pointer(line_address, line);
      stall_until(transact(tlm::TLM_READ_COMMAND, line_address, into != nullptr ? into : fill, line, 0));
    }
    m_dcache.count_hits(elements - 1);
    cursor = piece_end;
  }
  return data;
}

uint8_t* Host::store_span(uint32_t address, unsigned size, unsigned count) {
  const unsigned bytes = size * count;
  uint8_t* data = span_pointer(address, std::max(bytes, 1u));
  if (count == 0) return data;
  m_stores += count;
  const bool cache = m_dcache_on && m_dcache.enabled();
  const bool write_through = m_params.write_through;
  const unsigned line = cache ? m_dcache.line_bytes() : bytes;
  const PieceElements piece_elements(size);
  uint32_t cursor = address;
  const uint32_t end = address + bytes;
  // Runs of elements that miss the cache (or hit write-through lines) leave
  // as posted single stores.
  uint32_t miss_start = 0;
  unsigned miss_elements = 0;
  auto post_misses = [&] {
    if (miss_elements) post_write(miss_start, data + (miss_start - address), miss_elements * size, miss_elements);
    miss_elements = 0;
  };
  while (cursor < end) {
    const uint32_t line_end = cache ? m_dcache.line_address(cursor) + line : end;
    const uint32_t piece_end = std::min(end, line_end);
    const unsigned elements = piece_elements(piece_end - cursor);
    charge(uint64_t{m_params.store_cycles} * elements);
    const bool hit = cache && m_dcache.write(cursor, !write_through, piece_end - cursor);
    if (hit) m_dcache.count_hits(elements - 1);
    if (hit && !write_through) {
      post_misses();
    } else {
      if (!miss_elements) miss_start = cursor;
      miss_elements += elements;
    }
    cursor = piece_end;
  }
  post_misses();
  return data;
}

bool Host::irq_pending(unsigned line) {
  if (line >= irq.size())
    throw std::out_of_range("host: interrupt line " + std::to_string(line) +
                            " does not exist (host.irq_lines=" + std::to_string(irq.size()) + ")");
  sync();
  return irq[line].read();
}

template <typename Event, typename Done>
void Host::idle_until(const Event& event, Done done) {
  sync();
  if (done()) return;
  const uint64_t start = kernel_ticks();
  if (m_tracing) m_busy_trace.set_at(false, sc_core::sc_time_stamp());
  while (!done()) wait(event);
  restart_quantum();
  m_idle_ticks += kernel_ticks() - start;
  if (m_timeline && kernel_ticks() > start) {
    close_activity_slice();
    m_timeline->slice(m_timeline_track, "waiting for interrupt", sc_time::from_value(start),
                      sc_time::from_value(kernel_ticks()));
  }
  if (m_tracing) m_busy_trace.set_at(true, sc_core::sc_time_stamp());
}

void Host::wait_irq(unsigned line) {
  if (line >= irq.size())
    throw std::out_of_range("host: interrupt line " + std::to_string(line) +
                            " does not exist (host.irq_lines=" + std::to_string(irq.size()) + ")");
  idle_until(irq[line].value_changed_event(), [&] { return irq[line].read(); });
}

void Host::wait_for_interrupt() {
  if (core_irq.size() == 0 || core_fiq.size() == 0)
    throw std::logic_error(
        "host: wait for interrupt without an interrupt controller (the SoC builds one with "
        "host.model=iss)");
  sc_core::sc_event_or_list changes;
  changes |= core_irq->value_changed_event();
  changes |= core_fiq->value_changed_event();
  idle_until(changes, [&] { return irq_asserted() || fiq_asserted(); });
}

void Host::fetch(uint32_t address, unsigned bytes) {
  if (m_fetches == nullptr) {
    m_fetches = &counter("fetch.transactions", "instruction-side bus reads: cache line fills and uncached fetches");
    m_fetch_bytes = &counter("fetch.bytes", "bytes those reads carried");
  }
  ++*m_fetches;
  *m_fetch_bytes += bytes;
  uint8_t data[256];
  if (bytes > sizeof data)
    throw std::invalid_argument("host: instruction fetch of " + std::to_string(bytes) + " bytes");
  stall_until(transact(tlm::TLM_READ_COMMAND, address, data, bytes, 0));
}

bool Host::debug_access(tlm::tlm_command command, uint32_t address, uint8_t* data, unsigned bytes) {
  tlm::tlm_generic_payload request;
  request.set_command(command);
  request.set_address(address);
  request.set_data_ptr(data);
  request.set_data_length(bytes);
  request.set_streaming_width(bytes);
  return out->transport_dbg(request) == bytes;
}

bool Host::debug_read(uint32_t address, uint8_t* data, unsigned bytes) {
  if (const uint8_t* p = dmi_pointer(address, bytes)) {
    std::memcpy(data, p, bytes);
    return true;
  }
  return debug_access(tlm::TLM_READ_COMMAND, address, data, bytes);
}

bool Host::debug_write(uint32_t address, const uint8_t* data, unsigned bytes) {
  if (uint8_t* p = dmi_pointer(address, bytes)) {
    std::memcpy(p, data, bytes);
    return true;
  }
  return debug_access(tlm::TLM_WRITE_COMMAND, address, const_cast<uint8_t*>(data), bytes);
}

void Host::run() {
  // The global quantum is set during elaboration, after this module was built.
  restart_quantum();
  if (m_tracing) m_busy_trace.set_at(true, sc_core::sc_time_stamp());
  try {
    if (!m_program) throw std::logic_error("host: no program to run");
    log::info(name(), "program started");
    m_exit_code = m_program(*this);
    log::info(name(), "program returned " + std::to_string(m_exit_code));
    drain_write_buffer();
    if (m_exit_code != 0) m_failure = "program exited with status " + std::to_string(m_exit_code);
  } catch (const sc_core::sc_unwind_exception&) {
    throw;
  } catch (const ProgramInputError& e) {
    m_exit_code = 2;
    m_failure = e.what();
    log::error(name(), m_failure);
  } catch (const std::exception& e) {
    m_exit_code = 1;
    m_failure = e.what();
    log::error(name(), m_failure);
  }
  sync();
  if (m_tracing) m_busy_trace.set_at(false, sc_core::sc_time_stamp());
  m_finished = true;
  if (m_on_finish) m_on_finish();
}

nlohmann::json Host::stats_json(const sc_time& elapsed) const {
  const double elapsed_s = elapsed.to_seconds();
  const double busy_s = busy_time().to_seconds();
  const double stall_s = stall_time().to_seconds();
  nlohmann::json stats = Block::stats_json(elapsed);
  stats["clock_mhz"] = 1e-6 / m_params.clock_period.to_seconds();
  stats["busy_ns"] = busy_s * 1e9;
  stats["stalled_on_bus_ns"] = stall_s * 1e9;
  stats["idle_ns"] = std::max(0.0, elapsed_s - busy_s - stall_s) * 1e9;
  stats["waiting_for_irq_ns"] = idle_time().to_seconds() * 1e9;
  stats["utilisation"] = elapsed_s > 0 ? busy_s / elapsed_s : 0.0;
  stats["dcache"] = {{"hits", m_dcache.hits()}, {"misses", m_dcache.misses()}, {"writebacks", m_dcache.writebacks()}};
  if (m_program_statistics) stats["iss"] = m_program_statistics();
  return stats;
}

void Host::describe_stats(StatsSchema& schema) const {
  Block::describe_stats(schema);
  schema.add("clock_mhz", "MHz", "the host's clock frequency (host.clock_mhz)");
  schema.add("busy_ns", "ns", "time the host computed (its cycles, host-compiled or on the ISS)");
  schema.add("stalled_on_bus_ns", "ns", "time the host waited for its bus accesses");
  schema.add("idle_ns", "ns", "simulated time neither busy nor stalled on the bus");
  schema.add("waiting_for_irq_ns", "ns", "time the host slept waiting for an interrupt");
  schema.add("utilisation", "fraction", "busy_ns over the simulated time");
  schema.add("dcache.hits", "count", "data cache hits");
  schema.add("dcache.misses", "count", "data cache misses");
  schema.add("dcache.writebacks", "count", "dirty data cache lines written back");
}

SummaryRow Host::summary_row(const sc_time& elapsed) const {
  const double elapsed_s = elapsed.to_seconds();
  const double busy_s = busy_time().to_seconds();
  const double stall_s = stall_time().to_seconds();
  return busy_row(busy_time(), elapsed,
                  "stalled on bus " + format_duration(stall_s) + ", idle " +
                      format_duration(std::max(0.0, elapsed_s - busy_s - stall_s)));
}

void Host::timeline_to(TimelineSink& sink) {
  if (!sink.records(TimelineDetail::blocks)) return;
  m_timeline = &sink;
  m_note_segments = true;
  m_hit_lines.revoke_all();
  m_timeline_track = sink.track(name(), "activity");
  // The driver's phases reach the host-compiled model only (driver_phase).
  if (!m_params.iss) m_phase_track = sink.track(name(), "driver phase");
  m_call_timeline = sink.records(TimelineDetail::all) && !m_params.iss;
  if (m_call_timeline) m_call_track = sink.track(name(), "driver calls");
  m_timeline_all = sink.records(TimelineDetail::all);
  m_timeline_slice_ticks = sc_time(TIMELINE_SLICE_US, sc_core::SC_US).value();
}

void Host::timeline_segment(bool busy, uint64_t start_ticks, uint64_t end_ticks) {
  ActivitySlice& slice = m_activity;
  const bool joins =
      slice.end_ticks == start_ticks && slice.end_ticks > slice.start_ticks &&
      (m_timeline_all ? slice.busy == busy : slice.end_ticks - slice.start_ticks < m_timeline_slice_ticks);
  if (!joins) {
    close_activity_slice();
    slice = {start_ticks, start_ticks, 0, 0, busy};
  }
  slice.end_ticks = end_ticks;
  (busy ? slice.busy_ticks : slice.stalled_ticks) += end_ticks - start_ticks;
}

void Host::finish_timeline() {
  close_activity_slice();
  close_phase_slice();
  m_phase_name = nullptr;
}

void Host::driver_phase(const char* phase) {
  if (!m_timeline || m_params.iss) return;
  m_phase_since = close_phase_slice();
  m_phase_name = phase;
}

sc_time Host::close_phase_slice() {
  // The host's local time, exact in ticks.
  const sc_time now = sc_time::from_value(local_ticks());
  if (m_phase_name && now > m_phase_since) m_timeline->slice(m_phase_track, m_phase_name, m_phase_since, now);
  return now;
}

void Host::driver_call(const char* name, bool begins) {
  if (!m_call_timeline) return;
  const sc_time now = sc_time::from_value(local_ticks());
  if (begins) {
    m_calls.emplace_back(name, now);
  } else if (!m_calls.empty()) {
    m_timeline->slice(m_call_track, m_calls.back().first, m_calls.back().second, now);
    m_calls.pop_back();
  }
}

void Host::close_activity_slice() {
  ActivitySlice& slice = m_activity;
  if (!m_timeline || slice.end_ticks <= slice.start_ticks) return;
  const sc_time begin = sc_time::from_value(slice.start_ticks), end = sc_time::from_value(slice.end_ticks);
  if (m_timeline_all)
    m_timeline->slice(m_timeline_track, slice.busy ? "busy" : "stalled", begin, end);
  else
    m_timeline->slice(m_timeline_track, "running", begin, end,
                      {{"busy_ns", sc_time::from_value(slice.busy_ticks).to_seconds() * 1e9},
                       {"stalled_ns", sc_time::from_value(slice.stalled_ticks).to_seconds() * 1e9}});
  slice.start_ticks = slice.end_ticks;
}

void Host::note_ahead(bool busy, uint64_t start_ticks, uint64_t end_ticks) {
  if (end_ticks <= start_ticks) return;
  // What ended before the kernel's time can never be after a snapshot's.
  const uint64_t kernel = kernel_ticks();
  while (!m_ahead.empty() && m_ahead.front().end_ticks <= kernel) m_ahead.pop_front();
  if (!m_ahead.empty() && m_ahead.back().busy == busy && m_ahead.back().end_ticks == start_ticks)
    m_ahead.back().end_ticks = end_ticks;
  else
    m_ahead.push_back({start_ticks, end_ticks, busy});
}

std::pair<uint64_t, uint64_t> Host::ticks_after(uint64_t now_ticks) const {
  // The segments follow each other in time: walk back from the newest to
  // the first that ends before `now_ticks`.
  uint64_t busy = 0, stalled = 0;
  for (auto s = m_ahead.rbegin(); s != m_ahead.rend() && s->end_ticks > now_ticks; ++s)
    (s->busy ? busy : stalled) += s->end_ticks - std::max(s->start_ticks, now_ticks);
  return {busy, stalled};
}

EnergyActivity Host::energy_activity(const sc_time& now) const {
  const double period = m_params.clock_period.to_seconds();
  double busy_cycles = static_cast<double>(m_busy_cycles.value);
  double busy_s = busy_time().to_seconds();
  double stall_s = stall_time().to_seconds();
  if (m_attribute_in_time) {
    // Nothing ahead (a frame's request, the end of the run): the figures
    // as without the trace, to the last bit.
    const auto [busy_after, stalled_after] = ticks_after(now.value());
    if (busy_after > 0) {
      busy_cycles -= static_cast<double>(busy_after) / static_cast<double>(m_period_ticks);
      busy_s = busy_cycles * period;
    }
    if (stalled_after > 0) stall_s -= sc_time::from_value(stalled_after).to_seconds();
  }
  return {{"host",
           {{"busy_cycles", busy_cycles},
            {"stalled_cycles", stall_s / period},
            {"idle_cycles", std::max(0.0, now.to_seconds() - busy_s - stall_s) / period}}}};
}

}  // namespace tessera
