#include "cluster/rasterize.h"

#include <stdexcept>
#include <string>

namespace tessera::cluster {

const uint8_t* ArrayMemory::load(uint32_t address, unsigned size, unsigned count) {
  return store(address, size, count);
}

uint8_t* ArrayMemory::store(uint32_t address, unsigned size, unsigned count) {
  // The message in 32-bit numbers: a 64-bit one would bring in the 64-bit
  // division helper the core otherwise never needs.
  if (!contains(address, uint64_t{size} * count))
    throw std::out_of_range("ArrayMemory: " + std::to_string(count) + " elements of " + std::to_string(size) +
                            " bytes at address " + std::to_string(address) + " leave the memory");
  return m_bytes + (address - m_base);
}

bool ArrayMemory::contains(uint32_t address, uint64_t bytes) const {
  return address >= m_base && uint64_t{address} - m_base + bytes <= m_size;
}

const char* Stripe::error(const StripeBuffers& buffers, const ArrayMemory* memory) {
  if (buffers.width < 1 || buffers.width > MAX_SCREEN) return "width: must be in 1 .. 512";
  if (buffers.rows < 1 || buffers.first_row + buffers.rows > MAX_SCREEN)
    return "rows: the stripe must have rows, within the 512-row screen";
  if (memory != nullptr) {
    if (!memory->contains(buffers.color_address, buffers.color_bytes()))
      return "color_address: the colour buffer does not fit the memory";
    if (!memory->contains(buffers.depth_address, buffers.depth_bytes()))
      return "depth_address: the depth buffer does not fit the memory";
  }
  return nullptr;
}

namespace {

// pack_pixel's channel reductions for RGB565 by table, not by a division per
// pixel (the ARM has none).
struct ReduceTables {
  uint8_t five[256]{}, six[256]{};
  constexpr ReduceTables() {
    for (uint32_t c = 0; c < 256; ++c) {
      five[c] = static_cast<uint8_t>(reduce_channel(c, 5));
      six[c] = static_cast<uint8_t>(reduce_channel(c, 6));
    }
  }
};
constexpr ReduceTables REDUCE;

uint32_t pack(PixelFormat format, uint32_t r, uint32_t g, uint32_t b) {
  if (format == PixelFormat::rgba8888) return r | g << 8 | b << 16 | 0xffu << 24;
  return uint32_t{REDUCE.five[r]} << 11 | uint32_t{REDUCE.six[g]} << 5 | REDUCE.five[b];
}

uint32_t load32(const uint8_t* p) {
  return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
}

void store32(uint8_t* p, uint32_t value) {
  p[0] = static_cast<uint8_t>(value);
  p[1] = static_cast<uint8_t>(value >> 8);
  p[2] = static_cast<uint8_t>(value >> 16);
  p[3] = static_cast<uint8_t>(value >> 24);
}

// The start of a span of n pixels stepping by `step`, clamped into [0, top]
// and nudged so that the last pixel is too where the step allows; the
// pixels then step in 32 bits (top < 2^30, |step| <= top).
int32_t span_start(int64_t value, int32_t step, int n, int64_t top) {
  int64_t s = value < 0 ? 0 : (value > top ? top : value);
  const int64_t end = s + int64_t{step} * (n - 1);
  if (end < 0) s -= end;
  if (end > top) s -= end - top;
  return static_cast<int32_t>(s < 0 ? 0 : (s > top ? top : s));
}

int32_t span_step(int64_t dx, int64_t top) {
  return static_cast<int32_t>(dx > top ? top : (dx < -top ? -top : dx));
}

constexpr int64_t DEPTH_TOP = int64_t{MAX_DEPTH} << DEPTH_FRACTION_BITS;
constexpr int64_t COLOR_TOP = int64_t{255} << COLOR_FRACTION_BITS;
constexpr int32_t COLOR_HALF = 1 << (COLOR_FRACTION_BITS - 1);

uint32_t to_channel(int32_t v) {
  const int32_t c = (v + COLOR_HALF) >> COLOR_FRACTION_BITS;
  return static_cast<uint32_t>(c < 0 ? 0 : (c > 255 ? 255 : c));
}

// One step of a span's interpolant, wrapping as the ARM's ADD does: the
// values the span's pixels use stay in range, but the step after its last
// pixel may leave int32 (undefined in C++, the same bits on the ARM).
void advance(int32_t& value, int32_t delta) {
  value = static_cast<int32_t>(static_cast<uint32_t>(value) + static_cast<uint32_t>(delta));
}

// One span: pixels x0 .. x0 + n - 1 of stripe row `row`, planes started.
void draw_span(Stripe& stripe, unsigned row, int32_t x0, int n, const int32_t start[4], const int32_t step[4]) {
  const StripeBuffers& buffers = stripe.buffers();
  StripeMemory& memory = stripe.memory();
  WorkCounters& counters = stripe.counters();
  const uint32_t first = row * buffers.width + static_cast<uint32_t>(x0);
  const uint8_t* old_depth = memory.load(buffers.depth_address + first * 4, 4, static_cast<unsigned>(n));
  int32_t z = start[0], r = start[1], g = start[2], b = start[3];
  unsigned passes = 0;
  for (int i = 0; i < n; ++i) {
    int32_t depth = z >> DEPTH_FRACTION_BITS;
    depth = depth < 0 ? 0 : (depth > static_cast<int32_t>(MAX_DEPTH) ? static_cast<int32_t>(MAX_DEPTH) : depth);
    const bool pass = static_cast<uint32_t>(depth) < (load32(old_depth + 4 * i) & MAX_DEPTH);
    stripe.pass[i] = pass ? 1 : 0;
    if (pass) {
      stripe.depth[i] = static_cast<uint32_t>(depth);
      stripe.color[i] = pack(buffers.color_format, to_channel(r), to_channel(g), to_channel(b));
      ++passes;
    }
    advance(z, step[0]);
    advance(r, step[1]);
    advance(g, step[2]);
    advance(b, step[3]);
  }
  counters.pixels += static_cast<unsigned>(n);
  counters.depth_passes += passes;
  if (passes == 0) return;
  // The passing pixels as runs, each stored once to each buffer.
  const unsigned bytes = bytes_per_pixel(buffers.color_format);
  for (int begin = 0; begin < n;) {
    if (stripe.pass[begin] == 0) {
      ++begin;
      continue;
    }
    int end = begin + 1;
    while (end < n && stripe.pass[end] != 0) ++end;
    const auto count = static_cast<unsigned>(end - begin);
    const uint32_t at = first + static_cast<uint32_t>(begin);
    uint8_t* depth_out = memory.store(buffers.depth_address + at * 4, 4, count);
    for (int i = begin; i < end; ++i) store32(depth_out + 4 * (i - begin), stripe.depth[i]);
    uint8_t* color_out = memory.store(buffers.color_address + at * bytes, bytes, count);
    for (int i = begin; i < end; ++i)
      store_pixel(buffers.color_format, color_out + bytes * (i - begin), stripe.color[i]);
    begin = end;
  }
}

}  // namespace

void clear_stripe(Stripe& stripe, uint32_t rgba) {
  const StripeBuffers& buffers = stripe.buffers();
  const unsigned bytes = bytes_per_pixel(buffers.color_format);
  const uint32_t packed = pack_pixel(buffers.color_format, rgba);
  for (unsigned row = 0; row < buffers.rows; ++row) {
    const uint32_t first = row * buffers.width;
    uint8_t* color = stripe.memory().store(buffers.color_address + first * bytes, bytes, buffers.width);
    for (unsigned i = 0; i < buffers.width; ++i) store_pixel(buffers.color_format, color + bytes * i, packed);
    uint8_t* depth = stripe.memory().store(buffers.depth_address + first * 4, 4, buffers.width);
    for (unsigned i = 0; i < buffers.width; ++i) store32(depth + 4 * i, MAX_DEPTH);
  }
}

void rasterize_trapezoid(const Trapezoid& trapezoid, Stripe& stripe) {
  const StripeBuffers& buffers = stripe.buffers();
  WorkCounters& counters = stripe.counters();
  ++counters.trapezoids_in;
  TrapezoidEdge left = trapezoid.left, right = trapezoid.right;
  const TrapezoidPlane* planes[4] = {&trapezoid.z, &trapezoid.red, &trapezoid.green, &trapezoid.blue};
  const int64_t tops[4] = {DEPTH_TOP, COLOR_TOP, COLOR_TOP, COLOR_TOP};
  int64_t along[4];
  int32_t step[4];
  for (int k = 0; k < 4; ++k) {
    along[k] = planes[k]->start;
    step[k] = span_step(planes[k]->dx, tops[k]);
  }
  const int32_t stripe_begin = static_cast<int32_t>(buffers.first_row);
  const int32_t stripe_end = stripe_begin + static_cast<int32_t>(buffers.rows);
  const int32_t width = static_cast<int32_t>(buffers.width);
  for (int32_t row = trapezoid.first_row; row <= trapezoid.last_row && row < stripe_end; ++row) {
    if (row >= stripe_begin) {
      ++counters.rows;
      const int32_t x0 = left.pixel < 0 ? 0 : left.pixel;
      const int32_t x1 = right.pixel > width ? width : right.pixel;
      if (x0 < x1) {
        ++counters.spans;
        int32_t start[4];
        for (int k = 0; k < 4; ++k) {
          const int64_t value = x0 == left.pixel ? along[k] : along[k] + planes[k]->dx * (x0 - left.pixel);
          start[k] = span_start(value, step[k], x1 - x0, tops[k]);
        }
        draw_span(stripe, static_cast<unsigned>(row - stripe_begin), x0, x1 - x0, start, step);
      }
    }
    // Down one row: both edges, and the planes along the left edge.
    left.pixel += left.step;
    left.error -= left.step_error;
    bool carry = false;
    if (left.error < 0) {
      ++left.pixel;
      left.error += left.denominator;
      carry = true;
    }
    for (int k = 0; k < 4; ++k) along[k] += planes[k]->row_step + (carry ? planes[k]->dx : 0);
    right.pixel += right.step;
    right.error -= right.step_error;
    if (right.error < 0) {
      ++right.pixel;
      right.error += right.denominator;
    }
  }
}

}  // namespace tessera::cluster
