// What the study's applications share (study.cpp, forward_texture.cpp):
// their options, their figures in stats.json's driver section (study.*) and
// the usage-error guard.
#include "apps/study_common.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "costs/host_cost.h"
#include "renderers/common/host_time.h"

namespace tessera::study {

// Refuses an option the application does not take.
void check_options(const AppEnvironment& env, const char* app, std::initializer_list<const char*> known) {
  for (const std::string& arg : env.args) {
    if (arg.rfind("--", 0) != 0) continue;
    if (std::none_of(known.begin(), known.end(), [&](const char* name) { return arg == name; }))
      throw std::invalid_argument(std::string(app) + ": unknown option '" + arg + "'");
  }
}

unsigned option(const AppEnvironment& env, const char* app, const std::string& name, unsigned fallback, unsigned low,
                unsigned high) {
  for (size_t i = 0; i + 1 < env.args.size(); ++i)
    if (env.args[i] == name) {
      size_t used = 0;
      unsigned long value = 0;
      try {
        value = std::stoul(env.args[i + 1], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != env.args[i + 1].size() || value < low || value > high)
        throw std::invalid_argument(std::string(app) + ": " + name + " takes a whole number from " +
                                    std::to_string(low) + " to " + std::to_string(high) + ", not '" + env.args[i + 1] +
                                    "'");
      return static_cast<unsigned>(value);
    }
  return fallback;
}

void publish(AppEnvironment& env, const std::string& name, const char* description, uint64_t value) {
  if (env.counters != nullptr) env.counters->counter("study." + name, description).value = value;
}

uint64_t ns(HostApi& host, uint64_t cycles) {
  return static_cast<uint64_t>(std::llround(renderers::host_ns(host, cycles)));
}

// The measured cost table's units charged in the timed parts (the host
// split's buckets, renderers/common/host_time.h), as study.units_<split>_<row>
// beside study.<split>_ns: what scripts/measure_host_costs.py fits the
// rows of this file to. Natively only (the ISS charges nothing).
void publish_units(AppEnvironment& env) {
  for (const auto& [name, units] : costs::take_cost_units()) {
    for (unsigned b = costs::PHASE_BUCKETS; b < costs::COST_BUCKETS; ++b) {
      const std::string prefix = std::string("units_") + costs::COST_BUCKET_NAMES[b] + "_";
      if (name.compare(0, prefix.size(), prefix) == 0)
        publish(env, name, "units of a row of the measured cost table charged in the timed part",
                static_cast<uint64_t>(units));
    }
  }
}

// A bad argument or back end is a usage error (status 2, as soc_sim's own),
// named on standard error.
int usage_guarded(AppEnvironment& env, int (*run)(AppEnvironment&)) {
  try {
    return run(env);
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "%s\n", e.what());
    return 2;
  }
}

}  // namespace tessera::study
