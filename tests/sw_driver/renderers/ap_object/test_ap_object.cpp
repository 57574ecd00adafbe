#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "array/core/array_controller.h"
#include "array/core/pixel_port.h"
#include "array/isa/ap_isa.h"
#include "common/pixel_format.h"
#include "renderers/ap_object/object_reference.h"
#include "renderers/ap_object/object_setup.h"

namespace tessera::ap_object {
namespace {

using ap::ArrayController;
using ap::ArrayGeometry;
using ap::CuArray;
using ap::CycleTable;
using ap::RunResult;

constexpr int FRAME_W = 192, FRAME_H = 144;

gl::Triangle random_triangle(std::mt19937& rng) {
  std::uniform_int_distribution<int> x(-16 * 40, 16 * (FRAME_W + 40)), y(-16 * 40, 16 * (FRAME_H + 40));
  std::uniform_int_distribution<int> small(-16 * 12, 16 * 12), tiny(-24, 24);
  std::uniform_int_distribution<uint32_t> z(0, 0xffffff), byte(0, 255);
  gl::Triangle t{};
  const uint32_t kind = byte(rng) % 4;
  const int cx = x(rng), cy = y(rng);
  for (auto& v : t.v) {
    v.x = kind == 0 ? x(rng) : cx + (kind == 1 ? tiny(rng) : small(rng));
    v.y = kind == 0 ? y(rng) : cy + (kind == 1 ? tiny(rng) : small(rng));
    // Vertices on pixel centres and on shared heights, where the rule's ties are.
    if (byte(rng) < 64) v.x = (v.x & ~15) + 8;
    if (byte(rng) < 64) v.y = (v.y & ~15) + 8;
    v.z = z(rng);
    v.r = static_cast<uint8_t>(byte(rng));
    v.g = static_cast<uint8_t>(byte(rng));
    v.b = static_cast<uint8_t>(byte(rng));
    v.a = static_cast<uint8_t>(byte(rng));
    v.tex[0].s = std::uniform_real_distribution<float>(-2.0f, 3.0f)(rng);
    v.tex[0].t = std::uniform_real_distribution<float>(-2.0f, 3.0f)(rng);
    v.inv_w = 1;
  }
  if (byte(rng) < 40) t.v[1].y = t.v[0].y;  // a horizontal edge
  if (byte(rng) < 20) t.v[2].y = t.v[1].y;
  return t;
}

// The program with record h's row loop starting at rows[h] - 1.
std::vector<uint64_t> patched(const ap::Program& program, const ObjectLayout& layout, const unsigned rows[2]) {
  std::vector<uint64_t> words = program.words;
  for (unsigned h = 0; h < layout.units; ++h) {
    ap::Decoded decoded = ap::decode(words[layout.loop_word[h]]);
    decoded.instruction.a.value = static_cast<uint16_t>(rows[h] - 1);
    words[layout.loop_word[h]] = ap::encode(decoded.instruction);
  }
  return words;
}

// Every variant on 96 CUs against run_reference, every CMEM byte: random
// CMEM, records of random triangles' pieces (and random bytes), random row
// counts, several runs in a row.
TEST(ApObjectProgram, MatchesTheReferenceBitForBit) {
  std::mt19937 rng(2210);
  for (Unit unit : {Unit::half, Unit::triangle})
    for (unsigned span_class = 0; span_class < SPAN_CLASSES; ++span_class) {
      const ap::Program& program = program_of(unit, span_class);
      const ObjectLayout layout = ObjectLayout::of(program);
      EXPECT_EQ(layout.span, SPAN_WIDTHS[span_class]);
      EXPECT_EQ(layout.units, unit == Unit::half ? 1u : 2u);
      EXPECT_LE(layout.cmem_bytes, 4096u);
      ArrayGeometry geometry;
      ArrayController controller(geometry, CycleTable::defaults(), 4096, 100000000);
      CuArray& array = controller.array();
      const unsigned lanes = array.lanes(), bytes = geometry.cmem_bytes;
      std::vector<std::vector<uint8_t>> reference(lanes, std::vector<uint8_t>(bytes));
      for (unsigned lane = 0; lane < lanes; ++lane)
        for (unsigned a = 0; a < bytes; ++a) {
          const auto value = static_cast<uint8_t>(rng());
          array.set_cmem(lane, a, value);
          reference[lane][a] = value;
        }
      std::vector<uint8_t> record(layout.rec_bytes);
      for (unsigned run = 0; run < 3; ++run) {
        unsigned rows[2] = {1 + static_cast<unsigned>(rng() % layout.rows),
                            1 + static_cast<unsigned>(rng() % layout.rows)};
        if (run == 0) rows[0] = rows[1] = layout.rows;
        for (unsigned lane = 0; lane < lanes; ++lane)
          for (unsigned h = 0; h < layout.units; ++h) {
            if (rng() % 5 != 0) {
              const ObjectTriangle setup(random_triangle(rng), rng() % 5 == 0,
                                         PixelBox{0, 0, FRAME_W - 1, FRAME_H - 1});
              const unsigned half = static_cast<unsigned>(rng() % 2);
              if (setup.valid() && !setup.empty(half)) {
                encode_record(setup.record(half, setup.first_row(half), static_cast<int>(rng() % 3) * 8), layout,
                              record.data());
              } else {
                for (uint8_t& b : record) b = static_cast<uint8_t>(rng());
              }
            } else {
              for (uint8_t& b : record) b = static_cast<uint8_t>(rng());
            }
            for (unsigned b = 0; b < layout.rec_bytes; ++b) {
              array.set_cmem(lane, layout.record(h) + b, record[b]);
              reference[lane][layout.record(h) + b] = record[b];
            }
          }
        ASSERT_TRUE(controller.load(0, patched(program, layout, rows)));
        const RunResult result = controller.run(layout.entry);
        ASSERT_TRUE(result.ok) << result.error;
        for (unsigned lane = 0; lane < lanes; ++lane) run_reference(layout, reference[lane].data(), rows);
        for (unsigned lane = 0; lane < lanes; ++lane)
          for (unsigned a = 0; a < bytes; ++a)
            ASSERT_EQ(array.cmem(lane, a), reference[lane][a])
                << program.source_name << " W " << layout.span << " units " << layout.units << " run " << run << ", CU "
                << lane << ", address " << a;
      }
    }
}

// The exact edge test, written apart from the set-up: the triangle made
// counter-clockwise (y up), a pixel centre inside when it is left of every
// edge, or on an edge that goes down or, horizontal, goes left (the top-left
// rule: such edges are a triangle's left and top edges).
bool covered(const gl::Triangle& t, int i, int j) {
  int64_t x[3], y[3];
  for (unsigned k = 0; k < 3; ++k) {
    x[k] = t.v[k].x;
    y[k] = t.v[k].y;
  }
  const int64_t area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  if (area == 0) return false;
  if (area < 0) {
    std::swap(x[1], x[2]);
    std::swap(y[1], y[2]);
  }
  const int64_t px = 16 * i + 8, py = 16 * j + 8;
  for (unsigned k = 0; k < 3; ++k) {
    const unsigned n = (k + 1) % 3;
    const int64_t cross = (x[n] - x[k]) * (py - y[k]) - (y[n] - y[k]) * (px - x[k]);
    const bool top_left = y[n] < y[k] || (y[n] == y[k] && x[n] < x[k]);
    if (cross < 0 || (cross == 0 && !top_left)) return false;
  }
  return true;
}

// The value a plane takes at pixel (i, j)'s centre, in floating point.
double plane_at(const gl::Triangle& t, const double v[3], int i, int j) {
  const double px = 16.0 * i + 8, py = 16.0 * j + 8;
  const double x0 = t.v[0].x, y0 = t.v[0].y, x1 = t.v[1].x - x0, y1 = t.v[1].y - y0, x2 = t.v[2].x - x0,
               y2 = t.v[2].y - y0;
  const double area = x1 * y2 - y1 * x2;
  const double b1 = ((px - x0) * y2 - (py - y0) * x2) / area, b2 = ((py - y0) * x1 - (px - x0) * y1) / area;
  return v[0] + b1 * (v[1] - v[0]) + b2 * (v[2] - v[0]);
}

// Random triangles cut into pieces as the renderer cuts them, each piece's
// record run through the program's reference and its emitted pixels read
// back as the host reads them: within the box, every pixel the scalar edge
// test covers comes out exactly once, from the half whose rows hold it,
// and none else; depth and colour within one unit of the exact planes.
TEST(ApObjectSetup, EmitsExactlyTheCoveredPixels) {
  std::mt19937 rng(1998);
  unsigned pixels = 0, ties = 0;
  for (unsigned n = 0; n < 1500; ++n) {
    const gl::Triangle t = random_triangle(rng);
    PixelBox box{0, 0, FRAME_W - 1, FRAME_H - 1};
    if (n % 7 == 0) box = PixelBox{30, 20, 120, 100};
    const bool flat = n % 11 == 0;
    const ObjectTriangle setup(t, flat, box, 64, 32);
    const unsigned span_class = static_cast<unsigned>(n % SPAN_CLASSES);
    const ObjectLayout layout = ObjectLayout::of(program_of(Unit::half, span_class));
    const int w = static_cast<int>(layout.span);
    std::map<std::pair<int, int>, unsigned> emitted;
    std::vector<uint8_t> cmem(4096);
    if (setup.valid()) {
      for (unsigned h = 0; h < 2; ++h) {
        if (setup.empty(h)) continue;
        for (int j0 = setup.first_row(h); j0 <= setup.last_row(h); j0 += static_cast<int>(layout.rows)) {
          const int rows = std::min(static_cast<int>(layout.rows), setup.last_row(h) - j0 + 1);
          int widest = 0;
          for (int j = j0; j < j0 + rows; ++j) widest = std::max(widest, setup.right(h, j) - setup.left(h, j) + 1);
          for (int offset = 0; offset < widest; offset += w) {
            encode_record(setup.record(h, j0, offset), layout, cmem.data() + layout.record(0));
            const unsigned loop_rows[2] = {static_cast<unsigned>(rows), 1};
            run_reference(layout, cmem.data(), loop_rows);
            for (int r = 0; r < rows; ++r) {
              const unsigned l = static_cast<unsigned>(rows - 1 - r);
              const auto xl =
                  static_cast<int16_t>(cmem[layout.row_plane(0, 0, l)] << 8 | cmem[layout.row_plane(0, 1, l)]);
              const auto xr =
                  static_cast<int16_t>(cmem[layout.row_plane(0, 2, l)] << 8 | cmem[layout.row_plane(0, 3, l)]);
              const int j = j0 + r;
              for (int p = 0; p < w; ++p) {
                const int x = xl + offset + p;
                if (x > xr) break;
                if (x < box.x0 || x > box.x1) continue;
                ++emitted[{x, j}];
                ASSERT_TRUE(j >= setup.first_row(h) && j <= setup.last_row(h));
                const auto top = cmem[layout.slot(0, static_cast<unsigned>(p), 0, l)];
                const unsigned z16 = top >= 0x80 ? 0u
                                     : top != 0  ? 0xffffu
                                                 : unsigned{cmem[layout.slot(0, static_cast<unsigned>(p), 1, l)]} << 8 |
                                                      cmem[layout.slot(0, static_cast<unsigned>(p), 2, l)];
                const double zv[3] = {double(t.v[0].z), double(t.v[1].z), double(t.v[2].z)};
                EXPECT_NEAR(double(z16), std::clamp(std::floor(plane_at(t, zv, x, j) / 256.0), 0.0, 65535.0), 1.0)
                    << "triangle " << n;
                for (unsigned k = 0; k < 4; ++k) {
                  double cv[3];
                  for (unsigned v = 0; v < 3; ++v) {
                    const gl::ScreenVertex& sv = t.v[flat ? 2 : v];
                    const uint8_t ch[4] = {sv.r, sv.g, sv.b, sv.a};
                    cv[v] = ch[k];
                  }
                  EXPECT_NEAR(double(cmem[layout.slot(0, static_cast<unsigned>(p), 3 + k, l)]), plane_at(t, cv, x, j),
                              1.0)
                      << "triangle " << n << " channel " << k;
                }
                for (unsigned k = 0; k < 2; ++k) {
                  uint32_t code = 0;
                  for (unsigned b = 0; b < 3; ++b)
                    code = code << 8 | cmem[layout.slot(0, static_cast<unsigned>(p), 7 + 3 * k + b, l)];
                  const double texels = static_cast<int32_t>(code << 8) / 65536.0;
                  double tv[3];
                  for (unsigned v = 0; v < 3; ++v) tv[v] = (k == 0 ? t.v[v].tex[0].s * 64.0 : t.v[v].tex[0].t * 32.0);
                  EXPECT_NEAR(texels, plane_at(t, tv, x, j), 0.25) << "triangle " << n << " coordinate " << k;
                }
              }
            }
          }
        }
      }
    }
    for (const auto& [xy, count] : emitted) {
      ASSERT_EQ(count, 1u) << "triangle " << n << " pixel " << xy.first << ", " << xy.second;
      ASSERT_TRUE(covered(t, xy.first, xy.second)) << "triangle " << n << " pixel " << xy.first << ", " << xy.second;
    }
    for (int j = box.y0; j <= box.y1; ++j)
      for (int i = box.x0; i <= box.x1; ++i)
        if (covered(t, i, j)) {
          ASSERT_EQ(emitted.count({i, j}), 1u) << "triangle " << n << " pixel " << i << ", " << j << " missed";
          ++pixels;
          const int64_t px = 16 * i + 8, py = 16 * j + 8;
          for (const auto& v : t.v) ties += (v.x == px || v.y == py) ? 1 : 0;
        }
  }
  EXPECT_GT(pixels, 100000u);
  EXPECT_GT(ties, 100u);  // the rule's ties were reached
}

// The scalar model of the z-buffer unit's port: every pixel sent, by lane,
// in the order each lane sends them; each taken the cycle it arrives (the
// timing is the unit's, tested in tests/zbuf).
struct SentByLane : ap::PixelPort {
  std::vector<std::vector<ZsendPixel>> lanes;
  explicit SentByLane(unsigned count) : lanes(count) {}
  ap::SendTimes send(const std::vector<ap::SentPixel>& pixels, const ap::SendArrival& arrival) override {
    ap::SendTimes times;
    for (const ap::SentPixel& p : pixels) {
      lanes[p.lane].push_back(ZsendPixel{p.x, p.y, p.z, p.colour});
      times.cycles.push_back(std::max(arrival.first, arrival.arrival(p.lane)));
    }
    return times;
  }
};

// An array controller whose zsend goes to `port`.
std::unique_ptr<ArrayController> zsend_controller(ap::PixelPort& port) {
  auto controller = std::make_unique<ArrayController>(ArrayGeometry{}, CycleTable::defaults(), 4096, 1000000000);
  ap::EnabledOps ops = ap::j2210_ops();
  ops[static_cast<unsigned>(ap::Opcode::op_zsend)] = true;
  controller->enable_ops(ops);
  controller->set_pixel_port(&port);
  return controller;
}

// Every ZSEND variant on 96 CUs against run_reference_zsend: every CMEM
// byte and every pixel each CU sends, in order; records of random
// triangles' pieces with random rows left (0 included) and random bytes,
// random row counts, several runs in a row.
TEST(ApObjectZsendProgram, MatchesTheReferenceBitForBit) {
  std::mt19937 rng(2211);
  for (Unit unit : {Unit::half, Unit::triangle})
    for (unsigned span_class = 0; span_class < SPAN_CLASSES; ++span_class) {
      const ap::Program& program = program_of(unit, span_class, ZPath::unit);
      const ObjectLayout layout = ObjectLayout::of(program);
      ASSERT_TRUE(layout.zsend);
      EXPECT_EQ(layout.span, SPAN_WIDTHS[span_class]);
      EXPECT_EQ(layout.rows, ObjectLayout::of(program_of(unit, span_class)).rows);
      EXPECT_LE(layout.cmem_bytes, 4096u);
      SentByLane port(96);
      auto controller = zsend_controller(port);
      CuArray& array = controller->array();
      const unsigned lanes = array.lanes(), bytes = 4096;
      std::vector<std::vector<uint8_t>> reference(lanes, std::vector<uint8_t>(bytes));
      for (unsigned lane = 0; lane < lanes; ++lane)
        for (unsigned a = 0; a < bytes; ++a) {
          auto value = static_cast<uint8_t>(rng());
          if (a >= layout.konst && a < layout.konst + std::size(ZSEND_KONST)) value = ZSEND_KONST[a - layout.konst];
          array.set_cmem(lane, a, value);
          reference[lane][a] = value;
        }
      std::vector<uint8_t> record(layout.rec_bytes);
      unsigned sent = 0;
      for (unsigned run = 0; run < 3; ++run) {
        unsigned rows[2] = {1 + static_cast<unsigned>(rng() % layout.rows),
                            1 + static_cast<unsigned>(rng() % layout.rows)};
        if (run == 0) rows[0] = rows[1] = layout.rows;
        for (unsigned lane = 0; lane < lanes; ++lane)
          for (unsigned h = 0; h < layout.units; ++h) {
            const ObjectTriangle setup(random_triangle(rng), rng() % 5 == 0, PixelBox{0, 0, FRAME_W - 1, FRAME_H - 1});
            const unsigned half = static_cast<unsigned>(rng() % 2);
            if (rng() % 6 != 0 && setup.valid() && !setup.empty(half)) {
              UnitRecord r = setup.record(half, setup.first_row(half), static_cast<int>(rng() % 3) * 8);
              r.y_memory = static_cast<int16_t>(FRAME_H - 1 - setup.first_row(half));
              r.rows = static_cast<uint8_t>(rng() % (rows[h] + 1));
              encode_record(r, layout, record.data());
            } else {
              for (uint8_t& b : record) b = static_cast<uint8_t>(rng());
            }
            for (unsigned b = 0; b < layout.rec_bytes; ++b) {
              array.set_cmem(lane, layout.record(h) + b, record[b]);
              reference[lane][layout.record(h) + b] = record[b];
            }
          }
        for (auto& lane : port.lanes) lane.clear();
        ASSERT_TRUE(controller->load(0, patched(program, layout, rows)));
        const RunResult result = controller->run(layout.entry);
        ASSERT_TRUE(result.ok) << result.error;
        for (unsigned lane = 0; lane < lanes; ++lane) {
          std::vector<ZsendPixel> expected;
          run_reference_zsend(layout, reference[lane].data(), rows, expected);
          ASSERT_EQ(port.lanes[lane].size(), expected.size())
              << program.source_name << " run " << run << " CU " << lane;
          for (size_t i = 0; i < expected.size(); ++i)
            ASSERT_TRUE(port.lanes[lane][i] == expected[i])
                << program.source_name << " run " << run << " CU " << lane << " pixel " << i << ": sent ("
                << port.lanes[lane][i].x << ", " << port.lanes[lane][i].y << ", z " << port.lanes[lane][i].z
                << ", colour " << port.lanes[lane][i].colour << "), expected (" << expected[i].x << ", "
                << expected[i].y << ", z " << expected[i].z << ", colour " << expected[i].colour << ")";
          sent += static_cast<unsigned>(expected.size());
        }
        for (unsigned lane = 0; lane < lanes; ++lane)
          for (unsigned a = 0; a < bytes; ++a)
            ASSERT_EQ(array.cmem(lane, a), reference[lane][a])
                << program.source_name << " run " << run << ", CU " << lane << ", address " << a;
      }
      EXPECT_GT(sent, 1000u) << program.source_name;
    }
}

// The colour's rounding on the CU: every 8-bit channel value, red, green
// and blue, packed as pack_pixel packs it (a gradient of one code a pixel
// from 0 to 255 across 32 CUs of 8 pixels).
TEST(ApObjectZsendProgram, PacksEveryChannelValueAsTheHost) {
  const ap::Program& program = program_of(Unit::half, 0, ZPath::unit);
  const ObjectLayout layout = ObjectLayout::of(program);
  SentByLane port(96);
  auto controller = zsend_controller(port);
  CuArray& array = controller->array();
  for (unsigned lane = 0; lane < array.lanes(); ++lane) {
    UnitRecord r;
    r.xl = 0;
    r.xr = 1000;
    r.rows = lane < 32 ? 1 : 0;
    r.y_memory = static_cast<int16_t>(lane);
    for (unsigned k = 0; k < 3; ++k) {
      r.c[k] = static_cast<uint16_t>(((8 * lane + 85 * k) % 256) << 8 | 0x80);
      r.cgx[k] = 0x100;
    }
    std::vector<uint8_t> bytes(layout.rec_bytes);
    encode_record(r, layout, bytes.data());
    for (unsigned b = 0; b < layout.rec_bytes; ++b) array.set_cmem(lane, layout.record(0) + b, bytes[b]);
    for (unsigned k = 0; k < std::size(ZSEND_KONST); ++k) array.set_cmem(lane, layout.konst + k, ZSEND_KONST[k]);
  }
  const unsigned rows[2] = {1, 1};
  ASSERT_TRUE(controller->load(0, patched(program, layout, rows)));
  ASSERT_TRUE(controller->run(layout.entry).ok);
  std::set<unsigned> seen;
  for (unsigned lane = 0; lane < 32; ++lane) {
    ASSERT_EQ(port.lanes[lane].size(), 8u);
    for (unsigned p = 0; p < 8; ++p) {
      uint32_t rgba = 0;
      for (unsigned k = 0; k < 3; ++k) rgba |= ((8 * lane + 85 * k + p) % 256) << (8 * k);
      seen.insert(rgba & 0xff);
      EXPECT_EQ(port.lanes[lane][p].colour, pack_pixel(PixelFormat::rgb565, rgba)) << "CU " << lane << " pixel " << p;
      EXPECT_EQ(port.lanes[lane][p].x, p);
      EXPECT_EQ(port.lanes[lane][p].y, lane);
    }
  }
  EXPECT_EQ(seen.size(), 256u);
  for (unsigned lane = 32; lane < 96; ++lane) EXPECT_TRUE(port.lanes[lane].empty()) << "CU " << lane;
}

// Random triangles cut into pieces as the renderer cuts them, run 96 at a
// time through a ZSEND variant on the array's core: within the box's rows,
// every covered pixel is sent exactly once (x outside the box is the
// unit's to clip) and nothing else, each with the depth and colour the
// host path reads from the same piece's slots (run_reference) and packs.
TEST(ApObjectZsendProgram, SendsExactlyTheCoveredPixelsAsTheHostPathDraws) {
  std::mt19937 rng(1999);
  SentByLane port(96);
  auto controller = zsend_controller(port);
  CuArray& array = controller->array();
  for (unsigned lane = 0; lane < array.lanes(); ++lane)
    for (unsigned a = 0; a < 4096; ++a) array.set_cmem(lane, a, 0);
  unsigned pixels = 0;
  for (unsigned n = 0; n < 400; ++n) {
    const gl::Triangle t = random_triangle(rng);
    const PixelBox box{0, 0, FRAME_W - 1, FRAME_H - 1};
    const ObjectTriangle setup(t, n % 11 == 0, box);
    if (!setup.valid()) continue;
    const unsigned span_class = n % SPAN_CLASSES;
    const ap::Program& program = program_of(Unit::half, span_class, ZPath::unit);
    const ObjectLayout layout = ObjectLayout::of(program), host = ObjectLayout::of(program_of(Unit::half, span_class));
    for (unsigned k = 0; k < std::size(ZSEND_KONST); ++k)
      for (unsigned lane = 0; lane < array.lanes(); ++lane) array.set_cmem(lane, layout.konst + k, ZSEND_KONST[k]);
    const int w = static_cast<int>(layout.span);
    // The pieces, and what the host path makes of each.
    std::vector<UnitRecord> pieces;
    std::map<std::pair<int, int>, ZsendPixel> expected;
    std::vector<uint8_t> cmem(4096);
    for (unsigned h = 0; h < 2; ++h) {
      if (setup.empty(h)) continue;
      for (int j0 = setup.first_row(h); j0 <= setup.last_row(h); j0 += static_cast<int>(layout.rows)) {
        const int rows = std::min(static_cast<int>(layout.rows), setup.last_row(h) - j0 + 1);
        int widest = 0;
        for (int j = j0; j < j0 + rows; ++j) widest = std::max(widest, setup.right(h, j) - setup.left(h, j) + 1);
        for (int offset = 0; offset < widest; offset += w) {
          UnitRecord r = setup.record(h, j0, offset);
          r.y_memory = static_cast<int16_t>(FRAME_H - 1 - j0);
          r.rows = static_cast<uint8_t>(rows);
          pieces.push_back(r);
          encode_record(r, host, cmem.data() + host.record(0));
          const unsigned loop_rows[2] = {static_cast<unsigned>(rows), 1};
          run_reference(host, cmem.data(), loop_rows);
          for (int row = 0; row < rows; ++row) {
            const unsigned l = static_cast<unsigned>(rows - 1 - row);
            const auto xl = static_cast<int16_t>(cmem[host.row_plane(0, 0, l)] << 8 | cmem[host.row_plane(0, 1, l)]);
            const auto xr = static_cast<int16_t>(cmem[host.row_plane(0, 2, l)] << 8 | cmem[host.row_plane(0, 3, l)]);
            for (int p = 0; p < w && xl + offset + p <= xr; ++p) {
              const auto byte = [&](unsigned b) {
                return unsigned{cmem[host.slot(0, static_cast<unsigned>(p), b, l)]};
              };
              const unsigned top = byte(0);
              const auto z = static_cast<uint16_t>(top >= 0x80 ? 0 : top != 0 ? 0xffff : byte(1) << 8 | byte(2));
              const auto colour =
                  static_cast<uint16_t>(pack_pixel(PixelFormat::rgb565, byte(3) | byte(4) << 8 | byte(5) << 16));
              const int x = xl + offset + p, y = FRAME_H - 1 - (j0 + row);
              expected[{x, y}] = ZsendPixel{static_cast<uint16_t>(x), static_cast<uint16_t>(y), z, colour};
            }
          }
        }
      }
    }
    std::map<std::pair<int, int>, unsigned> sent;
    for (size_t first = 0; first < pieces.size(); first += array.lanes()) {
      const size_t count = std::min<size_t>(array.lanes(), pieces.size() - first);
      unsigned rows[2] = {1, 1};
      std::vector<uint8_t> bytes(layout.rec_bytes);
      for (size_t i = 0; i < count; ++i) {
        rows[0] = std::max<unsigned>(rows[0], pieces[first + i].rows);
        encode_record(pieces[first + i], layout, bytes.data());
        for (unsigned b = 0; b < layout.rec_bytes; ++b)
          array.set_cmem(static_cast<unsigned>(i), layout.record(0) + b, bytes[b]);
      }
      for (auto& lane : port.lanes) lane.clear();
      ASSERT_TRUE(controller->load(0, patched(program, layout, rows)));
      ASSERT_TRUE(controller->run(layout.entry).ok);
      for (const auto& lane : port.lanes)
        for (const ZsendPixel& p : lane) {
          const int x = static_cast<int16_t>(p.x), y = static_cast<int16_t>(p.y);
          ++sent[{x, y}];
          const auto it = expected.find({x, y});
          ASSERT_TRUE(it != expected.end()) << "triangle " << n << " sent " << x << ", " << y;
          ASSERT_TRUE(it->second == p) << "triangle " << n << " pixel " << x << ", " << y << ": z " << p.z << " vs "
                                       << it->second.z << ", colour " << p.colour << " vs " << it->second.colour;
        }
    }
    ASSERT_EQ(sent.size(), expected.size()) << "triangle " << n;
    for (const auto& [xy, count] : sent) {
      ASSERT_EQ(count, 1u) << "triangle " << n << " pixel " << xy.first << ", " << xy.second;
      const int i = xy.first, j = FRAME_H - 1 - xy.second;
      ASSERT_TRUE(covered(t, i, j)) << "triangle " << n << " pixel " << i << ", " << j;
      if (i >= box.x0 && i <= box.x1) ++pixels;
    }
    for (int j = box.y0; j <= box.y1; ++j)
      for (int i = box.x0; i <= box.x1; ++i) {
        if (!covered(t, i, j)) continue;
        ASSERT_EQ(sent.count({i, FRAME_H - 1 - j}), 1u) << "triangle " << n << " pixel " << i << ", " << j << " missed";
      }
  }
  EXPECT_GT(pixels, 20000u);
}

TEST(ApObjectSetup, UnitNames) {
  EXPECT_EQ(unit_named("half"), Unit::half);
  EXPECT_EQ(unit_named("triangle"), Unit::triangle);
  EXPECT_THROW(unit_named("quad"), std::invalid_argument);
  EXPECT_EQ(zpath_named("host"), ZPath::host);
  EXPECT_EQ(zpath_named("unit"), ZPath::unit);
  EXPECT_THROW(zpath_named("zbuf"), std::invalid_argument);
}

}  // namespace
}  // namespace tessera::ap_object
