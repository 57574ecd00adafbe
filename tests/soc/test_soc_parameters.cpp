// The SoC's parameter table as its blocks declare it (Soc::parameter_groups):
// every key has one owner, a description and a legal default, the documented
// defaults of the SoC hold, each block reads back exactly its declared
// defaults, and the combination checks name the keys involved.
#include <gtest/gtest.h>

#include <functional>
#include <set>
#include <string>

#include "config/config.h"
#include "soc/soc.h"
#include "tlm_bench/tlm_test_support.h"

namespace {

using tessera::Config;
using tessera::ConfigError;

Config soc_config() {
  return Config(tessera::Soc::parameter_groups());
}

std::string config_error(const std::function<void()>& action) {
  try {
    action();
  } catch (const ConfigError& e) {
    return e.what();
  }
  ADD_FAILURE() << "expected ConfigError";
  return {};
}

#define EXPECT_MENTIONS(message, text) \
  EXPECT_NE((message).find(text), std::string::npos) << "message: " << (message) << "\nlacks: " << (text)

TEST(SocParameters, EveryKeyHasOneOwnerADescriptionAndItsBlocksPrefix) {
  std::set<std::string> keys;
  for (const tessera::ParamGroup& group : tessera::Soc::parameter_groups()) {
    for (const tessera::ParamSpec& spec : group.specs) {
      SCOPED_TRACE(spec.key);
      EXPECT_TRUE(keys.insert(spec.key).second);
      EXPECT_FALSE(spec.description.empty());
      // A block's keys are under its own name; the SoC's own are the run's (sim.*).
      const std::string prefix = group.owner == "soc" ? "sim." : group.owner + ".";
      EXPECT_EQ(spec.key.rfind(prefix, 0), 0u) << "owner " << group.owner;
    }
  }
  EXPECT_NO_THROW(soc_config().validate());
}

TEST(SocParameters, DocumentedDefaultsOfTheSoc) {
  // docs/spec/soc.md: ARM922T at 192 MHz, a 32-bit bus at 96 MHz, a 320x240
  // RGB565 display, the rasterizer's 32x16 tiles and reciprocal Method 3.
  const Config config = soc_config();
  EXPECT_DOUBLE_EQ(config.get_real("host.clock_mhz"), 192.0);
  EXPECT_DOUBLE_EQ(config.get_real("bus.clock_mhz"), 96.0);
  EXPECT_EQ(config.get_uint("bus.width_bits"), 32u);
  EXPECT_EQ(config.get_uint("display.width"), 320u);
  EXPECT_EQ(config.get_uint("display.height"), 240u);
  EXPECT_EQ(config.get_string("display.format"), "rgb565");
  EXPECT_FALSE(config.get_bool("display.dma"));
  EXPECT_EQ(config.get_uint("raster.tile_width"), 32u);
  EXPECT_EQ(config.get_uint("raster.tile_height"), 16u);
  EXPECT_EQ(config.get_uint("raster.recip_method"), 3u);
  // docs/calibration.md: the board copies a 192x144 16-bit frame to the
  // display port in 36 ms.
  EXPECT_EQ(config.get_uint("display.port_cycles"), 248u);
}

TEST(SocParameters, EachBlockReadsItsDeclaredDefaults) {
  const Config config = soc_config();
  EXPECT_EQ(tessera::MemoryParams::defaults().first_access_cycles, config.get_uint("mem.first_access_cycles"));
  EXPECT_EQ(tessera::MemoryParams::defaults().size_bytes, config.get_uint("mem.size_mib") << 20);
  EXPECT_EQ(tessera::BusParams::defaults().width_bytes * 8, config.get_uint("bus.width_bits"));
  EXPECT_EQ(tessera::HostParams::defaults().write_buffer_words, config.get_uint("host.write_buffer.entries"));
  EXPECT_EQ(tessera::HostParams::defaults().write_buffer_addresses, config.get_uint("host.write_buffer.addresses"));
  EXPECT_TRUE(tessera::HostParams::defaults().dcache_round_robin);
  EXPECT_FALSE(tessera::HostParams::defaults().write_through);
  EXPECT_EQ(tessera::DisplayParams::defaults().port_cycles, config.get_uint("display.port_cycles"));
  EXPECT_EQ(tessera::RasterizerParams::defaults().costs.setup, config.get_uint("raster.cycles.setup"));
  EXPECT_EQ(tessera::RasterizerParams::defaults().burst_beats, config.get_uint("raster.burst_beats"));
  EXPECT_EQ(tessera::RasterizerParams::defaults().beat_bytes, 4u);
  EXPECT_EQ(tessera::RasterizerParams::defaults().beat_bytes, config.get_uint("raster.beat_bytes"));
}

TEST(SocParameters, FrameBuffersLargerThanMemoryNameTheKeys) {
  Config config = soc_config();
  for (const char* assignment :
       {"display.width=512", "display.height=512", "display.format=rgba8888", "mem.size_mib=1"})
    config.apply_override(assignment);  // each value is legal on its own
  const std::string message = config_error([&] { config.validate(); });
  EXPECT_MENTIONS(message, "impossible combination");
  EXPECT_MENTIONS(message, "display.width");
  EXPECT_MENTIONS(message, "display.height");
  EXPECT_MENTIONS(message, "display.format");
  EXPECT_MENTIONS(message, "mem.size_mib");
  // Enough memory makes the same display possible.
  config.apply_override("mem.size_mib=128");
  EXPECT_NO_THROW(config.validate());
}

TEST(SocParameters, OtherImpossibleCombinationsNameTheKeys) {
  struct Case {
    std::vector<const char*> assignments;
    const char* key;
  };
  const Case cases[] = {
      {{"bus.width_bits=48"}, "bus.width_bits"},
      {{"host.dcache.line_bytes=24"}, "host.dcache.line_bytes"},
      {{"host.dcache.size_bytes=1000"}, "host.dcache.size_bytes"},
      // 200-byte lines cannot be fetched in 64-byte bursts.
      {{"display.dma=true", "display.width=100"}, "display_dma.burst_beats"},
      {{"raster.beat_bytes=12"}, "raster.beat_bytes"},
      // A 64-bit rasterizer interface on the default 32-bit bus.
      {{"raster.beat_bytes=8"}, "bus.width_bits"},
  };
  for (const auto& c : cases) {
    Config config = soc_config();
    for (const char* assignment : c.assignments) config.apply_override(assignment);
    SCOPED_TRACE(c.assignments.back());
    EXPECT_MENTIONS(config_error([&] { config.validate(); }), c.key);
  }
  // The same 64-bit interface on a 64-bit bus is fine.
  Config wide = soc_config();
  wide.apply_override("raster.beat_bytes=8");
  wide.apply_override("bus.width_bits=64");
  EXPECT_NO_THROW(wide.validate());
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  return tessera::test::run_all_tests(argc, argv);
}
