// What soc_sim reports of a run: the statistics document (stats.json) and
// the summary on stdout. Both are written from what the run session hands
// over; neither names a block.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "frame_stats_stream.h"
#include "run_options.h"
#include "run_watch.h"
#include "soc/soc.h"
#include "time_limit.h"

namespace tessera {

// How a run ended, as stats.json records it.
struct RunOutcome {
  int exit_status = 0;
  RunEnd end = RunEnd::completed;
  std::string error;  // the first failure's message ("" if none)
  unsigned frames_shown = 0;
  unsigned frames_written = 0;
};

// stats.json: what soc_sim knows of the run (the plan, `config_json` being
// its configuration as JSON, and the outcome) and the SoC's statistics
// (null when the run was stopped from outside the simulation), dumped with
// an indent of 2 and a final newline.
std::string statistics_document(const RunPlan& plan, const nlohmann::json& config_json, const RunOutcome& outcome,
                                nlohmann::json stats);
// The description of statistics_document's numbers (--stats-schema): the
// document's own, then `stats` (the SoC's, keys relative to "stats.") and
// `driver_counters` (the driver's counters, stats.driver) and the back
// ends' figures of each frame; as StatsSchema::to_json gives it, under
// "statistics".
nlohmann::json statistics_document_schema(const StatsSchema& stats, const ActivityCounters& driver_counters);

// The summary: run, block table (each block's own row, its notes wrapped to
// 80 columns; the blocks that did nothing named on one line instead), the
// blocks' own tables (the bus's traffic per initiator), energy, the back
// ends' own figures, outputs.
void print_summary(const Soc& soc, const nlohmann::json& stats, const FrameStatsStream::Sums& frame_sums,
                   const std::string& app, double wall, const TimeLimit& time_limit,
                   const std::vector<std::string>& outputs);

}  // namespace tessera
