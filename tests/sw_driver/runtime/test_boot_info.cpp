// The frame figures' line (boot_info.h): what the program on the ISS writes
// and the simulator reads back must be the same doubles, bit for bit, and a
// damaged line must be refused with its field named.
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "runtime/boot_info.h"

namespace {

using tessera::boot_info::decode_figures;
using tessera::boot_info::encode_figures;

uint64_t bits_of(double value) {
  uint64_t bits = 0;
  std::memcpy(&bits, &value, sizeof bits);
  return bits;
}

TEST(FrameFigures, EveryValueComesBackBitForBit) {
  const std::vector<std::pair<std::string, double>> figures = {
      {"host_application_ns", 1366245.8880000089},
      {"zero", 0.0},
      {"negative_zero", -0.0},
      {"tiny", std::numeric_limits<double>::denorm_min()},
      {"huge", -std::numeric_limits<double>::max()},
      {"infinite", std::numeric_limits<double>::infinity()},
      {"third", 1.0 / 3.0},
  };
  const std::string line = encode_figures(figures);
  ASSERT_EQ(line.back(), '\n');
  const auto decoded = decode_figures(line.substr(0, line.size() - 1));
  ASSERT_EQ(decoded.size(), figures.size());
  for (size_t i = 0; i < figures.size(); ++i) {
    EXPECT_EQ(decoded[i].first, figures[i].first);
    EXPECT_EQ(bits_of(decoded[i].second), bits_of(figures[i].second)) << figures[i].first;
  }
}

TEST(FrameFigures, TheEncodingIsTheIeeeBitsInHex) {
  // 1.0 is 0x3ff0000000000000 in IEEE-754 binary64: the line a reader of a
  // saved figures file sees.
  EXPECT_EQ(encode_figures({{"one", 1.0}, {"two", 2.0}}), "one=3ff0000000000000\ttwo=4000000000000000\n");
  EXPECT_EQ(encode_figures({}), "\n");
}

TEST(FrameFigures, ADamagedFieldIsRefusedByName) {
  for (const std::string line : {"a=3ff0", "a=3ff000000000000g", "a", "a=3FF0000000000000"}) {
    try {
      decode_figures(line);
      ADD_FAILURE() << line << " was accepted";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find("'" + line + "'"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
