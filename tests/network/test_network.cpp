// TLM tests of the cluster network (tlm/network/network.h) and the network
// interface (tlm/network/network_interface.h) on a bench of their own:
// three nodes of a 4-node hypercube, each with a test initiator playing its
// host, a bus, a memory and an NI, protocol checkers on every socket; node
// 3 has no NI. A message by descriptor into the receiver's slot at the
// hand-computed time, the interrupts, ring wrap-around, a full receive ring
// and its release, loopback, every error with its code and address,
// statistics, and the parameter group.
//
// Bench: 100 MHz bus (10 ns); memory with 2 wait states, so a burst of n
// words holds the bus 1 (address) + 2 + n cycles; a register access 2
// cycles. The NI believes its memory is 128 KiB but the bus maps only the
// first 64 KiB, so 0x10000..0x1FFFF answers with a bus error and 0x20000 up
// is outside memory. Network: 20 ns a hop, 100 MB/s (10 ns a byte), 100 ns
// set-up, 8 header bytes.
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "bus/ahb_bus.h"
#include "checker/protocol_checker.h"
#include "mem/memory.h"
#include "network/network.h"
#include "network/network_interface.h"
#include "network/ni_regs.h"
#include "process/scratch_folder.h"
#include "tlm_bench/bench_params.h"
#include "tlm_bench/tlm_test_support.h"

using namespace tessera;
using sc_core::sc_time;
namespace regs = ni_regs;

namespace {

const sc_time CYCLE(10, sc_core::SC_NS);
const sc_time NS(1, sc_core::SC_NS);
constexpr uint64_t NI = 0x40000000;
constexpr uint64_t MAPPED_BYTES = 0x10000, NI_MEMORY_BYTES = 0x20000;
constexpr uint32_t TX = 0x1000, RX = 0x2000, PAYLOAD = 0x3000, SLOT = 64;
constexpr unsigned NODES = 4, BUILT = 3;

NetworkParams network_params() {
  NetworkParams p = NetworkParams::defaults();
  p.topology = "hypercube";
  p.hop_latency_ns = 20;
  p.link_mb_per_s = 100;
  p.message_latency_ns = 100;
  p.header_bytes = 8;
  p.nodes = NODES;
  return p;
}

NetworkInterfaceParams ni_params(unsigned node) {
  NetworkInterfaceParams p = NetworkInterfaceParams::defaults();
  p.node = node;
  p.nodes = NODES;
  p.burst_bytes = 4 * p.burst_beats;
  p.clock_period = CYCLE;
  p.memory_base = 0;
  p.memory_bytes = NI_MEMORY_BYTES;
  return p;
}

struct Node : sc_core::sc_module {
  test::TestInitiator host;
  ProtocolChecker<32> check_host, check_ni_out, check_ni_regs, check_memory;
  AhbBus bus;
  Memory memory;
  NetworkInterface ni;
  sc_core::sc_signal<bool> irq;

  Node(sc_core::sc_module_name name, unsigned node)
      : sc_core::sc_module(name),
        host("host"),
        check_host("check_host"),
        check_ni_out("check_ni_out"),
        check_ni_regs("check_ni_regs"),
        check_memory("check_memory"),
        bus("bus", test::bench_bus_params(CYCLE)),
        memory("memory", test::bench_memory_params(MAPPED_BYTES, CYCLE, 2)),
        ni("ni", ni_params(node)) {
    host.out.bind(check_host.in);
    bus.attach(check_host.out, "host", 3);
    ni.out.bind(check_ni_out.in);
    bus.attach(check_ni_out.out, "ni", 2);
    bus.map(check_memory.in, 0, MAPPED_BYTES, "memory");
    check_memory.out.bind(memory.in);
    bus.map(check_ni_regs.in, NI, 0x1000, "ni_regs");
    check_ni_regs.out.bind(ni.in);
    ni.irq.bind(irq);
  }

  // A register write, waiting for its completion.
  void reg(uint32_t offset, uint32_t value) {
    const auto r = host.write32(NI + offset, value);
    ASSERT_EQ(r.status, tlm::TLM_OK_RESPONSE) << "offset " << offset;
    sc_core::wait(r.delay);
  }
  tlm::tlm_response_status try_reg(uint32_t offset, uint32_t value) {
    const auto r = host.write32(NI + offset, value);
    sc_core::wait(r.delay);
    return r.status;
  }
  uint32_t reg(uint32_t offset) {
    test::TestInitiator::Result r;
    const uint32_t value = host.read32(NI + offset, &r);
    sc_core::wait(r.delay);
    return value;
  }
  void put32(uint32_t address, uint32_t value) { std::memcpy(memory.data() + address, &value, 4); }
  uint32_t get32(uint32_t address) {
    uint32_t value = 0;
    std::memcpy(&value, memory.data() + address, 4);
    return value;
  }
  void descriptor(unsigned index, uint32_t destination, uint32_t payload, uint32_t length, uint32_t tag) {
    const uint32_t at = TX + index * regs::DESCRIPTOR_BYTES;
    put32(at + regs::DESC_DESTINATION, destination);
    put32(at + regs::DESC_PAYLOAD, payload);
    put32(at + regs::DESC_LENGTH, length);
    put32(at + regs::DESC_TAG, tag);
  }
  // Rings of `tx` descriptors and `rx` slots of `slot` bytes, interrupts on, enabled.
  void setup(uint32_t tx = 4, uint32_t rx = 4, uint32_t slot = SLOT) {
    reg(regs::CTRL, 0);
    reg(regs::TX_BASE, TX);
    reg(regs::TX_COUNT, tx);
    reg(regs::RX_BASE, RX);
    reg(regs::RX_COUNT, rx);
    reg(regs::RX_SLOT_BYTES, slot);
    reg(regs::IRQ_STATUS, 0xffffffff);
    reg(regs::IRQ_ENABLE, regs::IRQ_TX_DONE | regs::IRQ_RX | regs::IRQ_ERROR);
    reg(regs::CTRL, regs::CTRL_ENABLE);
  }
  void wait_irq() {
    if (!irq.read()) sc_core::wait(irq.posedge_event());
  }
  uint64_t count(const std::string& name) const { return ni.counters().value(name); }
};

struct Bench : sc_core::sc_module {
  Network network;
  std::vector<std::unique_ptr<Node>> nodes;
  explicit Bench(sc_core::sc_module_name name) : sc_core::sc_module(name), network("network", network_params()) {
    for (unsigned n = 0; n < BUILT; ++n) {
      nodes.push_back(std::make_unique<Node>(("node" + std::to_string(n)).c_str(), n));
      nodes.back()->ni.connect(network);
    }
  }
  Node& node(unsigned n) { return *nodes.at(n); }
};

Bench* g_bench = nullptr;
sc_core::sc_trace_file* g_trace = nullptr;
std::filesystem::path g_trace_path;  // without ".vcd"

void fill(Node& node, uint32_t address, unsigned bytes, uint8_t seed) {
  for (unsigned i = 0; i < bytes; ++i) node.memory.data()[address + i] = static_cast<uint8_t>(seed + i);
}

bool same_bytes(Node& a, uint32_t at_a, Node& b, uint32_t at_b, unsigned bytes) {
  return std::memcmp(a.memory.data() + at_a, b.memory.data() + at_b, bytes) == 0;
}

}  // namespace

TEST(NetworkInterface, RegistersShowTheNodeAndTheClusterAndEnableChecksTheRings) {
  Bench& b = *g_bench;
  test::run_thread([&] {
    for (unsigned n = 0; n < BUILT; ++n) {
      EXPECT_EQ(b.node(n).reg(regs::ID), n);
      EXPECT_EQ(b.node(n).reg(regs::NODES), NODES);
    }
    Node& a = b.node(2);
    a.reg(regs::IRQ_ENABLE, regs::IRQ_ERROR);
    // TX_COUNT is 0 after reset: enabling is refused with bad_ring.
    a.reg(regs::CTRL, regs::CTRL_ENABLE);
    EXPECT_EQ(a.reg(regs::CTRL), 0u);
    EXPECT_EQ(a.reg(regs::ERROR_CODE), static_cast<uint32_t>(regs::Error::bad_ring));
    EXPECT_EQ(a.reg(regs::ERROR_ADDR), 0u);
    EXPECT_TRUE(a.irq.read());
    a.reg(regs::IRQ_STATUS, regs::IRQ_ERROR);
    EXPECT_FALSE(a.irq.read());
    // Read-only registers refuse writes.
    EXPECT_EQ(a.try_reg(regs::ID, 7), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(a.try_reg(regs::TX_HEAD, 1), tlm::TLM_COMMAND_ERROR_RESPONSE);
  });
}

TEST(NetworkInterface, AMessageByDescriptorArrivesInTheReceiversSlotAtTheHandComputedTime) {
  Bench& b = *g_bench;
  Node& tx = b.node(0);
  Node& rx = b.node(1);
  sc_time submitted, tx_done, rx_done;
  test::run_thread([&] {
    tx.setup();
    rx.setup();
    fill(tx, PAYLOAD, 32, 0x40);
    tx.descriptor(0, 1, PAYLOAD, 32, 0xCAFE);
    submitted = sc_core::sc_time_stamp();
    tx.reg(regs::TX_TAIL, 1);
    tx.wait_irq();
    tx_done = sc_core::sc_time_stamp();
    rx.wait_irq();
    rx_done = sc_core::sc_time_stamp();
    EXPECT_EQ(tx.reg(regs::IRQ_STATUS), regs::IRQ_TX_DONE);
    EXPECT_EQ(rx.reg(regs::IRQ_STATUS), regs::IRQ_RX);
    tx.reg(regs::IRQ_STATUS, 0xffffffff);
    rx.reg(regs::IRQ_STATUS, 0xffffffff);
  });
  // The TX_TAIL write holds the bus 2 cycles; then the descriptor (4 words:
  // 1 + 2 + 4 = 7 cycles) and the payload (8 words: 11 cycles): handed to
  // the network 200 ns after the write.
  EXPECT_EQ(tx_done, submitted + 200 * NS);
  // One hop (0 ^ 1): 100 ns set-up + 20 ns + 40 bytes x 10 ns = 520 ns;
  // then header and payload, 12 words in one burst: 1 + 2 + 12 = 15 cycles.
  EXPECT_EQ(rx_done, tx_done + 520 * NS + 150 * NS);
  EXPECT_EQ(rx.get32(RX + regs::HDR_SOURCE), 0u);
  EXPECT_EQ(rx.get32(RX + regs::HDR_LENGTH), 32u);
  EXPECT_EQ(rx.get32(RX + regs::HDR_TAG), 0xCAFEu);
  EXPECT_EQ(rx.get32(RX + regs::HDR_SEQUENCE), 0u);
  EXPECT_TRUE(same_bytes(tx, PAYLOAD, rx, RX + regs::HEADER_BYTES, 32));
  EXPECT_EQ(tx.ni.TX_HEAD.get(), 1u);
  EXPECT_EQ(rx.ni.RX_HEAD.get(), 1u);
  EXPECT_EQ(tx.count("messages_sent"), 1u);
  EXPECT_EQ(tx.count("bytes_sent"), 32u);
  EXPECT_EQ(rx.count("messages_received"), 1u);
  EXPECT_EQ(rx.count("bytes_received"), 32u);
  // Bus traffic: 16 + 32 bytes read by the sender's NI, 48 written by the receiver's.
  EXPECT_EQ(tx.count("bus.bytes_read"), 48u);
  EXPECT_EQ(rx.count("bus.bytes_written"), 48u);
}

TEST(NetworkInterface, BothRingsWrapAroundAndSequenceNumbersCountPerPair) {
  Bench& b = *g_bench;
  Node& tx = b.node(0);
  Node& rx = b.node(1);
  test::run_thread([&] {
    tx.setup(2, 3);  // 2 descriptors, 3 slots (2 usable)
    rx.setup(2, 3);
    for (unsigned i = 0; i < 5; ++i) {
      fill(tx, PAYLOAD + 0x100 * i, 8, static_cast<uint8_t>(0x10 * i));
      tx.descriptor(i % 2, 1, PAYLOAD + 0x100 * i, 8, 100 + i);
      tx.reg(regs::TX_TAIL, (i + 1) % 2);
      while (tx.ni.TX_HEAD.get() != (i + 1) % 2) sc_core::wait(tx.ni.progress_event());
      // The receiver reads the slot and gives it back.
      while (rx.ni.RX_HEAD.get() == rx.ni.RX_TAIL.get()) sc_core::wait(rx.ni.progress_event());
      const uint32_t slot = RX + rx.ni.RX_TAIL.get() * SLOT;
      EXPECT_EQ(rx.get32(slot + regs::HDR_TAG), 100 + i);
      // Sequence numbers continue from the previous test's message (0).
      EXPECT_EQ(rx.get32(slot + regs::HDR_SEQUENCE), 1 + i);
      EXPECT_TRUE(same_bytes(tx, PAYLOAD + 0x100 * i, rx, slot + regs::HEADER_BYTES, 8));
      rx.reg(regs::RX_TAIL, (rx.ni.RX_TAIL.get() + 1) % 3);
    }
    EXPECT_EQ(tx.ni.TX_HEAD.get(), 1u);  // 5 mod 2
    EXPECT_EQ(rx.ni.RX_HEAD.get(), 2u);  // 5 mod 3
    tx.reg(regs::IRQ_STATUS, 0xffffffff);
    rx.reg(regs::IRQ_STATUS, 0xffffffff);
  });
}

TEST(NetworkInterface, AFullReceiveRingHoldsArrivalsInOrderUntilSoftwareFreesASlot) {
  Bench& b = *g_bench;
  Node& tx = b.node(2);
  Node& rx = b.node(1);
  sc_time submitted, released, landed;
  test::run_thread([&] {
    tx.setup();
    rx.setup(4, 2);  // one usable slot
    for (unsigned i = 0; i < 3; ++i) {
      fill(tx, PAYLOAD + 0x100 * i, 4, static_cast<uint8_t>(i));
      tx.descriptor(i, 1, PAYLOAD + 0x100 * i, 4, 7 + i);
    }
    submitted = sc_core::sc_time_stamp();
    tx.reg(regs::TX_TAIL, 3);
    while (tx.ni.TX_HEAD.get() != 3) sc_core::wait(tx.ni.progress_event());
    sc_core::wait(5, sc_core::SC_US);  // all three have arrived long since
    EXPECT_EQ(rx.ni.RX_HEAD.get(), 1u);
    EXPECT_EQ(rx.ni.waiting_arrivals(), 2u);
    EXPECT_EQ(rx.reg(regs::STATUS), regs::STATUS_RX_WAITING);
    EXPECT_EQ(rx.count("rx_stalls"), 1u);
    EXPECT_EQ(rx.get32(RX + regs::HDR_TAG), 7u);
    // Software takes the message from slot 0: the next lands in slot 1 once
    // the write has been made (2 cycles): header and payload, 5 words,
    // 1 + 2 + 5 = 8 cycles.
    released = sc_core::sc_time_stamp();
    rx.reg(regs::RX_TAIL, 1);
    while (rx.ni.RX_HEAD.get() != 0) sc_core::wait(rx.ni.progress_event());
    landed = sc_core::sc_time_stamp();
    EXPECT_EQ(rx.get32(RX + SLOT + regs::HDR_TAG), 8u);
    EXPECT_EQ(rx.ni.waiting_arrivals(), 1u);
    rx.reg(regs::RX_TAIL, 0);
    while (rx.ni.RX_HEAD.get() != 1) sc_core::wait(rx.ni.progress_event());
    EXPECT_EQ(rx.get32(RX + regs::HDR_TAG), 9u);
    EXPECT_EQ(rx.get32(RX + regs::HDR_SOURCE), 2u);
    EXPECT_EQ(rx.get32(RX + regs::HDR_SEQUENCE), 2u);
    EXPECT_EQ(rx.ni.waiting_arrivals(), 0u);
    EXPECT_EQ(rx.reg(regs::STATUS), 0u);
    tx.reg(regs::IRQ_STATUS, 0xffffffff);
    rx.reg(regs::IRQ_STATUS, 0xffffffff);
  });
  EXPECT_EQ(landed, released + 20 * NS + 80 * NS);
  EXPECT_EQ(rx.count("rx_stalls"), 2u);
  // The sender hands the three over 130, 240 and 350 ns after the write (20
  // ns of write, then per message a descriptor, 70 ns, and a one-word
  // payload, 40 ns). 2 -> 1 is two hops (2->3, 3->1), 12 wire bytes 120 ns:
  // the second waits for 2->3 until 350 and arrives at 350 + 40 + 120 = 510
  // ns, to a full ring until software releases a slot. The third waits
  // from `landed`, when software at once releases the next slot: no time.
  EXPECT_DOUBLE_EQ(rx.ni.stats_json(sc_core::sc_time_stamp())["rx_stall_ns"].get<double>(),
                   (released - submitted - 510 * NS).to_seconds() * 1e9);
}

TEST(NetworkInterface, AMessageToItselfIsLoopedBackWithoutTheNetwork) {
  Bench& b = *g_bench;
  Node& n = b.node(2);
  const uint64_t network_messages = b.network.model().messages();
  sc_time submitted, landed;
  test::run_thread([&] {
    n.setup();
    fill(n, PAYLOAD, 12, 0x77);
    n.descriptor(0, 2, PAYLOAD, 12, 0x5E1F);
    submitted = sc_core::sc_time_stamp();
    n.reg(regs::TX_TAIL, 1);
    while (n.ni.RX_HEAD.get() != 1) sc_core::wait(n.ni.progress_event());
    landed = sc_core::sc_time_stamp();
    n.reg(regs::IRQ_STATUS, 0xffffffff);
  });
  // Write 20 ns, descriptor 70 ns, payload (3 words) 60 ns, then at once
  // the slot: 7 words, 1 + 2 + 7 = 10 cycles.
  EXPECT_EQ(landed, submitted + (20 + 70 + 60 + 100) * NS);
  EXPECT_EQ(n.get32(RX + regs::HDR_SOURCE), 2u);
  EXPECT_EQ(n.get32(RX + regs::HDR_TAG), 0x5E1Fu);
  EXPECT_TRUE(same_bytes(n, PAYLOAD, n, RX + regs::HEADER_BYTES, 12));
  EXPECT_EQ(b.network.model().messages(), network_messages);
  EXPECT_EQ(n.count("loopback"), 1u);
}

TEST(NetworkInterface, EverySendErrorStopsTheRingWithItsCodeAndAddress) {
  Bench& b = *g_bench;
  Node& n = b.node(0);
  test::ReportCapture capture;
  struct Case {
    const char* what;
    uint32_t tx_base, destination, payload, length;
    regs::Error error;
    uint32_t address;
  };
  const Case cases[] = {
      {"descriptor outside memory", 0x20000, 1, PAYLOAD, 4, regs::Error::descriptor_fault, 0x20000},
      {"descriptor read fails", 0x18000, 1, PAYLOAD, 4, regs::Error::descriptor_fault, 0x18000},
      {"destination", TX, 9, PAYLOAD, 4, regs::Error::bad_destination, 9},
      {"payload outside memory", TX, 1, 0x1FFFC, 8, regs::Error::payload_fault, 0x1FFFC},
      {"payload read fails", TX, 1, 0x18000, 8, regs::Error::payload_fault, 0x18000},
  };
  test::run_thread([&] {
    n.setup();
    for (const Case& c : cases) {
      n.reg(regs::CTRL, 0);
      n.reg(regs::TX_BASE, c.tx_base);  // resets TX_HEAD and TX_TAIL
      n.reg(regs::CTRL, regs::CTRL_ENABLE);
      n.descriptor(0, c.destination, c.payload, c.length, 1);
      const uint64_t errors = n.count("errors");
      n.reg(regs::TX_TAIL, 1);
      while (n.count("errors") == errors) sc_core::wait(n.ni.progress_event());
      EXPECT_EQ(n.reg(regs::ERROR_CODE), static_cast<uint32_t>(c.error)) << c.what;
      EXPECT_EQ(n.reg(regs::ERROR_ADDR), c.address) << c.what;
      EXPECT_EQ(n.reg(regs::CTRL) & regs::CTRL_ENABLE, 0u) << c.what;
      EXPECT_EQ(n.reg(regs::TX_HEAD), 0u) << c.what;  // the failing descriptor stays at the head
      EXPECT_EQ(n.reg(regs::IRQ_STATUS) & regs::IRQ_ERROR, regs::IRQ_ERROR) << c.what;
      EXPECT_TRUE(n.irq.read()) << c.what;
      n.reg(regs::IRQ_STATUS, 0xffffffff);
    }
    n.reg(regs::CTRL, 0);
    n.reg(regs::TX_BASE, TX);
  });
  EXPECT_TRUE(capture.contains("destination node not in the cluster (0x00000009); interface stopped"));
  EXPECT_TRUE(capture.contains("read of 16 bytes at 0x00018000 failed"));
}

TEST(NetworkInterface, BadRingRegistersAreErrorsAndRingWritesWhileEnabledAreRefused) {
  Bench& b = *g_bench;
  Node& n = b.node(2);
  test::ReportCapture capture;
  test::run_thread([&] {
    n.setup(4, 4);
    const uint64_t refused = n.count("refused_register_writes");
    EXPECT_EQ(n.try_reg(regs::TX_BASE, 0x1100), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(n.try_reg(regs::RX_SLOT_BYTES, 128), tlm::TLM_COMMAND_ERROR_RESPONSE);
    EXPECT_EQ(n.count("refused_register_writes"), refused + 2);
    // A tail beyond the ring.
    n.reg(regs::TX_TAIL, 4);
    EXPECT_EQ(n.reg(regs::ERROR_CODE), static_cast<uint32_t>(regs::Error::bad_ring));
    EXPECT_EQ(n.reg(regs::ERROR_ADDR), 4u);
    EXPECT_EQ(n.reg(regs::TX_TAIL), 0u);
    n.reg(regs::RX_TAIL, 9);
    EXPECT_EQ(n.reg(regs::ERROR_ADDR), 9u);
    struct Case {
      uint32_t offset, value;
    };
    for (const Case c : {Case{regs::TX_BASE, 0x1008}, Case{regs::TX_COUNT, 0}, Case{regs::RX_BASE, 0x2002},
                         Case{regs::RX_COUNT, 1}, Case{regs::RX_SLOT_BYTES, 12}, Case{regs::RX_SLOT_BYTES, 18}}) {
      n.setup(4, 4);
      n.reg(regs::CTRL, 0);
      n.reg(c.offset, c.value);
      n.reg(regs::CTRL, regs::CTRL_ENABLE);
      EXPECT_EQ(n.reg(regs::CTRL), 0u) << c.offset;
      EXPECT_EQ(n.reg(regs::ERROR_CODE), static_cast<uint32_t>(regs::Error::bad_ring)) << c.offset;
      EXPECT_EQ(n.reg(regs::ERROR_ADDR), c.value) << c.offset;
    }
    n.reg(regs::IRQ_STATUS, 0xffffffff);
    n.setup();
  });
  EXPECT_TRUE(capture.contains("refused: ring registers written while CTRL.ENABLE is set"));
}

TEST(NetworkInterface, ReceiveErrorsDropATooLongMessageAndHoldOneWhoseSlotFails) {
  Bench& b = *g_bench;
  Node& tx = b.node(0);
  Node& rx = b.node(1);
  test::ReportCapture capture;
  test::run_thread([&] {
    tx.setup();
    rx.setup(4, 4, 32);  // 16 bytes of payload per slot
    fill(tx, PAYLOAD, 20, 1);
    tx.descriptor(0, 1, PAYLOAD, 20, 0xB16);
    tx.descriptor(1, 1, PAYLOAD, 16, 0x516);
    const uint64_t errors = rx.count("errors");
    const uint64_t sender_errors = tx.count("errors");
    tx.reg(regs::TX_TAIL, 2);
    while (rx.ni.RX_HEAD.get() != 1) sc_core::wait(rx.ni.progress_event());
    // The 20-byte message was dropped at the receiver; the ring goes on.
    EXPECT_EQ(rx.count("errors"), errors + 1);
    EXPECT_EQ(rx.count("dropped"), 1u);
    EXPECT_EQ(rx.reg(regs::ERROR_CODE), static_cast<uint32_t>(regs::Error::message_too_long));
    EXPECT_EQ(rx.reg(regs::ERROR_ADDR), 20u);
    EXPECT_EQ(rx.reg(regs::CTRL), regs::CTRL_ENABLE);
    EXPECT_EQ(rx.get32(RX + regs::HDR_TAG), 0x516u);
    EXPECT_EQ(rx.reg(regs::IRQ_STATUS), regs::IRQ_RX | regs::IRQ_ERROR);
    EXPECT_EQ(tx.count("errors"), sender_errors);
    // A slot where the bus answers with an error: the ring stops and the
    // message waits.
    rx.reg(regs::CTRL, 0);
    rx.reg(regs::RX_BASE, 0x18000);
    rx.reg(regs::CTRL, regs::CTRL_ENABLE);
    tx.reg(regs::CTRL, 0);
    tx.reg(regs::TX_BASE, TX);
    tx.reg(regs::CTRL, regs::CTRL_ENABLE);
    tx.descriptor(0, 1, PAYLOAD, 8, 0x600D);
    tx.reg(regs::TX_TAIL, 1);
    while (rx.count("errors") == errors + 1) sc_core::wait(rx.ni.progress_event());
    EXPECT_EQ(rx.reg(regs::ERROR_CODE), static_cast<uint32_t>(regs::Error::slot_fault));
    EXPECT_EQ(rx.reg(regs::ERROR_ADDR), 0x18000u);
    EXPECT_EQ(rx.reg(regs::CTRL), 0u);
    EXPECT_EQ(rx.reg(regs::STATUS), regs::STATUS_RX_WAITING);
    // Software fixes the ring; the message lands.
    rx.reg(regs::RX_BASE, RX);
    rx.reg(regs::CTRL, regs::CTRL_ENABLE);
    while (rx.ni.RX_HEAD.get() != 1) sc_core::wait(rx.ni.progress_event());
    EXPECT_EQ(rx.get32(RX + regs::HDR_TAG), 0x600Du);
    // Out of memory altogether.
    rx.reg(regs::CTRL, 0);
    rx.reg(regs::RX_BASE, 0x1FFF0);  // the slot's 24 bytes run past 0x20000
    rx.reg(regs::CTRL, regs::CTRL_ENABLE);
    tx.descriptor(1, 1, PAYLOAD, 8, 0x600E);
    tx.reg(regs::TX_TAIL, 2);
    while (rx.count("errors") == errors + 2) sc_core::wait(rx.ni.progress_event());
    EXPECT_EQ(rx.reg(regs::ERROR_CODE), static_cast<uint32_t>(regs::Error::slot_fault));
    EXPECT_EQ(rx.reg(regs::ERROR_ADDR), 0x1FFF0u);
    rx.reg(regs::RX_BASE, RX);
    rx.reg(regs::CTRL, regs::CTRL_ENABLE);
    while (rx.ni.waiting_arrivals() != 0) sc_core::wait(rx.ni.progress_event());
    tx.reg(regs::IRQ_STATUS, 0xffffffff);
    rx.reg(regs::IRQ_STATUS, 0xffffffff);
  });
  EXPECT_TRUE(capture.contains("arriving payload longer than a receive slot holds; dropped (0x00000014)"));
}

TEST(NetworkInterface, InterruptsFollowTheEnableMask) {
  Bench& b = *g_bench;
  Node& tx = b.node(0);
  Node& rx = b.node(1);
  test::run_thread([&] {
    tx.setup();
    rx.setup();
    tx.reg(regs::IRQ_ENABLE, regs::IRQ_ERROR);  // TX_DONE not on the line
    tx.descriptor(0, 1, PAYLOAD, 4, 1);
    tx.reg(regs::TX_TAIL, 1);
    rx.wait_irq();
    EXPECT_EQ(tx.reg(regs::IRQ_STATUS), regs::IRQ_TX_DONE);
    EXPECT_FALSE(tx.irq.read());
    tx.reg(regs::IRQ_ENABLE, regs::IRQ_TX_DONE);
    EXPECT_TRUE(tx.irq.read());
    tx.reg(regs::IRQ_STATUS, regs::IRQ_TX_DONE);
    EXPECT_FALSE(tx.irq.read());
    rx.reg(regs::IRQ_STATUS, 0xffffffff);
  });
}

TEST(NetworkInterface, ThreeNodesExchangingManyMessagesThroughSmallRingsLoseNoneAndKeepEachPairInOrder) {
  Bench& b = *g_bench;
  constexpr unsigned MESSAGES = 30;  // per node: 15 to each other node
  constexpr uint32_t TX_COUNT = 3, RX_COUNT = 3;
  unsigned finished = 0;
  bool all_in_order = true;
  std::vector<uint64_t> errors, received_before;
  for (unsigned n = 0; n < BUILT; ++n) {
    errors.push_back(b.node(n).count("errors"));
    received_before.push_back(b.node(n).count("messages_received"));
  }
  test::run_thread([&] {
    for (unsigned n = 0; n < BUILT; ++n) b.node(n).setup(TX_COUNT, RX_COUNT);
    // Each node's software: submits while its send ring has room, takes
    // what arrived, and sleeps on its NI otherwise.
    for (unsigned n = 0; n < BUILT; ++n)
      sc_core::sc_spawn([&, n] {
        Node& node = b.node(n);
        unsigned sent = 0, received = 0;
        std::vector<uint32_t> next_sequence(BUILT, ~0u);
        while (sent < MESSAGES || received < MESSAGES) {
          bool progress = false;
          const uint32_t tail = node.ni.TX_TAIL.get();
          if (sent < MESSAGES && (tail + 1) % TX_COUNT != node.ni.TX_HEAD.get()) {
            const uint32_t payload = PAYLOAD + 0x100 * tail;
            node.put32(payload, n);
            node.put32(payload + 4, sent);
            node.descriptor(tail, (n + 1 + sent % 2) % BUILT, payload, 8, 0x1000 * n + sent);
            node.reg(regs::TX_TAIL, (tail + 1) % TX_COUNT);
            ++sent;
            progress = true;
          }
          const uint32_t head = node.ni.RX_HEAD.get(), rx_tail = node.ni.RX_TAIL.get();
          if (head != rx_tail) {
            const uint32_t slot = RX + rx_tail * SLOT;
            const uint32_t source = node.get32(slot + regs::HDR_SOURCE);
            const uint32_t sequence = node.get32(slot + regs::HDR_SEQUENCE);
            const uint32_t index = node.get32(slot + regs::HEADER_BYTES + 4);
            // Sequence numbers of a pair go up by one, from whatever the
            // earlier tests left; the payload is the sender's.
            if (source >= BUILT || node.get32(slot + regs::HEADER_BYTES) != source ||
                node.get32(slot + regs::HDR_TAG) != 0x1000 * source + index ||
                (next_sequence[source] != ~0u && sequence != next_sequence[source]))
              all_in_order = false;
            if (source < BUILT) next_sequence[source] = sequence + 1;
            node.reg(regs::RX_TAIL, (rx_tail + 1) % RX_COUNT);
            ++received;
            progress = true;
          }
          if (!progress) sc_core::wait(node.ni.progress_event());
        }
        node.reg(regs::IRQ_STATUS, 0xffffffff);
        ++finished;
      });
  });
  EXPECT_EQ(finished, BUILT);
  EXPECT_TRUE(all_in_order);
  for (unsigned n = 0; n < BUILT; ++n) {
    EXPECT_EQ(b.node(n).ni.waiting_arrivals(), 0u) << n;
    EXPECT_EQ(b.node(n).count("errors"), errors[n]) << n;
    EXPECT_EQ(b.node(n).count("messages_received"), received_before[n] + MESSAGES) << n;
  }
}

TEST(Network, AMessageToANodeWithoutAnInterfaceIsDroppedWithAWarning) {
  Bench& b = *g_bench;
  Node& tx = b.node(1);
  test::ReportCapture capture;
  test::run_thread([&] {
    tx.setup();
    tx.descriptor(0, 3, PAYLOAD, 4, 1);
    tx.reg(regs::TX_TAIL, 1);
    sc_core::wait(5, sc_core::SC_US);
    tx.reg(regs::IRQ_STATUS, 0xffffffff);
  });
  EXPECT_EQ(b.network.counters().value("undeliverable"), 1u);
  EXPECT_TRUE(capture.contains("message from node 1 to node 3, which has no network interface, dropped"));
}

TEST(Network, TwoSendersSharingALinkContendOnTheWay) {
  // Node 0 -> 3 goes 0->1, 1->3; node 1 -> 3 needs 1->3: the second waits.
  Bench& b = *g_bench;
  const uint64_t queue_before = b.network.model().total_queue_ps();
  test::ReportCapture capture;  // node 3 has no NI
  test::run_thread([&] {
    Node& a = b.node(0);
    Node& c = b.node(1);
    a.setup();
    c.setup();
    a.descriptor(0, 3, PAYLOAD, 92, 1);
    c.descriptor(0, 3, PAYLOAD, 92, 2);
    // Node 1 submits one cycle after node 0 (its host 10 ns ahead).
    const uint32_t one = 1;
    const auto ra = a.host.write32(NI + regs::TX_TAIL, one);
    const auto rc = c.host.transport(tlm::TLM_WRITE_COMMAND, NI + regs::TX_TAIL,
                                     reinterpret_cast<uint8_t*>(const_cast<uint32_t*>(&one)), 4, CYCLE);
    sc_core::wait(std::max(ra.delay, rc.delay));
    sc_core::wait(10, sc_core::SC_US);
    a.reg(regs::IRQ_STATUS, 0xffffffff);
    c.reg(regs::IRQ_STATUS, 0xffffffff);
  });
  // The same bus timing on each node: node 1's message is ready 10 ns after
  // node 0's, which holds 1->3 from one hop (20 ns) after its start for its
  // 100 wire bytes (1000 ns); the 10 ns gap before is too short, so node
  // 1's waits 1020 - 10 = 1010 ns.
  EXPECT_EQ(b.network.model().total_queue_ps() - queue_before, 1010000u);
}

static void parameters_have_their_keys();

// In a process of the kernel, as the tests above: an exception thrown on
// sc_main's own stack after the kernel has switched to its processes and
// back confuses the address sanitizer's view of the stack.
TEST(Network, ParametersHaveTheirKeysAndBadOnesNameThem) {
  test::run_thread([] { parameters_have_their_keys(); });
}

static void parameters_have_their_keys() {
  const NetworkParams d = NetworkParams::defaults();
  EXPECT_EQ(d.topology, "hypercube");
  EXPECT_EQ(d.hop_latency_ns, 20.0);
  EXPECT_EQ(d.link_mb_per_s, 200.0);
  EXPECT_EQ(d.message_latency_ns, 100.0);
  EXPECT_EQ(d.header_bytes, 8u);
  EXPECT_EQ(NetworkInterfaceParams::defaults().burst_beats, 16u);
  for (const ParamSpec& spec : NetworkParams::parameters().specs) EXPECT_EQ(spec.key.rfind("network.", 0), 0u);
  const ParamGroup cluster{"cluster", {param::integer("cluster.nodes", 6, 1, 128, "", "nodes")}, {}};
  Config config({NetworkParams::parameters(), cluster});
  try {
    config.validate();
    ADD_FAILURE() << "a hypercube of 6 nodes";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("cluster.nodes"), std::string::npos) << e.what();
  }
  config.apply_override("network.topology=mesh");
  EXPECT_NO_THROW(config.validate());
  EXPECT_THROW(config.apply_override("network.topology=torus"), ConfigError);
  EXPECT_THROW(config.apply_override("network.link_mb_per_s=0"), ConfigError);
  EXPECT_THROW(config.apply_override("network.hop_latency_ns=-1"), ConfigError);
  NetworkParams p = NetworkParams::from_config(config);
  p.nodes = 200;
  EXPECT_THROW(network::NetworkModel(p.core_config()), ConfigError);
  p.nodes = 6;
  p.topology = "torus";
  EXPECT_THROW(p.core_config(), ConfigError);
}

TEST(Network, StatisticsSummaryRowsAndNoProtocolViolations) {
  Bench& b = *g_bench;
  const sc_time now = sc_core::sc_time_stamp();
  const auto stats = b.network.stats_json(now);
  EXPECT_EQ(stats["topology"], "hypercube");
  EXPECT_EQ(stats["nodes"], NODES);
  EXPECT_EQ(stats["links"], 8u);
  EXPECT_EQ(stats["messages"].get<uint64_t>(), b.network.model().messages());
  EXPECT_GT(stats["link_bytes"].get<uint64_t>(), 0u);
  EXPECT_GT(stats["energy_estimate"]["dynamic_nj"].get<double>(), 0.0);
  EXPECT_EQ(stats["per_node"].size(), NODES);
  EXPECT_EQ(stats["per_node"][3]["messages_received"].get<uint64_t>(), 3u);
  const SummaryRow row = b.network.summary_row(now);
  EXPECT_NE(row.notes.find(" messages, "), std::string::npos) << row.notes;
  uint64_t sent = 0, received = 0, loopback = 0;
  size_t violations = 0;
  for (auto& node : b.nodes) {
    sent += node->count("messages_sent");
    received += node->count("messages_received");
    loopback += node->count("loopback");
    const auto s = node->ni.stats_json(now);
    EXPECT_GT(s["tx_busy_ns"].get<double>(), 0.0);
    EXPECT_TRUE(node->ni.summary_row(now).busy.has_value());
    violations += node->check_host.violation_count() + node->check_ni_out.violation_count() +
                  node->check_ni_regs.violation_count() + node->check_memory.violation_count();
  }
  // Every message sent went through the network or the loopback.
  EXPECT_EQ(sent, b.network.model().messages() + loopback);
  // Received: all but those to node 3 (3) and the one dropped.
  EXPECT_EQ(received, sent - 3 - 1);
  EXPECT_EQ(violations, 0u);
}

// The last test: it closes the trace file every test has written to.
TEST(Network, TheTraceShowsMessagesInFlightAndEachInterfacesInterrupt) {
  sc_core::sc_close_vcd_trace_file(g_trace);
  g_trace = nullptr;
  std::ifstream file(g_trace_path.string() + ".vcd");
  std::stringstream text;
  text << file.rdbuf();
  std::filesystem::remove(g_trace_path.string() + ".vcd");
  const std::string vcd = text.str();
  EXPECT_NE(vcd.find("in_flight"), std::string::npos);
  EXPECT_NE(vcd.find("\nb1 "), std::string::npos);  // a message in flight
  // One irq per NI, in its node's scope.
  size_t irqs = 0;
  for (size_t at = vcd.find(" irq "); at != std::string::npos; at = vcd.find(" irq ", at + 1)) ++irqs;
  EXPECT_EQ(irqs, BUILT);
  for (unsigned n = 0; n < BUILT; ++n)
    EXPECT_NE(vcd.find("$scope module node" + std::to_string(n) + " $end"), std::string::npos) << n;
}

int sc_main(int argc, char* argv[]) {
  g_bench = new Bench("bench");
  const test::ScratchFolder folder("test_network");
  g_trace_path = folder.path() / "trace";
  g_trace = sc_core::sc_create_vcd_trace_file(g_trace_path.string().c_str());
  g_bench->network.trace_signals(g_trace);
  for (auto& node : g_bench->nodes) node->ni.trace_signals(g_trace);
  const int status = test::run_all_tests(argc, argv);
  if (g_trace) {  // a filtered run that left the trace test out
    sc_core::sc_close_vcd_trace_file(g_trace);
    std::filesystem::remove(g_trace_path.string() + ".vcd");
  }
  return status;
}
