// TLM tests of the region of interest's register (tlm/soc/roi_register.h):
// each change of ROI is one edge at the access's annotated time, a write
// that changes nothing is none, a read shows whether a region is open, and
// any value but 0 or 1 is refused as a command error.
#include <vector>

#include "checker/protocol_checker.h"
#include "soc/roi_register.h"
#include "soc/sim_control_regs.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);

struct Edge {
  bool begins;
  sc_time when;
};

struct Bench {
  std::vector<Edge> edges;
  test::TestInitiator cpu{"cpu"};
  ProtocolChecker<32> check{"check"};
  RoiRegister roi{"roi", CYCLE, [this](bool begins, const sc_time& when) { edges.push_back({begins, when}); }};
  Bench() {
    cpu.out.bind(check.in);
    check.out.bind(roi.in);
  }
};

Bench* g_bench = nullptr;

TEST(RoiRegister, EachChangeIsOneEdgeAtTheAccessTime) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    EXPECT_EQ(b.cpu.read32(sim_control_regs::ROI), 0u);
    sc_core::wait(CYCLE);
    const sc_time start = sc_core::sc_time_stamp();
    uint32_t one = 1;
    const auto result =
        b.cpu.write(sim_control_regs::ROI, reinterpret_cast<const uint8_t*>(&one), 4, 3 * CYCLE);  // ahead by 3
    EXPECT_EQ(result.status, tlm::TLM_OK_RESPONSE);
    ASSERT_EQ(b.edges.size(), 1u);
    EXPECT_TRUE(b.edges[0].begins);
    EXPECT_EQ(b.edges[0].when, start + 3 * CYCLE);
    EXPECT_EQ(b.cpu.write32(sim_control_regs::ROI, 1).status, tlm::TLM_OK_RESPONSE);  // already open
    EXPECT_EQ(b.edges.size(), 1u);
    EXPECT_EQ(b.cpu.read32(sim_control_regs::ROI), 1u);
    sc_core::wait(5 * CYCLE);
    EXPECT_EQ(b.cpu.write32(sim_control_regs::ROI, 0).status, tlm::TLM_OK_RESPONSE);
    ASSERT_EQ(b.edges.size(), 2u);
    EXPECT_FALSE(b.edges[1].begins);
    EXPECT_EQ(b.edges[1].when, sc_core::sc_time_stamp());
    EXPECT_EQ(b.cpu.write32(sim_control_regs::ROI, 0).status, tlm::TLM_OK_RESPONSE);  // already closed
    EXPECT_EQ(b.edges.size(), 2u);
  });
}

TEST(RoiRegister, AValueOtherThanZeroOrOneIsRefused) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    b.edges.clear();
    for (uint32_t value : {2u, 0xFFFFFFFFu})
      EXPECT_EQ(b.cpu.write32(sim_control_regs::ROI, value).status, tlm::TLM_COMMAND_ERROR_RESPONSE) << value;
    EXPECT_TRUE(b.edges.empty());
    EXPECT_EQ(b.cpu.read32(sim_control_regs::ROI), 0u);
    EXPECT_EQ(b.cpu.write32(0x40, 1).status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  });
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench();
  sc_core::sc_start(sc_core::SC_ZERO_TIME);
  return test::run_all_tests(argc, argv);
}
