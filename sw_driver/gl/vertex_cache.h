// The front end's post-transform vertex cache: vertices already fetched,
// transformed and lit, kept by vertex index, so that an index that comes
// back within a draw call is not transformed again, as GPUs and the drivers
// of hardware without one keep them.
//
// Organisation: direct-mapped, index i in slot i mod ENTRIES. The driver
// runs on the ARM, so the look-up is the cost that every index pays, hit or
// miss: here one mask, one tag load and one compare, whatever the size. A
// FIFO or LRU cache, as in GPUs, would compare the index with every entry.
// Indexed meshes reuse vertices close to them in index order (a strip of a
// grid reuses the row before it), which a direct-mapped cache keeps as long
// as the rows are shorter than it is.
//
// Size: 32 entries. A cached vertex is about 60 bytes (clip position, eye
// position, colour, texture coordinates), so 32 take 2 KiB, a quarter of
// the ARM922T's 8 KiB data cache, and the arrays being read keep the rest.
// 32 holds a 5x5 patch of the teapot whole and rows of up to 31 vertices;
// measured hit rates of the built-in meshes are in sw_driver/gl/README.md.
//
// Invalidated at every draw call: between two calls any state (matrices,
// lights, arrays) may change what an index's vertex becomes.
#pragma once

#include <array>
#include <cstdint>

namespace tessera::gl {

inline constexpr unsigned VERTEX_CACHE_ENTRIES = 32;

template <typename Value, unsigned ENTRIES = VERTEX_CACHE_ENTRIES>
class VertexCache {
  static_assert(ENTRIES > 0 && (ENTRIES & (ENTRIES - 1)) == 0, "a power of two: the slot is the index's low bits");

 public:
  VertexCache() { invalidate(); }

  void invalidate() { m_tags.fill(EMPTY); }

  // The cached vertex of `index`, or nullptr (a miss).
  const Value* find(uint32_t index) const {
    const unsigned slot = index & (ENTRIES - 1);
    return m_tags[slot] == index ? &m_values[slot] : nullptr;
  }

  // The slot of `index`, now tagged with it (whatever it held is evicted);
  // the caller stores the vertex in it.
  Value& insert(uint32_t index) {
    const unsigned slot = index & (ENTRIES - 1);
    m_tags[slot] = index;
    return m_values[slot];
  }

 private:
  // Wider than any index, so an empty slot never matches.
  static constexpr uint64_t EMPTY = ~uint64_t{0};
  std::array<uint64_t, ENTRIES> m_tags;
  std::array<Value, ENTRIES> m_values{};
};

}  // namespace tessera::gl
