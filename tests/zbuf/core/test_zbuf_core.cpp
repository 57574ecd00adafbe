// The z-buffer unit's core (tlm/zbuf/core) and the array's zsend
// (tlm/array/core) against a scalar model: random sends from CUs with random
// masks, ports 1..4, the pairing rule on and off, lockstep and row-sequential
// issue, many pixels at one entry in one cycle; the port's reservation on
// hand-made instruction streams, lockstep and per row; the refusals.
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

ap::ArrayGeometry geometry(unsigned columns = COLUMNS, unsigned rows = ROWS) {
  ap::ArrayGeometry g;
  g.columns = columns;
  g.rows = rows;
  g.registers = 8;
  g.cmem_bytes = 256;
  return g;
}

// An array whose zsend goes to a z-buffer core, with a program loaded.
struct Machine {
  ZbufCore unit;
  ArrayController controller;

  explicit Machine(const ZbufCoreParams& params, const std::vector<Instruction>& program = {},
                   const ap::ArrayGeometry& shape = geometry())
      : unit(params), controller(shape, CycleTable::defaults(), 64, 1000000) {
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

// The port cycles of one send under row skew with K beyond any row's own
// cycles (24 at most): the rows never share a cycle, each row's pixels are
// taken from its arrival on, so the halt (at 2) waits for the row whose
// cycles end last, and the port's cycles are the rows' own.
struct RowsApart {
  uint64_t port_cycles = 0, halt_stall = 0;
};
RowsApart rows_apart(const std::vector<unsigned>& lanes, unsigned ports, bool pairs) {
  RowsApart r;
  for (unsigned row = 0; row < ROWS; ++row) {
    std::vector<unsigned> in_row;
    for (const unsigned lane : lanes)
      if (lane / COLUMNS == row) in_row.push_back(lane);
    const uint64_t cycles = expected_cycles(in_row, ports, pairs);
    r.port_cycles += cycles;
    // Taken in [K r, K r + cycles); the row runs the halt at 2 + K r.
    if (cycles > 2) r.halt_stall = std::max(r.halt_stall, cycles - 2);
  }
  return r;
}

void random_sends_match_the_scalar_model(ap::IssueSkew skew, unsigned skew_cycles) {
  std::mt19937 rng(20261203 + skew_cycles);
  for (unsigned ports = 1; ports <= 4; ++ports) {
    for (const bool pairs : {false, true}) {
      // A small window off the origin, so that pixels collide and some fall
      // outside it.
      const unsigned ox = 3, oy = 2, width = 7, height = 5;
      Machine machine({64, ports, pairs}, {zsend(reg(0), reg(4)), make(Opcode::op_halt)});
      machine.controller.set_issue_skew(skew, skew_cycles);
      const uint64_t skew_total = skew == ap::IssueSkew::row ? uint64_t{ROWS - 1} * skew_cycles : 0;
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
        const uint64_t port_before = machine.unit.counts().port_cycles;
        const ap::RunResult result = machine.controller.run(0);
        ASSERT_TRUE(result.ok) << result.error;
        pixels += senders.size();
        const uint64_t lockstep_cycles = expected_cycles(senders, ports, pairs);
        const RowsApart apart = rows_apart(senders, ports, pairs);
        const uint64_t taken = machine.unit.counts().port_cycles - port_before;
        if (skew == ap::IssueSkew::none) {
          port_cycles += lockstep_cycles;
          ASSERT_EQ(result.cycles, std::max<uint64_t>(lockstep_cycles, 2) + 1);
        } else if (skew_cycles >= COLUMNS) {
          port_cycles += apart.port_cycles;
          ASSERT_EQ(result.cycles, 2 + apart.halt_stall + 1 + skew_total) << "send " << send;
        } else {
          // Rows may share a cycle when the port is still taking the row
          // before as the next arrives: between the two counts.
          ASSERT_GE(taken, lockstep_cycles);
          ASSERT_LE(taken, apart.port_cycles);
          port_cycles += taken;
        }
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

TEST(ZbufCore, RandomSendsFromMaskedCusMatchTheScalarModel) {
  random_sends_match_the_scalar_model(ap::IssueSkew::none, 0);
}

// Under row skew the unit's planes are those of the same order: a send's
// pixels in ascending lanes (row by row, the order its rows arrive), sends in
// program order.
TEST(ZbufCore, UnderRowSkewRandomSendsMatchTheScalarModel) {
  random_sends_match_the_scalar_model(ap::IssueSkew::row, 1);
  random_sends_match_the_scalar_model(ap::IssueSkew::row, 4);
  random_sends_match_the_scalar_model(ap::IssueSkew::row, 30);
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

// Row-sequential issue (array.issue_skew = row, K = 4): row r runs the
// stream 4 r cycles after row 0, its pixels of a zsend issued at t reach the
// port at t + 4 r, the port takes sends in program order, each in ascending
// lanes, none before it arrives; a zsend or the halt stalls the whole stream
// until, in every row r, the row's earlier pixels are taken by the time the
// row runs it (t + 4 r).
struct RowTiming : Machine {
  explicit RowTiming(unsigned ports, bool pairs, const std::vector<Instruction>& program,
                     const ap::ArrayGeometry& shape = geometry(), unsigned skew = 4)
      : Machine({64, ports, pairs}, program, shape) {
    EXPECT_EQ(unit.set_frame(0, 0, 8, 8), "");
    controller.set_issue_skew(ap::IssueSkew::row, skew);
  }
};

TEST(ZbufTiming, UnderRowSkewEachRowsHaltWaitsForItsOwnPixels) {
  // 4 x 24, P = 2: row r's 24 pixels arrive at 4 r and are taken in
  // 12 r..12 r + 11 (the port is busy with the rows before), so row r's CUs
  // hold them to 12 (r + 1). The halt, issued at 2, runs in row r at 2 + 4 r:
  // it waits max(12 (r + 1) - 2 - 4 r) = 34 (row 3), then its cycle, then the
  // skew 3 x 4: 2 + 34 + 1 + 12 = 49, the lockstep 49 (the port's 48 cycles
  // bound both).
  RowTiming t(2, false, {zsend(reg(0), reg(4)), make(Opcode::op_halt)});
  const ap::RunResult result = t.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 49u);
  EXPECT_EQ(t.controller.activity().zbuf_stall_cycles, 34u);
  EXPECT_EQ(t.controller.activity().skew_cycles, 12u);
  EXPECT_EQ(t.controller.activity().zbuf_port_cycles, 48u);
  EXPECT_EQ(t.controller.activity().word_cycles[0], 2u);
  EXPECT_EQ(t.controller.activity().word_cycles[1], 34u + 1 + 12);
}

TEST(ZbufTiming, UnderRowSkewASendWaitsForEachRowsPreviousPixels) {
  // zsend 1 at 0: rows taken 0..11, 12..23, 24..35, 36..47. zsend 2, due
  // at 2, runs in row r at 2 + 4 r + stall, which must be >= 12 (r + 1):
  // stall 34 (row 3), issued at 36; the port is busy to 48, so its rows are
  // taken 48..59, 60..71, 72..83, 84..95. The halt, due at 38: stall
  // max(60 - 38, 72 - 42, 84 - 46, 96 - 50) = 46, at 84, + 1 + 12 = 97.
  RowTiming t(2, false, {zsend(reg(0), reg(4)), zsend(reg(0), reg(4)), make(Opcode::op_halt)});
  const ap::RunResult result = t.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 97u);
  EXPECT_EQ(t.controller.activity().zbuf_stall_cycles, 34u + 46u);
  EXPECT_EQ(t.controller.activity().word_cycles[1], 34u + 2);
  EXPECT_EQ(t.controller.activity().word_cycles[2], 46u + 1 + 12);
}

TEST(ZbufTiming, UnderRowSkewWorkBetweenSendsHidesEachRowsPort) {
  // zsend 1 at 0 (rows' pixels held to 12, 24, 36, 48), loop 1 + 20 adds:
  // zsend 2 due at 43 runs in row r at 43 + 4 r, after every row's pixels
  // are taken: no wait (lockstep waits 5, for row 3's). The port, busy to
  // 48, takes its rows 48..59, ..., 84..95; the halt due at 45 waits
  // max(60 - 45, 72 - 49, 84 - 53, 96 - 57) = 39: 45 + 39 + 1 + 12 = 97.
  RowTiming t(2, false,
              {zsend(reg(0), reg(4)), make(Opcode::op_loop, reg(0), reg(19), reg(1)),
               make(Opcode::op_add, reg(0), reg(0), reg(0)), make(Opcode::op_endloop), zsend(reg(0), reg(4)),
               make(Opcode::op_halt)});
  const ap::RunResult result = t.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 97u);
  EXPECT_EQ(t.controller.activity().zbuf_stall_cycles, 39u);
  EXPECT_EQ(t.controller.activity().word_cycles[4], 2u);
}

TEST(ZbufTiming, UnderRowSkewARowWaitsForItsEarlierPixelsEvenWhenItSendsNone) {
  // mmov z (row 0's CUs have Z), zsend: row 0's 24 pixels, issued at 1,
  // taken 1..12 (held to 13). mmov c (row 3's have C), zsend due at 4: row
  // 0 runs it at 4 and still holds its pixels: stall 9, issued at 13; row
  // 3's arrive at 13 + 12 and are taken 25..36. The halt, due at 15, runs
  // in row 3 at 27: stall 10, at 25, + 1 + 12 = 38 (lockstep: the same
  // stalls, 26 cycles).
  const Instruction mmov_z = make(Opcode::op_mmov, {}, reg(static_cast<unsigned>(ap::Cond::z)));
  const Instruction mmov_c = make(Opcode::op_mmov, {}, reg(static_cast<unsigned>(ap::Cond::c)));
  const std::vector<Instruction> program = {mmov_z, zsend(reg(0), reg(4)), mmov_c, zsend(reg(0), reg(4)),
                                            make(Opcode::op_halt)};
  const auto run = [&](Machine& m) {
    for (unsigned lane = 0; lane < LANES; ++lane)
      m.array().set_flags(lane, {lane >= 3 * COLUMNS, lane < COLUMNS, false});
    const ap::RunResult result = m.controller.run(0);
    EXPECT_TRUE(result.ok) << result.error;
    EXPECT_EQ(m.unit.counts().pixels, 48u);
    return std::pair{result.cycles, m.controller.activity().zbuf_stall_cycles};
  };
  RowTiming rows(2, false, program);
  EXPECT_EQ(run(rows), std::pair(uint64_t{38}, uint64_t{19}));
  Timing lockstep(2, false, program);
  EXPECT_EQ(run(lockstep), std::pair(uint64_t{26}, uint64_t{19}));
}

TEST(ZbufTiming, UnderRowSkewARowOfFourPairsSendsInFourCyclesAndRowsDoNotCollide) {
  // Davila et al.'s MorphoSys: 8 x 8 CUs, K = 4, two ports taking the two
  // halves of one triangle (lanes 2k, 2k + 1) per cycle. A row's 8 pixels
  // are 4 pairs, 4 cycles: row r's arrive at 4 r and are taken in 4 r ..
  // 4 r + 3, each pair the cycle it is due, so no row waits for another.
  const ap::ArrayGeometry morphosys = geometry(8, 8);
  std::vector<SentPixel> pixels;
  for (uint16_t lane = 0; lane < 64; ++lane) pixels.push_back({lane, 0, 0, 0, 0});
  const std::vector<uint64_t> cycles = ZbufCore::schedule(pixels, 2, true, {8, 4, 0});
  for (unsigned lane = 0; lane < 64; ++lane) EXPECT_EQ(cycles[lane], 4 * (lane / 8) + lane % 8 / 2) << lane;
  // With K = 2 they collide: row r arrives at 2 r but is taken from 4 r.
  const std::vector<uint64_t> close = ZbufCore::schedule(pixels, 2, true, {8, 2, 0});
  for (unsigned lane = 0; lane < 64; ++lane) EXPECT_EQ(close[lane], 4 * (lane / 8) + lane % 8 / 2) << lane;
  EXPECT_GT(close[63], 2u * 7 + 3);
  // zsend; halt: the halt, due at 2, waits in row r for 4 r + 4 - (2 + 4 r)
  // = 2 (lockstep: 32 - 2 = 30); 2 + 2 + 1 + 7 x 4 = 33.
  RowTiming once(2, true, {zsend(reg(0), reg(4)), make(Opcode::op_halt)}, morphosys);
  ap::RunResult result = once.controller.run(0);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.cycles, 33u);
  EXPECT_EQ(once.controller.activity().zbuf_stall_cycles, 2u);
  // A send every 32 cycles (zsend 2 + 15 adds 30), 20 of them: no stall at
  // all (every row's pixels are taken 4 cycles after they arrive, long
  // before the row's next zsend); 1 (loop) + 20 x 32 + 1 (halt) + 7 x 4 =
  // 670.
  const auto every = [&](unsigned adds, bool skewed) {
    std::vector<Instruction> program = {make(Opcode::op_loop, reg(0), reg(19), reg(1)), zsend(reg(0), reg(4))};
    for (unsigned i = 0; i < adds; ++i) program.push_back(make(Opcode::op_add, reg(0), reg(0), reg(0)));
    program.push_back(make(Opcode::op_endloop));
    program.push_back(make(Opcode::op_halt));
    RowTiming t(2, true, program, morphosys);
    if (!skewed) t.controller.set_issue_skew(ap::IssueSkew::none, 0);
    const ap::RunResult r = t.controller.run(0);
    EXPECT_TRUE(r.ok) << r.error;
    return std::pair{r.cycles, t.controller.activity().zbuf_stall_cycles};
  };
  EXPECT_EQ(every(15, true), std::pair(uint64_t{670}, uint64_t{0}));
  // Every 30 cycles the port (32 a send) falls behind by 2 a send: send k's
  // row 0 is taken 2 (k - 1) cycles after its issue, and from send 16 on a
  // row still holds the send before's pixels when it runs the next (28 + 4
  // > 30): sends 16..20 wait 2 each, the halt 2: 1 + 20 x 30 + 12 + 1 + 28 =
  // 642.
  EXPECT_EQ(every(14, true), std::pair(uint64_t{642}, uint64_t{12}));
  // Lockstep: every send waits for the whole previous one: sends 2..20
  // wait 2 each, the halt 2: 1 + 600 + 40 + 1 = 642 as well (the port's 32
  // cycles a send bound both), with no stall at a period of 32 either.
  EXPECT_EQ(every(14, false), std::pair(uint64_t{642}, uint64_t{40}));
  EXPECT_EQ(every(15, false), std::pair(uint64_t{1 + 20 * 32 + 1}, uint64_t{0}));
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

TEST(ZbufRefusals, ZsendWithoutAUnitOrUnderLaneSkewIsABadWord) {
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
  EXPECT_NE(result.error.find("array.issue_skew = lane"), std::string::npos) << result.error;
  // Row-sequential issue is modelled.
  controller.set_issue_skew(ap::IssueSkew::row, 4);
  EXPECT_TRUE(controller.run(0).ok);
}

}  // namespace
}  // namespace tessera
