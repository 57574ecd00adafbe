#include "runtime/boot_info.h"

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace tessera::boot_info {

namespace {

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::boolean: return "boolean";
    case ParamType::integer: return "integer";
    case ParamType::real: return "real";
    case ParamType::string: return "string";
    case ParamType::choice: return "choice";
  }
  return "?";
}

ParamType type_of(const std::string& name) {
  for (ParamType t : {ParamType::boolean, ParamType::integer, ParamType::real, ParamType::string, ParamType::choice})
    if (name == type_name(t)) return t;
  throw std::runtime_error("boot information: unknown parameter type '" + name + "'");
}

}  // namespace

std::vector<ParamSpec> effective_parameters(const Config& config) {
  std::vector<ParamSpec> out;
  for (const ParamSpec& spec : config.specs()) {
    // Aggregates built whole: ParamSpec's implicit default constructor is
    // declared noexcept, yet nlohmann::json's default constructor may throw
    // (clang-tidy's bugprone-exception-escape).
    nlohmann::json value;
    switch (spec.type) {
      case ParamType::boolean: value = config.get_bool(spec.key); break;
      case ParamType::integer: value = config.get_int(spec.key); break;
      case ParamType::real: value = config.get_real(spec.key); break;
      case ParamType::string:
      case ParamType::choice: value = config.get_string(spec.key); break;
    }
    out.push_back(ParamSpec{spec.key, spec.type, std::move(value), {}, {}, 0, 0, {}});
  }
  return out;
}

std::string encode(const BootInfo& info) {
  nlohmann::json config = nlohmann::json::array();
  for (const ParamSpec& p : info.config) config.push_back({p.key, type_name(p.type), p.default_value});
  const nlohmann::json doc = {{"app", info.app},
                              {"args", info.args},
                              {"frames", info.frames},
                              {"frame_buffers", {info.frame_buffers[0], info.frame_buffers[1]}},
                              {"memory_bytes", info.memory_bytes},
                              {"heap_base", info.heap_base},
                              {"heap_end", info.heap_end},
                              {"program_heap", {info.program_heap_base, info.program_heap_end}},
                              {"backend", info.backend},
                              {"config", config}};
  return doc.dump();
}

BootInfo decode(const std::string& text) {
  try {
    const nlohmann::json doc = nlohmann::json::parse(text);
    BootInfo info;
    info.app = doc.at("app").get<std::string>();
    info.args = doc.at("args").get<std::vector<std::string>>();
    info.frames = doc.at("frames").get<unsigned>();
    info.frame_buffers[0] = doc.at("frame_buffers").at(0).get<uint32_t>();
    info.frame_buffers[1] = doc.at("frame_buffers").at(1).get<uint32_t>();
    info.memory_bytes = doc.at("memory_bytes").get<uint32_t>();
    info.heap_base = doc.at("heap_base").get<uint32_t>();
    info.heap_end = doc.at("heap_end").get<uint32_t>();
    info.program_heap_base = doc.at("program_heap").at(0).get<uint32_t>();
    info.program_heap_end = doc.at("program_heap").at(1).get<uint32_t>();
    info.backend = doc.at("backend").get<std::string>();
    for (const nlohmann::json& entry : doc.at("config")) {
      ParamSpec p{
          entry.at(0).get<std::string>(), type_of(entry.at(1).get<std::string>()), entry.at(2), {}, {}, 0, 0, {}};
      // Read back, never set: the ranges are the values themselves.
      if (p.type == ParamType::integer || p.type == ParamType::real) p.min = p.max = p.default_value.get<double>();
      if (p.type == ParamType::choice) p.choices = {p.default_value.get<std::string>()};
      info.config.push_back(std::move(p));
    }
    return info;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("boot information: ") + e.what());
  }
}

// A figure's value travels as the 16 hex digits of its IEEE-754 bits: exact,
// and the same few integer operations whatever the value. The ISS runs this
// in the program's own time (the application phase of the next frame), and a
// board's driver would hand over numbers, not format them: newlib's "%.17g"
// costs thousands of soft-float cycles that depend on the digits of each value.
std::string encode_figures(const std::vector<std::pair<std::string, double>>& figures) {
  static constexpr char HEX_DIGITS[] = "0123456789abcdef";
  std::string line;
  for (const auto& [name, value] : figures) {
    if (!line.empty()) line += '\t';
    line += name;
    line += '=';
    uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    char digits[16];
    for (int i = 15; i >= 0; --i, bits >>= 4) digits[i] = HEX_DIGITS[bits & 0xf];
    line.append(digits, sizeof digits);
  }
  line += '\n';
  return line;
}

std::vector<std::pair<std::string, double>> decode_figures(const std::string& line) {
  std::vector<std::pair<std::string, double>> figures;
  size_t start = 0;
  while (start < line.size()) {
    size_t end = line.find('\t', start);
    if (end == std::string::npos) end = line.size();
    const std::string field = line.substr(start, end - start);
    const size_t equals = field.find('=');
    if (equals == std::string::npos) throw std::runtime_error("frame figures: '" + field + "' is not name=value");
    const std::string digits = field.substr(equals + 1);
    if (digits.size() != 16 || digits.find_first_not_of("0123456789abcdef") != std::string::npos)
      throw std::runtime_error("frame figures: '" + field + "' does not hold 16 hex digits after '='");
    const uint64_t bits = std::strtoull(digits.c_str(), nullptr, 16);
    double value = 0;
    std::memcpy(&value, &bits, sizeof value);
    figures.emplace_back(field.substr(0, equals), value);
    start = end + 1;
  }
  return figures;
}

}  // namespace tessera::boot_info
