// Unit tests of the ARM922T data-cache tag model: set mapping, round-robin
// and pseudo-random replacement, write-back of dirty victims (the whole line
// or its dirty half), write-through hits that leave the line clean, no
// allocation on write misses, c7's cleans and invalidations by address and
// by index, and the same behaviour for lines above the tag table.
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

// Two dirty bits per line, one per 16-byte half: a victim writes back the
// whole line, the dirty half or nothing (ARM922T TRM 4.3).
TEST(DataCache, DirtyVictimWritesBackTheDirtyHalfOrTheWholeLine) {
  DataCache cache = arm922t();
  for (uint32_t i = 0; i < WAYS; ++i) cache.read(0x40 + i * WAY);
  EXPECT_TRUE(cache.write(0x40 + 0 * WAY + 8));   // way 0: first half dirty
  EXPECT_TRUE(cache.write(0x40 + 1 * WAY + 20));  // way 1: second half dirty
  EXPECT_TRUE(cache.write(0x40 + 2 * WAY + 4));   // way 2: both
  EXPECT_TRUE(cache.write(0x40 + 2 * WAY + 28));
  const DataCache::Result first = cache.read(0x40 + WAYS * WAY);
  EXPECT_FALSE(first.hit);
  EXPECT_EQ(first.victim.address, 0x40u);
  EXPECT_EQ(first.victim.bytes, LINE / 2);
  const DataCache::Result second = cache.read(0x40 + (WAYS + 1) * WAY);
  EXPECT_EQ(second.victim.address, 0x40u + WAY + 16);
  EXPECT_EQ(second.victim.bytes, LINE / 2);
  const DataCache::Result third = cache.read(0x40 + (WAYS + 2) * WAY);
  EXPECT_EQ(third.victim.address, 0x40u + 2 * WAY);
  EXPECT_EQ(third.victim.bytes, LINE);
  const DataCache::Result fourth = cache.read(0x40 + (WAYS + 3) * WAY);
  EXPECT_EQ(fourth.victim.bytes, 0u) << "way 3 was clean";
  EXPECT_EQ(cache.writebacks(), 3u);
}

// A write of several bytes (a span's elements in one line) marks every half
// it covers.
TEST(DataCache, AWriteAcrossTheMiddleOfALineDirtiesBothHalves) {
  DataCache cache = arm922t();
  cache.read(0x3000);
  cache.read(0x3020);
  cache.read(0x3040);
  EXPECT_TRUE(cache.write(0x3008, true, 24));  // bytes 8 to 31
  EXPECT_TRUE(cache.write(0x3020, true, 16));  // the first half only
  EXPECT_TRUE(cache.write(0x3050, true, 64));  // from byte 16, clamped to the line
  EXPECT_EQ(cache.clean_line(0x3000, false).bytes, LINE);
  const DataCache::WriteBack first = cache.clean_line(0x3020, false);
  EXPECT_EQ(first.address, 0x3020u);
  EXPECT_EQ(first.bytes, LINE / 2);
  const DataCache::WriteBack second = cache.clean_line(0x3040, false);
  EXPECT_EQ(second.address, 0x3050u);
  EXPECT_EQ(second.bytes, LINE / 2);
  EXPECT_EQ(cache.hits(), 3u);
}

// Write-through: a store hit updates the line (a hit) but leaves it clean,
// the store itself going to the write buffer (the host's part).
TEST(DataCache, WriteThroughHitLeavesTheLineClean) {
  DataCache cache = arm922t();
  for (uint32_t i = 0; i < WAYS; ++i) cache.read(i * WAY);
  EXPECT_TRUE(cache.write(0, false));
  EXPECT_TRUE(cache.write(20, false));
  EXPECT_EQ(cache.read(WAYS * WAY).victim.bytes, 0u) << "way 0 is replaced without a write-back";
  EXPECT_EQ(cache.clean_line(WAY, false).bytes, 0u);
  EXPECT_EQ(cache.writebacks(), 0u);
  EXPECT_EQ(cache.hits(), 2u);
}

// Pseudo-random replacement (RR clear): the victim is the LFSR's next value
// modulo 64, whatever the ways hold (the victim choice ignores empty ways,
// so the set is filled round-robin first, way i holding line i). From the
// seed 0xace1 (bit 0 set): 0xace1 >> 1 = 0x5670, XOR the taps 0xb400 =
// 0xe270, and 0xe270 % 64 = 0x30 = 48; then 0xe270 (bit 0 clear) >> 1 =
// 0x7138, % 64 = 0x38 = 56. RR set again: the round-robin pointer is where
// the fills left it, at way 0.
TEST(DataCache, ReplacementFollowsTheRrBitAndTheLfsr) {
  DataCache cache = arm922t();
  EXPECT_TRUE(cache.round_robin());
  for (uint32_t i = 0; i < WAYS; ++i) cache.read(i * WAY);
  cache.set_round_robin(false);
  EXPECT_FALSE(cache.read(WAYS * WAY).hit);
  EXPECT_FALSE(cache.read((WAYS + 1) * WAY).hit);
  for (uint32_t i = 0; i < WAYS; ++i) {
    if (i == 48 || i == 56) continue;
    EXPECT_TRUE(cache.read(i * WAY).hit) << "line " << i;
  }
  cache.set_round_robin(true);
  EXPECT_FALSE(cache.read((WAYS + 2) * WAY).hit);
  EXPECT_FALSE(cache.read(0).hit) << "way 0 replaced";
  EXPECT_FALSE(cache.read(48 * WAY).hit) << "replaced by the LFSR";
  EXPECT_FALSE(cache.read(56 * WAY).hit) << "replaced by the LFSR";
  EXPECT_TRUE(cache.read(WAYS * WAY).hit);
}

// c7's clean D entry by address (c10, 1) and clean and invalidate (c14, 1):
// the dirty data once, then nothing; a line not in the cache: nothing.
TEST(DataCache, CleanLineByAddressWritesBackOnceAndMayInvalidate) {
  DataCache cache = arm922t();
  cache.read(0x5000);
  cache.write(0x5018);
  const DataCache::WriteBack first = cache.clean_line(0x5004, false);
  EXPECT_EQ(first.address, 0x5010u);
  EXPECT_EQ(first.bytes, LINE / 2);
  EXPECT_EQ(cache.clean_line(0x5000, false).bytes, 0u) << "clean now";
  EXPECT_TRUE(cache.read(0x5000).hit) << "cleaning keeps the line";
  cache.write(0x5000);
  EXPECT_EQ(cache.clean_line(0x5000, true).bytes, LINE / 2);
  EXPECT_FALSE(cache.read(0x5000).hit) << "clean and invalidate drops it";
  EXPECT_EQ(cache.clean_line(0x9000, true).bytes, 0u);
  EXPECT_EQ(cache.writebacks(), 2u);
}

// By index (c10, 2 and c14, 2): the way in bits 31:26, the set in bits 6:5.
// Lines 0x6000 + i * 128 all fall in set 0 (0x6000 / 32 % 4 = 0) and fill
// ways 0, 1, 2, ... in order (round-robin from an empty cache); 0x6020 is
// set 1's first line (way 0).
TEST(DataCache, CleanByIndexFindsTheWayAndSet) {
  DataCache cache = arm922t();
  for (uint32_t i = 0; i < 3; ++i) cache.read(0x6000 + i * WAY);
  cache.read(0x6020);
  cache.write(0x6000 + 2 * WAY);  // set 0, way 2
  cache.write(0x6020 + 16);       // set 1, way 0
  EXPECT_EQ(cache.clean_index((0u << 26) | (0u << 5), false).bytes, 0u) << "set 0 way 0 is clean";
  const DataCache::WriteBack way2 = cache.clean_index((2u << 26) | (0u << 5), false);
  EXPECT_EQ(way2.address, 0x6000u + 2 * WAY);
  EXPECT_EQ(way2.bytes, LINE / 2);
  const DataCache::WriteBack set1 = cache.clean_index((0u << 26) | (1u << 5), true);
  EXPECT_EQ(set1.address, 0x6030u);
  EXPECT_FALSE(cache.read(0x6020).hit) << "invalidated by index";
  EXPECT_TRUE(cache.read(0x6000 + 2 * WAY).hit);
}

TEST(DataCache, InvalidateLineDropsDirtyDataWithoutAWriteBack) {
  DataCache cache = arm922t();
  cache.read(0x7000);
  cache.read(0x7020);
  cache.write(0x7000);
  cache.invalidate_line(0x7004);
  EXPECT_EQ(cache.clean_line(0x7000, false).bytes, 0u);
  EXPECT_FALSE(cache.read(0x7000).hit);
  EXPECT_TRUE(cache.read(0x7020).hit) << "only that line";
  EXPECT_EQ(cache.writebacks(), 0u);
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
