#include "common/stats_schema.h"

#include <fnmatch.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace tessera {

void StatsSchema::add_counters(const ActivityCounters& counters, const std::string& prefix) {
  for (const ActivityCounter& c : counters.all()) add(prefix + c.name, counter_unit(c.name), c.description);
}

void StatsSchema::add_histogram(const std::string& key, const std::string& unit, const std::string& description) {
  add(key + ".count", "count", "samples of " + description);
  add(key + ".sum", unit, "sum of the samples of " + description);
  add_level(key + ".min", unit, "smallest sample of " + description + " (0 without samples)");
  add_level(key + ".max", unit, "largest sample of " + description + " (0 without samples)");
  add_level(key + ".mean", unit, "mean of the samples of " + description + " (0 without samples)");
  add(key + ".buckets[].low", unit, "smallest value of a power-of-two bucket of " + description);
  add(key + ".buckets[].high", unit, "largest value of a power-of-two bucket of " + description);
  add(key + ".buckets[].count", "count", "samples of " + description + " in the bucket (buckets without any left out)");
}

void StatsSchema::add_all(const std::string& prefix, const StatsSchema& other) {
  for (const StatDescription& d : other.entries())
    m_entries.push_back({prefix + d.key, d.unit, d.description, d.setting, d.level});
}

nlohmann::json StatsSchema::to_json() const {
  std::map<std::string, const StatDescription*> sorted;
  for (const StatDescription& d : m_entries) {
    const auto [it, added] = sorted.emplace(d.key, &d);
    if (!added && (it->second->unit != d.unit || it->second->description != d.description))
      throw std::invalid_argument("statistic " + d.key + " is described twice: '" + it->second->description + "' (" +
                                  it->second->unit + ") and '" + d.description + "' (" + d.unit + ")");
  }
  nlohmann::json schema = nlohmann::json::object();
  for (const auto& [key, d] : sorted) schema[key] = {{"unit", d->unit}, {"description", d->description}};
  return schema;
}

std::string counter_unit(const std::string& name) {
  // The last part that names a unit: "cycles.fill" counts cycles.
  for (size_t end = name.size(); end != std::string::npos && end > 0;) {
    const size_t dot = name.rfind('.', end - 1);
    const std::string part =
        name.substr(dot == std::string::npos ? 0 : dot + 1, end - (dot == std::string::npos ? 0 : dot + 1));
    if (part.size() > 3 && part.compare(part.size() - 3, 3, "_ns") == 0) return "ns";
    if (part.find("cycles") != std::string::npos) return "cycles";
    if (part.find("bytes") != std::string::npos) return "bytes";
    end = dot;
  }
  return "count";
}

bool accumulates(const StatDescription& statistic) {
  static const std::set<std::string> units = {"count", "ns", "s", "ms", "cycles", "bytes", "words", "J"};
  return !statistic.setting && !statistic.level && units.count(statistic.unit) != 0 &&
         statistic.key.find("[]") == std::string::npos;
}

namespace {

std::vector<std::string> key_parts(const std::string& key) {
  std::vector<std::string> parts;
  std::istringstream in(key);
  for (std::string part; std::getline(in, part, '.');) parts.push_back(part);
  return parts;
}

// The schema's accumulating keys, split into parts, matched part by part
// ("*" and names with one in them as shell patterns).
class AccumulatingKeys {
 public:
  explicit AccumulatingKeys(const StatsSchema& schema) {
    for (const StatDescription& d : schema.entries())
      if (accumulates(d)) m_keys.push_back(key_parts(d.key));
  }
  bool matches(const std::vector<std::string>& path) const {
    for (const std::vector<std::string>& key : m_keys) {
      if (key.size() != path.size()) continue;
      size_t i = 0;
      while (i < key.size() && fnmatch(key[i].c_str(), path[i].c_str(), 0) == 0) ++i;
      if (i == key.size()) return true;
    }
    return false;
  }

 private:
  std::vector<std::vector<std::string>> m_keys;
};

void add_growth_at(const AccumulatingKeys& keys, std::vector<std::string>& path, const nlohmann::json* begin,
                   const nlohmann::json& end, nlohmann::json& sum) {
  for (const auto& [name, value] : end.items()) {
    const nlohmann::json* before = begin && begin->is_object() && begin->contains(name) ? &(*begin)[name] : nullptr;
    const size_t depth = path.size();
    for (const std::string& part : key_parts(name)) path.push_back(part);  // a dotted name is a path
    if (value.is_object()) {
      add_growth_at(keys, path, before, value, sum[name]);
      if (sum[name].empty()) sum.erase(name);
    } else if (value.is_number() && keys.matches(path)) {
      const double growth = value.get<double>() - (before && before->is_number() ? before->get<double>() : 0.0);
      const double total = (sum.contains(name) ? sum[name].get<double>() : 0.0) + growth;
      // A count stays a whole number.
      if (value.is_number_integer())
        sum[name] = static_cast<int64_t>(std::llround(total));
      else
        sum[name] = total;
    }
    path.resize(depth);
  }
}

}  // namespace

void add_growth(const StatsSchema& schema, const nlohmann::json& begin, const nlohmann::json& end,
                nlohmann::json& sum) {
  if (!sum.is_object()) sum = nlohmann::json::object();
  std::vector<std::string> path;
  add_growth_at(AccumulatingKeys(schema), path, &begin, end, sum);
}

nlohmann::json histogram_json(const Log2Histogram& histogram) {
  nlohmann::json buckets = nlohmann::json::array();
  for (unsigned b = 0; b < Log2Histogram::BUCKETS; ++b)
    if (histogram.bucket(b) != 0)
      buckets.push_back({{"low", Log2Histogram::bucket_low(b)},
                         {"high", Log2Histogram::bucket_high(b)},
                         {"count", histogram.bucket(b)}});
  return {{"count", histogram.count()}, {"sum", histogram.sum()},   {"min", histogram.min()},
          {"max", histogram.max()},     {"mean", histogram.mean()}, {"buckets", buckets}};
}

}  // namespace tessera
