// The shape every block of the SoC shares. A Block is an sc_module with
// typed activity counters and the hooks the SoC calls over its list of
// blocks, so that the statistics, the VCD trace and soc_sim's summary name no
// block: stats_json (the block's section of stats.json), trace_signals (its
// signals in a VCD), summary_row (its row in the summary's block table) and
// summary_tables (a table of its own, such as the bus's traffic per
// initiator). A block with registers and an interrupt line derives from
// Peripheral (peripheral.h); a block that masters the bus has a BusMaster
// socket (bus_master.h). docs/how_to_add_a_block.md walks through a new one.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <systemc>

#include <nlohmann/json.hpp>

#include "common/activity_counters.h"
#include "common/energy_activity.h"
#include "common/stats_schema.h"
#include "common/text_format.h"
#include "common/timeline.h"

namespace tessera {

// A block's row in the summary: busy time and utilisation where the block
// has them (printed "-" otherwise), and notes.
struct SummaryRow {
  std::optional<sc_core::sc_time> busy;
  std::optional<double> utilisation;  // a fraction: 0.25 prints as 25.0%
  std::string notes;
};

// A table a block adds to the summary, below the block table.
struct SummaryTable {
  std::string title;
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;  // one text per column
};

class Block : public sc_core::sc_module {
 public:
  // The block's statistics over `elapsed` of simulated time: by default its
  // activity counters (a dotted name nests: "bus.errors" is
  // {"bus": {"errors": n}}); blocks add what they derive from them.
  virtual nlohmann::json stats_json(const sc_core::sc_time& elapsed) const;
  // Adds every statistic stats_json gives, with its unit and description,
  // keys relative to the block's section (stats_schema.h): by default the
  // activity counters; a block that adds to stats_json describes what it
  // adds here, next to it.
  virtual void describe_stats(StatsSchema& schema) const;
  // Adds the block's signals to a VCD file; called before the simulation
  // starts. By default the block has none.
  virtual void trace_signals(sc_core::sc_trace_file* file);
  // Records the block's activity on `sink` (common/timeline.h), which
  // outlives the simulation; called before the simulation starts. By
  // default the block records nothing.
  virtual void timeline_to(TimelineSink& sink);
  // The end of the run: the block records what it still holds back (an
  // interval it was extending). By default nothing.
  virtual void finish_timeline();
  virtual SummaryRow summary_row(const sc_core::sc_time& elapsed) const = 0;
  // By default none.
  virtual std::vector<SummaryTable> summary_tables(const sc_core::sc_time& elapsed) const;
  // The block's activity for the energy model (tlm/power/) from the start
  // of the run to `now`: one entry per energy unit the block holds, one count
  // per event class of energy_params.def. By default none.
  virtual EnergyActivity energy_activity(const sc_core::sc_time& now) const;

  const ActivityCounters& counters() const { return m_counters; }

  // Clock gating (power.sleep_unused): how long the block's clocks have run
  // from the start to `now`. A block made with sleeps_until_used() sleeps
  // until the software first uses it (mark_used); any other is clocked from
  // reset.
  double clocked_seconds(const sc_core::sc_time& now) const;
  bool sleeps() const { return m_sleeps_until_used; }
  // The software used the block at the kernel's time plus `delay` (an
  // access's annotated time), directly or through another block (the CIU
  // and the DMA reach the array's CMEM); only the first use counts.
  void mark_used(const sc_core::sc_time& delay = sc_core::SC_ZERO_TIME) {
    if (!m_used_at) m_used_at = sc_core::sc_time_stamp() + delay;
  }

 protected:
  explicit Block(sc_core::sc_module_name name) : sc_core::sc_module(name) {}

  // For a block the software switches on when it needs it (the array, the
  // CIU, the DMAs, the rasterizer): asleep until mark_used.
  void sleeps_until_used() { m_sleeps_until_used = true; }

  // The set the block's counters live in, for the block itself and for the
  // parts that count on its behalf (its BusMaster).
  ActivityCounters& activity() { return m_counters; }
  ActivityCounter& counter(const std::string& name, const std::string& description) {
    return m_counters.counter(name, description);
  }

 private:
  ActivityCounters m_counters;
  bool m_sleeps_until_used = false;
  std::optional<sc_core::sc_time> m_used_at;
};

// The row of a block that is busy for `busy` of `elapsed`: utilisation is
// their ratio (0 before any time has passed).
SummaryRow busy_row(const sc_core::sc_time& busy, const sc_core::sc_time& elapsed, std::string notes);

// The statistics of a block that is busy for `busy` of `elapsed`: busy_ns,
// utilisation (their ratio, 0 before any time has passed) and elapsed_ns,
// added to `stats`; and their descriptions, busy_ns described as `busy_is`.
void add_busy_stats(nlohmann::json& stats, const sc_core::sc_time& busy, const sc_core::sc_time& elapsed);
void describe_busy_stats(StatsSchema& schema, const std::string& busy_is);

}  // namespace tessera
