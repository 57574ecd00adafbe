// Tests of the system/array DMA's driver (sw_driver/device/dma_driver.h) on
// the assembled SoC with dma.enabled=true, the host running each test body
// as its program: the driver finds the DMA and its channels; a plain array
// of 16-bit values lands array-ready in CMEM (checked byte for byte in the
// array's CMEM) and comes back out to a plain array; a broadcast with a mask
// in memory writes only the masked CUs; a chain runs in order; wait() sleeps
// on the interrupt instead of polling (the host's bus traffic while it
// waits); a refused descriptor raises DmaError with the DMA's code, the
// descriptor and the offending address.
#include <cstring>
#include <vector>

#include "device/app_environment.h"
#include "device/dma_driver.h"
#include "dma/dma_descriptor.h"
#include "soc/soc.h"
#include "soc/software_layout.h"
#include "tlm_bench/host_program_runner.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;

namespace {

Config dma_config() {
  Config config(Soc::parameter_groups());
  config.apply_override("dma.enabled=true");
  return config;
}

struct Bench {
  Config config = dma_config();
  Soc soc{"soc", config};
  test::HostProgramRunner runner;
  software_layout::Layout layout = software_layout::layout(soc.memory.size(), soc.display.frame_bytes());

  Bench() { soc.set_program(runner.program()); }
  // Runs `body` with a driver on the host.
  void run(const std::function<void(HostApi&, DmaDriver&)>& body) {
    runner.run([&](HostApi& api) {
      AppEnvironment env;
      env.host = &api;
      DmaDriver dma(env);
      body(api, dma);
    });
  }
  unsigned lanes() const { return soc.array.params().geometry.lanes(); }
  uint8_t cmem(unsigned lane, unsigned address) const { return soc.array.core().array().cmem(lane, address); }
  // Scratch in system memory, in the driver's heap.
  uint32_t scratch(uint32_t offset) const { return layout.heap_base + offset; }
};

Bench* g_bench = nullptr;

}  // namespace

TEST(DmaDriver, FindsTheDmaAndItsChannels) {
  Bench& b = *g_bench;
  bool present = false;
  unsigned channels = 0;
  b.run([&](HostApi&, DmaDriver& dma) {
    present = dma.present();
    channels = dma.channels();
  });
  EXPECT_TRUE(present);
  EXPECT_EQ(channels, b.config.get_uint("dma.channels"));
}

TEST(DmaDriver, SixteenBitValuesLandArrayReadyAndComeBackOut) {
  Bench& b = *g_bench;
  const unsigned n = b.lanes();
  const uint32_t src = b.scratch(0), back = b.scratch(0x1000);
  constexpr unsigned CMEM = 100;
  std::vector<uint8_t> returned(2 * n);
  b.run([&](HostApi& api, DmaDriver& dma) {
    uint8_t* p = api.store_span(src, 2, n);
    for (unsigned k = 0; k < n; ++k) {
      const auto value = static_cast<uint16_t>(0x1000 * (k % 16) + 3 * k + 1);
      std::memcpy(p + 2 * k, &value, 2);
    }
    dma.start(0, DmaDriver::to_cmem(src, CMEM, n, 2));
    dma.wait(0);
    dma.start(1, DmaDriver::from_cmem(CMEM, back, n, 2));
    dma.wait(1);
    std::memcpy(returned.data(), api.load_span(back, 2, n), 2 * n);
  });
  for (unsigned k = 0; k < n; ++k) {
    const auto value = static_cast<uint16_t>(0x1000 * (k % 16) + 3 * k + 1);
    EXPECT_EQ(b.cmem(k, CMEM), value >> 8) << "CU " << k;
    EXPECT_EQ(b.cmem(k, CMEM + 1), value & 0xff) << "CU " << k;
    uint16_t got = 0;
    std::memcpy(&got, returned.data() + 2 * k, 2);
    EXPECT_EQ(got, value) << "CU " << k;
  }
}

TEST(DmaDriver, ABroadcastWithAMaskWritesOnlyTheMaskedCus) {
  Bench& b = *g_bench;
  const unsigned n = b.lanes();
  const uint32_t src = b.scratch(0x2000), mask = b.scratch(0x2100);
  constexpr unsigned CMEM = 200;
  const uint8_t bytes[5] = {0xa1, 0xb2, 0xc3, 0xd4, 0xe5};
  b.run([&](HostApi& api, DmaDriver& dma) {
    std::memcpy(api.store_span(src, 1, 5), bytes, 5);
    uint8_t* m = api.store_span(mask, 1, (n + 7) / 8);
    for (unsigned k = 0; k < (n + 7) / 8; ++k) m[k] = 0x55;  // the even CUs
    dma.start(0, DmaDriver::broadcast(src, CMEM, 5, 0));
    dma.wait(0);
    std::memset(api.store_span(src, 1, 5), 0x77, 5);
    dma.start(0, DmaDriver::broadcast(src, CMEM, 5, mask));
    dma.wait(0);
  });
  for (unsigned k = 0; k < n; ++k)
    for (unsigned j = 0; j < 5; ++j) EXPECT_EQ(b.cmem(k, CMEM + j), k % 2 == 0 ? 0x77 : bytes[j]) << k << " " << j;
}

TEST(DmaDriver, AChainRunsInOrderAndWaitSleepsOnTheInterrupt) {
  Bench& b = *g_bench;
  const unsigned n = b.lanes();
  const uint32_t src = b.scratch(0x3000), chain = b.scratch(0x3800);
  constexpr unsigned CMEM = 300;
  uint64_t host_transactions = 0;
  double waited = 0;
  b.run([&](HostApi& api, DmaDriver& dma) {
    uint8_t* p = api.store_span(src, 1, 4 * n);
    for (unsigned k = 0; k < 4 * n; ++k) p[k] = static_cast<uint8_t>(k / n + 1);
    // Two descriptors to the same CMEM byte: the second must win.
    dma.write_chain(chain, {DmaDriver::to_cmem(src, CMEM, n, 1), DmaDriver::to_cmem(src + n, CMEM, n, 1),
                            DmaDriver::to_cmem(src + 2 * n, CMEM + 1, 2 * n, 1)});
    dma.start_chain(0, chain);
    const uint64_t before = g_bench->soc.bus.initiator_stats()[0].transactions;
    const double start = api.now_seconds();
    dma.wait(0);
    waited = api.now_seconds() - start;
    host_transactions = g_bench->soc.bus.initiator_stats()[0].transactions - before;
  });
  for (unsigned k = 0; k < n; ++k) {
    EXPECT_EQ(b.cmem(k, CMEM), 2) << k;
    EXPECT_EQ(b.cmem(k, CMEM + 1), 3) << k;
    EXPECT_EQ(b.cmem(k, CMEM + 2), 4) << k;
  }
  // Three descriptors take microseconds; the host read
  // IRQ_STATUS, acknowledged and read STATUS: a handful of accesses, not a
  // poll loop.
  EXPECT_GT(waited, 1e-6);
  EXPECT_LE(host_transactions, 6u);
}

TEST(DmaDriver, ARefusedDescriptorRaisesDmaErrorNamingCodeDescriptorAndAddress) {
  Bench& b = *g_bench;
  const uint32_t beyond = static_cast<uint32_t>(b.soc.memory.size()) + 0x100;
  bool thrown = false;
  uint32_t code = 0, descriptor = 0;
  uint64_t address = 0;
  std::string what;
  b.run([&](HostApi&, DmaDriver& dma) {
    try {
      dma.start(1, DmaDriver::to_cmem(beyond, 0, b.lanes(), 1));
      dma.wait(1);
    } catch (const DmaError& error) {
      thrown = true;
      code = error.code();
      descriptor = error.descriptor();
      address = error.address();
      what = error.what();
    }
  });
  ASSERT_TRUE(thrown);
  EXPECT_EQ(code, static_cast<uint32_t>(dma::Error::src_outside_memory));
  EXPECT_EQ(descriptor, 0xFFFFFFFFu);
  EXPECT_EQ(address, beyond + b.lanes() - 1);  // the last byte of the range
  EXPECT_NE(what.find("channel 1"), std::string::npos) << what;
  EXPECT_NE(what.find("source outside system memory"), std::string::npos) << what;
}

int sc_main(int argc, char* argv[]) {
  test::ReportCapture quiet;
  g_bench = new Bench();
  return test::run_all_tests(argc, argv);
}
