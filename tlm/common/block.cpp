#include "common/block.h"

#include "common/activity_json.h"

namespace tessera {

nlohmann::json Block::stats_json(const sc_core::sc_time& elapsed) const {
  (void)elapsed;
  return to_json(m_counters);
}

void Block::describe_stats(StatsSchema& schema) const {
  schema.add_counters(m_counters);
}

void Block::trace_signals(sc_core::sc_trace_file* file) {
  (void)file;
}

void Block::timeline_to(TimelineSink& sink) {
  (void)sink;
}

void Block::finish_timeline() {}

std::vector<SummaryTable> Block::summary_tables(const sc_core::sc_time& elapsed) const {
  (void)elapsed;
  return {};
}

EnergyActivity Block::energy_activity(const sc_core::sc_time& now) const {
  (void)now;
  return {};
}

double Block::clocked_seconds(const sc_core::sc_time& now) const {
  if (!m_sleeps_until_used) return now.to_seconds();
  if (!m_used_at || *m_used_at >= now) return 0.0;
  return (now - *m_used_at).to_seconds();
}

SummaryRow busy_row(const sc_core::sc_time& busy, const sc_core::sc_time& elapsed, std::string notes) {
  const double elapsed_s = elapsed.to_seconds();
  return {busy, elapsed_s > 0 ? busy.to_seconds() / elapsed_s : 0.0, std::move(notes)};
}

void add_busy_stats(nlohmann::json& stats, const sc_core::sc_time& busy, const sc_core::sc_time& elapsed) {
  const double busy_s = busy.to_seconds(), elapsed_s = elapsed.to_seconds();
  stats["busy_ns"] = busy_s * 1e9;
  stats["utilisation"] = elapsed_s > 0 ? busy_s / elapsed_s : 0.0;
  stats["elapsed_ns"] = elapsed_s * 1e9;
}

void describe_busy_stats(StatsSchema& schema, const std::string& busy_is) {
  schema.add("busy_ns", "ns", busy_is);
  schema.add("utilisation", "fraction", "busy_ns over the simulated time");
  schema.add("elapsed_ns", "ns", "simulated time of the run (the denominator of utilisation)");
}

}  // namespace tessera
