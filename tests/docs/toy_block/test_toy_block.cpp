// docs/how_to_add_a_block.md followed for a toy block (toy.h): the walk-
// through's steps 1 to 4 and 7 give a block that answers its registers
// through a protocol checker, times its job from the access, raises its
// interrupt at the job's end, refuses bad writes by its own rule, and whose
// statistics are each described (the schema the run report and the region
// of interest use) with the busy figures the common helpers give. If the
// walk-through's names or shapes drift from the code (the register table's
// macros, register_members.inc, bind_irq_registers, the parameter group,
// add_busy_stats), this stops building or fails.
#include <functional>
#include <set>
#include <string>

#include "checker/protocol_checker.h"
#include "tlm_bench/tlm_test_support.h"
#include "toy.h"
#include "toy_regs.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

struct Bench {
  test::TestInitiator cpu{"cpu"};
  ProtocolChecker<32> check{"check"};
  Toy toy{"toy", ToyParams::defaults()};
  sc_core::sc_signal<bool> irq{"irq"};
  Bench() {
    cpu.out.bind(check.in);
    check.out.bind(toy.in);
    toy.irq.bind(irq);
  }
};

Bench* g_bench = nullptr;
const sc_time CYCLE(10, sc_core::SC_NS);  // toy.clock_mhz's default, 100 MHz
constexpr unsigned JOB_CYCLES = 16;       // toy.job_cycles' default

// Every leaf of a stats document as a dotted key.
void leaves(const nlohmann::json& node, const std::string& prefix, std::set<std::string>& out) {
  if (!node.is_object()) {
    out.insert(prefix);
    return;
  }
  for (const auto& [key, value] : node.items()) leaves(value, prefix.empty() ? key : prefix + "." + key, out);
}

TEST(HowToAddABlock, TheParameterGroupHoldsTheDefaultsAndRefusesBadValues) {
  const ToyParams defaults = ToyParams::defaults();
  EXPECT_EQ(defaults.job_cycles, JOB_CYCLES);
  EXPECT_EQ(defaults.clock_period, CYCLE);
  Config config({ToyParams::parameters()});
  try {
    config.apply_override("toy.job_cycles=0");
    FAIL() << "toy.job_cycles=0 was taken";
  } catch (const ConfigError& error) {
    EXPECT_NE(std::string(error.what()).find("toy.job_cycles"), std::string::npos) << error.what();
  }
  config.apply_override("toy.job_cycles=5");
  EXPECT_EQ(ToyParams::from_config(config).job_cycles, 5u);
}

TEST(HowToAddABlock, AJobRunsFromTheAccessAndRaisesItsInterruptAtItsEnd) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    EXPECT_EQ(b.cpu.write32(toy_regs::CTRL, toy_regs::CTRL_ENABLE).status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.cpu.write32(toy_regs::IRQ_ENABLE, toy_regs::IRQ_DONE).status, tlm::TLM_OK_RESPONSE);
    sc_core::wait(CYCLE);
    const sc_time start = sc_core::sc_time_stamp();
    const auto started = b.cpu.write32(toy_regs::START, 1);
    EXPECT_EQ(started.status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(started.delay, CYCLE);  // a register access costs one cycle of the block's clock
    EXPECT_EQ(b.cpu.read32(toy_regs::STATUS), toy_regs::STATUS_BUSY);
    sc_core::wait(b.irq.posedge_event());
    EXPECT_EQ(sc_core::sc_time_stamp(), start + CYCLE * double(JOB_CYCLES));
    EXPECT_EQ(b.cpu.read32(toy_regs::STATUS), 0u);
    EXPECT_EQ(b.cpu.read32(toy_regs::IRQ_STATUS), toy_regs::IRQ_DONE);
    EXPECT_EQ(b.cpu.write32(toy_regs::IRQ_STATUS, toy_regs::IRQ_DONE).status, tlm::TLM_OK_RESPONSE);  // w1c
    sc_core::wait(CYCLE);
    EXPECT_FALSE(b.irq.read());
    EXPECT_EQ(b.cpu.read32(toy_regs::IRQ_STATUS), 0u);
  });
}

TEST(HowToAddABlock, TheBlocksOwnRulesRefuseBadWrites) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    EXPECT_EQ(b.cpu.write32(toy_regs::START, 2).status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(b.cpu.write32(toy_regs::START, 1).status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.cpu.write32(toy_regs::START, 1).status, tlm::TLM_COMMAND_ERROR_RESPONSE);  // a job runs
    sc_core::wait(CYCLE * double(JOB_CYCLES));
    EXPECT_EQ(b.cpu.write32(toy_regs::CTRL, 0).status, tlm::TLM_OK_RESPONSE);
    EXPECT_EQ(b.cpu.write32(toy_regs::START, 1).status, tlm::TLM_COMMAND_ERROR_RESPONSE);   // disabled
    EXPECT_EQ(b.cpu.write32(toy_regs::STATUS, 1).status, tlm::TLM_COMMAND_ERROR_RESPONSE);  // read-only
    EXPECT_EQ(b.cpu.write32(0x40, 1).status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  });
}

// After the two tests before it (gtest runs a file's tests in order): two
// jobs, three refused writes.
TEST(HowToAddABlock, EveryStatisticIsDescribedAndTheBusyFiguresAreTheJobs) {
  Bench& b = *g_bench;
  const sc_time elapsed = sc_core::sc_time_stamp();
  const nlohmann::json stats = b.toy.stats_json(elapsed);
  EXPECT_EQ(stats["jobs"], 2u);
  EXPECT_EQ(stats["refused_register_writes"], 3u);  // START 2, START while running, START while disabled
  EXPECT_EQ(stats["job_cycles"], JOB_CYCLES);
  const double busy_ns = 2 * JOB_CYCLES * 10.0;
  EXPECT_DOUBLE_EQ(stats["busy_ns"].get<double>(), busy_ns);
  EXPECT_DOUBLE_EQ(stats["elapsed_ns"].get<double>(), elapsed.to_seconds() * 1e9);
  EXPECT_DOUBLE_EQ(stats["utilisation"].get<double>(), busy_ns / (elapsed.to_seconds() * 1e9));
  StatsSchema schema;
  b.toy.describe_stats(schema);
  std::set<std::string> described, given;
  for (const StatDescription& d : schema.entries()) described.insert(d.key);
  leaves(stats, "", given);
  EXPECT_EQ(given, described);
  EXPECT_NO_THROW(schema.to_json());  // no key described twice differently
  for (const StatDescription& d : schema.entries()) {
    const bool level = d.key == "job_cycles" || d.key == "utilisation";  // a setting, a ratio
    EXPECT_EQ(accumulates(d), !level) << d.key;
  }
  const SummaryRow row = b.toy.summary_row(elapsed);
  EXPECT_EQ(row.notes, "2 jobs");
  ASSERT_TRUE(row.utilisation.has_value());
  EXPECT_DOUBLE_EQ(*row.utilisation, stats["utilisation"].get<double>());
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench();
  sc_core::sc_start(sc_core::SC_ZERO_TIME);
  return test::run_all_tests(argc, argv);
}
