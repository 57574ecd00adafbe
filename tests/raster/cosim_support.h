// What the co-simulation tests of the datapath units share: the count of
// vectors and mismatches, and the closing report (the vector counts that
// ctest -L cosim prints, and the two checks every unit must pass).
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>

namespace tessera::raster {

// At least a million random vectors per unit, besides the corner cases.
constexpr uint64_t RANDOM_VECTORS = 1'000'000;

struct CosimTally {
  uint64_t vectors = 0;
  uint64_t mismatches = 0;

  // Counts one vector; true when it mismatched and is among the first ten,
  // which the caller reports in full.
  bool count(bool same) {
    ++vectors;
    return !same && ++mismatches <= 10;
  }
};

inline void report_cosim(const char* unit, const CosimTally& tally, uint64_t corner_vectors) {
  std::printf("%s cosim: %llu vectors (%llu corner, %llu random), %llu mismatches\n", unit,
              static_cast<unsigned long long>(tally.vectors), static_cast<unsigned long long>(corner_vectors),
              static_cast<unsigned long long>(tally.vectors - corner_vectors),
              static_cast<unsigned long long>(tally.mismatches));
  EXPECT_EQ(tally.mismatches, 0u);
  EXPECT_GE(tally.vectors - corner_vectors, RANDOM_VECTORS);
}

}  // namespace tessera::raster
