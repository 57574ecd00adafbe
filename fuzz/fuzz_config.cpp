// Fuzz target: the configuration loader (contract/config), a JSON file through
// Config::load_file and "key=value" overrides through apply_override, as
// soc_sim's --config and --set take them.
//
// Input: the file's text; then, after a line "%%", one override per line.
// The parameters are a fixed set of every type (not the SoC's, which would
// need the SystemC blocks): the loader's code is the same for any key.
//
// Checks: a bad input is a ConfigError (any other exception, a crash or a
// sanitizer report is a fault); after every accepted step each parameter
// reads back with its type and within its range or choices; the effective
// configuration merges back into a fresh one unchanged.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "config/config.h"
#include "fuzz_support.h"

namespace {

using tessera::Config;
using tessera::ConfigError;
using tessera::ParamGroup;
using tessera::ParamSpec;
using tessera::ParamType;
namespace param = tessera::param;

std::vector<ParamGroup> groups() {
  return {
      {"block",
       {
           param::boolean("block.enabled", true, "a boolean"),
           param::integer("block.width", 320, 16, 2048, "pixels", "an integer"),
           param::integer("block.offset", 0, -1000, 1000, "", "a signed integer"),
           param::integer("block.big", 1, 0, 4.0e18, "", "an integer near the 64-bit limit"),
           param::real("block.clock_mhz", 100.0, 1, 1000, "MHz", "a number"),
           param::choice("block.mode", "fast", {"fast", "exact", "off"}, "a choice"),
           param::text("block.name", "", "a string"),
       },
       [](const Config& config) {
         if (config.get_int("block.width") % 16 != 0) throw ConfigError("configuration: block.width: multiple of 16");
       }},
      {"sub",
       {
           param::integer("sub.deep.level", 3, 0, 8, "", "a nested integer"),
           param::real("sub.deep.ratio", 0.5, 0, 1, "", "a nested number"),
           param::boolean("sub.flag", false, "a nested boolean"),
       },
       nullptr},
  };
}

// Every parameter holds a value of its type within its range.
void check_values(const Config& config) {
  for (const ParamSpec& spec : config.specs()) {
    switch (spec.type) {
      case ParamType::boolean: (void)config.get_bool(spec.key); break;
      case ParamType::integer: {
        const auto v = static_cast<double>(config.get_int(spec.key));
        if (v < spec.min || v > spec.max) tessera::fuzz::fail(spec.key + " holds an integer out of its range");
        break;
      }
      case ParamType::real: {
        const double v = config.get_real(spec.key);
        if (!std::isfinite(v) || v < spec.min || v > spec.max)
          tessera::fuzz::fail(spec.key + " holds a number out of its range");
        break;
      }
      case ParamType::string: (void)config.get_string(spec.key); break;
      case ParamType::choice: {
        const std::string v = config.get_string(spec.key);
        bool known = false;
        for (const std::string& choice : spec.choices) known = known || choice == v;
        if (!known) tessera::fuzz::fail(spec.key + " holds '" + v + "', not one of its choices");
        break;
      }
    }
  }
}

// A step may reject its input only with a ConfigError.
template <typename Step>
bool accepted(Step&& step) {
  try {
    step();
    return true;
  } catch (const ConfigError&) {
    return false;
  } catch (const std::exception& e) {
    tessera::fuzz::fail(std::string("an exception other than ConfigError escaped: ") + e.what());
  }
}

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static tessera::fuzz::ScratchFile file(".json");
  const std::string input(reinterpret_cast<const char*>(data), size);
  const std::string separator = "\n%%\n";
  const size_t split = input.find(separator);
  const std::string json = input.substr(0, split);
  std::vector<std::string> overrides;
  if (split != std::string::npos) {
    size_t start = split + separator.size();
    while (start <= input.size()) {
      size_t end = input.find('\n', start);
      if (end == std::string::npos) end = input.size();
      overrides.push_back(input.substr(start, end - start));
      start = end + 1;
    }
  }

  Config config(groups());
  const std::string& path = file.write(reinterpret_cast<const uint8_t*>(json.data()), json.size());
  if (accepted([&] { config.load_file(path); })) check_values(config);
  for (const std::string& assignment : overrides)
    if (accepted([&] { config.apply_override(assignment); })) check_values(config);
  (void)accepted([&] { config.validate(); });

  // What the configuration says it holds is a configuration it accepts.
  Config copy(groups());
  if (!accepted([&] { copy.merge_json(config.to_json(), "the effective configuration"); }))
    tessera::fuzz::fail("the effective configuration does not merge back");
  if (copy.to_json() != config.to_json()) tessera::fuzz::fail("the effective configuration changes when merged back");
  return 0;
}
