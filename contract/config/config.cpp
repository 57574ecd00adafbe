#include "config/config.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

namespace tessera {
namespace {

const char* type_name(ParamType type) {
  switch (type) {
    case ParamType::boolean: return "a boolean";
    case ParamType::integer: return "an integer";
    case ParamType::real: return "a number";
    case ParamType::string: return "a string";
    case ParamType::choice: return "one of";
  }
  return "?";
}

std::string format_number(double v) {
  std::ostringstream out;
  if (std::floor(v) == v && std::fabs(v) < 1e18)
    out << static_cast<long long>(v);
  else
    out << v;
  return out.str();
}

std::string expectation(const ParamSpec& spec) {
  std::string text = type_name(spec.type);
  if (spec.type == ParamType::choice) {
    text += " ";
    for (size_t i = 0; i < spec.choices.size(); ++i) text += (i ? ", " : "") + spec.choices[i];
  } else if (spec.type == ParamType::integer || spec.type == ParamType::real) {
    text += " in [" + format_number(spec.min) + ", " + format_number(spec.max) + "]";
  }
  if (!spec.unit.empty() && (spec.type == ParamType::integer || spec.type == ParamType::real))
    text += " (" + spec.unit + ")";
  return text;
}

size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1u : 0u)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// A value as shown in an error message: invalid UTF-8 replaced rather than
// thrown about, and a long value (a big array) cut short.
std::string shown_value(const nlohmann::json& value) {
  constexpr std::size_t LIMIT = 80;
  std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  if (text.size() > LIMIT) text = text.substr(0, LIMIT) + "...";
  return text;
}

// Builds the document of a configuration file from the parser's events (the
// parser itself keeps its own state on the heap, not on the stack), so that
// a file can be refused with its key named: nesting beyond MAX_CONFIG_DEPTH
// (the document is later walked recursively), a key twice in one object, and
// a number that does not fit in a double (1e400, which the parser reports
// without saying where it stood).
class DocumentBuilder {
 public:
  using json = nlohmann::json;

  DocumentBuilder(const std::string& text, json* document) : m_text(text), m_document(document) {}

  bool null() { return add(nullptr); }
  bool boolean(bool value) { return add(value); }
  bool number_integer(json::number_integer_t value) { return add(value); }
  bool number_unsigned(json::number_unsigned_t value) { return add(value); }
  bool number_float(json::number_float_t value, const json::string_t& /*text*/) { return add(value); }
  bool string(json::string_t& value) { return add(std::move(value)); }
  bool binary(json::binary_t& /*value*/) { return refuse("binary values are not JSON"); }
  bool start_object(std::size_t /*elements*/) { return open(json::object()); }
  bool start_array(std::size_t /*elements*/) { return open(json::array()); }
  bool end_object() { return close(); }
  bool end_array() { return close(); }
  bool key(json::string_t& name) {
    Level& level = m_levels.back();
    if (level.node->contains(name)) {
      level.key = name;
      return refuse("has '" + path() + "' twice in one object");
    }
    level.key = name;
    return true;
  }
  bool parse_error(std::size_t byte, const std::string& token, const nlohmann::detail::exception& error) {
    if (error.id == 406) {  // out_of_range: number overflow
      const auto end = m_text.begin() + static_cast<std::ptrdiff_t>(std::min(byte, m_text.size()));
      const auto line = 1 + std::count(m_text.begin(), end, '\n');
      m_problem = "line " + std::to_string(line) + ": " +
                  (m_levels.empty() ? std::string("the value") : "'" + path() + "'") + " is " + token +
                  ", a number out of the range of a double";
    } else {
      m_problem = std::string("is not valid JSON: ") + error.what();
    }
    return false;
  }

  // Set when the builder stopped the parse; empty when the parser's message
  // is the whole story.
  const std::string& problem() const { return m_problem; }

 private:
  struct Level {
    json* node;
    std::string key;  // the key being read (objects) or the index (arrays)
  };

  // The dotted path of the value being read: "display.width", "a.b[3]". An
  // outer array already holds the element being read; the innermost one
  // does not yet.
  std::string path() const {
    std::string text;
    for (const Level& level : m_levels) {
      if (level.node->is_array()) {
        const std::size_t index = level.node->size() - (&level == &m_levels.back() ? 0 : 1);
        text += "[" + std::to_string(index) + "]";
      } else {
        if (!text.empty()) text += ".";
        text += level.key;
      }
    }
    return text;
  }

  bool refuse(const std::string& problem) {
    m_problem = problem;
    return false;
  }

  // Where a new value goes: the document itself, the current key of the
  // innermost object or the end of the innermost array.
  json* place(json&& value) {
    if (m_levels.empty()) {
      *m_document = std::move(value);
      return m_document;
    }
    Level& level = m_levels.back();
    if (level.node->is_array()) {
      level.node->push_back(std::move(value));
      return &level.node->back();
    }
    return &((*level.node)[level.key] = std::move(value));
  }

  bool add(json&& value) {
    place(std::move(value));
    return true;
  }

  bool open(json&& container) {
    if (m_levels.size() >= MAX_CONFIG_DEPTH)
      return refuse("nests objects and arrays more than " + std::to_string(MAX_CONFIG_DEPTH) + " deep (at '" + path() +
                    "')");
    json* node = place(std::move(container));
    m_levels.push_back({node, {}});
    return true;
  }

  bool close() {
    m_levels.pop_back();
    return true;
  }

  const std::string& m_text;
  json* m_document;
  std::vector<Level> m_levels;
  std::string m_problem;
};

// The text of a file, refused beyond MAX_CONFIG_FILE_BYTES (it may be a
// device such as /dev/zero, whose size is not known in advance).
std::string read_limited(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError("configuration: cannot open '" + path + "': " + std::strerror(errno));
  std::string text;
  std::vector<char> buffer(64 * 1024);
  while (in) {
    in.read(buffer.data(), static_cast<std::streamsize>(buffer.size()));
    text.append(buffer.data(), static_cast<std::size_t>(in.gcount()));
    if (text.size() > MAX_CONFIG_FILE_BYTES)
      throw ConfigError("configuration: '" + path + "' is larger than the limit of " +
                        std::to_string(MAX_CONFIG_FILE_BYTES) + " bytes");
  }
  if (in.bad()) throw ConfigError("configuration: cannot read '" + path + "': " + std::strerror(errno));
  return text;
}

}  // namespace

namespace param {

ParamSpec boolean(std::string key, bool value, std::string description) {
  return {std::move(key), ParamType::boolean, value, std::move(description), "", 0, 0, {}};
}
ParamSpec integer(std::string key, int64_t value, double min, double max, std::string unit, std::string description) {
  return {std::move(key), ParamType::integer, value, std::move(description), std::move(unit), min, max, {}};
}
ParamSpec real(std::string key, double value, double min, double max, std::string unit, std::string description) {
  return {std::move(key), ParamType::real, value, std::move(description), std::move(unit), min, max, {}};
}
ParamSpec choice(std::string key, std::string value, std::vector<std::string> choices, std::string description) {
  return {std::move(key), ParamType::choice, std::move(value), std::move(description), "", 0, 0, std::move(choices)};
}
ParamSpec text(std::string key, std::string value, std::string description) {
  return {std::move(key), ParamType::string, std::move(value), std::move(description), "", 0, 0, {}};
}

}  // namespace param

Config::Config(std::vector<ParamGroup> groups) : m_groups(std::move(groups)) {
  std::map<std::string, std::string> owners;
  for (const ParamGroup& group : m_groups) {
    for (const ParamSpec& spec : group.specs) {
      const auto [it, fresh] = owners.emplace(spec.key, group.owner);
      if (!fresh)
        throw std::logic_error("configuration: '" + spec.key + "' is declared by both " + it->second + " and " +
                               group.owner);
      m_index[spec.key] = m_specs.size();
      m_specs.push_back(spec);
      m_values[spec.key] = spec.default_value;
    }
  }
}

void Config::validate() const {
  for (const ParamGroup& group : m_groups)
    if (group.validate) group.validate(*this);
}

const ParamSpec& Config::spec(const std::string& key, const std::string& source) const {
  const auto it = m_index.find(key);
  if (it != m_index.end()) return m_specs[it->second];
  const auto& specs = m_specs;
  std::string message = "configuration: unknown key '" + key + "'";
  if (!source.empty()) message += " (from " + source + ")";
  const ParamSpec* best = nullptr;
  size_t best_distance = 4;
  for (const auto& s : specs) {
    size_t d = edit_distance(key, s.key);
    if (d < best_distance) best = &s, best_distance = d;
  }
  if (best)
    message += "; did you mean '" + best->key + "'?";
  else
    message += "; soc_sim --print-config lists the known keys";
  throw ConfigError(message);
}

void Config::set(const std::string& key, const nlohmann::json& value, const std::string& source) {
  const ParamSpec& s = spec(key, source);
  auto fail = [&](const std::string& got) {
    throw ConfigError("configuration: '" + key + "' expects " + expectation(s) + ", got " + got + " (from " + source +
                      ")");
  };
  const std::string shown = shown_value(value);
  switch (s.type) {
    case ParamType::boolean:
      if (!value.is_boolean()) fail(shown);
      break;
    case ParamType::integer: {
      if (!value.is_number_integer()) fail(shown);
      double v = value.is_number_unsigned() ? static_cast<double>(value.get<uint64_t>())
                                            : static_cast<double>(value.get<int64_t>());
      if (v < s.min || v > s.max) fail(shown);
      break;
    }
    case ParamType::real: {
      if (!value.is_number()) fail(shown);
      double v = value.get<double>();
      if (!std::isfinite(v) || v < s.min || v > s.max) fail(shown);
      break;
    }
    case ParamType::string:
      if (!value.is_string()) fail(shown);
      try {
        (void)value.dump();  // the effective configuration is written as JSON
      } catch (const nlohmann::json::type_error&) {
        fail(shown + ", text that is not valid UTF-8");
      }
      break;
    case ParamType::choice:
      if (!value.is_string() ||
          std::find(s.choices.begin(), s.choices.end(), value.get<std::string>()) == s.choices.end())
        fail(shown);
      break;
  }
  m_values[key] = value;
  m_set.insert(key);
}

bool Config::is_group(const std::string& prefix) const {
  const std::string start = prefix + ".";
  return std::any_of(m_specs.begin(), m_specs.end(),
                     [&](const ParamSpec& s) { return s.key.compare(0, start.size(), start) == 0; });
}

void Config::flatten(const nlohmann::json& node, const std::string& prefix,
                     std::vector<std::pair<std::string, nlohmann::json>>& out) const {
  for (auto it = node.begin(); it != node.end(); ++it) {
    std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    // An object is a group of keys, unless its key is a parameter (an object
    // where a value belongs) or it is empty and names no group (an unknown
    // key): those are handed to set(), which names the key and the problem.
    const bool group = it->is_object() && m_index.count(key) == 0 && (!it->empty() || is_group(key));
    if (group)
      flatten(*it, key, out);
    else
      out.emplace_back(key, *it);
  }
}

void Config::merge_json(const nlohmann::json& doc, const std::string& source) {
  if (!doc.is_object()) throw ConfigError("configuration: " + source + " must hold a JSON object at the top level");
  std::vector<std::pair<std::string, nlohmann::json>> entries;
  flatten(doc, "", entries);
  // Check everything before changing anything, so a bad file leaves the
  // configuration as it was.
  Config trial = *this;
  for (const auto& [key, value] : entries) trial.set(key, value, source);
  *this = std::move(trial);
}

void Config::load_file(const std::string& path) {
  const std::string text = read_limited(path);
  nlohmann::json doc;
  DocumentBuilder builder(text, &doc);
  bool parsed = false;
  try {
    parsed = nlohmann::json::sax_parse(text, &builder);
  } catch (const nlohmann::json::exception& e) {
    throw ConfigError("configuration: '" + path + "' is not valid JSON: " + e.what());
  }
  if (!parsed) throw ConfigError("configuration: '" + path + "' " + builder.problem());
  merge_json(doc, path);
}

void Config::apply_override(const std::string& assignment) {
  const std::string source = "--set " + assignment;
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw ConfigError("configuration: '" + assignment + "' is not of the form key=value");
  std::string key = assignment.substr(0, eq);
  std::string text = assignment.substr(eq + 1);
  const ParamSpec& s = spec(key, source);
  nlohmann::json value;
  switch (s.type) {
    case ParamType::boolean:
      if (text == "true" || text == "1" || text == "on")
        value = true;
      else if (text == "false" || text == "0" || text == "off")
        value = false;
      else
        value = text;  // rejected by set() with the key named
      break;
    case ParamType::integer: {
      errno = 0;
      char* end = nullptr;
      // Decimal, or hexadecimal with 0x; a leading zero is not octal.
      const bool hexadecimal = text.size() > 2 && text[0] == '0' && (text[1] == 'x' || text[1] == 'X');
      long long v = std::strtoll(text.c_str(), &end, hexadecimal ? 16 : 10);
      if (text.empty() || *end != '\0' || errno == ERANGE)
        value = text;
      else
        value = static_cast<int64_t>(v);
      break;
    }
    case ParamType::real: {
      errno = 0;
      char* end = nullptr;
      double v = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || errno == ERANGE)
        value = text;
      else
        value = v;
      break;
    }
    case ParamType::string:
    case ParamType::choice: value = text; break;
  }
  set(key, value, source);
}

const nlohmann::json& Config::value(const std::string& key, ParamType expected) const {
  auto it = m_values.find(key);
  const ParamSpec& s = spec(key, "");
  if (s.type != expected && !(expected == ParamType::string && s.type == ParamType::choice))
    throw std::logic_error("configuration: '" + key + "' read as the wrong type");
  return it->second;
}

bool Config::get_bool(const std::string& key) const {
  return value(key, ParamType::boolean).get<bool>();
}
int64_t Config::get_int(const std::string& key) const {
  return value(key, ParamType::integer).get<int64_t>();
}
uint64_t Config::get_uint(const std::string& key) const {
  int64_t v = get_int(key);
  if (v < 0) throw std::logic_error("configuration: '" + key + "' is negative");
  return static_cast<uint64_t>(v);
}
double Config::get_real(const std::string& key) const {
  return value(key, ParamType::real).get<double>();
}
std::string Config::get_string(const std::string& key) const {
  return value(key, ParamType::string).get<std::string>();
}

const nlohmann::json& Config::get_json(const std::string& key) const {
  (void)spec(key, "");  // a key no group declares is a programming error
  return m_values.at(key);
}

nlohmann::json Config::to_json() const {
  nlohmann::json doc = nlohmann::json::object();
  for (const auto& spec : m_specs) {
    nlohmann::json* node = &doc;
    std::string rest = spec.key;
    for (auto dot = rest.find('.'); dot != std::string::npos; dot = rest.find('.')) {
      node = &(*node)[rest.substr(0, dot)];
      rest = rest.substr(dot + 1);
    }
    (*node)[rest] = m_values.at(spec.key);
  }
  return doc;
}

std::string Config::reference_markdown() const {
  std::ostringstream out;
  out << "| key | type | default | description |\n| --- | --- | --- | --- |\n";
  for (const auto& spec : m_specs) {
    std::string type = expectation(spec);
    out << "| `" << spec.key << "` | " << type << " | `" << spec.default_value.dump() << "` | " << spec.description
        << " |\n";
  }
  return out.str();
}

}  // namespace tessera
