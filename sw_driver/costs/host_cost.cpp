// See host_cost.h.
#include "costs/host_cost.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace tessera::costs {

namespace {

struct HostCostRow {
  const char* name;
  double cycles;  // per unit, measured on the ISS
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

namespace {

struct Meter {
  unsigned bucket = 0;
  unsigned split = NO_SPLIT;
  double carry = 0;  // cycles charged less whole cycles given to the host, in [0, 1)
  std::array<std::array<uint64_t, HOST_COST_COUNT>, COST_BUCKETS> units{};
};

Meter& meter() {
  static Meter m;
  return m;
}

}  // namespace

void charge(HostApi& host, HostCost cost, uint64_t units) {
  const auto index = static_cast<size_t>(cost);
  if (index >= HOST_COST_COUNT) throw std::invalid_argument("host cost: no such row");
  if (units == 0) return;
  Meter& m = meter();
  m.units[m.bucket][index] += units;
  if (m.split != NO_SPLIT) m.units[m.split][index] += units;
  const double cycles = m.carry + ROWS[index].cycles * static_cast<double>(units);
  const double whole = std::floor(cycles);
  m.carry = cycles - whole;
  if (whole > 0) host.compute_cycles(static_cast<uint64_t>(whole));
}

void set_cost_bucket(unsigned bucket) {
  if (bucket >= PHASE_BUCKETS) throw std::invalid_argument("host cost: no such bucket");
  meter().bucket = bucket;
}

unsigned set_split_bucket(unsigned split) {
  if (split != NO_SPLIT && (split < PHASE_BUCKETS || split >= COST_BUCKETS))
    throw std::invalid_argument("host cost: no such split bucket");
  const unsigned previous = meter().split;
  meter().split = split;
  return previous;
}

void reset_cost_meter() {
  meter() = Meter{};
}

std::vector<std::pair<std::string, double>> take_cost_units() {
  std::vector<std::pair<std::string, double>> figures;
  Meter& m = meter();
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
  for (unsigned b = 0; b < PHASE_BUCKETS; ++b) units += meter().units[b][index];
  return units;
}

#endif

}  // namespace tessera::costs
