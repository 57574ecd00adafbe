#include "common/stats_schema.h"

#include <map>
#include <stdexcept>

namespace tessera {

void StatsSchema::add_counters(const ActivityCounters& counters, const std::string& prefix) {
  for (const ActivityCounter& c : counters.all()) add(prefix + c.name, counter_unit(c.name), c.description);
}

void StatsSchema::add_histogram(const std::string& key, const std::string& unit, const std::string& description) {
  add(key + ".count", "count", "samples of " + description);
  add(key + ".sum", unit, "sum of the samples of " + description);
  add(key + ".min", unit, "smallest sample of " + description + " (0 without samples)");
  add(key + ".max", unit, "largest sample of " + description + " (0 without samples)");
  add(key + ".mean", unit, "mean of the samples of " + description + " (0 without samples)");
  add(key + ".buckets[].low", unit, "smallest value of a power-of-two bucket of " + description);
  add(key + ".buckets[].high", unit, "largest value of a power-of-two bucket of " + description);
  add(key + ".buckets[].count", "count", "samples of " + description + " in the bucket (buckets without any left out)");
}

void StatsSchema::add_all(const std::string& prefix, const StatsSchema& other) {
  for (const StatDescription& d : other.entries()) add(prefix + d.key, d.unit, d.description);
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
