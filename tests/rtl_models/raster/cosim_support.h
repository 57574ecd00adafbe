// What the co-simulation tests of the datapath units share besides their
// random vectors (testbench/cosim/raster_vectors.h): the count of vectors and
// mismatches, the closing report (the vector counts that ctest -L cosim
// prints, and the two checks every unit must pass), and the batch forms'
// variants. Every vector goes through the RTL, the unit's scalar form and its
// batch form in every variant (batch.h) this machine runs.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <vector>

#include "cosim/raster_vectors.h"
#include "raster/datapath/batch.h"

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

// Every variant of the batch forms this machine runs (batch.h): each test
// runs every vector through each.
inline const std::vector<BatchIsa>& batch_isas() {
  return runnable_batch_isas();
}

// Lengths of the batches the random vectors are cut into: 1 to 64, so that
// lanes go through the vectorised loops' bodies and their remainders alike.
inline unsigned random_batch_length(uint64_t bits) {
  return 1 + static_cast<unsigned>(bits % 64);
}

inline void report_cosim(const char* unit, const CosimTally& tally, uint64_t corner_vectors) {
  std::printf(
      "%s cosim: %llu vectors (%llu corner, %llu random), each through the scalar form and %zu batch variant(s), %llu "
      "mismatches\n",
      unit, static_cast<unsigned long long>(tally.vectors), static_cast<unsigned long long>(corner_vectors),
      static_cast<unsigned long long>(tally.vectors - corner_vectors), batch_isas().size(),
      static_cast<unsigned long long>(tally.mismatches));
  EXPECT_EQ(tally.mismatches, 0u);
  EXPECT_GE(tally.vectors - corner_vectors, RANDOM_VECTORS);
}

}  // namespace tessera::raster
