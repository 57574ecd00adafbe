// What the sort-middle core's tests share: an independent reference of the
// fill rule, a sink that keeps the pieces, and a frame drawn through p
// stripes.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "cluster/rasterize.h"
#include "cluster/records.h"
#include "cluster/split.h"
#include "cluster/stripes.h"

namespace tessera::cluster::testing {

// Whether the centre of pixel (i, r) is drawn, from 64-bit edge functions:
// inside, or on an edge whose interior lies at greater x (a left edge), or on
// a horizontal edge with the interior below it (a top edge, y down).
inline bool reference_covers(const ScreenTriangle& t, int i, int r) {
  int64_t x[3], y[3];
  for (int k = 0; k < 3; ++k) {
    x[k] = t.v[k].x;
    y[k] = t.v[k].y;
  }
  const int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0) return false;
  if (area < 0) {  // make the interior the side where every edge function is positive
    std::swap(x[1], x[2]);
    std::swap(y[1], y[2]);
  }
  const int64_t px = 16 * int64_t{i} + 8, py = 16 * int64_t{r} + 8;
  for (int k = 0; k < 3; ++k) {
    const int64_t ax = x[k], ay = y[k], bx = x[(k + 1) % 3], by = y[(k + 1) % 3];
    // E = (b - a) x (p - a): positive on the interior side.
    const int64_t e = (bx - ax) * (py - ay) - (by - ay) * (px - ax);
    const int64_t de_dx = -(by - ay), de_dy = bx - ax;
    const bool left_or_top = de_dx > 0 || (de_dx == 0 && de_dy > 0);
    if (e < 0 || (e == 0 && !left_or_top)) return false;
  }
  return true;
}

struct Piece {
  unsigned stripe;
  Trapezoid trapezoid;
};

class CollectingSink : public TrapezoidSink {
 public:
  void put(unsigned stripe, const Trapezoid& trapezoid) override { pieces.push_back({stripe, trapezoid}); }
  std::vector<Piece> pieces;
};

// A whole frame in one memory, colour then depth, each stripe's buffers a
// window of it: drawing through p stripes composes the frame as it goes.
class Frame {
 public:
  Frame(unsigned width, unsigned height, unsigned p, PixelFormat format = PixelFormat::rgba8888)
      : width(width),
        height(height),
        m_bytes(std::size_t{width} * height * (bytes_per_pixel(format) + 4)),
        m_memory(m_bytes.data(), m_bytes.size()) {
    const uint32_t color_bytes = width * height * bytes_per_pixel(format);
    stripes.reserve(p);
    for (unsigned s = 0; s < p; ++s) {
      const RowRange rows = stripe_rows(s, height, p);
      StripeBuffers buffers;
      buffers.width = width;
      buffers.first_row = rows.begin;
      buffers.rows = rows.end - rows.begin;
      buffers.color_format = format;
      buffers.color_address = rows.begin * width * bytes_per_pixel(format);
      buffers.depth_address = color_bytes + rows.begin * width * 4;
      stripes.emplace_back(m_memory, buffers);
    }
    for (Stripe& stripe : stripes) clear_stripe(stripe, 0xff000000u);
  }

  // The triangles in order, each split and its pieces drawn in its stripes.
  void draw(const std::vector<ScreenTriangle>& triangles) {
    for (const ScreenTriangle& t : triangles) {
      CollectingSink sink;
      split_triangle(t, height, static_cast<unsigned>(stripes.size()), sink, &counters);
      for (const Piece& piece : sink.pieces) rasterize_trapezoid(piece.trapezoid, stripes[piece.stripe]);
    }
  }

  uint32_t color(unsigned i, unsigned r) const {
    const unsigned bytes = bytes_per_pixel(stripes[0].buffers().color_format);
    return load_pixel(stripes[0].buffers().color_format, m_bytes.data() + (std::size_t{r} * width + i) * bytes);
  }
  uint32_t depth(unsigned i, unsigned r) const {
    const uint8_t* p = m_bytes.data() +
                       std::size_t{width} * height * bytes_per_pixel(stripes[0].buffers().color_format) +
                       (std::size_t{r} * width + i) * 4;
    return uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
  }
  const std::vector<uint8_t>& bytes() const { return m_bytes; }

  unsigned width, height;
  std::vector<Stripe> stripes;
  WorkCounters counters;

 private:
  std::vector<uint8_t> m_bytes;
  ArrayMemory m_memory;
};

}  // namespace tessera::cluster::testing
