// The description of stats.json: for every statistic, its key, its unit
// and one line saying what it is (gem5's stats with their descriptions). Each
// block describes the statistics it produces (Block::describe_stats), next
// to the code that produces them; soc_sim --stats-schema writes what a run's
// blocks describe, and scripts/stats_schema.py merges the back ends' into
// docs/stats_schema.json, from which docs/statistics.md is generated.
//
// A key is the statistic's dotted path in the document; a part "*" (or a
// part with a "*" in it, "units_*") matches any name there (an initiator, a
// program's entry word), and "[]" after a part means every element of an
// array ("frames[].render_ns").
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "common/activity_counters.h"
#include "common/histogram.h"

namespace tessera {

struct StatDescription {
  std::string key;
  std::string unit;
  std::string description;
};

class StatsSchema {
 public:
  void add(const std::string& key, const std::string& unit, const std::string& description) {
    m_entries.push_back({key, unit, description});
  }
  // Every counter of `counters` under `prefix` (with its dot), its unit from
  // counter_unit().
  void add_counters(const ActivityCounters& counters, const std::string& prefix = "");
  // A Log2Histogram's statistics under `key` (histogram_json's layout),
  // samples in `unit`.
  void add_histogram(const std::string& key, const std::string& unit, const std::string& description);
  // Every entry of `other` with `prefix` (with its dot) before its key.
  void add_all(const std::string& prefix, const StatsSchema& other);

  const std::vector<StatDescription>& entries() const { return m_entries; }
  // {"key": {"unit": ..., "description": ...}} sorted by key; the same key
  // described twice differently is an error (std::invalid_argument).
  nlohmann::json to_json() const;

 private:
  std::vector<StatDescription> m_entries;
};

// A counter's unit, from its name, by the naming rule every counter follows
// (docs/statistics.md): the last part of the dotted name that names a unit
// gives it, "_ns" at a part's end nanoseconds, "cycles" in it clock cycles,
// "bytes" in it bytes ("cycles.fill" counts cycles); a name with none counts
// events.
std::string counter_unit(const std::string& name);

// A histogram as stats.json shows it: count, sum, min, max, mean, and the
// buckets that hold a sample, each {"low", "high", "count"} (low and high
// inclusive).
nlohmann::json histogram_json(const Log2Histogram& histogram);

}  // namespace tessera
