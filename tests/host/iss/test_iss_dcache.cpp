// The ARM922T's data side under a program's control, through soc_sim
// (host.model=iss by --app X.elf): iss_programs/dcache.S sets and clears
// CP15 c1's C and RR bits and issues c7's data-side operations, and the
// host's statistics must count what the launcher made of them (its
// LauncherCaches forwarding to the host's data cache and write buffer).
// The expected figures are the program's own accesses, block by block, as
// its comments give them; the hand-computed times of the same rules are
// test_host.cpp's.
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "fixtures/soc_sim_test.h"

namespace {

std::string g_program;

using IssDcache = tessera::test::SocSimTest;

TEST_F(IssDcache, ProgramsCp15OperationsReachTheHostsDataCacheAndWriteBuffer) {
  ASSERT_FALSE(g_program.empty()) << "usage: test_iss_dcache SOC_SIM dcache.elf";
  const tessera::test::SimResult result = run({"--app", g_program, "-q", "--no-frames", "--out", "out"});
  ASSERT_EQ(result.status, 0) << result.err;
  std::ifstream in(m_dir / "out" / "stats.json");
  const nlohmann::json stats = nlohmann::json::parse(in)["stats"];
  const nlohmann::json& host = stats["host"];
  const nlohmann::json& bus = stats["bus"]["initiators"]["host"];

  // Loads: 2 (first block), 5 (C off and the invalidations), 65 + 2 (the
  // round-robin block). Stores: 1, 4, and the 5 uncached stores.
  EXPECT_EQ(host["loads"].get<uint64_t>(), 2u + 5u + 67u);
  EXPECT_EQ(host["stores"].get<uint64_t>(), 1u + 4u + 5u);
  // Hits: 2 in the first block; the store before C is cleared, the read
  // after it is set again (the line kept), the two stores after misses; B2.
  EXPECT_EQ(host["dcache"]["hits"].get<uint64_t>(), 2u + 4u + 1u);
  // Misses: A's first fill, the three after clean+invalidate, invalidate
  // line and invalidate all; B0 ... B64 and B0 again. None with C clear.
  EXPECT_EQ(host["dcache"]["misses"].get<uint64_t>(), 1u + 3u + 65u + 1u);
  // Write-backs: the clean, the clean and invalidate, the clean by index;
  // the dirty half dropped by the invalidation is not written.
  EXPECT_EQ(host["dcache"]["writebacks"].get<uint64_t>(), 3u);
  // The fifth uncached store found the write buffer's 4 addresses taken.
  EXPECT_EQ(host["write_buffer_stalls"].get<uint64_t>(), 1u);
  // On the bus: the three 16-byte write-backs, the uncached store with C
  // clear and the five at the end (4 bytes each); 70 line fills and one
  // uncached read beside the instruction side's reads.
  EXPECT_EQ(bus["writes"].get<uint64_t>(), 3u + 1u + 5u);
  EXPECT_EQ(bus["reads"].get<uint64_t>(), host["fetch"]["transactions"].get<uint64_t>() + 70u + 1u);
  EXPECT_EQ(bus["bytes"].get<uint64_t>(), host["fetch"]["bytes"].get<uint64_t>() + 70u * 32u + 4u + 3u * 16u + 6u * 4u);
}

}  // namespace

int main(int argc, char** argv) {
  tessera::test::init_soc_sim_test(argc, argv);
  if (argc >= 3) g_program = std::filesystem::absolute(argv[2]).string();
  return RUN_ALL_TESTS();
}
