#include "power/energy_model.h"

#include <cmath>
#include <stdexcept>
#include <utility>

namespace tessera {

namespace {

std::string event_key(const std::string& unit, const std::string& event) {
  return "power." + unit + "." + event + "_pj";
}

std::string static_key(const std::string& unit) {
  return "power." + unit + ".static_mw";
}

void check_value(const std::string& key, double value, const char* unit) {
  if (!std::isfinite(value) || value < 0)
    throw ConfigError("configuration: '" + key + "' must be a finite, non-negative energy in " + unit + ", got " +
                      std::to_string(value));
}

// The table as (unit, event or "" for the static power, default, description).
struct Entry {
  const char* unit;
  const char* event;
  double value;
  const char* source;
  const char* description;
};

const std::vector<Entry>& table() {
  static const std::vector<Entry> entries = {
#define POWER_EVENT(unit, event, pj, source, description) {#unit, #event, pj, #source, description},
#define POWER_STATIC(unit, mw, source, description) {#unit, "", mw, #source, description},
#include "power/energy_params.def"
#undef POWER_EVENT
#undef POWER_STATIC
  };
  return entries;
}

// A parameter's largest legal value: far above any real figure, so that the
// range check only catches typing errors.
constexpr double MAX_PICOJOULES = 1e9;
constexpr double MAX_MILLIWATTS = 1e6;
// A window of a second already spans several frames.
constexpr double MAX_TRACE_WINDOW_MICROSECONDS = 1e6;

}  // namespace

double UnitEnergy::dynamic_joules() const {
  double sum = 0;
  for (const auto& [event, joules] : event_joules) sum += joules;
  return sum;
}

EnergyModel::EnergyModel(std::vector<UnitEnergyParams> units) : m_units(std::move(units)) {
  for (const UnitEnergyParams& u : m_units) {
    for (const EventEnergy& e : u.events) check_value(event_key(u.unit, e.event), e.picojoules, "pJ");
    check_value(static_key(u.unit), u.static_milliwatts, "mW");
  }
}

ParamGroup EnergyModel::parameters() {
  std::vector<ParamSpec> specs;
  for (const Entry& e : table()) {
    const std::string source = std::string(" [") + e.source + "]";
    if (*e.event)
      specs.push_back(
          param::real(event_key(e.unit, e.event), e.value, 0, MAX_PICOJOULES, "pJ", e.description + source));
    else
      specs.push_back(param::real(static_key(e.unit), e.value, 0, MAX_MILLIWATTS, "mW", e.description + source));
  }
  specs.push_back(param::boolean("power.sleep_unused", true,
                                 "a block the software has not used yet sleeps with its clocks gated and is charged "
                                 "no static power, as the board's measurements put every unused block to sleep "
                                 "(false: every block clocked from reset)"));
  specs.push_back(param::real("power.trace_window_us", 100, 0, MAX_TRACE_WINDOW_MICROSECONDS, "us",
                              "with a VCD trace (--vcd), each energy unit's average power in mW over consecutive "
                              "windows of this length, under the scope power (0: no power signals)"));
  return {"power", std::move(specs), nullptr};
}

EnergyModel EnergyModel::from_config(const Config& config) {
  std::vector<UnitEnergyParams> units;
  for (const Entry& e : table()) {
    if (units.empty() || units.back().unit != e.unit) units.push_back({e.unit, {}, 0});
    if (*e.event)
      units.back().events.push_back({e.event, config.get_real(event_key(e.unit, e.event))});
    else
      units.back().static_milliwatts = config.get_real(static_key(e.unit));
  }
  return EnergyModel(std::move(units));
}

EnergyModel EnergyModel::defaults() {
  return from_config(Config({parameters()}));
}

const UnitEnergyParams& EnergyModel::unit(const std::string& name) const {
  for (const UnitEnergyParams& u : m_units)
    if (u.unit == name) return u;
  throw std::logic_error("energy model: no unit '" + name + "' (tlm/power/energy_params.def)");
}

UnitEnergy EnergyModel::energy(const UnitActivity& activity, double seconds) const {
  const UnitEnergyParams& params = unit(activity.unit);
  UnitEnergy result{activity.unit, {}, params.static_milliwatts * 1e-3 * activity.clocked_seconds.value_or(seconds)};
  for (const auto& [event, count] : activity.counts) {
    const EventEnergy* found = nullptr;
    for (const EventEnergy& e : params.events)
      if (e.event == event) found = &e;
    if (!found)
      throw std::logic_error("energy model: unit '" + activity.unit + "' has no event class '" + event +
                             "' (tlm/power/energy_params.def)");
    result.event_joules[event] = count * found->picojoules * 1e-12;
  }
  return result;
}

std::vector<UnitEnergy> EnergyModel::unit_energies(const EnergyActivity& activity, double seconds) const {
  std::vector<UnitEnergy> result;
  for (const UnitActivity& a : activity) result.push_back(energy(a, seconds));
  return result;
}

EnergyActivity activity_difference(const EnergyActivity& later, const EnergyActivity& earlier) {
  EnergyActivity result = later;
  for (UnitActivity& unit : result)
    for (const UnitActivity& before : earlier)
      if (before.unit == unit.unit)
        for (auto& [event, count] : unit.counts) {
          const auto it = before.counts.find(event);
          if (it != before.counts.end()) count -= it->second;
        }
  for (UnitActivity& unit : result)
    if (unit.clocked_seconds)
      for (const UnitActivity& before : earlier)
        if (before.unit == unit.unit && before.clocked_seconds) *unit.clocked_seconds -= *before.clocked_seconds;
  return result;
}

}  // namespace tessera
