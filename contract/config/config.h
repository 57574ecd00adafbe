// The SoC's configuration: every parameter declared once, by the block that
// owns it (a ParamGroup of specs with type, default, range and description,
// next to the block's parameter struct), the groups put together by the
// program that builds the SoC; values merged from JSON files and from
// "key=value" overrides; every bad value rejected with an error that names
// the key and what was expected.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
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

// Declaring a parameter: the one place its default lives.
namespace param {
ParamSpec boolean(std::string key, bool value, std::string description);
ParamSpec integer(std::string key, int64_t value, double min, double max, std::string unit, std::string description);
ParamSpec real(std::string key, double value, double min, double max, std::string unit, std::string description);
ParamSpec choice(std::string key, std::string value, std::vector<std::string> choices, std::string description);
ParamSpec text(std::string key, std::string value, std::string description);
}  // namespace param

class Config;

// The parameters one block (or program) owns, and the check of combinations
// of them that are individually legal but impossible together. `validate`
// throws ConfigError naming the keys; it may read other groups' keys.
struct ParamGroup {
  std::string owner;  // "display", "soc_sim": names the group in messages
  std::vector<ParamSpec> specs;
  std::function<void(const Config&)> validate;
};

// Limits of a configuration file (load_file). Both are far above any real
// configuration (a few dozen keys, nested three deep) and keep a hostile or
// broken file from exhausting memory or the stack: a bigger file, or objects
// and arrays nested deeper, is a ConfigError naming the file.
constexpr std::size_t MAX_CONFIG_FILE_BYTES = 1024 * 1024;
constexpr std::size_t MAX_CONFIG_DEPTH = 32;  // the top-level object is depth 1

class Config {
 public:
  // All parameters of `groups` at their defaults. A key declared twice is a
  // programming error (std::logic_error naming the key and both owners).
  explicit Config(std::vector<ParamGroup> groups);

  // Merges a JSON document of nested objects ({"bus": {"arbitration": ...}})
  // or dotted keys. `source` names where it came from, for error messages.
  // An object where a parameter belongs, or an empty object whose key names
  // no group of parameters, is an error like any other wrong value.
  void merge_json(const nlohmann::json& doc, const std::string& source);
  // Reads at most MAX_CONFIG_FILE_BYTES of JSON nested at most
  // MAX_CONFIG_DEPTH deep, with no key twice in one object; a number out of
  // the range of a double (1e400) is an error naming the key and the line.
  void load_file(const std::string& path);
  // "key=value"; the value is parsed according to the key's type.
  void apply_override(const std::string& assignment);
  // Sets one parameter from a JSON value, checking type and range.
  void set(const std::string& key, const nlohmann::json& value, const std::string& source);

  // Checks combinations of parameters that are individually legal: every
  // group's validate, in order.
  void validate() const;

  // Every parameter, in the order of the groups.
  const std::vector<ParamSpec>& specs() const { return m_specs; }
  bool has(const std::string& key) const { return m_values.count(key) != 0; }
  // True when a file, an override or the program set `key` (even to its
  // default value); false while it holds the default it was declared with.
  bool is_set(const std::string& key) const { return m_set.count(key) != 0; }

  bool get_bool(const std::string& key) const;
  int64_t get_int(const std::string& key) const;
  uint64_t get_uint(const std::string& key) const;
  double get_real(const std::string& key) const;
  std::string get_string(const std::string& key) const;
  // The value as it is held (any type), for copying it into another
  // configuration.
  const nlohmann::json& get_json(const std::string& key) const;

  // The effective configuration as nested JSON objects.
  nlohmann::json to_json() const;

  // Markdown table of every parameter (for the README's reference).
  std::string reference_markdown() const;

 private:
  const ParamSpec& spec(const std::string& key, const std::string& source) const;
  // True when some parameter's key starts with `prefix` + ".".
  bool is_group(const std::string& prefix) const;
  void flatten(const nlohmann::json& node, const std::string& prefix,
               std::vector<std::pair<std::string, nlohmann::json>>& out) const;
  const nlohmann::json& value(const std::string& key, ParamType expected) const;

  std::vector<ParamGroup> m_groups;
  std::vector<ParamSpec> m_specs;
  std::map<std::string, size_t> m_index;  // key -> position in m_specs
  std::map<std::string, nlohmann::json> m_values;
  std::set<std::string> m_set;
};

}  // namespace tessera
