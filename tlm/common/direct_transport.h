// A blocking transport reached by one plain virtual call.
//
// tlm_fw_transport_if reaches b_transport through virtual bases: a call
// through it adjusts `this` by an offset read from the vtable, then enters a
// thunk that adjusts it back. On the paths every host access takes (the
// host's socket to the bus, the bus to the memory and the CIU) that is a
// chain of dependent loads per access. A forward interface that also
// derives from DirectTransport (publicly, as it derives from
// tlm_fw_transport_if, so that direct_transport_of finds it) is called here
// instead; its direct_b_transport must do exactly what its b_transport does
// (call it: b_transport is final there, so the call is direct, not a second
// dispatch).
//
// Whoever calls looks the interface up once, after binding (end of
// elaboration), and keeps the plain socket call for an interface without it
// (a protocol checker in between, a test's target).
//
// Beside the payload the direct call carries DirectExtras: the values of the
// two extensions this house's blocks read or set on every access
// (TransferTrain's count, ScheduleUntouched's flag) as plain fields, so that
// neither side calls tlm_generic_payload::get_extension, an out-of-line call
// into the SystemC library, per access. The payload still carries the
// extensions themselves, with the same values, for any target reached
// through a socket; a target sets the flag in DirectExtras when called
// directly and in the extension when called through its socket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include <systemc>
#include <tlm>

namespace tessera {

struct DirectExtras {
  unsigned transfers = 1;  // the single transfers the payload stands for (TransferTrain)
  bool untouched = false;  // set by a target whose access scheduled nothing (ScheduleUntouched)
};

// A store train as a unit (HostApi::write32_train): `count` single 32-bit
// writes, word k of values[k] at address + k * stride, each its own
// transfer, issued in order, each after the one before has completed (a
// posted write leaves the write buffer when the bus has finished the last).
struct WordTrain {
  uint64_t address = 0;
  uint64_t stride = 0;
  const uint32_t* values = nullptr;
  size_t count = 0;
};

// The bus's last reservation, from which a caller that holds the bus alone
// follows reserve()'s grants (AhbBus::reserve): a request at `at` (a bus
// cycle) holding the bus `hold` cycles starts at `at` when it is after the
// last reservation's end (or there is none), at that end when it is at or
// within it; before its start it would be a search among the reservations
// (false).
struct LastReservation {
  bool has = false;
  uint64_t start = 0;
  uint64_t end = 0;
  bool grant(uint64_t at, uint64_t hold, uint64_t& granted) {
    if (!has || at > end) {
      start = granted = at;
    } else if (at < start) {
      return false;
    } else {
      granted = end;
    }
    has = true;
    end = granted + hold;
    return true;
  }
};

// A frame copy as a unit (HostApi::copy_words): `blocks` blocks, block k a
// line fill of `bytes` bytes read at from + k * bytes and a burst of them
// written at to + k * bytes (a single transfer each). The requests go to
// the bus in order, each after the one before has been requested.
struct CopyPlan {
  uint64_t from = 0;
  uint64_t to = 0;
  unsigned bytes = 0;
  size_t blocks = 0;
};
// What the bus promises for a plan's requests (quote_copy): each holds it
// for the cycles of its kind, once it has it; a request is granted as
// reserve() grants it, which the caller follows from the bus's last
// reservation (`last`, in the bus's cycles of period_ticks); whether a
// fill, and a burst, left the kernel's schedule as it was.
struct CopyQuote {
  uint64_t period_ticks = 1;
  uint64_t fill_cycles = 0;
  uint64_t burst_cycles = 0;
  bool fill_untouched = false;
  bool burst_untouched = false;
  LastReservation last;
};
// One request of a copy or a posted train handed to the bus (direct_copy,
// direct_posts): the cycle it was requested at and the one the caller
// found it granted at.
struct CopyRequest {
  uint64_t request_cycle = 0;
  uint64_t start_cycle = 0;
};

// A posted train as the write buffer's requests (the host's post_write):
// single writes of `each` bytes back to back from `address`, in
// `requests` requests (bus requests of several transfers), the first of
// `first` transfers, the last of `last`, each between of `per_request`.
struct PostPlan {
  uint64_t address = 0;
  unsigned each = 0;
  unsigned first = 0;
  unsigned per_request = 0;
  unsigned last = 0;
  size_t requests = 0;
  // The kind of request r: 0 the first, 1 one between, 2 the last; the
  // transfers of a request of each kind, and of request r.
  static constexpr unsigned KINDS = 3;
  unsigned kind(size_t r) const { return r == 0 ? 0 : r + 1 == requests ? 2 : 1; }
  unsigned kind_transfers(unsigned k) const { return k == 0 ? first : k == 1 ? per_request : last; }
  unsigned transfers(size_t r) const { return kind_transfers(kind(r)); }
  // The transfers before request r.
  uint64_t before(size_t r) const { return r == 0 ? 0 : first + uint64_t{per_request} * (r - 1); }
  uint64_t total() const { return requests == 1 ? first : before(requests - 1) + last; }
};
// What the bus promises for a posted train's requests (quote_posts): each
// holds it for the cycles of its kind, granted as reserve() grants it
// (followed from `last`); whether they leave the kernel's schedule as it
// was.
struct PostQuote {
  uint64_t period_ticks = 1;
  uint64_t cycles[PostPlan::KINDS] = {0, 0, 0};
  bool untouched = false;
  LastReservation last;
};

// The timing a target or the bus promises for a train's words (quote_train):
// a word that arrives at absolute tick t completes at done(t), the arrival
// rounded up to a multiple of edge_ticks (the bus's clock edge) plus
// latency_ticks (a multiple of edge_ticks); and whether the words schedule nothing in the kernel
// (ScheduleUntouched), which the caller's quantum keeping needs.
struct TrainQuote {
  uint64_t edge_ticks = 1;
  uint64_t latency_ticks = 0;
  bool untouched = false;
  uint64_t done(uint64_t t) const { return (t + edge_ticks - 1) / edge_ticks * edge_ticks + latency_ticks; }
  // The latency is a whole number of edges, so a completion is on an edge:
  // a word issued at `previous_done` (the word before's completion, as a
  // posted write that waited for the buffer is) completes a latency later,
  // without the division.
  uint64_t done_after(uint64_t t, uint64_t previous_done) const {
    return t == previous_done ? t + latency_ticks : done(t);
  }
};

class DirectTransport {
 public:
  virtual void direct_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, DirectExtras& extras) = 0;

  // Store trains (WordTrain). quote_train: whether the target would serve
  // every word of `train`, the first arriving at absolute tick `first_ticks`
  // or later and each later one after the one before, exactly as it serves
  // the same words one payload at a time (same data, counters, times and
  // outcome: no error), and with what timing; false, the default: the
  // caller sends the words one payload at a time. The answer holds while
  // nothing else reaches the target and the kernel's time stands (the
  // caller's quantum). direct_train: serves a quoted train, word k arriving
  // at absolute tick arrivals[k]; only called after a true quote_train.
  virtual bool quote_train(const WordTrain& /*train*/, uint64_t /*first_ticks*/, TrainQuote& /*quote*/) {
    return false;
  }
  virtual void direct_train(const WordTrain& /*train*/, const uint64_t* /*arrivals*/) {
    throw std::logic_error("direct_train on a target that quotes no trains");
  }
  // Accesses as a unit (a frame copy's fills or bursts, a posted train's
  // stores): quote_accesses: whether the target would serve `count`
  // accesses of `bytes` bytes, the k-th at address + k * bytes (command,
  // no byte enables, one transfer each), in payloads of `transfers` of them
  // (DirectExtras::transfers), exactly as direct_b_transport serves each
  // payload (same data, counters, outcome: no error) with a delay of its
  // own that does not depend on the time: latency_ticks, per payload; and
  // whether each leaves the kernel's schedule as it was (ScheduleUntouched,
  // or DMI granted: memory). false, the default: one payload each.
  // direct_accesses: serves them, their bytes at `data` one after the
  // other; only after a true quote_accesses (of any payload size).
  virtual bool quote_accesses(tlm::tlm_command /*command*/, uint64_t /*address*/, unsigned /*bytes*/, size_t /*count*/,
                              unsigned /*transfers*/, uint64_t& /*latency_ticks*/, bool& /*untouched*/) {
    return false;
  }
  virtual void direct_accesses(tlm::tlm_command /*command*/, uint64_t /*address*/, uint8_t* /*data*/,
                               unsigned /*bytes*/, size_t /*count*/) {
    throw std::logic_error("direct_accesses on a target that quotes no accesses");
  }
  // A copy (CopyPlan) through the bus, from an initiator's door:
  // quote_copy: whether the bus would serve every request of `plan` by
  // reserve() alone (nothing observed or logged, no synchronised request
  // waiting, both ranges in targets that quote their accesses), and how
  // (CopyQuote); the answer holds while the kernel's time stands and no
  // other initiator has the bus. direct_copy: serves blocks first_block ..
  // first_block + blocks - 1 of it as `quote` (quote_copy's answer, while
  // it holds) says, fill and burst each, as requested at requests[2 k] and
  // [2 k + 1] (k from 0), the bursts' bytes from `data`: the bus's
  // reservations and figures, the targets' accesses.
  virtual bool quote_copy(const CopyPlan& /*plan*/, CopyQuote& /*quote*/) { return false; }
  virtual void direct_copy(const CopyPlan& /*plan*/, const CopyQuote& /*quote*/, size_t /*first_block*/,
                           size_t /*blocks*/, const CopyRequest* /*requests*/, uint8_t* /*data*/) {
    throw std::logic_error("direct_copy through a door that quotes no copies");
  }
  // A posted train (PostPlan) through the bus, from an initiator's door:
  // quote_posts: whether the bus would serve every request of `plan` by
  // reserve() alone (as quote_copy), its range in one target that quotes
  // its writes; the answer holds as quote_copy's does. direct_posts: serves
  // requests first .. first + count - 1 of it as `quote` (quote_posts's
  // answer, while it holds) says, request k (from 0) as requested at
  // requests[k], their bytes from `data`.
  virtual bool quote_posts(const PostPlan& /*plan*/, PostQuote& /*quote*/) { return false; }
  virtual void direct_posts(const PostPlan& /*plan*/, const PostQuote& /*quote*/, size_t /*first*/, size_t /*count*/,
                            const CopyRequest* /*requests*/, const uint8_t* /*data*/) {
    throw std::logic_error("direct_posts through a door that quotes no posted trains");
  }

 protected:
  DirectTransport() = default;
  DirectTransport(const DirectTransport&) = default;
  DirectTransport& operator=(const DirectTransport&) = default;
  ~DirectTransport() = default;
};

// The DirectTransport of a bound forward interface, or null.
inline DirectTransport* direct_transport_of(tlm::tlm_fw_transport_if<>* fw) {
  return dynamic_cast<DirectTransport*>(fw);
}

}  // namespace tessera
