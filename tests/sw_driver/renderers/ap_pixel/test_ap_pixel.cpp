#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ap_programs/ap_pixel.h"
#include "array/core/array_controller.h"
#include "renderers/ap_pixel/pixel_setup.h"
#include "renderers/ap_pixel/study_reference.h"

namespace tessera::ap_pixel {
namespace {

using ap::ArrayController;
using ap::ArrayGeometry;
using ap::CuArray;
using ap::CycleTable;
using ap::RunResult;

const ap::Program& program() {
  return ap::programs::ap_pixel();
}

constexpr Attribute ALL[] = {Attribute::red, Attribute::green, Attribute::blue, Attribute::alpha,
                             Attribute::s,   Attribute::t,     Attribute::z};

gl::Triangle triangle(int x0, int y0, int x1, int y1, int x2, int y2) {
  gl::Triangle t{};
  const int xy[3][2] = {{x0, y0}, {x1, y1}, {x2, y2}};
  for (unsigned i = 0; i < 3; ++i) {
    t.v[i].x = xy[i][0];
    t.v[i].y = xy[i][1];
    t.v[i].z = 0x400000u * (i + 1);
    t.v[i].r = static_cast<uint8_t>(100 * i);
    t.v[i].g = static_cast<uint8_t>(255 - 100 * i);
    t.v[i].b = 77;
    t.v[i].a = 255;
    t.v[i].tex[0].s = 0.5f * static_cast<float>(i);
    t.v[i].tex[0].t = 1.0f - 0.25f * static_cast<float>(i);
    t.v[i].inv_w = 1;
  }
  return t;
}

// Whether pixel (i, j)'s centre is inside, by the rule written in
// arm_rasterizer.h: sample at (i + 0.5 + e, j + 0.5 - e^2) for a tiny e,
// evaluated exactly in rationals (sixteenths scaled by 2^20).
bool inside_brute_force(const gl::Triangle& t, int i, int j) {
  const int64_t s = int64_t{1} << 20;
  const int64_t px = (16 * int64_t{i} + 8) * s + 1, py = (16 * int64_t{j} + 8) * s;
  __extension__ typedef __int128 Wide;
  Wide e[3];
  for (unsigned k = 0; k < 3; ++k) {
    const gl::ScreenVertex &a = t.v[k], &b = t.v[(k + 1) % 3];
    e[k] = Wide{px - int64_t{a.x} * s} * (int64_t{b.y} - a.y) - Wide{py - int64_t{a.y} * s} * (int64_t{b.x} - a.x);
    // py - tiny^2: a second-order nudge below, applied as a tie-break.
    if (e[k] == 0) e[k] = Wide{int64_t{b.x} - a.x};  // d/dy of -(y)(dx) with y lowered
  }
  return (e[0] > 0 && e[1] > 0 && e[2] > 0) || (e[0] < 0 && e[1] < 0 && e[2] < 0);
}

// The program, for every block size, on 96 CUs with random triangle values
// and block offsets written as the host writes them, leaves in every CU's
// results what the reference computes, byte for byte, and writes nothing
// outside its results and scratch.
TEST(ApPixelProgram, EveryBlockSizeMatchesTheReference) {
  const PixelLayout layout = PixelLayout::of(program());
  ASSERT_EQ(layout.max_block, 5u);
  ArrayGeometry geometry;
  ArrayController controller(geometry, CycleTable::defaults(), 4096, 100000000);
  ASSERT_TRUE(controller.load(0, program().words));
  CuArray& array = controller.array();
  const unsigned lanes = array.lanes();
  std::mt19937 rng(2210);
  std::uniform_int_distribution<int> offset(-128, 127), gradient(-32768, 32767);
  std::uniform_int_distribution<uint32_t> start(0, 0xffffff);
  for (unsigned k = 1; k <= 5; ++k)
    for (unsigned trial = 0; trial < 20; ++trial) {
      SCOPED_TRACE("block " + std::to_string(k) + ", trial " + std::to_string(trial));
      TriangleValues values;
      for (unsigned a = 0; a < ATTRIBUTES; ++a) {
        values.c0[a] = start(rng);
        // Small gradients half of the time: sums that stay in range too.
        const int limit = trial % 2 == 0 ? 32767 : 300;
        values.gx[a] = static_cast<int16_t>(std::clamp(gradient(rng), -limit, limit));
        values.gy[a] = static_cast<int16_t>(std::clamp(gradient(rng), -limit, limit));
      }
      for (unsigned lane = 0; lane < lanes; ++lane)
        for (unsigned a = 0; a < geometry.cmem_bytes; ++a) array.set_cmem(lane, a, 0x5a);
      for_each_value_byte(values, layout, [&](unsigned address, uint8_t byte) {
        for (unsigned lane = 0; lane < lanes; ++lane) array.set_cmem(lane, address, byte);
      });
      std::vector<int> dx(lanes), dy(lanes);
      for (unsigned lane = 0; lane < lanes; ++lane) {
        dx[lane] = offset(rng);
        dy[lane] = offset(rng);
        array.set_cmem(lane, layout.dx, static_cast<uint8_t>(dx[lane]));
        array.set_cmem(lane, layout.dy, static_cast<uint8_t>(dy[lane]));
      }
      const RunResult result = controller.run(layout.entry[k]);
      ASSERT_TRUE(result.ok) << result.error;
      for (unsigned lane = 0; lane < lanes; ++lane) {
        for (unsigned v = 0; v < k; ++v)
          for (unsigned u = 0; u < k; ++u)
            for (Attribute a : ALL) {
              const uint32_t expected = shade_reference(values, a, dx[lane], dy[lane], u, v);
              const unsigned at = layout.result(u, v, a);
              const uint32_t got = uint32_t{array.cmem(lane, at)} << 16 | uint32_t{array.cmem(lane, at + 1)} << 8 |
                                   array.cmem(lane, at + 2);
              ASSERT_EQ(got, expected) << "CU " << lane << ", pixel (" << u << ", " << v << "), attribute "
                                       << static_cast<unsigned>(a);
            }
        // Outside the block's pixels the results keep their old bytes.
        for (unsigned v = 0; v < layout.max_block; ++v) {
          for (unsigned u = 0; u < layout.max_block; ++u) {
            if (u >= k || v >= k) {
              ASSERT_EQ(array.cmem(lane, layout.result(u, v, Attribute::red)), 0x5a);
            }
          }
        }
      }
    }
}

// A bigger block costs more cycles, but less than a full evaluation per
// pixel, the neighbours coming from additions: runs `layout`'s block
// entries k = 1..5 on `controller` (its program loaded) into cycles[k] and
// checks that each costs more than the one before and less than k x k
// full evaluations.
void expect_blocks_share_the_full_evaluation(ArrayController& controller, const PixelLayout& layout,
                                             uint64_t (&cycles)[6]) {
  for (unsigned k = 1; k <= 5; ++k) {
    const RunResult result = controller.run(layout.entry[k]);
    ASSERT_TRUE(result.ok) << result.error;
    cycles[k] = result.cycles;
  }
  for (unsigned k = 2; k <= 5; ++k) {
    EXPECT_GT(cycles[k], cycles[k - 1]);
    EXPECT_LT(cycles[k], cycles[1] * k * k) << "block " << k;
  }
}

TEST(ApPixelProgram, BlocksShareTheFullEvaluation) {
  const PixelLayout layout = PixelLayout::of(program());
  ArrayController controller(ArrayGeometry{}, CycleTable::defaults(), 4096, 100000000);
  ASSERT_TRUE(controller.load(0, program().words));
  uint64_t cycles[6] = {};
  expect_blocks_share_the_full_evaluation(controller, layout, cycles);
}

// The study program, for every block size and for the shading test's
// entries (one pixel, 1 to 7 attributes), on 96 CUs whose CMEM starts as
// random bytes, with random values and offsets written as the host writes
// them: every CMEM byte of every CU equals what the reference leaves in a
// copy of that CU's CMEM, and the results are the planes modulo 2^16.
TEST(ApPixelStudyProgram, EveryEntryMatchesTheReferenceByteForByte) {
  const PixelLayout layout = PixelLayout::of(ProgramVariant::study);
  ASSERT_EQ(layout.max_block, 5u);
  ASSERT_EQ(layout.value_bytes, 2u);
  ArrayGeometry geometry;
  ArrayController controller(geometry, CycleTable::defaults(), 4096, 100000000);
  ASSERT_TRUE(controller.load(0, program_of(ProgramVariant::study).words));
  CuArray& array = controller.array();
  const unsigned lanes = array.lanes();
  std::mt19937 rng(2008);
  std::uniform_int_distribution<int> offset(-128, 127), gradient(-32768, 32767), byte(0, 255);
  std::uniform_int_distribution<uint32_t> start(0, 0xffffff);
  struct Run {
    unsigned block, attributes, entry;
  };
  std::vector<Run> runs;
  for (unsigned k = 1; k <= 5; ++k) runs.push_back({k, ATTRIBUTES, layout.entry[k]});
  for (unsigned n = 1; n <= ATTRIBUTES; ++n) runs.push_back({1, n, layout.shade_entry[n]});
  for (const Run& run : runs)
    for (unsigned trial = 0; trial < 8; ++trial) {
      SCOPED_TRACE("block " + std::to_string(run.block) + ", " + std::to_string(run.attributes) +
                   " attributes, trial " + std::to_string(trial));
      TriangleValues values;
      for (unsigned a = 0; a < ATTRIBUTES; ++a) {
        values.c0[a] = start(rng);
        const int limit = trial % 2 == 0 ? 32767 : 300;
        values.gx[a] = static_cast<int16_t>(std::clamp(gradient(rng), -limit, limit));
        values.gy[a] = static_cast<int16_t>(std::clamp(gradient(rng), -limit, limit));
      }
      std::vector<std::vector<uint8_t>> before(lanes, std::vector<uint8_t>(geometry.cmem_bytes));
      for (unsigned lane = 0; lane < lanes; ++lane)
        for (unsigned a = 0; a < geometry.cmem_bytes; ++a) array.set_cmem(lane, a, static_cast<uint8_t>(byte(rng)));
      for_each_value_byte(
          values, layout,
          [&](unsigned address, uint8_t value) {
            for (unsigned lane = 0; lane < lanes; ++lane) array.set_cmem(lane, address, value);
          },
          run.attributes);
      std::vector<int> dx(lanes), dy(lanes);
      for (unsigned lane = 0; lane < lanes; ++lane) {
        dx[lane] = offset(rng);
        dy[lane] = offset(rng);
        array.set_cmem(lane, layout.dx, static_cast<uint8_t>(dx[lane]));
        array.set_cmem(lane, layout.dy, static_cast<uint8_t>(dy[lane]));
        for (unsigned a = 0; a < geometry.cmem_bytes; ++a) before[lane][a] = array.cmem(lane, a);
      }
      const RunResult result = controller.run(run.entry);
      ASSERT_TRUE(result.ok) << result.error;
      for (unsigned lane = 0; lane < lanes; ++lane) {
        std::vector<uint8_t> expected = before[lane];
        run_study_reference(layout, run.block, run.attributes, expected.data());
        for (unsigned a = 0; a < geometry.cmem_bytes; ++a)
          ASSERT_EQ(array.cmem(lane, a), expected[a]) << "CU " << lane << ", CMEM byte " << a;
        // The planes themselves, modulo 2^16 (the 16.8 sum's low bits).
        for (unsigned v = 0; v < run.block; ++v)
          for (unsigned u = 0; u < run.block; ++u)
            for (unsigned a = 0; a < run.attributes; ++a) {
              const unsigned at = layout.result(u, v, static_cast<Attribute>(a));
              const unsigned got = unsigned{array.cmem(lane, at)} << 8 | array.cmem(lane, at + 1);
              ASSERT_EQ(got, shade_reference(values, static_cast<Attribute>(a), dx[lane], dy[lane], u, v) & 0xffffu)
                  << "CU " << lane << ", pixel (" << u << ", " << v << "), attribute " << a;
            }
      }
    }
}

// The study program's cycles: each attribute costs the same, a bigger
// block more, but less than a full evaluation per pixel; the shading
// test's entry for all seven attributes is block1.
TEST(ApPixelStudyProgram, CyclesFollowTheWork) {
  const PixelLayout study = PixelLayout::of(ProgramVariant::study);
  ArrayController controller(ArrayGeometry{}, CycleTable::defaults(), 4096, 100000000);
  ASSERT_TRUE(controller.load(0, program_of(ProgramVariant::study).words));
  uint64_t cycles[6] = {}, shade[ATTRIBUTES + 1] = {};
  expect_blocks_share_the_full_evaluation(controller, study, cycles);
  if (HasFatalFailure()) return;
  for (unsigned n = 1; n <= ATTRIBUTES; ++n) {
    const RunResult result = controller.run(study.shade_entry[n]);
    ASSERT_TRUE(result.ok) << result.error;
    shade[n] = result.cycles;
    if (n > 1) {
      EXPECT_EQ(shade[n] - shade[n - 1], shade[2] - shade[1]) << n << " attributes";
    }
  }
  EXPECT_EQ(shade[ATTRIBUTES], cycles[1]);
}

// The study program's CMEM: its variables, all of them, below the tuned
// program's extent (8.8 values, no sign bytes), and the 4 KB of a CU.
TEST(ApPixelStudyProgram, UsesLessCmemThanTuned) {
  const PixelLayout study = PixelLayout::of(ProgramVariant::study), tuned = PixelLayout::of(ProgramVariant::tuned);
  unsigned sizes = 0;
  for (const auto& [name, variable] : program_of(ProgramVariant::study).variables) sizes += variable.size;
  EXPECT_EQ(study.cmem_bytes, sizes) << "the study program's variables leave gaps";
  EXPECT_LT(study.cmem_bytes, tuned.cmem_bytes);
  EXPECT_LE(tuned.cmem_bytes, 4096u);
}

// ap.pixel.program's values, and a clear error naming the key and the
// allowed values for anything else.
TEST(ApPixelStudyProgram, ProgramNamesAreChecked) {
  EXPECT_EQ(program_variant("tuned"), ProgramVariant::tuned);
  EXPECT_EQ(program_variant("study"), ProgramVariant::study);
  EXPECT_STREQ(program_variant_name(ProgramVariant::study), "study");
  try {
    program_variant("fast");
    FAIL() << "accepted 'fast'";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ap.pixel.program"), std::string::npos) << what;
    EXPECT_NE(what.find("'fast'"), std::string::npos) << what;
    EXPECT_NE(what.find("tuned"), std::string::npos) << what;
    EXPECT_NE(what.find("study"), std::string::npos) << what;
  }
}

// The host's coverage is the fill rule exactly: against a brute-force test
// of every pixel, for random triangles of every size and winding.
TEST(ApPixelCoverage, SpansAreTheFillRule) {
  std::mt19937 rng(96);
  std::uniform_int_distribution<int> x(-16 * 20, 16 * 212), y(-16 * 20, 16 * 164), small(-16 * 6, 16 * 6);
  const PixelBox box{0, 0, 191, 143};
  for (unsigned n = 0; n < 400; ++n) {
    gl::Triangle t = triangle(x(rng), y(rng), x(rng), y(rng), x(rng), y(rng));
    if (n % 2 == 0) {
      const int cx = x(rng), cy = y(rng);
      for (auto& v : t.v) {
        v.x = cx + small(rng);
        v.y = cy + small(rng);
      }
    }
    if (n % 7 == 0) t.v[1].y = t.v[0].y;  // horizontal edges
    if (n % 5 == 0) t.v[2].x = t.v[1].x;  // vertical edges
    const PixelTriangle setup(t, false, 0, 0, box);
    for (int j = box.y0; j <= box.y1; ++j) {
      int first = 0, last = -1;
      const bool any = setup.span(j, first, last);
      for (int i = box.x0; i <= box.x1; ++i) {
        const bool expected = inside_brute_force(t, i, j);
        const bool got = any && i >= first && i <= last;
        ASSERT_EQ(got, expected) << "triangle " << n << ", pixel (" << i << ", " << j << ")";
      }
    }
  }
}

// Two triangles sharing an edge (both windings) cover every pixel of their
// union exactly once.
TEST(ApPixelCoverage, SharedEdgesAreDrawnOnce) {
  const PixelBox box{0, 0, 191, 143};
  const gl::Triangle a = triangle(16 * 10, 16 * 10, 16 * 150 + 3, 16 * 20 + 8, 16 * 60 + 8, 16 * 130);
  const gl::Triangle b = triangle(16 * 150 + 3, 16 * 20 + 8, 16 * 180, 16 * 120, 16 * 60 + 8, 16 * 130);
  const PixelTriangle sa(a, false, 0, 0, box), sb(b, false, 0, 0, box);
  std::vector<int> count(192 * 144, 0);
  for (const PixelTriangle* s : {&sa, &sb})
    for (int j = 0; j < 144; ++j) {
      int first = 0, last = -1;
      if (s->span(j, first, last))
        for (int i = first; i <= last; ++i) ++count[j * 192 + i];
    }
  int drawn = 0;
  for (int c : count) {
    ASSERT_LE(c, 1);
    drawn += c;
  }
  EXPECT_GT(drawn, 5000);
}

// Zero-area and far-away triangles draw nothing; a triangle wholly outside
// the box, or a box narrowed by a scissor, clips the spans.
TEST(ApPixelCoverage, DegenerateAndOffScreenTriangles) {
  const PixelBox box{0, 0, 191, 143};
  EXPECT_FALSE(PixelTriangle(triangle(0, 0, 160, 160, 320, 320), false, 0, 0, box).valid());
  EXPECT_FALSE(PixelTriangle(triangle(16, 16, 16, 16, 400, 30), false, 0, 0, box).valid());
  EXPECT_FALSE(PixelTriangle(triangle(16 << 19, 0, 0, 16, 16, 0), false, 0, 0, box).valid());
  EXPECT_FALSE(
      PixelTriangle(triangle(16 * 10, -16 * 50, 16 * 100, -16 * 40, 16 * 50, -16 * 10), false, 0, 0, box).valid());
  const gl::Triangle big = triangle(-16 * 500, -16 * 500, 16 * 900, -16 * 500, 16 * 100, 16 * 900);
  const PixelBox scissor{20, 30, 39, 49};
  const PixelTriangle clipped(big, false, 0, 0, scissor);
  ASSERT_TRUE(clipped.valid());
  EXPECT_EQ(clipped.y_first(), 30);
  EXPECT_EQ(clipped.y_last(), 49);
  int first = 0, last = -1;
  ASSERT_TRUE(clipped.span(40, first, last));
  EXPECT_EQ(first, 20);
  EXPECT_EQ(last, 39);
  EXPECT_FALSE(clipped.span(29, first, last));
}

// Depth is the exact 0.24 plane at the centre, truncated to 16 bits; the
// 21 values reproduce the planes at pixel centres within the rounding of
// their gradients (half an 8.8 step per pixel of distance).
TEST(ApPixelSetup, DepthAndValuesFollowThePlanes) {
  const gl::Triangle t = triangle(16 * 5, 16 * 7, 16 * 170 + 5, 16 * 20 + 11, 16 * 80 + 3, 16 * 135 + 2);
  const PixelTriangle setup(t, false, 64, 32, PixelBox{0, 0, 191, 143});
  ASSERT_TRUE(setup.valid());
  // The plane through the vertices, in doubles, at a pixel centre.
  auto plane = [&](int i, int j, double v0, double v1, double v2) {
    const double x[3] = {t.v[0].x / 16.0, t.v[1].x / 16.0, t.v[2].x / 16.0};
    const double y[3] = {t.v[0].y / 16.0, t.v[1].y / 16.0, t.v[2].y / 16.0};
    const double det = (x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]);
    const double gx = ((v1 - v0) * (y[2] - y[0]) - (v2 - v0) * (y[1] - y[0])) / det;
    const double gy = ((v2 - v0) * (x[1] - x[0]) - (v1 - v0) * (x[2] - x[0])) / det;
    return v0 + gx * (i + 0.5 - x[0]) + gy * (j + 0.5 - y[0]);
  };
  const int ox = 90, oy = 60;
  const TriangleValues values = setup.values(ox, oy);
  for (int j = 20; j < 120; j += 7) {
    int first = 0, last = -1;
    if (!setup.span(j, first, last)) continue;
    for (int i = first; i <= last; i += 3) {
      const double z = plane(i, j, t.v[0].z, t.v[1].z, t.v[2].z);
      EXPECT_NEAR(setup.depth16(i, j), std::floor(z / 256.0), 1.0) << i << ", " << j;
      const double distance = std::abs(i - ox) + std::abs(j - oy);
      const double red = plane(i, j, t.v[0].r, t.v[1].r, t.v[2].r);
      const auto r = static_cast<int32_t>(shade_reference(values, Attribute::red, i - ox, j - oy, 0, 0));
      EXPECT_NEAR((r - 128) / 256.0, red, 0.5 + distance / 512.0) << i << ", " << j;
      const double s = plane(i, j, 0.0, 0.5 * 64, 1.0 * 64);
      const auto sv = static_cast<int32_t>(shade_reference(values, Attribute::s, i - ox, j - oy, 0, 0) << 8) >> 8;
      EXPECT_NEAR(sv / 256.0, s, 0.5 / 256 + distance / 512.0) << i << ", " << j;
    }
  }
}

// The set-up's 32-bit arithmetic (pixel_setup.cpp) against the README's
// formulas evaluated exactly in 128-bit integers, at the extremes of the
// ranges: a 512 x 512 frame, vertices at +-2^14 sixteenths, slivers a
// sixteenth wide and the frame long, depths 0 and 2^24 - 1, texture
// coordinates across 40 repeats. Spans are the pixels whose centres the
// exact edge functions put inside (top-left rule), the depth the exact
// plane truncated, the 21 values the exact planes rounded (halves up) with
// the vertices' texture coordinates in 1/4096 texel.
TEST(ApPixelSetup, SpansDepthAndValuesAreExactAtTheExtremes) {
  __extension__ typedef __int128 Exact;
  const PixelBox box{0, 0, 511, 511};
  const int limit = PixelTriangle::COORDINATE_LIMIT, w = 16 * 512;
  std::mt19937 rng(1202);
  std::uniform_int_distribution<int> sx(0, w - 1), far(-limit, limit), one(-1, 1);
  std::uniform_int_distribution<uint32_t> z(0, 0xffffff), byte(0, 255);
  std::uniform_real_distribution<float> st(-20.0f, 20.0f);
  std::vector<gl::Triangle> cases = {triangle(0, 0, w - 1, 0, w - 1, w - 1), triangle(0, 0, w - 1, w - 1, 0, w - 1),
                                     triangle(-limit, -limit, limit, -limit, -limit, limit)};
  for (unsigned n = 0; n < 24; ++n) {
    const int ax = sx(rng), ay = sx(rng), bx = sx(rng), by = sx(rng);
    cases.push_back(triangle(ax, ay, bx, by, (ax + bx) / 2 + one(rng), (ay + by) / 2 + one(rng)));  // sliver
    cases.push_back(triangle(far(rng), far(rng), far(rng), far(rng), far(rng), far(rng)));
  }
  unsigned pixels = 0;
  for (size_t c = 0; c < cases.size(); ++c) {
    gl::Triangle& t = cases[c];
    for (unsigned i = 0; i < 3; ++i) {
      t.v[i].z = c % 2 == 0 ? (i == 1 ? 0xffffffu : 0u) : z(rng);
      t.v[i].r = static_cast<uint8_t>(byte(rng));
      t.v[i].a = static_cast<uint8_t>(c % 2 == 0 ? 255 * (i % 2) : byte(rng));
      t.v[i].tex[0].s = st(rng);
      t.v[i].tex[0].t = st(rng);
    }
    const unsigned tex_w = 256, tex_h = 32;
    const PixelTriangle setup(t, false, tex_w, tex_h, box);
    const Exact x[3] = {t.v[0].x, t.v[1].x, t.v[2].x}, y[3] = {t.v[0].y, t.v[1].y, t.v[2].y};
    const Exact area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
    ASSERT_EQ(setup.valid(), area != 0 && setup.y_first() <= setup.y_last()) << "case " << c;
    if (!setup.valid()) continue;
    const auto floor_div = [](Exact n, Exact d) {
      if (d < 0) n = -n, d = -d;
      return n >= 0 ? n / d : -((-n + d - 1) / d);
    };
    // The exact edge functions, inside positive.
    const Exact sign = area > 0 ? -1 : 1;
    const auto edge = [&](unsigned e, Exact px, Exact py) {
      const unsigned n = (e + 1) % 3;
      return sign * ((px - x[e]) * (y[n] - y[e]) - (py - y[e]) * (x[n] - x[e]));
    };
    const auto owns = [&](unsigned e) {
      const unsigned n = (e + 1) % 3;
      const Exact a = sign * (y[n] - y[e]), b = -sign * (x[n] - x[e]);
      return a > 0 || (a == 0 && b < 0);
    };
    for (int j = setup.y_first(); j <= setup.y_last(); j += 5) {
      int lo = 0, hi = -1;
      const bool any = setup.span(j, lo, hi);
      int expected_lo = 1, expected_hi = 0;
      for (int i = box.x0; i <= box.x1; ++i) {
        bool in = true;
        for (unsigned e = 0; e < 3; ++e) {
          const Exact v = edge(e, 16 * i + 8, 16 * j + 8);
          in = in && (owns(e) ? v >= 0 : v > 0);
        }
        if (!in) continue;
        if (expected_lo > expected_hi) expected_lo = i;
        expected_hi = i;
        if ((i - expected_lo) % 3 == 0) {
          Exact sum = 0;
          for (unsigned e = 0; e < 3; ++e) sum += edge(e, 16 * i + 8, 16 * j + 8) * t.v[(e + 2) % 3].z;
          const Exact z24 = sum / (area < 0 ? -area : area);
          ASSERT_EQ(setup.depth16(i, j), static_cast<uint16_t>(std::clamp<Exact>(z24, 0, 0xffffff) >> 8))
              << "case " << c << ", pixel " << i << ", " << j;
          ++pixels;
        }
      }
      ASSERT_EQ(any, expected_lo <= expected_hi) << "case " << c << ", row " << j;
      if (!any) continue;
      ASSERT_EQ(lo, expected_lo) << "case " << c << ", row " << j;
      ASSERT_EQ(hi, expected_hi) << "case " << c << ", row " << j;
    }
    // The values at an origin in the frame: per attribute the plane in
    // 2^-fraction code units, at the origin's centre and per pixel.
    const int ox = sx(rng) / 16, oy = sx(rng) / 16;
    const TriangleValues got = setup.values(ox, oy);
    for (unsigned k = 0; k < ATTRIBUTES; ++k) {
      Exact v[3];
      unsigned fraction = 8;
      for (unsigned i = 0; i < 3; ++i) {
        const gl::ScreenVertex& p = t.v[i];
        const uint8_t channels[4] = {p.r, p.g, p.b, p.a};
        if (k < 4) v[i] = Exact{channels[k]} << 16;
        if (k == 6) v[i] = p.z;
        if (k == 4 || k == 5) {
          const double scaled = static_cast<double>(k == 4 ? p.tex[0].s : p.tex[0].t) * (k == 4 ? tex_w : tex_h) * 4096;
          v[i] = static_cast<Exact>(scaled < 0 ? -std::floor(-scaled + 0.5) : std::floor(scaled + 0.5));  // halves away
          fraction = 4;
        }
      }
      const Exact d1 = v[1] - v[0], d2 = v[2] - v[0];
      const Exact cx = d1 * (y[2] - y[0]) - d2 * (y[1] - y[0]), cy = d2 * (x[1] - x[0]) - d1 * (x[2] - x[0]);
      const Exact at = v[0] * area + cx * (16 * ox + 8 - x[0]) + cy * (16 * oy + 8 - y[0]);
      const Exact half = Exact{1} << (fraction - 1), unit = Exact{1} << fraction;
      const Exact c0 = floor_div(at + half * area, unit * area) + (k < 4 ? 128 : 0);
      EXPECT_EQ(got.c0[k], static_cast<uint32_t>(c0) & 0xffffffu) << "case " << c << ", attribute " << k;
      const Exact gx = floor_div(16 * cx + half * area, unit * area),
                  gy = floor_div(16 * cy + half * area, unit * area);
      EXPECT_EQ(got.clamped[k], gx > 32767 || gx < -32767 || gy > 32767 || gy < -32767) << "case " << c;
      EXPECT_EQ(got.gx[k], static_cast<int16_t>(std::clamp<Exact>(gx, -32768, 32767))) << "case " << c << ", " << k;
      EXPECT_EQ(got.gy[k], static_cast<int16_t>(std::clamp<Exact>(gy, -32768, 32767))) << "case " << c << ", " << k;
    }
  }
  EXPECT_GT(pixels, 10000u);
}

// A program that lacks what the host expects is refused, naming it.
TEST(ApPixelSetup, LayoutNamesWhatTheProgramLacks) {
  ap::Program broken = program();
  broken.variables.erase("gy");
  try {
    PixelLayout::of(broken);
    FAIL() << "accepted a program without gy";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'gy'"), std::string::npos) << e.what();
  }
  broken = program();
  broken.entries.erase("block3");
  EXPECT_THROW(PixelLayout::of(broken), std::invalid_argument);
}

}  // namespace
}  // namespace tessera::ap_pixel
