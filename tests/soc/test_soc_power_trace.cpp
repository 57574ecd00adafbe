// TLM test of the SoC's power trace (Soc::trace_to, power.trace_window_us):
// the host clears part of a buffer, then waits for an interrupt that never
// comes, for 20.5 windows. The windows end on the window grid, a window
// after the clear holds static power only (and the host's idle cycles; the
// array, never used, sleeps without it), and
// the windows' energies, the last partial one included, add up to the energy
// the statistics report for the run.
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string>

#include "process/scratch_folder.h"
#include "soc/irq_map.h"
#include "soc/soc.h"
#include "soc/software_layout.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

constexpr unsigned CLEAR_PIXELS = 4000;

struct Bench {
  Config config{Soc::parameter_groups()};
  Soc soc{"soc", config};
  sc_time window = sc_time(config.get_real("power.trace_window_us"), sc_core::SC_US);
  double clear_end_seconds = 0;
};

Bench* g_bench = nullptr;

const UnitEnergyParams& params_of(const std::string& unit) {
  for (const UnitEnergyParams& u : g_bench->soc.recorder().energy_model().units())
    if (u.unit == unit) return u;
  throw std::logic_error("no unit " + unit);
}

double pj_of(const std::string& unit, const std::string& event) {
  for (const EventEnergy& e : params_of(unit).events)
    if (e.event == event) return e.picojoules;
  throw std::logic_error("no event " + event);
}

}  // namespace

TEST(SocPowerTrace, WindowsEndOnTheWindowGrid) {
  const PowerTrace* trace = g_bench->soc.recorder().power_trace();
  ASSERT_NE(trace, nullptr);
  EXPECT_EQ(trace->windows(), 20u);
  EXPECT_EQ(sc_time(trace->last_window().start_seconds, sc_core::SC_SEC), g_bench->window * 19);
  EXPECT_EQ(sc_time(trace->last_window().end_seconds, sc_core::SC_SEC), g_bench->window * 20);
}

TEST(SocPowerTrace, AWindowWithoutActivityShowsStaticPowerOnly) {
  const PowerWindow& quiet = g_bench->soc.recorder().power_trace()->last_window();
  ASSERT_LT(g_bench->clear_end_seconds, quiet.start_seconds) << "the clear is still running";
  ASSERT_EQ(quiet.units.size(), 9u);  // dma.enabled is false: no dma unit
  for (const UnitEnergy& unit : quiet.units) {
    if (unit.unit == "host") continue;
    EXPECT_EQ(unit.dynamic_joules(), 0.0) << unit.unit;
    // The program never uses the array: it sleeps (power.sleep_unused).
    const bool asleep = unit.unit == "cu_array" || unit.unit == "array_controller" || unit.unit == "ciu";
    EXPECT_NEAR(quiet.milliwatts(unit.total_joules()), asleep ? 0.0 : params_of(unit.unit).static_milliwatts, 1e-9)
        << unit.unit;
  }
  // The host waits for its interrupt: idle cycles and leakage, the board's
  // 52.2 mW idling on NOPs.
  const double host_period = HostParams::from_config(g_bench->config).clock_period.to_seconds();
  const double idle_mw = pj_of("host", "idle_cycles") * 1e-12 / host_period * 1e3;
  EXPECT_NEAR(quiet.milliwatts(quiet.units.at(0).total_joules()), params_of("host").static_milliwatts + idle_mw, 1e-9);
  EXPECT_EQ(quiet.units.at(0).unit, "host");
}

TEST(SocPowerTrace, TheWindowsAddUpToTheRunsEnergy) {
  Soc& soc = g_bench->soc;
  soc.recorder().close_power_window();
  EXPECT_EQ(soc.recorder().power_trace()->windows(), 21u);
  EXPECT_EQ(sc_time(soc.recorder().power_trace()->last_window().end_seconds, sc_core::SC_SEC), g_bench->window * 20.5);
  const nlohmann::json energy = soc.recorder().stats_json()["energy"];
  double total = 0;
  for (const auto& [unit, joules] : soc.recorder().power_trace()->summed_joules()) {
    const double reported = energy["units"][unit]["total_j"].get<double>();
    EXPECT_NEAR(joules, reported, 1e-12 * reported + 1e-24) << unit;
    total += joules;
  }
  EXPECT_NEAR(total, energy["total_j"].get<double>(), 1e-12 * total);
  // The clear is in the windows: the bus carried it.
  EXPECT_GT(soc.recorder().power_trace()->summed_joules().at("bus"), 0.0);
}

int sc_main(int argc, char* argv[]) {
  test::ReportCapture quiet;
  g_bench = new Bench();
  Bench& b = *g_bench;
  const software_layout::Layout layout = software_layout::layout(b.soc.memory.size(), b.soc.display.frame_bytes());
  b.soc.set_program([&b, &layout](HostApi& api) {
    uint8_t* data = api.store_span(layout.frame_buffers[1], 2, CLEAR_PIXELS);
    std::memset(data, 0x5a, 2 * CLEAR_PIXELS);
    b.clear_end_seconds = api.now_seconds();
    api.wait_irq(irq_map::array);
    return 0;
  });
  const test::ScratchFolder folder("tessera_soc_power_trace");
  const std::filesystem::path trace = folder.path() / "power";
  b.soc.recorder().trace_to(trace.string());
  sc_core::sc_start(b.window * 20.5);
  const int status = test::run_all_tests(argc, argv);
  b.soc.recorder().close_trace();
  return status;
}
