// The host-compiled model's costs, measured on the ISS (README.md): every
// place in the driver whose host time the native model charges names a row
// of host_costs.def and a count of that row's unit (a vertex transformed,
// a pixel shaded, a span walked); the row's cycles per unit are what the
// ISS spends there running the same code compiled for the ARM922T, fitted
// by scripts/measure_host_costs.py. On the ISS itself a charge is nothing:
// the instructions take the time.
//
// Natively the meter also counts the units charged per bucket (the GL
// driver's phases), which the frame records carry as units_<bucket>_<row>,
// so that the script can fit the rows to the ISS's phase times.
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <iterator>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "host/host_api.h"

namespace tessera::costs {

enum class HostCost : uint16_t {
#define HOST_COST(name, cycles, unit) name,
#include "costs/host_costs.def"
#undef HOST_COST
  count_
};

inline constexpr size_t HOST_COST_COUNT = static_cast<size_t>(HostCost::count_);

// The row named `name`, if the table has one (a lookup by name: resolve a
// row once, where its name is made, not at each charge).
std::optional<HostCost> find_host_cost(const std::string& name);

// Buckets the meter counts units in: the GL phases (0 .. PHASE_BUCKETS - 1,
// one at a time), and within them the array back ends' split of their host
// time (PHASE_BUCKETS .., renderers/common/host_time.h: compute, array
// write, array read, array wait, frame out), in which a charge counts as
// well while one is open.
inline constexpr unsigned PHASE_BUCKETS = 4;
inline constexpr unsigned SPLIT_BUCKETS = 5;
inline constexpr unsigned COST_BUCKETS = PHASE_BUCKETS + SPLIT_BUCKETS;
// The buckets' names, as the frame records and statistics name them
// (units_<bucket>_<row>).
inline constexpr const char* COST_BUCKET_NAMES[COST_BUCKETS] = {
    "application", "geometry", "rasterization", "presenting", "compute", "write", "read", "wait", "frame_out"};
inline constexpr unsigned NO_SPLIT = ~0u;

#if defined(TESSERA_HOST_ISS)

inline void charge(HostApi& /*host*/, HostCost /*cost*/, uint64_t /*units*/ = 1) {}
inline void set_cost_bucket(unsigned /*bucket*/) {}
inline unsigned set_split_bucket(unsigned /*split*/) {
  return NO_SPLIT;
}
inline void reset_cost_meter() {}
inline std::vector<std::pair<std::string, double>> take_cost_units() {
  return {};
}
inline uint64_t units_since_taken(HostCost /*cost*/) {
  return 0;
}

#else

namespace detail {
// Each row's cycles per unit (host_costs.def), and the meter: the units
// charged per bucket and row, and the fraction of a cycle carried over.
inline constexpr double ROW_CYCLES[] = {
#define HOST_COST(name, cycles, unit) cycles,
#include "costs/host_costs.def"
#undef HOST_COST
};
static_assert(std::size(ROW_CYCLES) == HOST_COST_COUNT);
struct Meter {
  unsigned bucket = 0;
  unsigned split = NO_SPLIT;
  double carry = 0;  // cycles charged less whole cycles given to the host, in [0, 1)
  std::array<std::array<uint64_t, HOST_COST_COUNT>, COST_BUCKETS> units{};
};
inline Meter meter;
[[noreturn]] void no_such_row();
// A charge of 2^63 cycles or more: an error (std::overflow_error naming it),
// since no run reaches it (the host counts cycles in 64 bits).
[[noreturn]] void charge_huge(double cycles);
}  // namespace detail

// Charges `units` of `cost` to the host: the row's cycles times units, in
// whole cycles (the fractions carry over to the next charge). Inline: the
// driver charges at every span and access (natively, charging had been a
// tenth of an `arm` frame's time as a call).
inline void charge(HostApi& host, HostCost cost, uint64_t units = 1);
// The whole cycles charge() would give the host for `units` of `cost`,
// counted in the meter as charge() counts them, for the caller to hand the
// host itself (a store train's cycles before each store:
// HostApi::write32_train).
inline uint64_t meter_cycles(HostCost cost, uint64_t units = 1) {
  const auto index = static_cast<size_t>(cost);
  if (index >= HOST_COST_COUNT) detail::no_such_row();
  if (units == 0) return 0;
  detail::Meter& m = detail::meter;
  m.units[m.bucket][index] += units;
  if (m.split != NO_SPLIT) m.units[m.split][index] += units;
  const double cycles = m.carry + detail::ROW_CYCLES[index] * static_cast<double>(units);
  // The whole cycles: cycles is at least 0, so below 2^63 its truncation to
  // an integer is its floor, exactly (one conversion each way, where
  // std::floor without SSE4.1 is a dozen instructions on the chain of
  // charges through the carry).
  if (__builtin_expect(cycles >= 0x1p63, 0)) detail::charge_huge(cycles);
  const auto whole = static_cast<int64_t>(cycles);
  m.carry = cycles - static_cast<double>(whole);
  return static_cast<uint64_t>(whole);
}
// meter_cycles(cost) `count` times, into cycles[0 .. count - 1].
inline void meter_cycles_each(HostCost cost, uint64_t* cycles, size_t count) {
  const auto index = static_cast<size_t>(cost);
  if (index >= HOST_COST_COUNT) detail::no_such_row();
  detail::Meter& m = detail::meter;
  m.units[m.bucket][index] += count;
  if (m.split != NO_SPLIT) m.units[m.split][index] += count;
  double carry = m.carry;
  for (size_t k = 0; k < count; ++k) {
    const double total = carry + detail::ROW_CYCLES[index];
    if (__builtin_expect(total >= 0x1p63, 0)) detail::charge_huge(total);
    const auto whole = static_cast<int64_t>(total);
    const double next = total - static_cast<double>(whole);
    cycles[k] = static_cast<uint64_t>(whole);
    // Each step is a function of the carry alone: once it carries the
    // fraction it was given (a row of whole cycles does from its second
    // word), every later word takes the same cycles.
    if (next == carry) {
      std::fill(cycles + k + 1, cycles + count, cycles[k]);
      break;
    }
    carry = next;
  }
  m.carry = carry;
}
inline void charge(HostApi& host, HostCost cost, uint64_t units) {
  if (const uint64_t whole = meter_cycles(cost, units)) host.compute_cycles(whole);
}
// Counts later charges in phase bucket `bucket` (< PHASE_BUCKETS).
void set_cost_bucket(unsigned bucket);
// Counts later charges also in split bucket `split` (PHASE_BUCKETS ..
// COST_BUCKETS - 1; NO_SPLIT: in none); returns the split open before.
unsigned set_split_bucket(unsigned split);
// Forgets the counts and the carried fraction (a new program starts).
void reset_cost_meter();
// The units charged since the last call, per bucket and row, as
// units_<bucket name>_<row name> (COST_BUCKET_NAMES; rows with none are
// left out).
std::vector<std::pair<std::string, double>> take_cost_units();
// The units of `cost` charged since the last take_cost_units (natively: in
// a GL frame, since its swap), over the phase buckets; 0 on the ISS.
uint64_t units_since_taken(HostCost cost);

#endif

}  // namespace tessera::costs
