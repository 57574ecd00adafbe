// TLM test of the power trace under a known steady load: the host charges
// one computation of 40.5 windows' worth of cycles in a single call (as the
// native model charges a measured row), then waits for an interrupt that
// never comes. The host's cycles are charged at once but spent over 40
// windows: each window inside the computation must show the power of a
// host busy all the time, not the whole computation in the window where it
// was charged and idling in the others. The array is never used, so with
// power.sleep_unused (the default) its clocked power is charged in no window.
#include <filesystem>
#include <string>
#include <vector>

#include "process/scratch_folder.h"
#include "soc/irq_map.h"
#include "soc/soc.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

constexpr unsigned BUSY_WINDOWS = 40;
constexpr unsigned TRACED_WINDOWS = 50;

struct Bench {
  Config config{Soc::parameter_groups()};
  Soc soc{"soc", config};
  sc_time window = sc_time(config.get_real("power.trace_window_us"), sc_core::SC_US);
  sc_time period = HostParams::from_config(config).clock_period;
  std::vector<PowerWindow> windows;
};

Bench* g_bench = nullptr;

// Copies each window once the SoC has closed it (just after its end).
struct WindowReader : sc_core::sc_module {
  SC_HAS_PROCESS(WindowReader);
  explicit WindowReader(sc_core::sc_module_name name) : sc_core::sc_module(name) { SC_THREAD(read); }
  void read() {
    wait(g_bench->window + sc_time(1, sc_core::SC_NS));
    for (unsigned k = 0; k < TRACED_WINDOWS; ++k) {
      g_bench->windows.push_back(g_bench->soc.recorder().power_trace()->last_window());
      wait(g_bench->window);
    }
  }
};

double pj_of(const std::string& unit, const std::string& event) {
  for (const UnitEnergyParams& u : g_bench->soc.recorder().energy_model().units())
    if (u.unit == unit)
      for (const EventEnergy& e : u.events)
        if (e.event == event) return e.picojoules;
  throw std::logic_error("no event " + unit + "." + event);
}

double static_mw_of(const std::string& unit) {
  for (const UnitEnergyParams& u : g_bench->soc.recorder().energy_model().units())
    if (u.unit == unit) return u.static_milliwatts;
  throw std::logic_error("no unit " + unit);
}

double unit_mw(const PowerWindow& w, const std::string& unit) {
  for (const UnitEnergy& u : w.units)
    if (u.unit == unit) return w.milliwatts(u.total_joules());
  throw std::logic_error("no unit " + unit + " in the window");
}

}  // namespace

TEST(SocPowerSteady, EveryWindowOfTheComputationShowsTheHostBusy) {
  const Bench& b = *g_bench;
  ASSERT_EQ(b.windows.size(), TRACED_WINDOWS);
  const double busy_mw = static_mw_of("host") + pj_of("host", "busy_cycles") * 1e-12 / b.period.to_seconds() * 1e3;
  const double idle_mw = static_mw_of("host") + pj_of("host", "idle_cycles") * 1e-12 / b.period.to_seconds() * 1e3;
  // The program starts a few cycles into the first window and ends halfway
  // through window 40; every window between is busy throughout.
  for (unsigned k = 1; k < BUSY_WINDOWS; ++k)
    EXPECT_NEAR(unit_mw(b.windows[k], "host"), busy_mw, 1e-6 * busy_mw) << "window " << k;
  // After it, the host idles for its interrupt.
  for (unsigned k = BUSY_WINDOWS + 1; k < TRACED_WINDOWS; ++k)
    EXPECT_NEAR(unit_mw(b.windows[k], "host"), idle_mw, 1e-6 * idle_mw) << "window " << k;
}

TEST(SocPowerSteady, AnUnusedArraySleeps) {
  for (const PowerWindow& w : g_bench->windows) {
    EXPECT_EQ(unit_mw(w, "cu_array"), 0.0);
    EXPECT_EQ(unit_mw(w, "array_controller"), 0.0);
  }
}

int sc_main(int argc, char* argv[]) {
  test::ReportCapture quiet;
  g_bench = new Bench();
  Bench& b = *g_bench;
  const uint64_t cycles = static_cast<uint64_t>((BUSY_WINDOWS + 0.5) * (b.window / b.period));
  b.soc.set_program([cycles](HostApi& api) {
    api.compute_cycles(cycles);
    api.wait_irq(irq_map::array);
    return 0;
  });
  WindowReader reader("reader");
  const test::ScratchFolder folder("tessera_soc_power_steady");
  const std::filesystem::path trace = folder.path() / "power";
  b.soc.recorder().trace_to(trace.string());
  sc_core::sc_start(b.window * (TRACED_WINDOWS + 1));
  const int status = test::run_all_tests(argc, argv);
  b.soc.recorder().close_trace();
  return status;
}
