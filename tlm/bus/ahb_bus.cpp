#include "bus/ahb_bus.h"

#include <algorithm>
#include <stdexcept>

#include "common/log.h"
#include "common/schedule_untouched.h"
#include "common/transfer_train.h"

namespace tessera {

using sc_core::sc_time;

Arbitration parse_arbitration(const std::string& name) {
  if (name == "fixed_priority") return Arbitration::fixed_priority;
  if (name == "round_robin") return Arbitration::round_robin;
  throw std::invalid_argument("unknown arbitration '" + name + "' (expected fixed_priority or round_robin)");
}

// One initiator's end of the bus: a target socket that is its own forward
// interface and calls the bus with the initiator's index, one virtual call
// per access (multi_passthrough_target_socket adds a binder, a functor and
// a member-function pointer to every call); or, to an initiator that looks
// for it, one plain virtual call as a DirectTransport.
class AhbBus::InitiatorPort : public tlm::tlm_target_socket<32>,
                              public tlm::tlm_fw_transport_if<>,
                              public DirectTransport {
 public:
  InitiatorPort(const char* name, AhbBus& bus, unsigned index)
      : tlm::tlm_target_socket<32>(name), m_bus(bus), m_index(index) {
    bind(static_cast<tlm::tlm_fw_transport_if<>&>(*this));
  }

 private:
  // A forwarder either way (the socket's thunk jumps straight on): the
  // bus has an entry for each door.
  void b_transport(tlm::tlm_generic_payload& gp, sc_time& delay) final { m_bus.b_transport(m_index, gp, delay); }
  void direct_b_transport(tlm::tlm_generic_payload& gp, sc_time& delay, DirectExtras& extras) override {
    m_bus.b_transport(m_index, gp, delay, extras);
  }
  bool quote_train(const WordTrain& train, uint64_t first_ticks, TrainQuote& quote) override {
    return m_bus.quote_train(m_index, train, first_ticks, quote);
  }
  void direct_train(const WordTrain& train, const uint64_t* arrivals) override {
    m_bus.direct_train(m_index, train, arrivals);
  }
  bool quote_copy(const CopyPlan& plan, CopyQuote& quote) override { return m_bus.quote_copy(plan, quote); }
  bool quote_posts(const PostPlan& plan, PostQuote& quote) override { return m_bus.quote_posts(plan, quote); }
  void direct_posts(const PostPlan& plan, const PostQuote& quote, size_t first, size_t count,
                    const CopyRequest* requests, const uint8_t* data) override {
    m_bus.direct_posts(m_index, plan, quote, first, count, requests, data);
  }
  void direct_copy(const CopyPlan& plan, const CopyQuote& quote, size_t first_block, size_t blocks,
                   const CopyRequest* requests, uint8_t* data) override {
    m_bus.direct_copy(m_index, plan, quote, first_block, blocks, requests, data);
  }
  unsigned transport_dbg(tlm::tlm_generic_payload& gp) override { return m_bus.transport_dbg(m_index, gp); }
  bool get_direct_mem_ptr(tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) override {
    return m_bus.get_direct_mem_ptr(m_index, gp, dmi);
  }
  // Loosely timed only.
  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& gp, tlm::tlm_phase& phase, sc_time& delay) override {
    (void)phase;
    (void)delay;
    log::warning(m_bus.name(), "nb_transport_fw by " + m_bus.m_stats[m_index].name +
                                   " is not supported (loosely timed: b_transport only)");
    gp.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
    return tlm::TLM_COMPLETED;
  }

  AhbBus& m_bus;
  unsigned m_index;
};

AhbBus::AhbBus(sc_core::sc_module_name name, const BusParams& params)
    : Block(name),
      out("out"),
      m_params(params),
      m_context(sc_core::sc_get_curr_simcontext()),
      m_period_ticks(params.clock_period.value()),
      // Checked below, with the bus's name in the message.
      m_cycles(std::max<uint64_t>(1, m_period_ticks)),
      m_beats(std::max(1u, params.width_bytes)),
      m_busy_cycles(counter("busy_cycles", "bus cycles reserved by transfers, all initiators")) {
  if (m_period_ticks == 0) throw std::invalid_argument(std::string(this->name()) + ": zero clock period");
  if (params.width_bytes == 0) throw std::invalid_argument(std::string(this->name()) + ": zero bus width");
  out.register_invalidate_direct_mem_ptr(this, &AhbBus::invalidate_direct_mem_ptr);
}

AhbBus::~AhbBus() = default;

void AhbBus::add_initiator(const std::string& initiator_name, unsigned priority, BindInitiator bind) {
  if (sc_core::sc_get_status() != sc_core::SC_ELABORATION)
    throw std::logic_error(std::string(name()) + ": initiator " + initiator_name + " attached after elaboration");
  BusInitiatorStats stats;
  stats.name = initiator_name;
  stats.priority = priority;
  m_stats.push_back(stats);
  m_wait_histograms.emplace_back();
  m_request_memo.emplace_back();
  m_binds.push_back(std::move(bind));
  // attach() runs outside the bus's constructor, so these modules land in
  // the caller's scope: the bus's name keeps them apart from another bus's.
  const std::string prefix = std::string(basename()) + "_" + initiator_name;
  m_request_traces.push_back(std::make_unique<TimedTrace>((prefix + "_request").c_str()));
  m_grant_traces.push_back(std::make_unique<TimedTrace>((prefix + "_grant").c_str()));
}

void AhbBus::before_end_of_elaboration() {
  // A socket is made inside a module: here the kernel has made the bus the
  // current one, wherever attach() was called from.
  for (size_t i = 0; i < m_binds.size(); ++i) {
    m_ports.push_back(
        std::make_unique<InitiatorPort>((m_stats[i].name + "_in").c_str(), *this, static_cast<unsigned>(i)));
    m_binds[i](*m_ports.back());
  }
  m_binds.clear();
}

void AhbBus::end_of_elaboration() {
  Block::end_of_elaboration();
  for (auto& r : m_regions) r.direct = direct_transport_of(out[static_cast<int>(r.target_index)]);
}

void AhbBus::add_region(uint64_t base, uint64_t size, const std::string& target_name) {
  if (size == 0) throw std::invalid_argument(std::string(name()) + ": region " + target_name + " has size 0");
  for (const auto& r : m_regions)
    if (base < r.base + r.size && r.base < base + size)
      throw std::invalid_argument(std::string(name()) + ": region " + target_name + " at " + log::hex(base) +
                                  " overlaps " + r.name + " at " + log::hex(r.base));
  m_regions.push_back({base, size, target_name, static_cast<unsigned>(m_regions.size()), CycleMemo{}});
}

const AhbBus::Region* AhbBus::decode_other(uint64_t address) const {
  for (const auto& r : m_regions)
    if (address >= r.base && address - r.base < r.size) {
      m_other_region = m_last_region;
      return m_last_region = &r;
    }
  return nullptr;
}

void AhbBus::trace_signals(sc_core::sc_trace_file* file) {
  m_tracing = m_observed = true;
  for (size_t i = 0; i < m_stats.size(); ++i) {
    sc_core::sc_trace(file, m_request_traces[i]->signal, std::string(name()) + "." + m_stats[i].name + "_request");
    sc_core::sc_trace(file, m_grant_traces[i]->signal, std::string(name()) + "." + m_stats[i].name + "_grant");
  }
}

void AhbBus::prune(uint64_t now) {
  // Nothing can be requested before the current time, so the intervals
  // that ended by then (a prefix: they are sorted and disjoint) go.
  const auto ended = std::find_if(m_reserved.begin(), m_reserved.end(),
                                  [&](const Interval& i) { return i.end * m_period_ticks > now; });
  if (ended != m_reserved.begin()) m_pruned_end_cycle = std::max(m_pruned_end_cycle, std::prev(ended)->end);
  m_reserved.erase(m_reserved.begin(), ended);
  // The next pruning when the timeline has doubled: constant cost per
  // reservation, however many intervals are still to come.
  m_prune_at = std::max<size_t>(PRUNE_AT_LEAST, 2 * m_reserved.size());
}

uint64_t AhbBus::reserve_among(uint64_t now, uint64_t request_cycle, uint64_t length_cycles) {
  prune(now);
  uint64_t start = request_cycle;
  const auto by_start = [](uint64_t t, const Interval& i) { return t < i.start; };
  // The first interval starting after the request; the one before it may
  // still be running at the request time.
  auto it = std::upper_bound(m_reserved.begin(), m_reserved.end(), start, by_start);
  if (it != m_reserved.begin() && std::prev(it)->end > start) start = std::prev(it)->end;
  // Skip every interval the transfer would overlap.
  while (it != m_reserved.end() && it->start < start + length_cycles) {
    start = std::max(start, it->end);
    ++it;
  }
  // `it` is now the first interval starting at or after the transfer's
  // end, so the transfer goes just before it; it joins an interval that
  // ends exactly where it starts, to keep the timeline short under
  // back-to-back traffic.
  if (it != m_reserved.begin() && std::prev(it)->end == start)
    std::prev(it)->end = start + length_cycles;
  else
    m_reserved.insert(it, Interval{start, start + length_cycles});
  return start;
}

void AhbBus::resolve_batch() {
  const size_t count = m_stats.size();
  auto rank = [&](const Request* r) -> uint64_t {
    if (m_params.arbitration == Arbitration::fixed_priority)
      return (static_cast<uint64_t>(m_stats[r->initiator].priority) << 32) | r->initiator;
    return (r->initiator + count - m_last_granted - 1) % count;
  };
  const auto before = [&](const Request* a, const Request* b) {
    if (a->request_cycle != b->request_cycle) return a->request_cycle < b->request_cycle;
    return rank(a) < rank(b);
  };
  // A stable insertion sort: a batch holds at most one request per
  // initiator, and std::stable_sort would allocate a buffer each time.
  for (size_t i = 1; i < m_batch.size(); ++i) {
    Request* r = m_batch[i];
    size_t j = i;
    for (; j > 0 && before(r, m_batch[j - 1]); --j) m_batch[j] = m_batch[j - 1];
    m_batch[j] = r;
  }
  const uint64_t now = sc_core::sc_time_stamp().value();
  for (Request* r : m_batch) {
    r->start_cycle = reserve(now, r->request_cycle, r->occupancy_cycles);
    r->granted = true;
    m_last_granted = r->initiator;
  }
  m_batch.clear();
}

void AhbBus::trace_grant(unsigned initiator, uint64_t request_cycle, uint64_t start_cycle, uint64_t end_cycle) {
  const uint64_t end = end_cycle * m_period_ticks;
  m_request_traces[initiator]->set_at(true, sc_time::from_value(request_cycle * m_period_ticks));
  m_grant_traces[initiator]->set_at(true, sc_time::from_value(start_cycle * m_period_ticks));
  m_request_traces[initiator]->set_at(false, sc_time::from_value(end));
  m_grant_traces[initiator]->set_at(false, sc_time::from_value(end));
}

void AhbBus::observe(unsigned initiator, const tlm::tlm_generic_payload& gp, const Region* region,
                     uint64_t request_cycle, uint64_t start_cycle, uint64_t end_cycle) {
  if (m_tracing) trace_grant(initiator, request_cycle, start_cycle, end_cycle);
  if (!m_transactions) return;
  static const std::string unmapped_name = "unmapped";
  m_transactions->transaction(
      {m_stats[initiator].name, region ? region->name : unmapped_name, gp.is_write(), gp.get_address(),
       gp.get_data_length(), sc_time::from_value(request_cycle * m_period_ticks),
       sc_time::from_value(start_cycle * m_period_ticks), sc_time::from_value(end_cycle * m_period_ticks)});
}

uint64_t AhbBus::unmapped(unsigned initiator, tlm::tlm_generic_payload& gp) {
  gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
  ++m_stats[initiator].errors;
  log::warning(name(), "unmapped " + std::string(gp.is_write() ? "write" : "read") + " by " + m_stats[initiator].name +
                           " at " + log::hex(gp.get_address()));
  return m_params.address_cycles + m_params.error_cycles;
}

uint64_t AhbBus::collect(unsigned initiator, uint64_t request_cycle, uint64_t occupancy_cycles) {
  Request request{initiator, request_cycle, occupancy_cycles};
  m_batch.push_back(&request);
  wait(sc_core::SC_ZERO_TIME);
  if (!request.granted) resolve_batch();
  return request.start_cycle;
}

void AhbBus::log_grant(unsigned initiator, const tlm::tlm_generic_payload& gp, uint64_t start_cycle,
                       uint64_t occupancy_cycles) const {
  log::debug(name(), m_stats[initiator].name + (gp.is_write() ? " write " : " read ") +
                         std::to_string(gp.get_data_length()) + " bytes at " + log::hex(gp.get_address()) +
                         ", granted " + sc_time::from_value(start_cycle * m_period_ticks).to_string() + ", " +
                         std::to_string(occupancy_cycles) + " cycles");
}

bool AhbBus::must_collect() const {
  // A delta cycle collects the synchronised requests of this instant, to
  // serve them in arbitration order. When no other request is waiting and
  // nothing else can run at this time (no runnable process, no delta
  // notification, no pending update), the request would be alone in its
  // batch and nothing would happen during its delta cycle: serving it at
  // once gives the same grant and the same times, one delta cycle earlier,
  // without the two context switches. (A run stopped by sc_stop() in this
  // delta cycle never wakes the waiting request, so then it waits as
  // before; sc_pause() is not used by the SoC.)
  return !m_batch.empty() || sc_core::sc_pending_activity_at_current_time() ||
         sc_core::sc_get_simulator_status() != sc_core::SC_SIM_OK;
}

uint64_t AhbBus::train_beats(uint64_t length, unsigned transfers) const {
  return transfers * single_beats(length / transfers);
}

inline void AhbBus::serve(unsigned initiator, tlm::tlm_generic_payload& gp, sc_time& delay, DirectExtras& extras) {
  const uint64_t now = m_context->time_stamp().value();
  const uint64_t local_ticks = now + delay.value();
  // Request time: the initiator's local time, rounded up to a clock edge.
  const uint64_t request_cycle = ceil_cycles(local_ticks, m_request_memo[initiator]);
  const uint64_t request_ticks = request_cycle * m_period_ticks;

  // From the local time to the clock edge: zero for most requests (an
  // initiator's next request is usually at the end of its last one).
  sc_time to_edge;
  if (request_ticks != local_ticks) to_edge = ticks_time(request_ticks - local_ticks);

  const uint64_t address = gp.get_address();
  const Region* region = decode(address);
  uint64_t target_cycles = 0;
  if (region) {
    gp.set_address(address - region->base);
    // The target sees the access at the time it is requested (the
    // initiator's local time, as loosely-timed targets expect) and adds
    // its latency, which sets the data phase.
    sc_time target_delay = delay;
    target_delay += to_edge;
    if (region->direct)
      region->direct->direct_b_transport(gp, target_delay, extras);
    else
      out[region->target_index]->b_transport(gp, target_delay);
    gp.set_address(address);
    target_cycles = ceil_cycles(target_delay.value() - (request_ticks - now), region->latency);
  }
  const unsigned transfers = extras.transfers > 0 ? extras.transfers : 1;
  const uint64_t length = gp.get_data_length();
  const uint64_t beats = transfers == 1 ? single_beats(length) : train_beats(length, transfers);
  BusInitiatorStats& s = m_stats[initiator];
  uint64_t occupancy_cycles;
  if (region) {
    occupancy_cycles = occupancy(target_cycles, beats, transfers);
    if (gp.is_response_error()) ++s.errors;
  } else {
    occupancy_cycles = unmapped(initiator, gp);
  }

  uint64_t start_cycle;
  if (delay.value() == 0 && must_collect()) {
    // Synchronised request: let every request of this instant arrive, then
    // the first to wake serves them all in arbitration order.
    start_cycle = collect(initiator, request_cycle, occupancy_cycles);
  } else {
    // Pending synchronised requests are for the current time, so no later
    // than this one: they are served first.
    if (!m_batch.empty()) resolve_batch();
    start_cycle = reserve(now, request_cycle, occupancy_cycles);
    m_last_granted = initiator;
  }
  const uint64_t end_cycle = start_cycle + occupancy_cycles;

  s.transactions += transfers;
  if (gp.is_read()) s.reads += transfers;
  if (gp.is_write()) s.writes += transfers;
  s.bytes += length;
  s.beats += beats;
  s.busy_cycles += occupancy_cycles;
  s.wait_cycles += start_cycle - request_cycle;
  m_wait_histograms[initiator].sample(start_cycle - request_cycle);
  if (m_observed) observe(initiator, gp, region, request_cycle, start_cycle, end_cycle);
  if (log::enabled(log::Level::debug)) log_grant(initiator, gp, start_cycle, occupancy_cycles);

  // The initiator's next request is usually at this one's end.
  m_request_memo[initiator] = {end_cycle * m_period_ticks, end_cycle};
  // Returned delay: the end minus the kernel's time (a delta cycle does not
  // move it), that is the delay given, to the edge, then whole cycles.
  delay += to_edge;
  delay += cycles_time(end_cycle - request_cycle);
}

// Through the socket: the extensions' values read from the payload, and a
// target's "untouched" handed back in its extension.
void AhbBus::b_transport(unsigned initiator, tlm::tlm_generic_payload& gp, sc_time& delay) {
  DirectExtras extras;
  extras.transfers = transfers_of(gp);
  serve(initiator, gp, delay, extras);
  if (extras.untouched) mark_schedule_untouched(gp);
}

void AhbBus::b_transport(unsigned initiator, tlm::tlm_generic_payload& gp, sc_time& delay, DirectExtras& extras) {
  serve(initiator, gp, delay, extras);
}

bool AhbBus::quote_train(unsigned initiator, const WordTrain& train, uint64_t first_ticks, TrainQuote& quote) {
  // Served as a unit only where serve() would do nothing but reserve each
  // word's cycles at its request with no search, no delta cycle and
  // nothing observed: the words in one target that quotes them, the first
  // requested after the kernel's time (serve() collects a request at it)
  // and at or after the last reservation's end. Each later word is
  // requested at or after the one before ends (the caller's promise), so
  // it follows the reservations too.
  (void)initiator;
  const uint64_t now = m_context->time_stamp().value();
  if (train.count == 0 || m_observed || log::enabled(log::Level::debug) || !m_batch.empty() || first_ticks <= now)
    return false;
  const Region* region = decode(train.address);
  if (region == nullptr || region->direct == nullptr || region->size < 4) return false;
  const uint64_t offset = train.address - region->base;
  if (offset > region->size - 4 || (train.stride != 0 && train.count - 1 > (region->size - 4 - offset) / train.stride))
    return false;
  const uint64_t request_cycle = m_cycles.ceil(first_ticks);
  if (!m_reserved.empty() && m_reserved.back().end > request_cycle) return false;
  WordTrain relative = train;
  relative.address -= region->base;
  TrainQuote target;
  if (!region->direct->quote_train(relative, request_cycle * m_period_ticks, target) || target.edge_ticks != 1)
    return false;
  quote.edge_ticks = m_period_ticks;
  quote.latency_ticks = occupancy(m_cycles.ceil(target.latency_ticks), single_beats(4)) * m_period_ticks;
  quote.untouched = target.untouched;
  return true;
}

void AhbBus::direct_train(unsigned initiator, const WordTrain& train, const uint64_t* arrivals) {
  if (train.count == 0) return;
  const uint64_t now = m_context->time_stamp().value();
  const Region* region = decode(train.address);
  if (region == nullptr || region->direct == nullptr)
    throw std::logic_error(std::string(name()) + ": a train unquoted");
  // Each word as serve() would reserve it: at its request's clock edge,
  // arriving at the target there.
  const uint64_t beats = single_beats(4);
  // Grown, never shrunk: a shorter train leaves the vector as it is.
  if (m_train_arrivals.size() < train.count) m_train_arrivals.resize(train.count);
  uint64_t* const at_target = m_train_arrivals.data();
  uint64_t occupancy_cycles = 0, end_cycle = 0;
  for (size_t k = 0; k < train.count; ++k) {
    if (k > 0 && arrivals[k] == end_cycle * m_period_ticks) {
      // Words requested each at the end of the one before: each is
      // reserve()'s first case, joining the last reservation (the word
      // before's) at its end. (The step in a local: a member would be
      // read again after each store.)
      const size_t first = k;
      const uint64_t step = occupancy_cycles * m_period_ticks;
      for (uint64_t at = arrivals[k]; k < train.count && arrivals[k] == at; ++k, at += step) at_target[k] = at;
      // The run as one request at the last reservation's end: reserve()
      // joins it to that reservation.
      const uint64_t cycles = occupancy_cycles * (k - first);
      if (reserve(now, end_cycle, cycles) != end_cycle)
        throw std::logic_error(std::string(name()) + ": a train's word found the bus reserved");
      end_cycle += cycles;
      m_request_memo[initiator] = {end_cycle * m_period_ticks, end_cycle};
      if (k == train.count) break;
    }
    const uint64_t request_cycle = ceil_cycles(arrivals[k], m_request_memo[initiator]);
    at_target[k] = request_cycle * m_period_ticks;
    if (k == 0) {
      TrainQuote target;
      WordTrain relative = train;
      relative.address -= region->base;
      if (!region->direct->quote_train(relative, at_target[0], target))
        throw std::logic_error(std::string(name()) + ": a train its target no longer quotes");
      occupancy_cycles = occupancy(ceil_cycles(target.latency_ticks, region->latency), beats);
    }
    const uint64_t start_cycle = reserve(now, request_cycle, occupancy_cycles);
    if (start_cycle != request_cycle)
      throw std::logic_error(std::string(name()) + ": a train's word found the bus reserved");
    end_cycle = start_cycle + occupancy_cycles;
    m_request_memo[initiator] = {end_cycle * m_period_ticks, end_cycle};
  }
  WordTrain relative = train;
  relative.address -= region->base;
  region->direct->direct_train(relative, at_target);
  BusInitiatorStats& s = m_stats[initiator];
  s.transactions += train.count;
  s.writes += train.count;
  s.bytes += 4 * train.count;
  s.beats += beats * train.count;
  s.busy_cycles += occupancy_cycles * train.count;
  m_wait_histograms[initiator].sample(0, train.count);
  m_last_granted = initiator;
}

bool AhbBus::units_served() const {
  return !m_observed && !log::enabled(log::Level::debug) && m_batch.empty();
}

bool AhbBus::quote_copy(const CopyPlan& plan, CopyQuote& quote) {
  // Served as a unit only where serve() would do nothing but reserve each
  // request (as quote_train asks), both ranges each in one target that
  // quotes its accesses; the caller keeps every request after the kernel's
  // time (no delta cycle) and follows reserve() from the last reservation.
  if (plan.blocks == 0 || plan.bytes == 0 || !units_served()) return false;
  const uint64_t length = uint64_t{plan.bytes} * plan.blocks;
  const Region* fill = decode(plan.from);
  const Region* burst = decode(plan.to);
  if (fill == nullptr || burst == nullptr || fill == burst || fill->direct == nullptr || burst->direct == nullptr)
    return false;
  if (plan.from - fill->base > fill->size - length || length > fill->size ||
      plan.to - burst->base > burst->size - length || length > burst->size)
    return false;
  uint64_t fill_latency = 0, burst_latency = 0;
  if (!fill->direct->quote_accesses(tlm::TLM_READ_COMMAND, plan.from - fill->base, plan.bytes, plan.blocks, 1,
                                    fill_latency, quote.fill_untouched) ||
      !burst->direct->quote_accesses(tlm::TLM_WRITE_COMMAND, plan.to - burst->base, plan.bytes, plan.blocks, 1,
                                     burst_latency, quote.burst_untouched))
    return false;
  const uint64_t beats = single_beats(plan.bytes);
  quote.period_ticks = m_period_ticks;
  quote.fill_cycles = occupancy(ceil_cycles(fill_latency, fill->latency), beats);
  quote.burst_cycles = occupancy(ceil_cycles(burst_latency, burst->latency), beats);
  quote.last = last_reservation();
  return true;
}

void AhbBus::direct_copy(unsigned initiator, const CopyPlan& plan, const CopyQuote& quote, size_t first_block,
                         size_t blocks, const CopyRequest* requests, uint8_t* data) {
  if (blocks == 0) return;
  // The quote's conditions that a caller could have let change.
  const Region* fill = decode(plan.from);
  const Region* burst = decode(plan.to);
  if (fill == nullptr || burst == nullptr || fill->direct == nullptr || burst->direct == nullptr || !units_served() ||
      first_block + blocks > plan.blocks)
    throw std::logic_error(std::string(name()) + ": a copy the bus no longer quotes");
  // Each request as serve() would reserve it and count it.
  const uint64_t now = m_context->time_stamp().value();
  const uint64_t beats = single_beats(plan.bytes);
  BusInitiatorStats& s = m_stats[initiator];
  uint64_t end_cycle = 0;
  for (size_t r = 0; r < 2 * blocks; ++r) {
    const uint64_t occupancy_cycles = r % 2 == 0 ? quote.fill_cycles : quote.burst_cycles;
    const CopyRequest& request = requests[r];
    if (reserve(now, request.request_cycle, occupancy_cycles) != request.start_cycle)
      throw std::logic_error(std::string(name()) + ": a copy's request granted where its quote did not say");
    end_cycle = request.start_cycle + occupancy_cycles;
    s.busy_cycles += occupancy_cycles;
    s.wait_cycles += request.start_cycle - request.request_cycle;
    m_wait_histograms[initiator].sample(request.start_cycle - request.request_cycle);
  }
  s.transactions += 2 * blocks;
  s.reads += blocks;
  s.writes += blocks;
  s.bytes += 2 * uint64_t{plan.bytes} * blocks;
  s.beats += 2 * beats * blocks;
  m_last_granted = initiator;
  m_request_memo[initiator] = {end_cycle * m_period_ticks, end_cycle};
  const uint64_t offset = uint64_t{plan.bytes} * first_block;
  fill->direct->direct_accesses(tlm::TLM_READ_COMMAND, plan.from + offset - fill->base, data, plan.bytes, blocks);
  burst->direct->direct_accesses(tlm::TLM_WRITE_COMMAND, plan.to + offset - burst->base, data, plan.bytes, blocks);
}

bool AhbBus::quote_posts(const PostPlan& plan, PostQuote& quote) {
  // As quote_copy: served as a unit only where serve() would do nothing
  // but reserve each request, the range in one target that quotes its
  // writes in payloads of each request's transfers.
  if (plan.requests == 0 || plan.each == 0 || plan.first == 0 || plan.per_request == 0 || plan.last == 0 ||
      !units_served())
    return false;
  const uint64_t transfers = plan.total();
  const Region* region = decode(plan.address);
  if (region == nullptr || region->direct == nullptr || transfers > region->size / plan.each ||
      plan.address - region->base > region->size - transfers * plan.each)
    return false;
  const uint64_t address = plan.address - region->base;
  bool untouched = true;
  const uint64_t beats = single_beats(plan.each);
  for (unsigned k = 0; k < PostPlan::KINDS; ++k) {
    const unsigned transfers_each = plan.kind_transfers(k);
    if (k != 0 && transfers_each == plan.kind_transfers(k - 1)) {
      quote.cycles[k] = quote.cycles[k - 1];
      continue;
    }
    uint64_t latency = 0;
    bool each_untouched = false;
    if (!region->direct->quote_accesses(tlm::TLM_WRITE_COMMAND, address, plan.each, transfers, transfers_each, latency,
                                        each_untouched))
      return false;
    untouched = untouched && each_untouched;
    // serve()'s occupancy of a request of that many transfers (train_beats).
    quote.cycles[k] = occupancy(ceil_cycles(latency, region->latency), transfers_each * beats, transfers_each);
  }
  quote.period_ticks = m_period_ticks;
  quote.untouched = untouched;
  quote.last = last_reservation();
  return true;
}

void AhbBus::direct_posts(unsigned initiator, const PostPlan& plan, const PostQuote& quote, size_t first, size_t count,
                          const CopyRequest* requests, const uint8_t* data) {
  if (count == 0) return;
  // The quote's conditions that a caller could have let change.
  const Region* region = decode(plan.address);
  if (region == nullptr || region->direct == nullptr || !units_served() || first + count > plan.requests)
    throw std::logic_error(std::string(name()) + ": a posted train the bus no longer quotes");
  // Each request as serve() would reserve it and count it; the waits
  // sampled a run of equal ones at a time.
  const uint64_t now = m_context->time_stamp().value();
  BusInitiatorStats& s = m_stats[initiator];
  Log2Histogram& waits = m_wait_histograms[initiator];
  uint64_t end_cycle = 0, busy = 0, wait_sum = 0, wait = 0, same = 0;
  for (size_t k = 0; k < count; ++k) {
    const uint64_t occupancy_cycles = quote.cycles[plan.kind(first + k)];
    const CopyRequest& request = requests[k];
    if (reserve(now, request.request_cycle, occupancy_cycles) != request.start_cycle)
      throw std::logic_error(std::string(name()) + ": a posted train's request granted where its quote did not say");
    end_cycle = request.start_cycle + occupancy_cycles;
    busy += occupancy_cycles;
    const uint64_t w = request.start_cycle - request.request_cycle;
    wait_sum += w;
    if (w != wait && same != 0) {
      waits.sample(wait, same);
      same = 0;
    }
    wait = w;
    ++same;
  }
  waits.sample(wait, same);
  const uint64_t before = plan.before(first);
  const uint64_t transfers = plan.before(first + count - 1) + plan.transfers(first + count - 1) - before;
  // Every request's beats (train_beats): a single transfer's for each.
  s.transactions += transfers;
  s.writes += transfers;
  s.bytes += uint64_t{plan.each} * transfers;
  s.beats += transfers * single_beats(plan.each);
  s.busy_cycles += busy;
  s.wait_cycles += wait_sum;
  m_last_granted = initiator;
  m_request_memo[initiator] = {end_cycle * m_period_ticks, end_cycle};
  region->direct->direct_accesses(tlm::TLM_WRITE_COMMAND, plan.address + before * plan.each - region->base,
                                  const_cast<uint8_t*>(data), plan.each, transfers);
}

unsigned AhbBus::transport_dbg(unsigned initiator, tlm::tlm_generic_payload& gp) {
  const uint64_t address = gp.get_address();
  const Region* region = decode(address);
  ++m_stats[initiator].debug_accesses;
  if (!region) {
    gp.set_response_status(tlm::TLM_ADDRESS_ERROR_RESPONSE);
    return 0;
  }
  gp.set_address(address - region->base);
  unsigned count = out[region->target_index]->transport_dbg(gp);
  gp.set_address(address);
  return count;
}

bool AhbBus::get_direct_mem_ptr(unsigned initiator, tlm::tlm_generic_payload& gp, tlm::tlm_dmi& dmi) {
  const uint64_t address = gp.get_address();
  const Region* region = decode(address);
  if (!region) {
    dmi.allow_none();
    dmi.set_start_address(0);
    dmi.set_end_address(~sc_dt::uint64(0));
    return false;
  }
  gp.set_address(address - region->base);
  bool granted = out[region->target_index]->get_direct_mem_ptr(gp, dmi);
  gp.set_address(address);
  // Translate the target's range back into the bus address space, clipped to
  // the region.
  const uint64_t last = region->base + region->size - 1;
  uint64_t start = dmi.get_start_address() + region->base;
  uint64_t end = dmi.get_end_address() > region->size - 1 ? last : dmi.get_end_address() + region->base;
  if (start < region->base) start = region->base;
  if (granted) {
    const uint64_t offset = start - (dmi.get_start_address() + region->base);
    dmi.set_dmi_ptr(dmi.get_dmi_ptr() + offset);
    ++m_stats[initiator].dmi_grants;
    // The bus adds its address phase to the target's latencies.
    const sc_time address_phase = m_params.clock_period * m_params.address_cycles;
    dmi.set_read_latency(dmi.get_read_latency() + address_phase);
    dmi.set_write_latency(dmi.get_write_latency() + address_phase);
  }
  dmi.set_start_address(start);
  dmi.set_end_address(end);
  return granted;
}

void AhbBus::invalidate_direct_mem_ptr(int id, sc_dt::uint64 start, sc_dt::uint64 end) {
  for (const auto& r : m_regions) {
    if (r.target_index != static_cast<unsigned>(id)) continue;
    const uint64_t global_start = r.base + std::min<uint64_t>(start, r.size - 1);
    const uint64_t global_end = end >= r.size - 1 ? r.base + r.size - 1 : r.base + end;
    for (const auto& port : m_ports) (*port)->invalidate_direct_mem_ptr(global_start, global_end);
  }
}

double AhbBus::span_cycles(const sc_time& elapsed) const {
  // Busy cycles are counted when a transfer is granted, so the period they
  // are spread over runs to the end of the last granted transfer.
  const uint64_t last_end_cycle = std::max(m_pruned_end_cycle, m_reserved.empty() ? 0 : m_reserved.back().end);
  const uint64_t span = std::max<uint64_t>(elapsed.value(), last_end_cycle * m_period_ticks);
  return span / static_cast<double>(m_period_ticks);
}

uint64_t AhbBus::bytes() const {
  uint64_t total = 0;
  for (const auto& s : m_stats) total += s.bytes;
  return total;
}

nlohmann::json AhbBus::stats_json(const sc_time& elapsed) const {
  const double cycles = span_cycles(elapsed);
  nlohmann::json initiators = nlohmann::json::object();
  for (const auto& s : m_stats) {
    initiators[s.name] = {
        {"priority", s.priority},
        {"transactions", s.transactions},
        {"reads", s.reads},
        {"writes", s.writes},
        {"bytes", s.bytes},
        {"beats", s.beats},
        {"busy_cycles", s.busy_cycles},
        {"wait_cycles", s.wait_cycles},
        {"errors", s.errors},
        {"debug_accesses", s.debug_accesses},
        {"dmi_grants", s.dmi_grants},
        {"utilisation", cycles > 0 ? s.busy_cycles / cycles : 0.0},
    };
  }
  nlohmann::json stats = Block::stats_json(elapsed);
  stats["clock_mhz"] = 1e-6 / m_params.clock_period.to_seconds();
  stats["width_bits"] = m_params.width_bytes * 8;
  stats["arbitration"] = m_params.arbitration == Arbitration::fixed_priority ? "fixed_priority" : "round_robin";
  stats["utilisation"] = cycles > 0 ? m_busy_cycles.value / cycles : 0.0;
  stats["initiators"] = initiators;
  nlohmann::json waits = nlohmann::json::object();
  for (size_t i = 0; i < m_stats.size(); ++i) waits[m_stats[i].name] = histogram_json(m_wait_histograms[i]);
  stats["histograms"]["wait_cycles"] = waits;
  return stats;
}

void AhbBus::describe_stats(StatsSchema& schema) const {
  Block::describe_stats(schema);
  schema.add("clock_mhz", "MHz", "the bus clock frequency (bus.clock_mhz)");
  schema.add("width_bits", "bits", "width of the data bus (bus.width_bytes x 8)");
  schema.add("utilisation", "fraction", "busy_cycles over the bus cycles of the run");
  schema.add_setting("initiators.*.priority", "count",
                     "the initiator's priority (lower is served first under fixed_priority)");
  schema.add("initiators.*.transactions", "count",
             "bus transfers of the initiator (a burst of a longer access is one)");
  schema.add("initiators.*.reads", "count", "read transfers of the initiator");
  schema.add("initiators.*.writes", "count", "write transfers of the initiator");
  schema.add("initiators.*.bytes", "bytes", "bytes the initiator moved");
  schema.add("initiators.*.beats", "count", "data beats (bus words) of the initiator's transfers");
  schema.add("initiators.*.busy_cycles", "cycles", "bus cycles the initiator's transfers occupied the bus");
  schema.add("initiators.*.wait_cycles", "cycles", "bus cycles the initiator's requests waited for the bus");
  schema.add("initiators.*.errors", "count", "transfers of the initiator that got an error response");
  schema.add("initiators.*.debug_accesses", "count", "debug (transport_dbg) accesses of the initiator");
  schema.add("initiators.*.dmi_grants", "count", "direct memory interface grants to the initiator");
  schema.add("initiators.*.utilisation", "fraction", "the initiator's busy_cycles over the bus cycles of the run");
  schema.add_histogram("histograms.wait_cycles.*", "cycles",
                       "the bus cycles each access of the initiator waited for the bus (arbitration and contention)");
}

SummaryRow AhbBus::summary_row(const sc_time& elapsed) const {
  const double cycles = span_cycles(elapsed);
  return {m_params.clock_period * static_cast<double>(m_busy_cycles.value),
          cycles > 0 ? m_busy_cycles.value / cycles : 0.0,
          std::string(m_params.arbitration == Arbitration::fixed_priority ? "fixed_priority" : "round_robin") + ", " +
              std::to_string(m_params.width_bytes * 8) + "-bit"};
}

std::vector<SummaryTable> AhbBus::summary_tables(const sc_time& elapsed) const {
  const double cycles = span_cycles(elapsed);
  SummaryTable table{"bus traffic per initiator",
                     {"initiator", "transactions", "bytes", "busy cycles", "wait cycles", "utilisation"},
                     {}};
  for (const auto& s : m_stats)
    table.rows.push_back({s.name, std::to_string(s.transactions), std::to_string(s.bytes),
                          std::to_string(s.busy_cycles), std::to_string(s.wait_cycles),
                          format_percent(cycles > 0 ? s.busy_cycles / cycles : 0.0)});
  return {table};
}

EnergyActivity AhbBus::energy_activity(const sc_time& now) const {
  (void)now;
  uint64_t beats = 0;
  for (const BusInitiatorStats& s : m_stats) beats += s.beats;
  return {{"bus", {{"beats", static_cast<double>(beats)}}}};
}

}  // namespace tessera
