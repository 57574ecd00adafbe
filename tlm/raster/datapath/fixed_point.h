// Fixed-point types of the rasterizer datapath, named by format.
//
// The datapath interface formats come from Crisu et al., "Design Tradeoffs
// for an Embedded OpenGL-Compliant Hardware Rasterizer" (Section V) and the
// rasterizer spec: screen x, y unsigned 9.4,
// colour unsigned 0.8, depth unsigned 0.24, stencil 8.0. The reciprocal unit
// delivers 1/(|dx|+|dy|) as unsigned 5.16.
//
// A value is stored as its raw integer code (`raw`); the real value is
// raw * 2^-frac_bits. Unsigned normalised formats (unorm8, unorm24) follow
// OpenGL: code c means c / (2^n - 1), so the largest code is exactly 1.0.
// Each Verilog reference unit in rtl_models/raster/ takes the same raw codes
// on its ports, so a type converts to a port by reading `raw`.
#pragma once

#include <algorithm>
#include <cstdint>
#include <type_traits>

namespace tessera::raster {

// Unsigned fixed point with IntBits integer and FracBits fraction bits.
template <unsigned IntBits, unsigned FracBits>
struct UFixed {
  static constexpr unsigned INT_BITS = IntBits;
  static constexpr unsigned FRAC_BITS = FracBits;
  static constexpr unsigned WIDTH = IntBits + FracBits;
  static_assert(WIDTH <= 32, "ufixed is stored in 32 bits");
  static constexpr uint32_t MAX_RAW = WIDTH == 32 ? 0xffffffffu : (uint32_t{1} << WIDTH) - 1;

  uint32_t raw = 0;

  // The code is cut to the format's width, as a register of that width would.
  static constexpr UFixed from_raw(uint32_t code) { return UFixed{code & MAX_RAW}; }
  double to_double() const { return static_cast<double>(raw) / static_cast<double>(uint64_t{1} << FracBits); }

  friend constexpr bool operator==(UFixed a, UFixed b) { return a.raw == b.raw; }
  friend constexpr bool operator!=(UFixed a, UFixed b) { return a.raw != b.raw; }
};

// Two's complement signed fixed point, Width bits in all, FracBits of them
// fraction. Held sign-extended in an int64_t.
template <unsigned Width, unsigned FracBits>
struct SFixed {
  static constexpr unsigned WIDTH = Width;
  static constexpr unsigned FRAC_BITS = FracBits;
  static_assert(Width >= 2 && Width <= 63, "sfixed is held in an int64_t");
  static constexpr int64_t MIN_RAW = -(int64_t{1} << (Width - 1));
  static constexpr int64_t MAX_RAW = (int64_t{1} << (Width - 1)) - 1;

  int64_t raw = 0;

  // Wraps to Width bits, as a register of that width would.
  static constexpr SFixed from_raw(int64_t code);
  double to_double() const { return static_cast<double>(raw) / static_cast<double>(int64_t{1} << FracBits); }

  friend constexpr bool operator==(SFixed a, SFixed b) { return a.raw == b.raw; }
  friend constexpr bool operator!=(SFixed a, SFixed b) { return a.raw != b.raw; }
};

// Sign-extends the low `width` bits of `value`.
constexpr int64_t sign_extend(uint64_t value, unsigned width) {
  const uint64_t mask = width >= 64 ? ~uint64_t{0} : (uint64_t{1} << width) - 1;
  const uint64_t sign = uint64_t{1} << (width - 1);
  const uint64_t v = value & mask;
  return static_cast<int64_t>((v ^ sign) - sign);
}

template <unsigned Width, unsigned FracBits>
constexpr SFixed<Width, FracBits> SFixed<Width, FracBits>::from_raw(int64_t code) {
  return SFixed{sign_extend(static_cast<uint64_t>(code), Width)};
}

constexpr int64_t clamp_i64(int64_t v, int64_t lo, int64_t hi) {
  return v < lo ? lo : (v > hi ? hi : v);
}

// Arithmetic shift right rounding to nearest, ties towards +infinity
// (add half an output unit, then floor). `shift` must be at least 1.
constexpr int64_t round_shift_right(int64_t v, unsigned shift) {
  return (v + (int64_t{1} << (shift - 1))) >> shift;
}

// The value a state code selects, `values[code]`, with `fallback` for a code
// past the last value: each value ANDed with an all-ones or all-zero mask of
// its code and the results ORed, so branch-free. Neither an array indexed
// by the code nor a chain of `code == k ?` (which the compiler turns into a
// switch): in a batch (batch.h) the compiler vectorises this form across
// lanes and neither of the others.
template <class T, class... Values>
constexpr T select_code(unsigned code, T fallback, Values... values) {
  static_assert(std::is_integral_v<T>, "select_code picks between integer codes or words");
  using U = std::make_unsigned_t<T>;
  const auto mask = [](bool selected) { return selected ? static_cast<U>(~U{0}) : U{0}; };
  U result = 0;
  unsigned k = 0;
  ((result |= mask(code == k++) & static_cast<U>(static_cast<T>(values))), ...);
  result |= mask(code >= sizeof...(Values)) & static_cast<U>(fallback);
  return static_cast<T>(result);
}

// `condition ? a : b` by masks, for a condition that is the same for every
// lane of a batch (a state flag) choosing between values that are not: the
// vectoriser turns a conditional expression of that kind into a branch
// around each value's computation, which stops it.
template <class T>
constexpr T select_if(bool condition, T a, T b) {
  static_assert(std::is_integral_v<T>, "select_if picks between integer codes or words");
  using U = std::make_unsigned_t<T>;
  const U mask = condition ? static_cast<U>(~U{0}) : U{0};
  return static_cast<T>((static_cast<U>(a) & mask) | (static_cast<U>(b) & ~mask));
}

// Interface formats.
using q9_4 = UFixed<9, 4>;      // screen x, y
using q10_4 = UFixed<10, 4>;    // |dx| + |dy| of an edge, input of the reciprocal unit
using q5_16 = UFixed<5, 16>;    // reciprocal 1/(|dx|+|dy|)
using unorm8 = UFixed<0, 8>;    // colour channel, alpha, coverage
using unorm24 = UFixed<0, 24>;  // depth
using stencil8 = UFixed<8, 0>;  // stencil value

// Texture coordinate as the interpolator hands it to texel addressing:
// signed 15.16 in 32 bits; 1.0 spans the texture once, so REPEAT sees up to
// +-32768 repetitions and the 16 fraction bits resolve 8 bits of texel index
// for a 256-texel texture plus 8 bits of bilinear weight.
using q15_16 = SFixed<32, 16>;

struct Rgba8 {
  unorm8 r, g, b, a;

  // Port packing used by the Verilog units: R in bits 7:0, A in 31:24.
  constexpr uint32_t pack() const { return r.raw | (g.raw << 8) | (b.raw << 16) | (a.raw << 24); }
  static constexpr Rgba8 unpack(uint32_t v) {
    return {unorm8::from_raw(v), unorm8::from_raw(v >> 8), unorm8::from_raw(v >> 16), unorm8::from_raw(v >> 24)};
  }
  friend constexpr bool operator==(Rgba8 x, Rgba8 y) { return x.pack() == y.pack(); }
  friend constexpr bool operator!=(Rgba8 x, Rgba8 y) { return x.pack() != y.pack(); }
};

}  // namespace tessera::raster
