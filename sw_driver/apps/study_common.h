// What the study's applications share: their options (after "--"), their
// figures in stats.json's driver section (study.*), and the guard that turns
// a bad argument into a usage error.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>

#include "apps/apps.h"

namespace tessera::study {

// Refuses an option the application does not take (std::invalid_argument).
void check_options(const AppEnvironment& env, const char* app, std::initializer_list<const char*> known);

// The whole number after `name`, or `fallback`; std::invalid_argument naming
// it when it is not a whole number in [low, high].
unsigned option(const AppEnvironment& env, const char* app, const std::string& name, unsigned fallback, unsigned low,
                unsigned high);

// stats.json's driver.study.<name>.
void publish(AppEnvironment& env, const std::string& name, const char* description, uint64_t value);

// `cycles` of the host's clock in ns.
uint64_t ns(HostApi& host, uint64_t cycles);

// The measured cost table's units charged in the timed parts, as
// study.units_<split>_<row>: what scripts/measure_host_costs.py fits the
// rows charged there to. Natively only (the ISS charges nothing).
void publish_units(AppEnvironment& env);

// run(env), with a bad argument or back end (std::invalid_argument) a usage
// error: status 2, named on standard error.
int usage_guarded(AppEnvironment& env, int (*run)(AppEnvironment&));

}  // namespace tessera::study
