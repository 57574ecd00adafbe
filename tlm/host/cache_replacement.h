// The ARM922T caches' choice of the line a line fill replaces in a set (its
// "victim"): round-robin or pseudo-random, selected by CP15 c1's RR bit,
// random at reset (ARM922T TRM, ARM DDI 0184B, 4.2 "ICache" and 4.3 "DCache
// and write buffer"). Shared by the instruction cache's tag model
// (iss/arm922t_timing.h) and the data cache's (data_cache.h), each with its
// own state, as each cache has its own on the chip.
#pragma once

#include <cstdint>
#include <vector>

namespace tessera {

class CacheReplacement {
 public:
  CacheReplacement(unsigned sets, unsigned ways) : m_next(sets, 0), m_ways(ways) {}

  // The way to replace in `set`. Round-robin: a pointer per set (the TRM's
  // segment), advanced at each replacement. Pseudo-random: the TRM does not
  // give the generator; a 16-bit Galois LFSR (x^16 + x^14 + x^13 + x^11 + 1)
  // shared by the sets stands for it, deterministic so that runs repeat.
  unsigned victim(unsigned set, bool round_robin) {
    if (round_robin) {
      const unsigned way = m_next[set];
      m_next[set] = (way + 1) % m_ways;
      return way;
    }
    m_lfsr = next_lfsr();
    return m_lfsr % m_ways;
  }
  // The way victim() would return, without advancing anything.
  unsigned peek(unsigned set, bool round_robin) const { return round_robin ? m_next[set] : next_lfsr() % m_ways; }

 private:
  uint16_t next_lfsr() const { return static_cast<uint16_t>((m_lfsr >> 1) ^ (-(m_lfsr & 1u) & 0xb400u)); }

  std::vector<unsigned> m_next;
  unsigned m_ways;
  uint16_t m_lfsr = 0xace1u;
};

}  // namespace tessera
