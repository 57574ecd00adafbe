// The histogram statistic (power-of-two buckets, exact count, sum, min and
// max) and the statistics' descriptions (stats_schema.h).
#include <gtest/gtest.h>

#include <map>
#include <stdexcept>

#include "common/histogram.h"
#include "common/stats_schema.h"
#include "tlm_bench/tlm_test_support.h"

namespace {

using tessera::Log2Histogram;

// The count of the bucket whose smallest value is `low` in histogram_json's
// output, 0 when it is left out.
uint64_t bucket_count(const nlohmann::json& histogram, uint64_t low) {
  for (const auto& bucket : histogram["buckets"])
    if (bucket["low"].get<uint64_t>() == low) return bucket["count"].get<uint64_t>();
  return 0;
}

TEST(Log2Histogram, SamplesFallInPowerOfTwoBucketsWithExactSummaries) {
  Log2Histogram h;
  for (uint64_t value : {0, 1, 2, 3, 4, 7, 8, 1000, 1023, 1024}) h.sample(value);
  const nlohmann::json json = tessera::histogram_json(h);
  EXPECT_EQ(json["count"], 10u);
  EXPECT_EQ(json["sum"], 0u + 1 + 2 + 3 + 4 + 7 + 8 + 1000 + 1023 + 1024);
  EXPECT_EQ(json["min"], 0u);
  EXPECT_EQ(json["max"], 1024u);
  EXPECT_DOUBLE_EQ(json["mean"].get<double>(), 3072.0 / 10);
  // 0 | 1 | 2-3 | 4-7 | 8-15 | 512-1023 | 1024-2047, the empty ones left out.
  ASSERT_EQ(json["buckets"].size(), 7u);
  EXPECT_EQ(bucket_count(json, 0), 1u);
  EXPECT_EQ(bucket_count(json, 1), 1u);
  EXPECT_EQ(bucket_count(json, 2), 2u);
  EXPECT_EQ(bucket_count(json, 4), 2u);
  EXPECT_EQ(bucket_count(json, 8), 1u);
  EXPECT_EQ(bucket_count(json, 512), 2u);
  EXPECT_EQ(bucket_count(json, 1024), 1u);
  EXPECT_EQ(json["buckets"][5]["high"], 1023u);
  EXPECT_EQ(json["buckets"][0]["high"], 0u);
}

TEST(Log2Histogram, TheLargestValueHasABucketAndAnEmptyHistogramIsAllZero) {
  Log2Histogram h;
  EXPECT_EQ(tessera::histogram_json(h)["buckets"].size(), 0u);
  EXPECT_EQ(h.min(), 0u);
  EXPECT_EQ(h.mean(), 0.0);
  h.sample(~uint64_t(0));
  const nlohmann::json json = tessera::histogram_json(h);
  EXPECT_EQ(json["buckets"][0]["low"], uint64_t(1) << 63);
  EXPECT_EQ(json["buckets"][0]["high"], ~uint64_t(0));
}

TEST(Log2Histogram, MergingIsSamplingBoth) {
  Log2Histogram a, b, both;
  for (uint64_t v : {5, 9, 9}) a.sample(v), both.sample(v);
  for (uint64_t v : {2, 100}) b.sample(v), both.sample(v);
  Log2Histogram empty;
  a.merge(empty);
  a.merge(b);
  EXPECT_EQ(tessera::histogram_json(a), tessera::histogram_json(both));
  EXPECT_EQ(a.min(), 2u);
  EXPECT_EQ(a.max(), 100u);
}

TEST(StatsSchema, AKeyDescribedTwiceDifferentlyIsAnErrorNamingIt) {
  tessera::StatsSchema schema;
  schema.add("bus.utilisation", "fraction", "busy over elapsed");
  schema.add("bus.utilisation", "fraction", "busy over elapsed");  // the same twice: one entry
  EXPECT_EQ(schema.to_json().size(), 1u);
  schema.add("bus.utilisation", "percent", "busy over elapsed");
  try {
    schema.to_json();
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("bus.utilisation"), std::string::npos) << e.what();
  }
}

TEST(StatsSchema, CountersTakeTheirUnitFromTheirNameAndHistogramsDescribeEveryField) {
  tessera::ActivityCounters counters;
  counters.counter("host_wait_ns", "waited");
  counters.counter("cycles.fill", "fill cycles");
  counters.counter("cmem.bytes_read", "read");
  counters.counter("vertex_cache.hits", "hits");
  tessera::StatsSchema schema;
  schema.add_counters(counters, "driver.");
  schema.add_histogram("h", "cycles", "waits");
  const nlohmann::json json = schema.to_json();
  EXPECT_EQ(json["driver.host_wait_ns"]["unit"], "ns");
  EXPECT_EQ(json["driver.cycles.fill"]["unit"], "cycles");
  EXPECT_EQ(json["driver.cmem.bytes_read"]["unit"], "bytes");
  EXPECT_EQ(json["driver.vertex_cache.hits"]["unit"], "count");
  EXPECT_EQ(json["driver.vertex_cache.hits"]["description"], "hits");
  // Every number histogram_json gives is described.
  for (const char* key :
       {"h.count", "h.sum", "h.min", "h.max", "h.mean", "h.buckets[].low", "h.buckets[].high", "h.buckets[].count"})
    EXPECT_TRUE(json.contains(key)) << key;
  EXPECT_EQ(json["h.mean"]["unit"], "cycles");
}

}  // namespace

using tessera::accumulates;
using tessera::add_growth;
using tessera::StatsSchema;

TEST(StatsSchema, OnlyStatisticsThatGrowWithTheRunAccumulate) {
  EXPECT_TRUE(accumulates({"host.busy_ns", "ns", "busy"}));
  EXPECT_TRUE(accumulates({"bus.initiators.*.bytes", "bytes", "moved"}));
  EXPECT_TRUE(accumulates({"energy.total_j", "J", "energy"}));
  EXPECT_FALSE(accumulates({"array.columns", "count", "columns", true}));  // a setting
  EXPECT_FALSE(accumulates({"bus.utilisation", "fraction", "a ratio"}));
  EXPECT_FALSE(accumulates({"energy.average_w", "W", "a power"}));
  EXPECT_FALSE(accumulates({"frames[].render_ns", "ns", "an element of a list"}));
  // A level in cycles does not (add_level), nor does a histogram's min, max
  // or mean, which add_histogram describes as levels; its count and sum do.
  EXPECT_FALSE(accumulates({"host.peak_cycles", "cycles", "a level", false, true}));
  StatsSchema histogram;
  histogram.add_histogram("bus.histograms.wait_cycles.host", "cycles", "waits");
  std::map<std::string, bool> grows;
  for (const auto& d : histogram.entries()) grows[d.key] = accumulates(d);
  EXPECT_TRUE(grows.at("bus.histograms.wait_cycles.host.count"));
  EXPECT_TRUE(grows.at("bus.histograms.wait_cycles.host.sum"));
  EXPECT_FALSE(grows.at("bus.histograms.wait_cycles.host.min"));
  EXPECT_FALSE(grows.at("bus.histograms.wait_cycles.host.max"));
  EXPECT_FALSE(grows.at("bus.histograms.wait_cycles.host.mean"));
  // A counter that happens to be named max is no level.
  EXPECT_TRUE(accumulates({"zbuf.max", "count", "a count named max"}));
}

TEST(StatsSchema, GrowthIsTheDifferenceOfTheAccumulatingNumbersSummedOverStretches) {
  StatsSchema schema;
  schema.add("simulated_ns", "ns", "time");
  schema.add("bus.initiators.*.bytes", "bytes", "moved");
  schema.add("bus.utilisation", "fraction", "a ratio");
  schema.add_setting("array.columns", "count", "columns");
  schema.add_histogram("bus.histograms.wait", "cycles", "waits");
  schema.add("host.cycles.fill", "cycles", "a dotted counter name");
  const auto at = [](double ns, uint64_t host_bytes, double utilisation, uint64_t waits, uint64_t max_wait) {
    return nlohmann::json{
        {"simulated_ns", ns},
        {"bus",
         {{"utilisation", utilisation},
          {"initiators", {{"host", {{"bytes", host_bytes}}}}},
          {"histograms", {{"wait", {{"count", waits}, {"sum", 3 * waits}, {"max", max_wait}, {"buckets", {}}}}}}}},
        {"array", {{"columns", 24}}},
        {"host", {{"cycles.fill", ns / 10}}},
        {"frames", nlohmann::json::array({1, 2})}};
  };
  nlohmann::json growth;
  add_growth(schema, at(100, 40, 0.5, 2, 7), at(300, 100, 0.25, 5, 9), growth);
  add_growth(schema, at(1000, 500, 0.1, 10, 9), at(1500, 520, 0.2, 11, 12), growth);
  EXPECT_DOUBLE_EQ(growth["simulated_ns"].get<double>(), 200 + 500);
  EXPECT_EQ(growth["bus"]["initiators"]["host"]["bytes"], 60 + 20);
  EXPECT_TRUE(growth["bus"]["initiators"]["host"]["bytes"].is_number_integer());
  EXPECT_EQ(growth["bus"]["histograms"]["wait"]["count"], 3 + 1);
  EXPECT_EQ(growth["bus"]["histograms"]["wait"]["sum"], 9 + 3);
  EXPECT_DOUBLE_EQ(growth["host"]["cycles.fill"].get<double>(), 20 + 50);
  // Not repeated: a ratio, a setting, a histogram's max and buckets, a list.
  EXPECT_FALSE(growth["bus"].contains("utilisation"));
  EXPECT_FALSE(growth["bus"]["histograms"]["wait"].contains("max"));
  EXPECT_FALSE(growth["bus"]["histograms"]["wait"].contains("buckets"));
  EXPECT_FALSE(growth.contains("array"));
  EXPECT_FALSE(growth.contains("frames"));
}

// tessera_common links SystemC, whose library calls sc_main: the tests run from it.
int sc_main(int argc, char* argv[]) {
  return tessera::test::run_all_tests(argc, argv);
}
