// TLM tests of the system/array DMA (tlm/dma/dma.h) on a bench of its own:
// a test initiator playing the host, the DMA, a bus, a memory and an array
// (the DMA's CMEM side), with protocol checkers on the host's socket, the
// DMA's bus-master socket, its register socket and the memory. Register
// descriptors and chains, the reshuffle byte for byte in CMEM both ways,
// broadcast with and without a mask and its one-pass cost, each error
// (code, descriptor, address, interrupt, warning, nothing written), waiting
// for a running program, contention with the host on the bus, statistics
// and the summary row.
//
// Bench: 100 MHz bus and array clock; memory of 64 KiB with 2 wait states.
#include <cstring>
#include <vector>

#include "array/array_processor.h"
#include "array/array_regs.h"
#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "dma/dma.h"
#include "dma/dma_regs.h"
#include "mem/memory.h"
#include "tlm_bench/bench_block_params.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;
namespace regs = dma_regs;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
constexpr uint64_t MEMORY_BYTES = 0x10000;
constexpr uint64_t DMA = 0x40000000, AC = 0x50000000, PROGRAM = 0x50010000;
constexpr unsigned LANES = 96, CMEM_BYTES = 4096;

DmaParams dma_params() {
  DmaParams p = DmaParams::defaults();
  p.burst_bytes = 64;
  p.clock_period = CYCLE;
  p.cmem_clock_period = CYCLE;
  p.memory_base = 0;
  p.memory_bytes = MEMORY_BYTES;
  return p;
}

ArrayParams array_params() {
  return test::bench_array_params(CYCLE);
}

struct Bench : sc_core::sc_module {
  test::TestInitiator host;
  ProtocolChecker<32> check_host, check_dma_out, check_dma_regs, check_memory;
  AhbBus bus;
  Memory memory;
  ArrayProcessor array;
  Dma dma;
  sc_core::sc_signal<bool> dma_irq, array_irq;
  explicit Bench(sc_core::sc_module_name name)
      : sc_core::sc_module(name),
        host("host"),
        check_host("check_host"),
        check_dma_out("check_dma_out"),
        check_dma_regs("check_dma_regs"),
        check_memory("check_memory"),
        bus("bus", test::bench_bus_params(CYCLE)),
        memory("memory", test::bench_memory_params(MEMORY_BYTES, CYCLE, 2)),
        array("array", array_params()),
        dma("dma", dma_params()) {
    host.out.bind(check_host.in);
    bus.attach(check_host.out, "host", 3);
    dma.out.bind(check_dma_out.in);
    bus.attach(check_dma_out.out, "dma", 2);
    bus.map(check_memory.in, 0, 0x10000000, "memory");
    check_memory.out.bind(memory.in);
    bus.map(check_dma_regs.in, DMA, 0x1000, "dma_regs");
    check_dma_regs.out.bind(dma.in);
    bus.map(array.in, AC, 0x1000, "array_regs");
    bus.map(array.program_in, PROGRAM, 0x10000, "array_program");
    dma.irq.bind(dma_irq);
    array.irq.bind(array_irq);
    dma.connect_cmem(array);
    dma.set_bus_wait_probe([this] { return bus.initiator_stats()[1].wait_cycles; });
  }

  void reg(unsigned channel, uint32_t offset, uint32_t value) {
    ASSERT_EQ(host.write32(DMA + regs::channel_base(channel) + offset, value).status, tlm::TLM_OK_RESPONSE);
  }
  uint32_t reg(unsigned channel, uint32_t offset) { return host.read32(DMA + regs::channel_base(channel) + offset); }
  void load(unsigned channel, const dma::Descriptor& d) {
    const auto words = dma::encode(d);
    for (unsigned i = 0; i < dma::DESCRIPTOR_WORDS; ++i) reg(channel, 4 * i, words[i]);
  }
  // Starts the channel and returns when it has finished (its time).
  sc_time run(unsigned channel, uint32_t start = regs::START_GO) {
    reg(channel, regs::CH_START, start);
    while (dma.channel_busy(channel)) sc_core::wait(dma.channel_finished_event());
    return sc_core::sc_time_stamp();
  }
  void put(uint32_t address, const dma::Descriptor& d) { dma::encode_bytes(d, memory.data() + address); }
  uint64_t count(const std::string& name) const { return dma.counters().value(name); }
  uint8_t cmem(unsigned lane, unsigned address) const { return array.read_cmem(lane, address); }
};

Bench* g_bench = nullptr;

dma::Descriptor make(dma::Kind kind, unsigned element, uint32_t src, uint32_t dst, uint32_t length) {
  dma::Descriptor d;
  d.ctrl = dma::Descriptor::make_ctrl(kind, element);
  d.src = src;
  d.dst = dst;
  d.length = length;
  return d;
}

void clear_irq(Bench& b) {
  b.host.write32(DMA + regs::IRQ_STATUS, 0xffffffff);
}

}  // namespace

TEST(Dma, RegistersShowTheConfiguration) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    EXPECT_EQ(b.host.read32(DMA + regs::ID), regs::ID_VALUE);
    EXPECT_EQ(b.host.read32(DMA + regs::CHANNELS), 2u);
    EXPECT_EQ(b.host.read32(DMA + regs::CMEM_BYTES_PER_CYCLE), 4u);
    // A channel that does not exist has no registers.
    test::TestInitiator::Result r;
    b.host.read32(DMA + regs::channel_base(2) + regs::CH_STATUS, &r);
    EXPECT_EQ(r.status, tlm::TLM_ADDRESS_ERROR_RESPONSE);
  });
}

TEST(Dma, ReshuffleLandsEachValueByteForByteInItsCuAndTheCostIsTheRate) {
  Bench& b = *g_bench;
  for (unsigned k = 0; k < 2 * LANES; ++k) {
    const auto value = static_cast<uint16_t>(0x4000 + 13 * k);
    b.memory.data()[0x1000 + 2 * k] = static_cast<uint8_t>(value);  // the host's little-endian uint16_t
    b.memory.data()[0x1000 + 2 * k + 1] = static_cast<uint8_t>(value >> 8);
  }
  const uint64_t cycles = b.count("cmem.cycles");
  sc_time start, done;
  test::run_thread([&] {
    b.host.write32(DMA + regs::IRQ_ENABLE, 0xff);
    b.load(0, make(dma::Kind::mem_to_cmem, 2, 0x1000, 100, 4 * LANES));
    start = sc_core::sc_time_stamp();
    done = b.run(0);
    sc_core::wait(CYCLE);  // the line follows the status at the next delta
    EXPECT_TRUE(b.dma_irq.read());
    EXPECT_EQ(b.host.read32(DMA + regs::IRQ_STATUS), regs::irq_done(0));
    EXPECT_EQ(b.reg(0, regs::CH_STATUS), regs::STATUS_DONE);
    clear_irq(b);
  });
  for (unsigned k = 0; k < 2 * LANES; ++k) {
    const auto value = static_cast<uint16_t>(0x4000 + 13 * k);
    const unsigned lane = k % LANES, address = 100 + 2 * (k / LANES);
    ASSERT_EQ(b.cmem(lane, address), value >> 8) << k;
    ASSERT_EQ(b.cmem(lane, address + 1), value & 0xff) << k;
  }
  EXPECT_EQ(b.cmem(0, 99), 0);
  EXPECT_EQ(b.cmem(0, 104), 0);
  // Two rows of 192 bytes on 4-byte data lines: 96 array cycles.
  EXPECT_EQ(b.count("cmem.cycles") - cycles, 96u);
  // Each row: 3 bursts of 64 bytes (address phase, 2 wait states, 16 beats)
  // and then its CMEM pass of 48 cycles, not overlapped; the bound above
  // allows for the register writes' latency before the START takes effect.
  EXPECT_GE(done - start, CYCLE * (2.0 * (3 * (1 + 2 + 16) + 48)));
  EXPECT_LE(done - start, CYCLE * (2.0 * (3 * (1 + 2 + 16) + 48) + 30));
}

TEST(Dma, CmemToMemoryReadsACuVariableOutToAPlainArray) {
  Bench& b = *g_bench;
  for (unsigned l = 0; l < LANES; ++l) {
    b.array.write_cmem(l, 2000, static_cast<uint8_t>(l));
    b.array.write_cmem(l, 2001, static_cast<uint8_t>(~l));
  }
  std::memset(b.memory.data() + 0x3000, 0xee, 0x100);
  test::run_thread([&] {
    b.load(0, make(dma::Kind::cmem_to_mem, 2, 2000, 0x3000, 2 * LANES));
    b.run(0);
    clear_irq(b);
  });
  for (unsigned l = 0; l < LANES; ++l) {
    // CMEM's high byte first becomes the host's little-endian uint16_t.
    ASSERT_EQ(b.memory.data()[0x3000 + 2 * l], static_cast<uint8_t>(~l));
    ASSERT_EQ(b.memory.data()[0x3000 + 2 * l + 1], l);
  }
  EXPECT_EQ(b.memory.data()[0x3000 + 2 * LANES], 0xee);
}

TEST(Dma, AChainInMemoryRunsEveryDescriptorInOrder) {
  Bench& b = *g_bench;
  for (unsigned i = 0; i < LANES; ++i) b.memory.data()[0x5000 + i] = static_cast<uint8_t>(i + 1);
  for (unsigned i = 0; i < 8; ++i) b.memory.data()[0x5100 + i] = static_cast<uint8_t>(0x70 + i);
  dma::Descriptor first = make(dma::Kind::mem_to_cmem, 1, 0x5000, 500, LANES);
  first.next = 0x6040;
  dma::Descriptor second = make(dma::Kind::broadcast, 1, 0x5100, 510, 8);
  second.next = 0x6060;
  dma::Descriptor third = make(dma::Kind::cmem_to_mem, 1, 500, 0x5200, LANES);
  b.put(0x6020, first);
  b.put(0x6040, second);
  b.put(0x6060, third);
  const uint64_t descriptors = b.count("ch1.descriptors");
  const nlohmann::json sizes_before = b.dma.stats_json(sc_core::sc_time_stamp())["histograms"]["descriptor_bytes"];
  test::run_thread([&] {
    b.reg(1, regs::CH_D_NEXT, 0x6020);
    b.run(1, regs::START_GO | regs::START_CHAIN_ONLY);
    EXPECT_EQ(b.reg(1, regs::CH_STATUS), regs::STATUS_DONE);
    clear_irq(b);
  });
  EXPECT_EQ(b.count("ch1.descriptors") - descriptors, 3u);
  // The sizes: LANES (96, bucket 64-127) twice and 8 (bucket 8-15) once.
  const nlohmann::json sizes = b.dma.stats_json(sc_core::sc_time_stamp())["histograms"]["descriptor_bytes"];
  const auto in_bucket = [](const nlohmann::json& histogram, uint64_t low) {
    for (const auto& bucket : histogram["buckets"])
      if (bucket["low"] == low) return bucket["count"].get<uint64_t>();
    return uint64_t{0};
  };
  EXPECT_EQ(sizes["count"].get<uint64_t>() - sizes_before["count"].get<uint64_t>(), 3u);
  EXPECT_EQ(sizes["sum"].get<uint64_t>() - sizes_before["sum"].get<uint64_t>(), 2u * 96 + 8);
  EXPECT_EQ(in_bucket(sizes, 64) - in_bucket(sizes_before, 64), 2u);
  EXPECT_EQ(in_bucket(sizes, 8) - in_bucket(sizes_before, 8), 1u);
  for (unsigned l = 0; l < LANES; ++l) {
    ASSERT_EQ(b.cmem(l, 500), l + 1);
    ASSERT_EQ(b.cmem(l, 517), 0x77);
    ASSERT_EQ(b.memory.data()[0x5200 + l], l + 1);
  }
}

TEST(Dma, ARegisterDescriptorThenItsChain) {
  Bench& b = *g_bench;
  b.memory.data()[0x5300] = 0x11;
  b.memory.data()[0x5301] = 0x22;
  dma::Descriptor regs_desc = make(dma::Kind::broadcast, 1, 0x5300, 700, 1);
  regs_desc.next = 0x6080;
  b.put(0x6080, make(dma::Kind::broadcast, 1, 0x5301, 701, 1));
  test::run_thread([&] {
    b.load(0, regs_desc);
    b.run(0);
    clear_irq(b);
  });
  EXPECT_EQ(b.cmem(40, 700), 0x11);
  EXPECT_EQ(b.cmem(40, 701), 0x22);
}

TEST(Dma, BroadcastWithoutAMaskWritesEveryCuInOnePass) {
  Bench& b = *g_bench;
  for (unsigned j = 0; j < 21; ++j) b.memory.data()[0x7000 + j] = static_cast<uint8_t>(0xc0 + j);
  const uint64_t cycles = b.count("cmem.cycles"), passes = b.count("cmem.passes");
  test::run_thread([&] {
    b.load(0, make(dma::Kind::broadcast, 1, 0x7000, 1000, 21));
    b.run(0);
    clear_irq(b);
  });
  for (unsigned l = 0; l < LANES; ++l)
    for (unsigned j = 0; j < 21; ++j) ASSERT_EQ(b.cmem(l, 1000 + j), 0xc0 + j);
  // 21 bytes once on the 4-byte data lines, whatever the CUs: 6 cycles, one pass.
  EXPECT_EQ(b.count("cmem.cycles") - cycles, 6u);
  EXPECT_EQ(b.count("cmem.passes") - passes, 1u);
}

TEST(Dma, BroadcastWithAMaskWritesOnlyTheMaskedCus) {
  Bench& b = *g_bench;
  for (unsigned j = 0; j < 4; ++j) b.memory.data()[0x7100 + j] = static_cast<uint8_t>(0x90 + j);
  // CUs 0..7 and 88..95 (the first and last bytes of the 12-byte mask).
  std::memset(b.memory.data() + 0x7200, 0, 12);
  b.memory.data()[0x7200] = 0xff;
  b.memory.data()[0x7200 + 11] = 0xff;
  dma::Descriptor d = make(dma::Kind::broadcast, 1, 0x7100, 1100, 4);
  d.mask = 0x7200;
  test::run_thread([&] {
    b.load(1, d);
    b.run(1);
    clear_irq(b);
  });
  for (unsigned l = 0; l < LANES; ++l)
    for (unsigned j = 0; j < 4; ++j) ASSERT_EQ(b.cmem(l, 1100 + j), (l < 8 || l >= 88) ? 0x90 + j : 0) << l;
}

namespace {

// Runs a failing descriptor set-up on channel 0 and checks the channel's
// error registers, the interrupt and the warning.
void expect_error(Bench& b, const std::function<void()>& setup, uint32_t start, dma::Error error, uint32_t desc,
                  uint32_t address, const std::string& warning) {
  test::ReportCapture reports;
  const uint64_t errors = b.count("ch0.errors");
  test::run_thread([&] {
    setup();
    b.run(0, start);
    EXPECT_EQ(b.reg(0, regs::CH_STATUS), regs::STATUS_ERROR);
    EXPECT_EQ(b.reg(0, regs::CH_ERROR_CODE), static_cast<uint32_t>(error));
    EXPECT_EQ(b.reg(0, regs::CH_ERROR_DESC), desc);
    EXPECT_EQ(b.reg(0, regs::CH_ERROR_ADDR), address);
    EXPECT_EQ(b.host.read32(DMA + regs::IRQ_STATUS), regs::irq_error(0));
    clear_irq(b);
  });
  EXPECT_EQ(b.count("ch0.errors") - errors, 1u);
  EXPECT_TRUE(reports.contains(warning)) << warning;
}

}  // namespace

TEST(Dma, EachErrorStopsTheChannelNamingDescriptorAndAddressAndWritesNothing) {
  Bench& b = *g_bench;
  // Sentinels in CMEM and memory that no failing descriptor may touch.
  for (unsigned l = 0; l < LANES; ++l) b.array.write_cmem(l, CMEM_BYTES - 1, 0x5a);
  std::memset(b.memory.data() + 0x8000, 0xa5, 0x400);
  const auto go = regs::START_GO;
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::mem_to_cmem, 2, MEMORY_BYTES - 100, 0, 2 * LANES)); }, go,
      dma::Error::src_outside_memory, regs::ERROR_DESC_REGISTERS, MEMORY_BYTES + 91,
      "channel 0: descriptor in registers: source outside system memory at 0x000100");
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::mem_to_cmem, 2, 0x8000, CMEM_BYTES - 1, 2 * LANES)); }, go,
      dma::Error::dst_outside_cmem, regs::ERROR_DESC_REGISTERS, CMEM_BYTES, "destination outside CMEM at 0x00001000");
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::cmem_to_mem, 1, 0, MEMORY_BYTES - 10, LANES)); }, go,
      dma::Error::dst_outside_memory, regs::ERROR_DESC_REGISTERS, MEMORY_BYTES + 85,
      "destination outside system memory");
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::cmem_to_mem, 1, CMEM_BYTES, 0x8000, LANES)); }, go,
      dma::Error::src_outside_cmem, regs::ERROR_DESC_REGISTERS, CMEM_BYTES, "source outside CMEM");
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::mem_to_mem, 1, 0x8000, 0x8100, 0)); }, go, dma::Error::zero_length,
      regs::ERROR_DESC_REGISTERS, 0, "zero length");
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::mem_to_cmem, 2, 0x8000, 0, 3)); }, go, dma::Error::misaligned_length,
      regs::ERROR_DESC_REGISTERS, 3, "not aligned");
  // A chain whose third descriptor points back to the second.
  dma::Descriptor a = make(dma::Kind::mem_to_mem, 1, 0x8000, 0x8200, 4);
  a.next = 0x9020;
  dma::Descriptor c = a;
  c.next = 0x9000;
  b.put(0x9000, a);
  b.put(0x9020, c);
  expect_error(
      b, [&] { b.reg(0, regs::CH_D_NEXT, 0x9000); }, go | regs::START_CHAIN_ONLY, dma::Error::chain_loop, 0x9000,
      0x9000, "channel 0: descriptor at 0x00009000: chain loop");
  expect_error(
      b, [&] { b.reg(0, regs::CH_D_NEXT, MEMORY_BYTES - 16); }, go | regs::START_CHAIN_ONLY,
      dma::Error::descriptor_outside_memory, MEMORY_BYTES - 16, MEMORY_BYTES + 15, "descriptor outside system memory");
  expect_error(
      b,
      [&] {
        dma::Descriptor d = make(dma::Kind::broadcast, 1, 0x8000, 0, 4);
        d.mask = MEMORY_BYTES - 4;
        b.load(0, d);
      },
      go, dma::Error::mask_outside_memory, regs::ERROR_DESC_REGISTERS, MEMORY_BYTES + 7, "CU mask outside");
  for (unsigned l = 0; l < LANES; ++l) {
    ASSERT_EQ(b.cmem(l, CMEM_BYTES - 1), 0x5a);
    ASSERT_EQ(b.cmem(l, 0), 0);
  }
  // The loop's first two descriptors ran (4 bytes to 0x8200); nothing else was written.
  for (unsigned i = 0; i < 0x400; ++i)
    if (i < 0x200 || i >= 0x204) {
      ASSERT_EQ(b.memory.data()[0x8000 + i], 0xa5) << i;
    }
}

// A faulting address past 32 bits (a range running off the top of the
// address space) keeps its 33rd bit: ERROR_ADDR holds the low 32 bits and
// ERROR_ADDR_HI the rest, as the warning shows the whole address. A fault
// below 4 GiB reads 0 in ERROR_ADDR_HI.
TEST(Dma, AFaultingAddressBeyond32BitsKeepsItsHighBitInErrorAddrHi) {
  Bench& b = *g_bench;
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::mem_to_mem, 1, 0xFFFFFFF0u, 0x8000, 0x20)); }, regs::START_GO,
      dma::Error::src_outside_memory, regs::ERROR_DESC_REGISTERS, 0x0000000Fu,
      "source outside system memory at 0x10000000f");
  test::run_thread([&] { EXPECT_EQ(b.reg(0, regs::CH_ERROR_ADDR_HI), 1u); });
  expect_error(
      b, [&] { b.load(0, make(dma::Kind::mem_to_mem, 1, MEMORY_BYTES - 4, 0x8000, 8)); }, regs::START_GO,
      dma::Error::src_outside_memory, regs::ERROR_DESC_REGISTERS, MEMORY_BYTES + 3, "source outside system memory");
  test::run_thread([&] { EXPECT_EQ(b.reg(0, regs::CH_ERROR_ADDR_HI), 0u); });
}

TEST(Dma, WritesToABusyChannelAreRefused) {
  Bench& b = *g_bench;
  test::ReportCapture reports;
  test::run_thread([&] {
    b.load(0, make(dma::Kind::mem_to_mem, 1, 0, 0xa000, 0x1000));
    b.reg(0, regs::CH_START, regs::START_GO);
    const auto r = b.host.write32(DMA + regs::channel_base(0) + regs::CH_D_SRC, 4);
    EXPECT_EQ(r.status, tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(b.reg(0, regs::CH_STATUS), regs::STATUS_BUSY | regs::STATUS_REFUSED);
    while (b.dma.channel_busy(0)) sc_core::wait(b.dma.channel_finished_event());
    clear_irq(b);
  });
  EXPECT_EQ(std::memcmp(b.memory.data(), b.memory.data() + 0xa000, 0x1000), 0);
}

TEST(Dma, ACmemPassWaitsForARunningProgram) {
  Bench& b = *g_bench;
  const uint64_t stalls = b.count("cmem_stalls");
  b.memory.data()[0x7300] = 0x33;
  sc_time program_end;
  test::run_thread([&] {
    // Program memory is zeros (nops); the AC runs off its end: an error, but busy all the same.
    b.host.write32(AC + array_regs::ENTRY, 0);
    b.host.write32(AC + array_regs::START, 1);
    program_end = b.array.busy_until();
    b.load(0, make(dma::Kind::broadcast, 1, 0x7300, 1200, 1));
    const sc_time done = b.run(0);
    EXPECT_GE(done, program_end + CYCLE);
    clear_irq(b);
    b.host.write32(AC + array_regs::IRQ_STATUS, 0xff);
  });
  EXPECT_EQ(b.count("cmem_stalls") - stalls, 1u);
  EXPECT_EQ(b.cmem(5, 1200), 0x33);
}

TEST(Dma, TheHostAndTheDmaSeeEachOthersOccupancyOfTheBus) {
  Bench& b = *g_bench;
  const uint64_t host_wait = b.bus.initiator_stats()[0].wait_cycles;
  const uint64_t dma_wait = b.bus.initiator_stats()[1].wait_cycles;
  sc_time dma_done, host_alone, host_shared;
  test::run_thread([&] {
    // The host alone: 64 single reads.
    uint32_t value = 0;
    sc_time t0 = sc_core::sc_time_stamp();
    for (unsigned i = 0; i < 64; ++i) {
      auto r = b.host.read(0x100 + 4 * i, reinterpret_cast<uint8_t*>(&value), 4);
      sc_core::wait(r.delay);
    }
    host_alone = sc_core::sc_time_stamp() - t0;
    // The same reads while the DMA copies 8 KiB.
    b.load(1, make(dma::Kind::mem_to_mem, 1, 0, 0xc000, 0x2000));
    b.reg(1, regs::CH_START, regs::START_GO);
    t0 = sc_core::sc_time_stamp();
    for (unsigned i = 0; i < 64; ++i) {
      auto r = b.host.read(0x100 + 4 * i, reinterpret_cast<uint8_t*>(&value), 4);
      sc_core::wait(r.delay);
    }
    host_shared = sc_core::sc_time_stamp() - t0;
    while (b.dma.channel_busy(1)) sc_core::wait(b.dma.channel_finished_event());
    clear_irq(b);
  });
  EXPECT_GT(host_shared, host_alone);
  EXPECT_GT(b.bus.initiator_stats()[0].wait_cycles, host_wait);
  EXPECT_GT(b.bus.initiator_stats()[1].wait_cycles, dma_wait);
  const auto stats = b.dma.stats_json(sc_core::sc_time_stamp());
  EXPECT_GT(stats["ch1"]["bus_wait_ns"].get<double>(), 0.0);
}

TEST(Dma, StatisticsSummaryRowAndNoProtocolViolations) {
  Bench& b = *g_bench;
  const sc_time now = sc_core::sc_time_stamp();
  const auto stats = b.dma.stats_json(now);
  EXPECT_EQ(stats["channels"], 2);
  EXPECT_GT(stats["ch0"]["descriptors"].get<uint64_t>(), 0u);
  EXPECT_GT(stats["ch0"]["bytes"].get<uint64_t>(), 0u);
  // The errors the tests above provoked on channel 0: 9 in
  // EachErrorStops..., 2 in AFaultingAddressBeyond32Bits...
  EXPECT_EQ(stats["ch0"]["errors"].get<uint64_t>(), 11u);
  EXPECT_GT(stats["ch0"]["busy_ns"].get<double>(), 0.0);
  EXPECT_GT(stats["busy_ns"].get<double>(), 0.0);
  const SummaryRow row = b.dma.summary_row(now);
  ASSERT_TRUE(row.busy.has_value());
  EXPECT_NE(row.notes.find("11 errors"), std::string::npos) << row.notes;
  EXPECT_EQ(b.check_host.violation_count() + b.check_dma_out.violation_count() + b.check_dma_regs.violation_count() +
                b.check_memory.violation_count(),
            0u);
}

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench("bench");
  return test::run_all_tests(argc, argv);
}
