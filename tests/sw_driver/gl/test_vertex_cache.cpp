// Unit tests of the post-transform vertex cache (gl/vertex_cache.h):
// direct-mapped by vertex index, emptied by invalidate().
#include <gtest/gtest.h>

#include <cstdint>

#include "gl/vertex_cache.h"

using tessera::gl::VertexCache;

TEST(VertexCache, MissThenHitUntilEvictedByAnIndexOfTheSameSlot) {
  VertexCache<int, 8> cache;
  EXPECT_EQ(cache.find(3), nullptr);
  cache.insert(3) = 30;
  ASSERT_NE(cache.find(3), nullptr);
  EXPECT_EQ(*cache.find(3), 30);
  cache.insert(4) = 40;  // another slot: both stay
  EXPECT_EQ(*cache.find(3), 30);
  EXPECT_EQ(*cache.find(4), 40);
  cache.insert(11) = 110;  // 11 mod 8 = 3: evicts 3
  EXPECT_EQ(cache.find(3), nullptr);
  EXPECT_EQ(*cache.find(11), 110);
  EXPECT_EQ(*cache.find(4), 40);
}

TEST(VertexCache, EmptyCacheAndInvalidateMatchNoIndex) {
  VertexCache<int, 4> cache;
  // No tag of an empty slot may equal an index, 0 and the largest included.
  for (uint32_t index : {0u, 1u, 4u, 0xFFFFFFFFu}) EXPECT_EQ(cache.find(index), nullptr) << index;
  cache.insert(0) = 1;
  cache.insert(0xFFFFFFFFu) = 2;
  EXPECT_NE(cache.find(0), nullptr);
  EXPECT_NE(cache.find(0xFFFFFFFFu), nullptr);
  cache.invalidate();
  EXPECT_EQ(cache.find(0), nullptr);
  EXPECT_EQ(cache.find(0xFFFFFFFFu), nullptr);
}

TEST(VertexCache, DefaultSizeHoldsARowOfAGrid) {
  // A strip between two rows of a grid reuses the row before it: with rows
  // shorter than the cache, every vertex is transformed once.
  VertexCache<uint32_t> cache;
  constexpr uint32_t ROW = tessera::gl::VERTEX_CACHE_ENTRIES - 2;
  unsigned misses = 0, lookups = 0;
  for (uint32_t row = 0; row + 1 < 6; ++row)
    for (uint32_t column = 0; column + 1 < ROW; ++column) {
      const uint32_t a = row * ROW + column, b = a + 1, c = a + ROW, d = c + 1;
      for (uint32_t index : {a, c, b, b, c, d}) {
        ++lookups;
        if (!cache.find(index)) {
          ++misses;
          cache.insert(index) = index;
        }
      }
    }
  EXPECT_EQ(misses, 6 * ROW);
  EXPECT_EQ(lookups, 5 * (ROW - 1) * 6);
}
