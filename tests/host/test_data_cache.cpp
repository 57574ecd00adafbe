// Unit tests of the ARM922T data-cache tag model: set mapping, round-robin
// replacement, write-back of dirty victims, no allocation on write misses,
// invalidation, and the same behaviour for lines above the tag table.
#include <gtest/gtest.h>

#include "host/data_cache.h"

using tessera::DataCache;

namespace {

// 8 KiB, 32-byte lines, 64 ways: 4 sets; set = (address / 32) % 4.
constexpr unsigned LINE = 32;
constexpr unsigned SETS = 4;
constexpr unsigned WAYS = 64;
constexpr uint32_t WAY = LINE * SETS;  // addresses this far apart share a set

DataCache arm922t() {
  return DataCache(8192, LINE, WAYS);
}

}  // namespace

TEST(DataCache, ReadMissAllocatesAndLaterReadsOfTheLineHit) {
  DataCache cache = arm922t();
  EXPECT_FALSE(cache.read(0x1000).hit);
  EXPECT_TRUE(cache.read(0x1000).hit);
  EXPECT_TRUE(cache.read(0x101C).hit) << "same 32-byte line";
  EXPECT_FALSE(cache.read(0x1020).hit) << "next line";
  EXPECT_EQ(cache.hits(), 2u);
  EXPECT_EQ(cache.misses(), 2u);
}

TEST(DataCache, WriteMissDoesNotAllocate) {
  DataCache cache = arm922t();
  EXPECT_FALSE(cache.write(0x2000));
  EXPECT_FALSE(cache.read(0x2000).hit) << "the write miss left no line behind";
  EXPECT_TRUE(cache.write(0x2004)) << "a write hit once the line is in";
}

TEST(DataCache, SixtyFifthLineOfASetEvictsTheFirstRoundRobin) {
  DataCache cache = arm922t();
  for (uint32_t i = 0; i < WAYS; ++i) EXPECT_FALSE(cache.read(i * WAY).hit) << i;
  for (uint32_t i = 0; i < WAYS; ++i) EXPECT_TRUE(cache.read(i * WAY).hit) << i;
  // The other sets are untouched by this one's traffic.
  EXPECT_FALSE(cache.read(LINE).hit);
  // The 65th line replaces way 0 (the first allocated), then way 1.
  EXPECT_FALSE(cache.read(WAYS * WAY).hit);
  EXPECT_FALSE(cache.read(0).hit) << "way 0 was the victim";
  EXPECT_TRUE(cache.read(2 * WAY).hit) << "way 2 not yet replaced";
}

TEST(DataCache, DirtyVictimIsWrittenBackWithItsAddress) {
  DataCache cache = arm922t();
  for (uint32_t i = 0; i < WAYS; ++i) cache.read(0x40 + i * WAY);
  EXPECT_TRUE(cache.write(0x40 + 0 * WAY + 8));  // way 0 dirty
  const DataCache::Result first = cache.read(0x40 + WAYS * WAY);
  EXPECT_FALSE(first.hit);
  EXPECT_EQ(first.victim.bytes, LINE);
  EXPECT_EQ(first.victim.address, 0x40u);
  const DataCache::Result second = cache.read(0x40 + (WAYS + 1) * WAY);
  EXPECT_EQ(second.victim.bytes, 0u) << "way 1 was clean";
  EXPECT_EQ(cache.writebacks(), 1u);
}

TEST(DataCache, InvalidateAllEmptiesTheCache) {
  DataCache cache = arm922t();
  cache.read(0x3000);
  cache.invalidate_all();
  EXPECT_FALSE(cache.write(0x3000));
  EXPECT_FALSE(cache.read(0x3000).hit);
}

// Lines above the tag table (addresses from 128 MiB with 32-byte lines) are
// found by searching their set: same hits, misses and victims.
TEST(DataCache, HighAddressesBehaveLikeLowOnes) {
  for (uint32_t base : {0x00000000u, 0x08000000u, 0xF0000000u}) {
    SCOPED_TRACE(base);
    DataCache cache = arm922t();
    for (uint32_t i = 0; i < WAYS; ++i) EXPECT_FALSE(cache.read(base + i * WAY).hit);
    EXPECT_TRUE(cache.write(base + 5 * WAY));
    EXPECT_FALSE(cache.write(base + WAYS * WAY)) << "absent line";
    const DataCache::Result r = cache.read(base + WAYS * WAY);
    EXPECT_FALSE(r.hit);
    EXPECT_FALSE(cache.read(base).hit) << "way 0 replaced";
    for (uint32_t i = 2; i < WAYS; ++i) EXPECT_TRUE(cache.read(base + i * WAY).hit) << i;
    cache.invalidate_all();
    EXPECT_FALSE(cache.read(base + 5 * WAY).hit);
  }
}

TEST(DataCache, SizeZeroMissesEverythingAndAllocatesNothing) {
  DataCache cache(0, LINE, WAYS);
  EXPECT_FALSE(cache.enabled());
  EXPECT_FALSE(cache.read(0).hit);
  EXPECT_FALSE(cache.read(0).hit);
  EXPECT_FALSE(cache.write(0));
  EXPECT_EQ(cache.misses(), 2u);
}
