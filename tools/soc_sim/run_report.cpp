#include "run_report.h"

#include <algorithm>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "build_info.h"
#include "common/text_format.h"
#include "progress_line.h"

namespace tessera {

namespace {

// The back ends' own figures: for each driver section with a host-time
// split (the array back ends), where the host's time went, and the
// averages of the per-frame figures the back end gave (the frame records'
// "driver", summed as they were streamed to stats.json).
void print_driver_summary(const nlohmann::json& stats, const FrameStatsStream::Sums& sums) {
  const nlohmann::json& driver = stats["driver"];
  const double simulated = stats["simulated_ns"].get<double>() * 1e-9;
  for (const auto& [section, counters] : driver.items()) {
    if (!counters.is_object() || !counters.contains("host_compute_ns")) continue;
    std::printf("\n  %s: host time          total  of simulated\n", section.c_str());
    for (const char* part : {"compute", "write", "read", "wait", "frame_out"}) {
      const std::string key = std::string("host_") + part + "_ns";
      if (!counters.contains(key)) continue;
      const double seconds = counters[key].get<double>() * 1e-9;
      std::printf("    %-12s %14s %12s\n", part, format_duration(seconds).c_str(),
                  format_percent(simulated > 0 ? seconds / simulated : 0).c_str());
    }
    if (sums.driver_frames == 0) continue;
    std::printf("  %s: per frame (mean of %zu)\n", section.c_str(), sums.driver_frames);
    for (const auto& [name, sum] : sums.driver)
      std::printf("    %-28s %14.3f\n", name.c_str(), sum / static_cast<double>(sums.driver_frames));
  }
}

// The summary's width: it fits a terminal of 80 columns.
constexpr size_t SUMMARY_COLUMNS = 80;

// `text` in lines of at most `width` characters, broken after ", " (a part
// longer than `width` is a line of its own).
std::vector<std::string> wrap_at_commas(const std::string& text, size_t width) {
  std::vector<std::string> lines(1);
  for (size_t start = 0; start < text.size();) {
    size_t end = text.find(", ", start);
    end = end == std::string::npos ? text.size() : end + 1;  // the comma ends the part, the space is dropped
    const std::string part = text.substr(start, end - start);
    const std::string joined = lines.back().empty() ? part : lines.back() + " " + part;
    if (!lines.back().empty() && joined.size() > width)
      lines.push_back(part);
    else
      lines.back() = joined;
    start = end < text.size() ? end + 1 : end;
  }
  return lines;
}

// Each energy unit's energy over the run, its average power and its mean
// energy per frame shown (tlm/power/); units that spent none are named on
// one line instead, as the blocks that did nothing are above.
void print_energy_summary(const nlohmann::json& stats, const FrameStatsStream::Sums& sums) {
  const nlohmann::json& energy = stats["energy"];
  std::printf("\n  %-18s %12s %12s %14s\n", "energy (1.2 V)", "total", "average", "per frame");
  const auto row = [&sums](const std::string& name, const nlohmann::json& unit, double frame_sum) {
    const std::string mean = sums.frames == 0 ? "-" : format_energy(frame_sum / static_cast<double>(sums.frames));
    std::printf("  %-18s %12s %12s %14s\n", name.c_str(), format_energy(unit["total_j"].get<double>()).c_str(),
                format_power(unit["average_w"].get<double>()).c_str(), mean.c_str());
  };
  std::string none;
  for (const auto& [name, unit] : energy["units"].items()) {
    if (unit["total_j"].get<double>() == 0) {
      none += (none.empty() ? "" : ", ") + name;
      continue;
    }
    const auto found = sums.energy_unit_j.find(name);
    row(name, unit, found == sums.energy_unit_j.end() ? 0.0 : found->second);
  }
  row("total", energy, sums.energy_total_j);
  if (!none.empty())
    for (const std::string& line : wrap_at_commas("no energy: " + none, SUMMARY_COLUMNS - 2))
      std::printf("  %s\n", line.c_str());
}

// A block that did nothing in the run: no busy time and every counter 0.
bool did_nothing(const Block& block, const SummaryRow& row) {
  if (row.busy && row.busy->value() != 0) return false;
  const auto& all = block.counters().all();
  return std::all_of(all.begin(), all.end(), [](const ActivityCounter& c) { return c.value == 0; });
}

}  // namespace

void print_summary(const Soc& soc, const nlohmann::json& stats, const FrameStatsStream::Sums& frame_sums,
                   const std::string& app, double wall, const TimeLimit& time_limit,
                   const std::vector<std::string>& outputs) {
  const sc_core::sc_time elapsed = sc_core::sc_time_stamp();
  const double simulated = elapsed.to_seconds();
  std::printf("\ntessera soc_sim: application '%s', display %s mode\n", app.c_str(),
              stats["display"]["mode"].get<std::string>().c_str());
  std::printf("  simulated time  %s\n  wall time       %s (%s simulated per wall second)\n",
              format_duration(simulated).c_str(), format_duration(wall).c_str(),
              format_duration(wall > 0 ? simulated / wall : 0).c_str());
  std::printf("  time limit      %s\n", time_limit.describe().c_str());
  // "  name          busy  utilisation  notes": 40 columns before the notes.
  constexpr int NOTES_COLUMN = 40;
  std::printf("\n  %-12s %11s %11s  %s\n", "block", "busy", "utilisation", "notes");
  std::vector<SummaryTable> tables;
  std::string idle;
  std::set<std::string> idle_blocks;
  for (const Block* block : soc.blocks()) {
    const SummaryRow row = block->summary_row(elapsed);
    if (did_nothing(*block, row)) {
      idle += (idle.empty() ? "" : ", ") + std::string(block->basename());
      idle_blocks.insert(block->basename());
      continue;
    }
    const std::vector<std::string> notes = wrap_at_commas(row.notes, SUMMARY_COLUMNS - NOTES_COLUMN);
    std::printf("  %-12s %11s %11s  %s\n", block->basename(),
                row.busy ? format_duration(row.busy->to_seconds()).c_str() : "-",
                row.utilisation ? format_percent(*row.utilisation).c_str() : "-", notes.front().c_str());
    for (size_t i = 1; i < notes.size(); ++i) std::printf("%*s%s\n", NOTES_COLUMN, "", notes[i].c_str());
    for (SummaryTable& table : block->summary_tables(elapsed)) tables.push_back(std::move(table));
  }
  if (!idle.empty())
    for (const std::string& line : wrap_at_commas("did nothing: " + idle, SUMMARY_COLUMNS - 2))
      std::printf("  %s\n", line.c_str());
  for (const SummaryTable& table : tables) {
    std::printf("\n  %s\n ", table.title.c_str());
    for (size_t i = 0; i < table.columns.size(); ++i)
      std::printf(i == 0 ? " %-12s" : " %12s", table.columns[i].c_str());
    std::printf("\n");
    for (const auto& row : table.rows) {
      if (!row.empty() && idle_blocks.count(row.front())) continue;  // named above, a row of zeros
      std::printf(" ");
      for (size_t i = 0; i < row.size(); ++i) std::printf(i == 0 ? " %-12s" : " %12s", row[i].c_str());
      std::printf("\n");
    }
  }
  print_energy_summary(stats, frame_sums);
  print_driver_summary(stats, frame_sums);
  std::printf("\n  outputs\n");
  for (const auto& line : outputs) std::printf("    %s\n", line.c_str());
}

namespace {

// The figures the back ends give for each frame (stats.json's
// frames[].driver): the driver (sw_driver) names them without a
// description, so they are described here, where soc_sim puts them in
// stats.json; a key the driver adds is found missing by the stats_schema
// test.
void describe_frame_driver_figures(StatsSchema& schema) {
  const auto add = [&schema](const std::string& key, const std::string& unit, const std::string& description) {
    schema.add("stats.frames[].driver." + key, unit, description + " (in the frame)");
  };
  add("host_*_ns", "ns", "host time in that phase or part of the driver's host-time split");
  add("units_*", "count", "units of the host-cost row charged in that bucket (units_<bucket>_<row>, sw_driver/costs)");
  add("triangles", "count", "triangles the back end drew");
  add("passes", "count", "passes of the array programs (ap-tile: a group of tiles; ap-pixel: a batch)");
  add("cycles", "cycles", "array cycles of the back end's programs");
  add("cycles.*", "cycles", "array cycles of the back end's programs of that stage");
  add("runs", "count", "array program runs");
  add("runs_w*", "count", "array program runs of that lane width");
  add("units", "count", "depth units the back end used");
  add("pieces", "count", "pieces of halves walked by a CU");
  add("pixels_emitted", "pixels", "covered pixels read back from the array");
  add("pixels_written", "pixels", "pixels written to the colour buffer");
  add("blocks", "count", "blocks sent to a CU (each k x k pixels)");
  add("visible_pixels", "pixels", "pixels the host found inside and passing the depth test");
  add("host_shaded_triangles", "count", "slivers the host shaded");
  add("ciu_words_read", "words", "CIU words the host read");
  add("ciu_words_written", "words", "CIU words the host wrote");
  add("values_read", "count", "values the host read from the array");
  add("values_written", "count", "values the host wrote to the array");
  add("dma_descriptors", "count", "DMA descriptors the back end queued");
  add("cu_triangles", "count", "triangles sent to CUs, a triangle once per CU that draws it");
  add("busiest_cu_triangles", "count", "triangles of the CU with the most");
  add("triangles_per_pass", "count", "cu_triangles per pass (a mean)");
  add("cu_occupancy", "fraction", "cu_triangles over passes x CUs: the mean triangles per CU and pass");
  add("values_written_per_triangle", "count", "values written per triangle (a mean)");
  schema.add("stats.frames[].wall_ns", "ns", "wall-clock time soc_sim took for the frame (--wall-clock only)");
  schema.add("stats.frames[].cpu_ns", "ns", "CPU time soc_sim took for the frame (--wall-clock only)");
}

}  // namespace

nlohmann::json statistics_document_schema(const StatsSchema& stats, const ActivityCounters& driver_counters) {
  StatsSchema schema;
  schema.add("time_limit_ms", "ms", "the simulated-time limit in effect (sim.time_limit_ms or the automatic one)");
  schema.add("frames_shown", "count", "frames the display showed");
  schema.add("frames_written", "count", "frames written as PNG files");
  schema.add("exit_status", "code", "soc_sim's exit status (0: the run completed)");
  schema.add_all("stats.", stats);
  schema.add_counters(driver_counters, "stats.driver.");
  describe_frame_driver_figures(schema);
  return {{"statistics", schema.to_json()}};
}

std::string statistics_document(const RunPlan& plan, const nlohmann::json& config_json, const RunOutcome& outcome,
                                nlohmann::json stats) {
  nlohmann::json document = {{"application", plan.config.get_string("sim.app")},
                             {"version", build_info::version()},
                             {"commit", build_info::commit()},
                             {"command_line", plan.command_line},
                             {"time_limit_ms", plan.time_limit.ms},
                             {"time_limit_automatic", plan.time_limit.automatic},
                             {"frames_shown", outcome.frames_shown},
                             {"frames_written", outcome.frames_written},
                             {"exit_status", outcome.exit_status},
                             {"run_status", run_end_name(outcome.end)},
                             {"config", config_json},
                             {"stats", std::move(stats)}};
  if (!outcome.error.empty()) document["error"] = outcome.error;
  return document.dump(2) + "\n";
}

}  // namespace tessera
