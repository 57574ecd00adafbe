// The sort-middle renderer's rasteriser (README.md, step 4): a trapezoid
// into the receiving node's stripe, row by row, with z-buffered Gouraud
// shading.
//
// Buffers. The stripe's colour buffer is RGB565 or RGBA8888
// (contract/common/pixel_format.def), packed by pack_pixel (rounded to
// nearest); its depth buffer is 24-bit z in 32-bit little-endian words,
// cleared to MAX_DEPTH; a pixel is written when its z is less than the
// stored one. Both are width x rows elements, row 0 = the stripe's first
// (top) row.
//
// Values. z is the plane >> DEPTH_FRACTION_BITS (floor), colour (plane +
// 2^15) >> 16 (rounded to nearest); each span's start is clamped into the
// format's range and nudged so that its last pixel is too (records.h,
// README.md "The fill rule").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "cluster/records.h"
#include "common/pixel_format.h"

namespace tessera::cluster {

// How the rasteriser reaches its buffers: the shape of the arm renderer's
// PixelMemory (renderers/arm/pixel_memory.h). Accesses are declared per run
// of consecutive elements, so the node program can charge them through
// HostApi per cache line; on the ISS they are plain memory.
class StripeMemory {
 public:
  virtual ~StripeMemory() = default;
  // `count` loads of `size` bytes at consecutive addresses from `address`;
  // a pointer to the first element's bytes, valid until the next call.
  virtual const uint8_t* load(uint32_t address, unsigned size, unsigned count) = 0;
  // `count` stores of `size` bytes, consecutive from `address`: where the
  // caller writes them (valid until the next call).
  virtual uint8_t* store(uint32_t address, unsigned size, unsigned count) = 0;
};

// Plain memory: `size` bytes at `bytes`, seen at addresses base ..
// base + size - 1. Counts nothing. An access outside is a bug of the
// caller's buffer placement (Stripe::error checks it): std::out_of_range.
class ArrayMemory : public StripeMemory {
 public:
  ArrayMemory(uint8_t* bytes, size_t size, uint32_t base = 0) : m_bytes(bytes), m_size(size), m_base(base) {}
  const uint8_t* load(uint32_t address, unsigned size, unsigned count) override;
  uint8_t* store(uint32_t address, unsigned size, unsigned count) override;
  bool contains(uint32_t address, uint64_t bytes) const;

 private:
  uint8_t* m_bytes;
  size_t m_size;
  uint32_t m_base;
};

struct StripeBuffers {
  unsigned width = 0;      // the screen's width, 1 .. MAX_SCREEN
  unsigned first_row = 0;  // the stripe's rows on the screen: first_row .. first_row + rows - 1
  unsigned rows = 0;
  PixelFormat color_format = PixelFormat::rgb565;
  uint32_t color_address = 0, depth_address = 0;

  uint32_t color_bytes() const { return width * rows * bytes_per_pixel(color_format); }
  uint32_t depth_bytes() const { return width * rows * 4; }
};

class Stripe {
 public:
  Stripe(StripeMemory& memory, const StripeBuffers& buffers) : m_memory(memory), m_buffers(buffers) {}

  // Null when the buffers can be drawn (sizes in range, and inside `memory`
  // when given); else what is wrong, naming the field.
  static const char* error(const StripeBuffers& buffers, const ArrayMemory* memory = nullptr);

  const StripeBuffers& buffers() const { return m_buffers; }
  StripeMemory& memory() { return m_memory; }
  WorkCounters& counters() { return m_counters; }
  const WorkCounters& counters() const { return m_counters; }

  // Per-span scratch, sized once: nothing is allocated while drawing.
  std::array<uint32_t, MAX_SCREEN> depth{}, color{};
  std::array<uint8_t, MAX_SCREEN> pass{};

 private:
  StripeMemory& m_memory;
  StripeBuffers m_buffers;
  WorkCounters m_counters;
};

// Colour (RGBA8 as r | g << 8 | b << 16 | a << 24) to every pixel, MAX_DEPTH
// to every depth word.
void clear_stripe(Stripe& stripe, uint32_t rgba);

// Draws the trapezoid's rows that lie in the stripe (a trapezoid for another
// stripe draws nothing), its spans scissored to the width. Counts
// trapezoids_in, rows, spans, pixels and depth_passes in stripe.counters().
void rasterize_trapezoid(const Trapezoid& trapezoid, Stripe& stripe);

}  // namespace tessera::cluster
