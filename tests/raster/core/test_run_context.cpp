// RunContext (tlm/raster/core/run_context.h) on its own: what every stage
// shares of a run. Expected behaviour from its header and README.md
// ("Errors", "Counters and cycle costs"): the run's error is the first one,
// at the address of the failing access; every access adds its bytes;
// cycles are charged to a bucket and reported to the port together.
#include <gtest/gtest.h>

#include "raster/core/run_context.h"
#include "raster_core_test_support.h"

using namespace tessera::raster;
using tessera::raster::test::StageRun;

namespace {

TEST(RunContext, AccessesCountTheirBytesAndTheFirstRefusalIsTheError) {
  StageRun b(0x100, RunConfig{});
  uint8_t data[16] = {};
  EXPECT_TRUE(b.run.read(0x10, data, 12));
  EXPECT_TRUE(b.run.write(0x20, data, 8));
  EXPECT_EQ(b.run.result().bytes_read, 12u);
  EXPECT_EQ(b.run.result().bytes_written, 8u);
  EXPECT_FALSE(b.run.failed());
  // Past the end of the 256-byte memory: refused, with the error asked for.
  EXPECT_FALSE(b.run.read(0xf8, data, 16, RasterError::bad_texture));
  EXPECT_TRUE(b.run.failed());
  EXPECT_EQ(b.run.result().error, RasterError::bad_texture);
  EXPECT_EQ(b.run.result().error_address, 0xf8u);
  EXPECT_EQ(b.run.result().bytes_read, 12u);  // a refused access moves nothing
  // A later refusal or fail() keeps the first error.
  EXPECT_FALSE(b.run.write(0x100, data, 4));
  b.run.fail(RasterError::bad_opcode, 0x40);
  EXPECT_EQ(b.run.result().error, RasterError::bad_texture);
  EXPECT_EQ(b.run.result().error_address, 0xf8u);
}

TEST(RunContext, CyclesAreChargedToABucketAndReportedTogether) {
  StageRun b(0x100, RunConfig{});
  b.run.charge(b.run.result().setup_cycles, 8);
  b.run.charge(b.run.result().fragment_cycles, 5);
  EXPECT_EQ(b.port.total_cycles, 0u);  // not reported yet
  b.run.report_cycles();
  EXPECT_EQ(b.port.total_cycles, 13u);
  b.run.report_cycles();  // nothing pending: nothing more
  EXPECT_EQ(b.port.total_cycles, 13u);
  b.run.charge(b.run.result().texel_cycles, 2);
  b.run.report_cycles();
  EXPECT_EQ(b.port.total_cycles, 15u);
  const RunResult& r = b.run.result();
  EXPECT_EQ(r.setup_cycles, 8u);
  EXPECT_EQ(r.fragment_cycles, 5u);
  EXPECT_EQ(r.texel_cycles, 2u);
  EXPECT_EQ(r.setup_cycles + r.tile_cycles + r.fragment_cycles + r.texel_cycles, b.port.total_cycles);
}

}  // namespace
