// Activity counters: declared once by name, stable references, nested JSON.
#include <gtest/gtest.h>

#include "common/activity_counters.h"
#include "common/activity_json.h"

namespace {

TEST(ActivityCounters, ACounterIsCreatedOnceAndKeepsItsAddress) {
  tessera::ActivityCounters counters;
  tessera::ActivityCounter& hits = counters.counter("cache.hits", "hits");
  for (int i = 0; i < 100; ++i) counters.counter("filler." + std::to_string(i), "grows the set");
  hits += 3;
  ++hits;
  EXPECT_EQ(&counters.counter("cache.hits", "asked again"), &hits);
  EXPECT_EQ(counters.value("cache.hits"), 4u);
  EXPECT_EQ(counters.value("cache.misses"), 0u) << "never declared";
  EXPECT_EQ(counters.all().size(), 101u);
}

TEST(ActivityCounters, DottedNamesNestInJson) {
  tessera::ActivityCounters counters;
  counters.counter("vertex_cache.hits", "") += 7;
  counters.counter("vertex_cache.misses", "") += 2;
  counters.counter("triangles", "") += 5;
  const nlohmann::json doc = tessera::to_json(counters);
  EXPECT_EQ(doc["vertex_cache"]["hits"], 7);
  EXPECT_EQ(doc["vertex_cache"]["misses"], 2);
  EXPECT_EQ(doc["triangles"], 5);
}

}  // namespace
