// See host_cost.h.
#include "costs/host_cost.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace tessera::costs {

namespace {

struct HostCostRow {
  const char* name;
  // Per unit, measured on the ISS. Read by nothing (charge(), inline, reads
  // detail::ROW_CYCLES); kept because the ARM program links this table (for
  // find_host_cost) and dropping it moves the ARM code, and with it every
  // ISS figure the cost table is fitted to: to go at the next measurement.
  double cycles;
  const char* unit;
};

constexpr HostCostRow ROWS[] = {
#define HOST_COST(name, cycles, unit) {#name, cycles, unit},
#include "costs/host_costs.def"
#undef HOST_COST
};
static_assert(std::size(ROWS) == HOST_COST_COUNT);

}  // namespace

std::optional<HostCost> find_host_cost(const std::string& name) {
  for (size_t i = 0; i < HOST_COST_COUNT; ++i) {
    if (name == ROWS[i].name) return static_cast<HostCost>(i);
  }
  return std::nullopt;
}

#if !defined(TESSERA_HOST_ISS)

void detail::no_such_row() {
  throw std::invalid_argument("host cost: no such row");
}

void detail::charge_huge(double cycles) {
  throw std::overflow_error("host cost: a charge of " + std::to_string(cycles) +
                            " cycles (2^63 or more: more than the host counts)");
}

void set_cost_bucket(unsigned bucket) {
  if (bucket >= PHASE_BUCKETS) throw std::invalid_argument("host cost: no such bucket");
  detail::meter.bucket = bucket;
}

unsigned set_split_bucket(unsigned split) {
  if (split != NO_SPLIT && (split < PHASE_BUCKETS || split >= COST_BUCKETS))
    throw std::invalid_argument("host cost: no such split bucket");
  const unsigned previous = detail::meter.split;
  detail::meter.split = split;
  return previous;
}

void reset_cost_meter() {
  detail::meter = detail::Meter{};
}

std::vector<std::pair<std::string, double>> take_cost_units() {
  std::vector<std::pair<std::string, double>> figures;
  detail::Meter& m = detail::meter;
  for (unsigned b = 0; b < COST_BUCKETS; ++b) {
    for (size_t i = 0; i < HOST_COST_COUNT; ++i) {
      if (m.units[b][i] == 0) continue;
      figures.emplace_back(std::string("units_") + COST_BUCKET_NAMES[b] + "_" + ROWS[i].name,
                           static_cast<double>(m.units[b][i]));
      m.units[b][i] = 0;
    }
  }
  return figures;
}

uint64_t units_since_taken(HostCost cost) {
  const auto index = static_cast<size_t>(cost);
  if (index >= HOST_COST_COUNT) throw std::invalid_argument("host cost: no such row");
  uint64_t units = 0;
  for (unsigned b = 0; b < PHASE_BUCKETS; ++b) units += detail::meter.units[b][index];
  return units;
}

#endif

}  // namespace tessera::costs
