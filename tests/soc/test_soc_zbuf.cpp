// The z-buffer unit in the assembled SoC (zbuf.enabled, with the
// system/array DMA): the host clears the unit's window, runs an array
// program whose zsend fills it, and has the DMA copy the colour window into
// system memory at frame end, the path tlm/zbuf/README.md gives; the unit is
// one of the SoC's blocks only when enabled.
#include <set>
#include <string>
#include <vector>

#include "array/array_regs.h"
#include "dma/core/dma_engine.h"
#include "dma/dma_regs.h"
#include "soc/memory_map.h"
#include "soc/soc.h"
#include "tlm_bench/host_program_runner.h"
#include "tlm_bench/tlm_test_support.h"
#include "zbuf/zbuf_regs.h"

using namespace tessera;

namespace {

constexpr unsigned WIDTH = 16, HEIGHT = 8, LANES = 96;
constexpr uint16_t CLEAR_COLOUR = 0x0f0f;
constexpr uint32_t DESTINATION = memory_map::sysmem.base + 0x00100000u;

Config zbuf_config() {
  Config config(Soc::parameter_groups());
  for (const char* setting : {"zbuf.enabled=true", "array.features.zsend=true", "dma.enabled=true"})
    config.apply_override(setting);
  return config;
}

struct Bench {
  Config config = zbuf_config();
  Soc soc{"soc", config};
  test::HostProgramRunner runner;
  Bench() { soc.set_program(runner.program()); }
};

Bench* g_bench = nullptr;

uint64_t word(ap::Opcode opcode, ap::Operand a = {}, ap::Operand b = {}) {
  ap::Instruction in;
  in.opcode = opcode;
  in.a = a;
  in.b = b;
  return ap::encode(in);
}

}  // namespace

TEST(SocZbuf, TheUnitIsABlockOfTheSocWhenEnabled) {
  std::set<std::string> names;
  for (const Block* block : g_bench->soc.blocks()) names.insert(block->basename());
  EXPECT_EQ(names.count("zbuf"), 1u);
  EXPECT_TRUE(g_bench->soc.recorder().stats_json().contains("zbuf"));
}

TEST(SocZbuf, SendsReachTheBackBufferThroughTheDma) {
  Soc& soc = g_bench->soc;
  // CU l sends (l % 16, l / 16) with colour 0x8000 + l: 96 of the window's
  // 128 entries; the rest keep the clear colour.
  ap::CuArray& cus = soc.array.core().array();
  for (unsigned lane = 0; lane < LANES; ++lane) {
    const uint16_t values[4] = {static_cast<uint16_t>(lane % WIDTH), static_cast<uint16_t>(lane / WIDTH), 10,
                                static_cast<uint16_t>(0x8000 + lane)};
    for (unsigned i = 0; i < 4; ++i) {
      cus.set_reg(lane, 2 * i, static_cast<uint8_t>(values[i] >> 8));
      cus.set_reg(lane, 2 * i + 1, static_cast<uint8_t>(values[i]));
    }
  }
  std::vector<uint16_t> copied(WIDTH * HEIGHT, 0);
  uint32_t dma_status = 0;
  g_bench->runner.run([&](HostApi& api) {
    const uint32_t unit = memory_map::zbuf_regs.base, ac = memory_map::array_regs.base;
    api.write32(unit + zbuf_regs::FRAME_SIZE, WIDTH | HEIGHT << 16);
    api.write32(unit + zbuf_regs::CLEAR_COLOUR, CLEAR_COLOUR);
    api.write32(unit + zbuf_regs::CONTROL, zbuf_regs::CONTROL_CLEAR);
    const uint64_t program[2] = {word(ap::Opcode::op_zsend, {false, 0, 0}, {false, 4, 0}), word(ap::Opcode::op_halt)};
    for (unsigned w = 0; w < 2; ++w) {
      api.write32(memory_map::array_program.base + 8 * w, static_cast<uint32_t>(program[w]));
      api.write32(memory_map::array_program.base + 8 * w + 4, static_cast<uint32_t>(program[w] >> 32));
    }
    api.write32(ac + array_regs::ENTRY, 0);
    api.write32(ac + array_regs::START, 1);
    while ((api.read32(ac + array_regs::STATUS) & array_regs::STATUS_BUSY) != 0) api.compute_cycles(100);
    // Frame end: one copy of the window into memory.
    const uint32_t channel = memory_map::dma_regs.base + dma_regs::channel_base(0);
    api.write32(channel + dma_regs::CH_D_CTRL, dma::Descriptor::make_ctrl(dma::Kind::mem_to_mem));
    api.write32(channel + dma_regs::CH_D_SRC, memory_map::zbuf_colour.base);
    api.write32(channel + dma_regs::CH_D_DST, DESTINATION);
    api.write32(channel + dma_regs::CH_D_LENGTH, WIDTH * HEIGHT * zbuf_regs::COLOUR_ENTRY_BYTES);
    api.write32(channel + dma_regs::CH_START, dma_regs::START_GO);
    do {
      api.compute_cycles(100);
      dma_status = api.read32(channel + dma_regs::CH_STATUS);
    } while ((dma_status & dma_regs::STATUS_BUSY) != 0);
    for (unsigned e = 0; e < WIDTH * HEIGHT; ++e) copied[e] = api.read16(DESTINATION + 2 * e);
  });
  EXPECT_EQ(dma_status & (dma_regs::STATUS_DONE | dma_regs::STATUS_ERROR), dma_regs::STATUS_DONE);
  for (unsigned e = 0; e < WIDTH * HEIGHT; ++e)
    EXPECT_EQ(copied[e], e < LANES ? 0x8000 + e : CLEAR_COLOUR) << "entry " << e;
  EXPECT_EQ(soc.zbuf->core().counts().written, LANES);
}

int sc_main(int argc, char* argv[]) {
  test::ReportCapture quiet;
  g_bench = new Bench();
  return test::run_all_tests(argc, argv);
}
