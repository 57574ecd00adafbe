// The SoC's configuration: every parameter declared once (parameters.cpp)
// with its type, default, range and description; values merged from a JSON
// file and from "key=value" overrides; every bad value rejected with an error
// that names the key and what was expected.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace tessera {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ParamType { boolean, integer, real, string, choice };

struct ParamSpec {
  std::string key;  // dotted: "bus.arbitration"
  ParamType type;
  nlohmann::json default_value;
  std::string description;
  std::string unit;
  double min = 0;  // integer and real only
  double max = 0;
  std::vector<std::string> choices;  // choice only
};

// The parameter table; defined in parameters.cpp, the one place defaults live.
const std::vector<ParamSpec>& parameter_specs();

class Config {
 public:
  // All parameters at their defaults.
  Config();

  // Merges a JSON document of nested objects ({"bus": {"arbitration": ...}})
  // or dotted keys. `source` names where it came from, for error messages.
  void merge_json(const nlohmann::json& doc, const std::string& source);
  void load_file(const std::string& path);
  // "key=value"; the value is parsed according to the key's type.
  void apply_override(const std::string& assignment);
  // Sets one parameter from a JSON value, checking type and range.
  void set(const std::string& key, const nlohmann::json& value, const std::string& source);

  // Checks combinations of parameters that are individually legal.
  void validate() const;

  bool get_bool(const std::string& key) const;
  int64_t get_int(const std::string& key) const;
  uint64_t get_uint(const std::string& key) const;
  double get_real(const std::string& key) const;
  std::string get_string(const std::string& key) const;

  // The effective configuration as nested JSON objects.
  nlohmann::json to_json() const;

  // Markdown table of every parameter (for the README's reference).
  static std::string reference_markdown();

 private:
  const ParamSpec& spec(const std::string& key, const std::string& source) const;
  const nlohmann::json& value(const std::string& key, ParamType expected) const;

  std::map<std::string, nlohmann::json> m_values;
};

}  // namespace tessera
