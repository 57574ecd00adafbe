// The z-buffer unit's core (tlm/zbuf/core) and the array's zsend
// (tlm/array/core) against a scalar model: random sends from CUs with random
// masks, ports 1..4, the pairing rule on and off, many pixels at one entry in
// one cycle; the port's reservation on hand-made instruction streams; the
// refusals.
#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <vector>

#include "array/core/array_controller.h"
#include "zbuf/core/zbuf_core.h"

namespace tessera {
namespace {

using ap::ArrayController;
using ap::CycleTable;
using ap::Instruction;
using ap::Opcode;
using ap::Operand;
using ap::SentPixel;
using zbuf::ZbufCore;
using zbuf::ZbufCoreParams;

constexpr unsigned COLUMNS = 24, ROWS = 4, LANES = COLUMNS * ROWS;

Operand reg(unsigned index) {
  return {false, static_cast<uint16_t>(index), 0};
}
Operand mem(unsigned address, unsigned loop = 0) {
  return {true, static_cast<uint16_t>(address), static_cast<uint8_t>(loop)};
}
Instruction make(Opcode opcode, Operand d = {}, Operand a = {}, Operand b = {}) {
  Instruction in;
  in.opcode = opcode;
  in.d = d;
  in.a = a;
  in.b = b;
  return in;
}
Instruction zsend(Operand a, Operand b) {
  return make(Opcode::op_zsend, {}, a, b);
}

ap::ArrayGeometry geometry() {
  ap::ArrayGeometry g;
  g.columns = COLUMNS;
  g.rows = ROWS;
  g.registers = 8;
  g.cmem_bytes = 256;
  return g;
}

// An array whose zsend goes to a z-buffer core, with a program loaded.
struct Machine {
  ZbufCore unit;
  ArrayController controller{geometry(), CycleTable::defaults(), 64, 1000000};

  explicit Machine(const ZbufCoreParams& params, const std::vector<Instruction>& program = {}) : unit(params) {
    ap::EnabledOps ops = ap::j2210_ops();
    ops[static_cast<unsigned>(Opcode::op_zsend)] = true;
    controller.enable_ops(ops);
    controller.set_pixel_port(&unit);
    load(program);
  }
  void load(const std::vector<Instruction>& program) {
    std::vector<uint64_t> words;
    words.reserve(program.size());
    for (const Instruction& in : program) words.push_back(ap::encode(in));
    EXPECT_TRUE(controller.load(0, words));
  }
  ap::CuArray& array() { return controller.array(); }
  // The pixel of `lane` into registers r0..r7 (x, y, z, colour, big-endian).
  void set_pixel(unsigned lane, uint16_t x, uint16_t y, uint16_t z, uint16_t colour) {
    const uint16_t values[4] = {x, y, z, colour};
    for (unsigned i = 0; i < 4; ++i) {
      array().set_reg(lane, 2 * i, static_cast<uint8_t>(values[i] >> 8));
      array().set_reg(lane, 2 * i + 1, static_cast<uint8_t>(values[i]));
    }
  }
};

// The scalar model: the planes of a window, each pixel of a send applied on
// its own in ascending lanes, GL_LESS on 16-bit depth.
struct ScalarZbuffer {
  unsigned origin_x, origin_y, width, height;
  std::vector<uint16_t> depth, colour;
  ScalarZbuffer(unsigned ox, unsigned oy, unsigned w, unsigned h)
      : origin_x(ox), origin_y(oy), width(w), height(h), depth(w * h, 0xffff), colour(w * h, 0) {}
  void apply(unsigned x, unsigned y, uint16_t z, uint16_t c) {
    if (x < origin_x || y < origin_y || x - origin_x >= width || y - origin_y >= height) return;
    const unsigned e = (y - origin_y) * width + (x - origin_x);
    if (z < depth[e]) {
      depth[e] = z;
      colour[e] = c;
    }
  }
};

// The cycles a send of `lanes` takes, counted from the rule's own words.
uint64_t expected_cycles(const std::vector<unsigned>& lanes, unsigned ports, bool pairs) {
  if (lanes.empty()) return 0;
  if (!pairs) return (lanes.size() + ports - 1) / ports;
  if (ports == 1) return lanes.size();
  uint64_t cycles = 0;
  for (size_t i = 0; i < lanes.size(); ++i)
    if (i == 0 || lanes[i] / 2 != lanes[i - 1] / 2) ++cycles;
  return cycles;
}

TEST(ZbufCore, ScheduleTakesPortsPerCycleOrOnePairPerCycle) {
  std::vector<SentPixel> pixels;
  for (uint16_t lane : {1, 2, 3, 6, 7}) pixels.push_back({lane, 0, 0, 0, 0});
  EXPECT_EQ(ZbufCore::schedule(pixels, 2, false), (std::vector<uint64_t>{0, 0, 1, 1, 2}));
  EXPECT_EQ(ZbufCore::schedule(pixels, 1, false), (std::vector<uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(ZbufCore::schedule(pixels, 4, false), (std::vector<uint64_t>{0, 0, 0, 0, 1}));
  // Pairs (0,1) (2,3) (6,7): lane 1 alone, then 2 and 3, then 6 and 7.
  EXPECT_EQ(ZbufCore::schedule(pixels, 2, true), (std::vector<uint64_t>{0, 1, 1, 2, 2}));
  EXPECT_EQ(ZbufCore::schedule(pixels, 4, true), (std::vector<uint64_t>{0, 1, 1, 2, 2}));
  EXPECT_EQ(ZbufCore::schedule(pixels, 1, true), (std::vector<uint64_t>{0, 1, 2, 3, 4}));
  EXPECT_TRUE(ZbufCore::schedule({}, 2, false).empty());
}

TEST(ZbufCore, PixelsAtOneEntryInOneCycleAreTestedInAscendingLanes) {
  ZbufCore unit({16, 4, false});
  ASSERT_EQ(unit.set_frame(0, 0, 4, 4), "");
  unit.clear(100, 0);
  // One cycle, four ports, all at (1, 1): 50 wins, 60 loses to it, 50 ties
  // (GL_LESS: not written), 10 wins.
  EXPECT_EQ(unit.send({{0, 1, 1, 50, 0xa}, {1, 1, 1, 60, 0xb}, {2, 1, 1, 50, 0xc}, {3, 1, 1, 10, 0xd}}), 1u);
  EXPECT_EQ(unit.depth(5), 10);
  EXPECT_EQ(unit.colour(5), 0xd);
  EXPECT_EQ(unit.counts().written, 2u);
  EXPECT_EQ(unit.counts().failed, 2u);
  EXPECT_EQ(unit.counts().conflicts, 3u);
  // The lower lane first: 20 then 30 keeps 20, whichever is written last.
  unit.send({{0, 2, 2, 20, 0x1}, {1, 2, 2, 30, 0x2}});
  EXPECT_EQ(unit.colour(10), 0x1);
  // Outside the window: clipped, but its port slot is taken.
  EXPECT_EQ(unit.send({{0, 4, 0, 0, 0}, {1, 0, 4, 0, 0}, {2, 0, 0, 0, 0}, {3, 0, 0, 0, 0}, {4, 0, 0, 0, 0}}), 2u);
  EXPECT_EQ(unit.counts().clipped, 2u);
}

TEST(ZbufCore, RandomSendsFromMaskedCusMatchTheScalarModel) {
  std::mt19937 rng(20261203);
  for (unsigned ports = 1; ports <= 4; ++ports) {
    for (const bool pairs : {false, true}) {
      // A small window off the origin, so that pixels collide and some fall
      // outside it.
      const unsigned ox = 3, oy = 2, width = 7, height = 5;
      Machine machine({64, ports, pairs}, {zsend(reg(0), reg(4)), make(Opcode::op_halt)});
      ASSERT_EQ(machine.unit.set_frame(ox, oy, width, height), "");
      machine.unit.clear(0xffff, 0);
      ScalarZbuffer model(ox, oy, width, height);
      uint64_t pixels = 0, port_cycles = 0;
      for (unsigned send = 0; send < 300; ++send) {
        std::vector<unsigned> senders;
        const unsigned density = rng() % 4;  // none, few, half, all
        for (unsigned lane = 0; lane < LANES; ++lane) {
          const bool on = density == 3 || (density == 2 && rng() % 2 == 0) || (density == 1 && rng() % 10 == 0);
          machine.array().set_mask(lane, on);
          const auto x = static_cast<uint16_t>(rng() % 12), y = static_cast<uint16_t>(rng() % 9);
          const auto z = static_cast<uint16_t>(rng() % 16 == 0 ? 0xffff : rng() % 40);
          const auto c = static_cast<uint16_t>(rng());
          machine.set_pixel(lane, x, y, z, c);
          if (on) {
            senders.push_back(lane);
            model.apply(x, y, z, c);
          }
        }
        const ap::RunResult result = machine.controller.run(0);
        ASSERT_TRUE(result.ok) << result.error;
        pixels += senders.size();
        port_cycles += expected_cycles(senders, ports, pairs);
        for (unsigned e = 0; e < width * height; ++e) {
          ASSERT_EQ(machine.unit.depth(e), model.depth[e])
              << "ports " << ports << " pairs " << pairs << " send " << send << " entry " << e;
          ASSERT_EQ(machine.unit.colour(e), model.colour[e])
              << "ports " << ports << " pairs " << pairs << " send " << send << " entry " << e;
        }
        // The entries beyond the window are never touched.
        for (unsigned e = width * height; e < 64; ++e) ASSERT_EQ(machine.unit.depth(e), 0xffff);
      }
      EXPECT_EQ(machine.unit.counts().pixels, pixels);
      EXPECT_EQ(machine.controller.activity().zbuf_pixels, pixels);
      EXPECT_EQ(machine.unit.counts().port_cycles, port_cycles);
      EXPECT_EQ(machine.controller.activity().zbuf_port_cycles, port_cycles);
      // One port: one pixel a cycle, nothing to collide within a cycle.
      if (ports > 1) {
        EXPECT_GT(machine.unit.counts().conflicts, 0u);
      }
      EXPECT_GT(machine.unit.counts().clipped, 0u);
    }
  }
}

TEST(ZbufCore, OperandsComeFromCmemBigEndianAndMaskedCusDoNotSend) {
  // x:2 y:2 at CMEM 10, z:2 colour:2 at CMEM 20 + the loop variable: three
  // sends in program order, the later ones nearer.
  Machine machine({256, 2, false}, {make(Opcode::op_loop, reg(0), reg(2), reg(1)), zsend(mem(10), mem(20, 1)),
                                    make(Opcode::op_endloop), make(Opcode::op_halt)});
  ASSERT_EQ(machine.unit.set_frame(0, 0, 16, 16), "");
  ap::CuArray& cus = machine.array();
  for (unsigned lane = 0; lane < LANES; ++lane) cus.set_mask(lane, false);
  cus.set_mask(5, true);
  for (unsigned lane : {4u, 5u}) {
    const uint8_t position[4] = {0x00, 0x03, 0x00, 0x02};  // x 3, y 2
    for (unsigned i = 0; i < 4; ++i) cus.set_cmem(lane, 10 + i, position[i]);
    // Loop variable 2, 1, 0: z at 22:23, 21:22, 20:21; colour two bytes on.
    const uint8_t plane[6] = {0x01, 0x00, 0x02, 0x00, 0xbe, 0xef};
    for (unsigned i = 0; i < 6; ++i) cus.set_cmem(lane, 20 + i, plane[i]);
  }
  const ap::RunResult result = machine.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  // i = 2: z 0x0200, colour 0xbeef; i = 1: z 0x0002 colour 0x00be wins;
  // i = 0: z 0x0100 loses. Lane 4 is masked off: three pixels in all.
  EXPECT_EQ(machine.unit.depth(2 * 16 + 3), 0x0002);
  EXPECT_EQ(machine.unit.colour(2 * 16 + 3), 0x00be);
  EXPECT_EQ(machine.unit.counts().pixels, 3u);
  EXPECT_EQ(machine.unit.counts().written, 2u);
}

// Every lane masked in, registers as operands: the hand-made streams below.
struct Timing : Machine {
  explicit Timing(unsigned ports, bool pairs, const std::vector<Instruction>& program)
      : Machine({64, ports, pairs}, program) {
    EXPECT_EQ(unit.set_frame(0, 0, 8, 8), "");
  }
};

TEST(ZbufTiming, AHaltWaitsForThePortToTakeEveryPixel) {
  // 96 senders, 2 ports: the port is busy 48 cycles from the zsend's issue
  // (cycle 0); the halt, issued at 2, waits until 48, then takes its cycle.
  Timing t(2, false, {zsend(reg(0), reg(4)), make(Opcode::op_halt)});
  const ap::RunResult result = t.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 49u);
  EXPECT_EQ(t.controller.activity().zbuf_stall_cycles, 46u);
  EXPECT_EQ(t.controller.activity().word_cycles[0], 2u);
  EXPECT_EQ(t.controller.activity().word_cycles[1], 47u);
}

TEST(ZbufTiming, ASendWaitsForThePreviousSendsPixels) {
  // zsend at 0 holds the port to 48; the second, issued at 2, waits 46 and
  // holds it 48..96; the halt, issued at 50, waits 46 until 96.
  Timing t(2, false, {zsend(reg(0), reg(4)), zsend(reg(0), reg(4)), make(Opcode::op_halt)});
  const ap::RunResult result = t.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 97u);
  EXPECT_EQ(t.controller.activity().zbuf_stall_cycles, 92u);
  EXPECT_EQ(t.controller.activity().word_cycles[1], 48u);
  EXPECT_EQ(t.controller.activity().word_cycles[2], 47u);
}

TEST(ZbufTiming, WorkBetweenSendsHidesThePort) {
  // zsend (0..2), loop (1) + 20 adds (40): the second zsend is issued at 43
  // and waits 5 for the port (free at 48); its pixels hold it 48..96; the
  // halt, issued at 50, waits 46.
  Timing t(2, false,
           {zsend(reg(0), reg(4)), make(Opcode::op_loop, reg(0), reg(19), reg(1)),
            make(Opcode::op_add, reg(0), reg(0), reg(0)), make(Opcode::op_endloop), zsend(reg(0), reg(4)),
            make(Opcode::op_halt)});
  const ap::RunResult result = t.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 97u);
  EXPECT_EQ(t.controller.activity().zbuf_stall_cycles, 5u + 46u);
  // With 120 adds between them the port is free again: only the halt waits.
  Timing slow(2, false,
              {zsend(reg(0), reg(4)), make(Opcode::op_loop, reg(0), reg(59), reg(1)),
               make(Opcode::op_add, reg(0), reg(0), reg(0)), make(Opcode::op_endloop), zsend(reg(0), reg(4)),
               make(Opcode::op_halt)});
  const ap::RunResult slow_result = slow.controller.run(0);
  // 2 + 1 + 120 = 123: zsend holds 123..171, halt at 125 waits 46.
  EXPECT_EQ(slow_result.cycles, 172u);
  EXPECT_EQ(slow.controller.activity().zbuf_stall_cycles, 46u);
}

TEST(ZbufTiming, PortsPairingAndMasksSetTheHoldTime) {
  const auto halt_stall = [](unsigned ports, bool pairs, bool even_lanes_only, bool cmem) {
    Timing t(ports, pairs, {cmem ? zsend(mem(0), mem(4)) : zsend(reg(0), reg(4)), make(Opcode::op_halt)});
    if (even_lanes_only)
      for (unsigned lane = 1; lane < LANES; lane += 2) t.array().set_mask(lane, false);
    const ap::RunResult result = t.controller.run(0);
    EXPECT_TRUE(result.ok) << result.error;
    return t.controller.activity().zbuf_stall_cycles;
  };
  // The port's hold minus the zsend's own 2 cycles (3 with CMEM operands).
  EXPECT_EQ(halt_stall(1, false, false, false), 96u - 2);
  EXPECT_EQ(halt_stall(4, false, false, false), 24u - 2);
  EXPECT_EQ(halt_stall(4, true, false, false), 48u - 2);  // pairs: 2 a cycle at most
  EXPECT_EQ(halt_stall(2, false, true, false), 24u - 2);  // 48 senders
  EXPECT_EQ(halt_stall(2, true, true, false), 48u - 2);   // one sender per pair
  EXPECT_EQ(halt_stall(2, false, false, true), 48u - 3);
  EXPECT_EQ(halt_stall(96, false, false, false), 0u);  // 1 cycle, within the zsend's own
}

TEST(ZbufTiming, NoSendersHoldNothing) {
  Timing t(2, false, {zsend(reg(0), reg(4)), make(Opcode::op_halt)});
  for (unsigned lane = 0; lane < LANES; ++lane) t.array().set_mask(lane, false);
  const ap::RunResult result = t.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 3u);
  EXPECT_EQ(t.unit.counts().pixels, 0u);
  EXPECT_EQ(t.unit.counts().sends, 1u);
}

TEST(ZbufRefusals, TheCoreRefusesImpossibleSizes) {
  EXPECT_THROW(ZbufCore({0, 2, false}), std::invalid_argument);
  EXPECT_THROW(ZbufCore({65537, 2, false}), std::invalid_argument);
  EXPECT_THROW(ZbufCore({65536, 0, false}), std::invalid_argument);
  ZbufCore unit({1000, 2, false});
  const std::string error = unit.set_frame(0, 0, 40, 26);
  EXPECT_NE(error.find("zbuf.entries"), std::string::npos) << error;
  EXPECT_EQ(unit.width(), 0u);
  EXPECT_EQ(unit.set_frame(0, 0, 40, 25), "");
}

TEST(ZbufRefusals, ZsendWithoutAUnitOrUnderSkewIsABadWord) {
  ArrayController controller{geometry(), CycleTable::defaults(), 16, 1000};
  controller.load(0, {ap::encode(zsend(reg(0), reg(4))), ap::encode(make(Opcode::op_halt))});
  ap::RunResult result = controller.run(0);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("array.features.zsend"), std::string::npos) << result.error;
  ap::EnabledOps ops = ap::j2210_ops();
  ops[static_cast<unsigned>(Opcode::op_zsend)] = true;
  controller.enable_ops(ops);
  result = controller.run(0);
  EXPECT_EQ(result.kind, ap::RunError::bad_word);
  EXPECT_NE(result.error.find("zbuf.enabled"), std::string::npos) << result.error;
  ZbufCore unit({64, 2, false});
  controller.set_pixel_port(&unit);
  EXPECT_TRUE(controller.run(0).ok);
  controller.set_issue_skew(1);
  result = controller.run(0);
  EXPECT_EQ(result.kind, ap::RunError::bad_word);
  EXPECT_NE(result.error.find("array.issue_skew"), std::string::npos) << result.error;
}

}  // namespace
}  // namespace tessera
