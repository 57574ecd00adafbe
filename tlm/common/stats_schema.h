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
  // A setting the run was built with (array.columns, a burst's length), not
  // anything that happened: it does not grow with the run (accumulates).
  bool setting = false;
  // A level of the run so far in a unit that otherwise grows (a histogram's
  // min, max and mean): it does not grow with the run either.
  bool level = false;
};

class StatsSchema {
 public:
  void add(const std::string& key, const std::string& unit, const std::string& description) {
    m_entries.push_back({key, unit, description});
  }
  // A statistic that reports a setting of the run (StatDescription::setting).
  void add_setting(const std::string& key, const std::string& unit, const std::string& description) {
    m_entries.push_back({key, unit, description, true, false});
  }
  // A statistic that reports a level (StatDescription::level).
  void add_level(const std::string& key, const std::string& unit, const std::string& description) {
    m_entries.push_back({key, unit, description, false, true});
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

// Whether a statistic grows with the run, so that its growth over a stretch
// of the run is the difference of its values at the stretch's ends (the
// region of interest's statistics, stats.json's "roi"): a count, a time,
// cycles, bytes, words or energy (units count, ns, s, ms, cycles, bytes,
// words, J) that is not a setting or a level. Settings (add_setting), levels
// (add_level: a histogram's min, max and mean), ratios and rates
// (utilisation, power, clocks), and the elements of lists ("[]") do not.
bool accumulates(const StatDescription& statistic);

// Adds to `sum` the growth from `begin` to `end` (two stats documents, or
// parts of them, of one run) of every number in `end` that `schema`
// describes as accumulating, at the same place in `sum`; lists are left
// out, and so is a number `schema` does not describe or `begin` lacks
// (counted from 0 then: a block built later).
void add_growth(const StatsSchema& schema, const nlohmann::json& begin, const nlohmann::json& end, nlohmann::json& sum);

// A histogram as stats.json shows it: count, sum, min, max, mean, and the
// buckets that hold a sample, each {"low", "high", "count"} (low and high
// inclusive).
nlohmann::json histogram_json(const Log2Histogram& histogram);

}  // namespace tessera
