// A distribution of non-negative integer samples (a bus access's wait in
// cycles, a program's cycles, a descriptor's bytes, a span's pixels) in
// power-of-two buckets, with the exact count, sum, minimum and maximum:
// gem5's distributions, small enough to sample on the hot path (a count
// leading zeros and four additions). Plain C++, no SystemC.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <limits>

namespace tessera {

class Log2Histogram {
 public:
  // Bucket 0 holds 0; bucket b >= 1 holds [2^(b-1), 2^b - 1]: 1, 2-3, 4-7...
  static constexpr unsigned BUCKETS = 65;

  // The value's bit length, by one count of leading zeros (a loop over the
  // bits took 30 instructions for a bus wait of a thousand cycles).
  static unsigned bucket_of(uint64_t value) { return value == 0 ? 0 : 64 - __builtin_clzll(value); }
  static uint64_t bucket_low(unsigned bucket) { return bucket == 0 ? 0 : uint64_t(1) << (bucket - 1); }
  static uint64_t bucket_high(unsigned bucket) {
    return bucket == 0 ? 0 : bucket == 64 ? std::numeric_limits<uint64_t>::max() : (uint64_t(1) << bucket) - 1;
  }

  void sample(uint64_t value) {
    ++m_buckets[bucket_of(value)];
    m_min = m_count == 0 ? value : std::min(m_min, value);
    m_max = m_count == 0 ? value : std::max(m_max, value);
    ++m_count;
    m_sum += value;
  }
  // `times` samples of `value`: what as many calls of sample(value) add.
  void sample(uint64_t value, uint64_t times) {
    if (times == 0) return;
    m_buckets[bucket_of(value)] += times;
    m_min = m_count == 0 ? value : std::min(m_min, value);
    m_max = m_count == 0 ? value : std::max(m_max, value);
    m_count += times;
    m_sum += value * times;
  }

  // Adds every sample of `other`.
  void merge(const Log2Histogram& other) {
    if (other.m_count == 0) return;
    for (unsigned b = 0; b < BUCKETS; ++b) m_buckets[b] += other.m_buckets[b];
    m_min = m_count == 0 ? other.m_min : std::min(m_min, other.m_min);
    m_max = m_count == 0 ? other.m_max : std::max(m_max, other.m_max);
    m_count += other.m_count;
    m_sum += other.m_sum;
  }

  uint64_t count() const { return m_count; }
  uint64_t sum() const { return m_sum; }
  uint64_t min() const { return m_min; }  // 0 when empty
  uint64_t max() const { return m_max; }
  double mean() const { return m_count == 0 ? 0.0 : static_cast<double>(m_sum) / static_cast<double>(m_count); }
  uint64_t bucket(unsigned index) const { return m_buckets[index]; }

 private:
  std::array<uint64_t, BUCKETS> m_buckets{};
  uint64_t m_count = 0, m_sum = 0, m_min = 0, m_max = 0;
};

}  // namespace tessera
