#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <vector>

#include "ap_programs/ap_tile.h"
#include "ap_programs/ap_tile_study.h"
#include "array/core/array_controller.h"
#include "renderers/ap_tile/tile_host.h"
#include "renderers/ap_tile/tile_reference.h"
#include "renderers/ap_tile/tile_setup.h"
#include "renderers/ap_tile/tile_study.h"
#include "renderers/ap_tile/tile_study_reference.h"

namespace tessera::ap_tile {
namespace {

using ap::ArrayController;
using ap::ArrayGeometry;
using ap::CuArray;
using ap::CycleTable;
using ap::RunResult;

const ap::Program& program() {
  return ap::programs::ap_tile();
}

// One CU's CMEM with the constants the host writes once (row heights, 0).
std::vector<uint8_t> fresh_cmem(const CmemLayout& layout) {
  std::vector<uint8_t> cmem(4096, 0);
  for (unsigned l = 0; l < layout.tile_height; ++l)
    cmem[layout.yc + l] = static_cast<uint8_t>(layout.tile_height - 1 - l);
  return cmem;
}

// Scratch the program keeps between rows and the reference does not.
bool scratch(unsigned address) {
  for (const char* name : {"erow", "crow", "strow"}) {
    const ap::Variable& v = program().variables.at(name);
    if (address >= v.address && address < v.address + v.size) return true;
  }
  return false;
}

gl::Triangle triangle(int x0, int y0, int x1, int y1, int x2, int y2) {
  gl::Triangle t{};
  const int xy[3][2] = {{x0, y0}, {x1, y1}, {x2, y2}};
  for (unsigned i = 0; i < 3; ++i) {
    t.v[i].x = xy[i][0];
    t.v[i].y = xy[i][1];
    t.v[i].z = 0x800000;
    t.v[i].r = t.v[i].g = t.v[i].b = t.v[i].a = 255;
    t.v[i].inv_w = 1;
  }
  return t;
}

gl::Triangle random_triangle(std::mt19937& rng, const FrameGeometry& frame) {
  std::uniform_int_distribution<int> x(-16 * 40, 16 * (static_cast<int>(frame.width()) + 40));
  std::uniform_int_distribution<int> y(-16 * 40, 16 * (static_cast<int>(frame.height()) + 40));
  std::uniform_int_distribution<int> small(-16 * 12, 16 * 12);
  std::uniform_int_distribution<uint32_t> z(0, 0xffffff), byte(0, 255);
  std::uniform_real_distribution<float> st(-2.0f, 3.0f);
  gl::Triangle t{};
  const bool tiny = byte(rng) < 128;
  const int cx = x(rng), cy = y(rng);
  for (auto& v : t.v) {
    v.x = tiny ? cx + small(rng) : x(rng);
    v.y = tiny ? cy + small(rng) : y(rng);
    v.z = z(rng);
    v.r = static_cast<uint8_t>(byte(rng));
    v.g = static_cast<uint8_t>(byte(rng));
    v.b = static_cast<uint8_t>(byte(rng));
    v.a = 255;
    v.tex[0].s = st(rng);
    v.tex[0].t = st(rng);
    v.inv_w = 1;
  }
  return t;
}

// The array program on the AC's functional core and the reference on 96
// CMEM images, driven with the same records pass after pass, stay equal
// byte for byte in every CU's CMEM.
TEST(ApTileProgram, MatchesTheReferenceBitForBit) {
  const CmemLayout layout = CmemLayout::of(program());
  const FrameGeometry frame;
  ArrayGeometry geometry;
  ArrayController controller(geometry, CycleTable::defaults(), 4096, 100000000);
  ASSERT_TRUE(controller.load(0, program().words));
  CuArray& array = controller.array();
  const unsigned lanes = array.lanes(), bytes = geometry.cmem_bytes;
  std::vector<std::vector<uint8_t>> reference(lanes, std::vector<uint8_t>(bytes));
  std::mt19937 rng(2210);
  // Random buffers to start with, the same in both, and the constants.
  for (unsigned lane = 0; lane < lanes; ++lane)
    for (unsigned a = 0; a < bytes; ++a) {
      auto value = static_cast<uint8_t>(rng());
      if (a >= layout.yc && a < layout.yc + layout.tile_height)
        value = static_cast<uint8_t>(layout.tile_height - 1 - (a - layout.yc));
      if (a == layout.zero) value = 0;
      array.set_cmem(lane, a, value);
      reference[lane][a] = value;
    }
  auto run = [&](TileStage stage) {
    const RunResult result = controller.run(program().entries.at(stage_entry(stage)));
    ASSERT_TRUE(result.ok) << result.error;
    for (unsigned lane = 0; lane < lanes; ++lane) run_reference(stage, layout, reference[lane].data());
  };
  std::vector<uint8_t> record(layout.record_bytes);
  unsigned drawn_lanes = 0;
  for (unsigned pass = 0; pass < 12; ++pass) {
    for (unsigned lane = 0; lane < lanes; ++lane) {
      DrawFlags flags;
      flags.depth_test = rng() % 4 != 0;
      flags.depth_lequal = rng() % 2 != 0;
      flags.depth_write = rng() % 4 != 0;
      flags.flat = rng() % 5 == 0;
      flags.tex = static_cast<uint8_t>(rng() % 3);
      flags.tex_width = 64;
      flags.tex_height = 32;
      const TriangleSetup setup(random_triangle(rng, frame), flags, frame);
      const TileRecord r = setup.record(lane % frame.columns, lane / frame.columns);
      drawn_lanes += r.live;
      encode_record(r, layout, record.data());
      for (unsigned b = 0; b < layout.record_bytes; ++b) {
        array.set_cmem(lane, layout.record_first + b, record[b]);
        reference[lane][layout.record_first + b] = record[b];
      }
    }
    if (pass == 5) {
      for (unsigned lane = 0; lane < lanes; ++lane)
        for (unsigned a : {layout.clear_c, static_cast<uint16_t>(layout.clear_c + 1), layout.clear_z,
                           static_cast<uint16_t>(layout.clear_z + 1)}) {
          const auto value = static_cast<uint8_t>(rng());
          array.set_cmem(lane, a, value);
          reference[lane][a] = value;
        }
      run(TileStage::clear_colour);
      run(TileStage::clear_depth);
    }
    for (TileStage stage : {TileStage::fill, TileStage::depth, TileStage::colour, TileStage::texcoord}) run(stage);
    for (unsigned lane = 0; lane < lanes; ++lane)
      for (unsigned a = 0; a < bytes; ++a)
        if (!scratch(a)) {
          ASSERT_EQ(array.cmem(lane, a), reference[lane][a]) << "pass " << pass << ", CU " << lane << ", address " << a;
        }
  }
  EXPECT_GT(drawn_lanes, 100u);  // the random triangles reached many CUs
}

// The study's program on 96 CUs against run_study_reference, every CMEM
// byte, its own variables included: random buffers, the constants the
// host writes once, 12 passes of seeded random triangles (CUs the
// triangle misses get the dead record) with clears between.
TEST(ApTileStudyProgram, MatchesTheReferenceOnEveryCmemByte) {
  const ap::Program& study = ap::programs::ap_tile_study();
  const StudyLayout layout = StudyLayout::of(study);
  const FrameGeometry frame;
  ArrayGeometry geometry;
  ArrayController controller(geometry, CycleTable::defaults(), 4096, 100000000);
  ASSERT_TRUE(controller.load(0, study.words));
  CuArray& array = controller.array();
  const unsigned lanes = array.lanes(), bytes = geometry.cmem_bytes;
  std::vector<std::vector<uint8_t>> reference(lanes, std::vector<uint8_t>(bytes));
  std::mt19937 rng(1998);
  auto set = [&](unsigned lane, unsigned a, uint8_t value) {
    array.set_cmem(lane, a, value);
    reference[lane][a] = value;
  };
  for (unsigned lane = 0; lane < lanes; ++lane) {
    for (unsigned a = 0; a < bytes; ++a) set(lane, a, static_cast<uint8_t>(rng()));
    set(lane, layout.xpos, static_cast<uint8_t>(lane % frame.columns));
    set(lane, layout.ypos, static_cast<uint8_t>(lane / frame.columns));
    set(lane, layout.one, 1);
    set(lane, layout.ff, 0xff);
    for (unsigned x = 0; x < layout.tile_width; ++x) set(lane, layout.xcounter + x, static_cast<uint8_t>(x));
    for (unsigned y = 0; y < layout.tile_height; ++y) set(lane, layout.ycounter + y, static_cast<uint8_t>(y));
  }
  auto run = [&](TileStage stage) {
    const RunResult result = controller.run(study.entries.at(stage_entry(stage)));
    ASSERT_TRUE(result.ok) << result.error;
    for (unsigned lane = 0; lane < lanes; ++lane) run_study_reference(stage, layout, reference[lane].data());
  };
  auto compare = [&](const char* after, unsigned pass) {
    for (unsigned lane = 0; lane < lanes; ++lane)
      for (unsigned a = 0; a < bytes; ++a)
        ASSERT_EQ(array.cmem(lane, a), reference[lane][a])
            << "pass " << pass << " after " << after << ", CU " << lane << ", address " << a;
  };
  std::vector<uint8_t> record(layout.record_bytes);
  unsigned drawn_lanes = 0, drawn_pixels = 0;
  for (unsigned pass = 0; pass < 12; ++pass) {
    for (unsigned lane = 0; lane < lanes; ++lane) {
      DrawFlags flags;
      flags.depth_test = true;
      flags.flat = rng() % 5 == 0;
      flags.tex = static_cast<uint8_t>(rng() % 3);
      flags.tex_width = 64;
      flags.tex_height = 32;
      const TriangleSetup setup(random_triangle(rng, frame), flags, frame);
      const StudyRecord r = setup.study_record(lane % frame.columns, lane / frame.columns);
      drawn_lanes += r.live;
      encode_study_record(r, layout, record.data());
      for (unsigned b = 0; b < layout.record_bytes; ++b) set(lane, layout.record_first + b, record[b]);
    }
    if (pass % 4 == 0) {
      for (unsigned lane = 0; lane < lanes; ++lane)
        for (unsigned a : {layout.clear_rg, static_cast<uint16_t>(layout.clear_rg + 1), layout.clear_b, layout.clear_z,
                           static_cast<uint16_t>(layout.clear_z + 1)})
          set(lane, a, static_cast<uint8_t>(rng()));
      run(TileStage::clear_colour);
      run(TileStage::clear_depth);
      compare("the clears", pass);
    }
    for (TileStage stage : {TileStage::fill, TileStage::depth, TileStage::colour, TileStage::texcoord}) {
      run(stage);
      compare(stage_entry(stage), pass);
    }
    for (unsigned lane = 0; lane < lanes; ++lane)
      for (unsigned x = 0; x < layout.tile_width; ++x)
        for (unsigned y = 0; y < layout.tile_height; ++y)
          drawn_pixels += array.cmem(lane, layout.pixel(layout.we, x, y)) != 0;
  }
  EXPECT_GT(drawn_lanes, 100u);    // the random triangles reached many CUs
  EXPECT_GT(drawn_pixels, 1000u);  // and drew pixels that passed the depth test
}

// The study's fill draws exactly the tuned program's pixels: the same
// edges, reached by multiplications and steps right and down instead of
// steps left and up.
TEST(ApTileStudyProgram, FillsThePixelsTheTunedProgramFills) {
  const StudyLayout study = StudyLayout::of(ap::programs::ap_tile_study());
  const CmemLayout tuned = CmemLayout::of(program());
  const FrameGeometry frame;
  std::mt19937 rng(9);
  unsigned inside = 0;
  for (unsigned trial = 0; trial < 300; ++trial) {
    const TriangleSetup setup(random_triangle(rng, frame), DrawFlags{}, frame);
    const unsigned c = rng() % frame.columns, r = rng() % frame.rows;
    std::vector<uint8_t> a = fresh_cmem(tuned), b(4096, 0);
    b[study.one] = 1;
    for (unsigned x = 0; x < study.tile_width; ++x) b[study.xcounter + x] = static_cast<uint8_t>(x);
    for (unsigned y = 0; y < study.tile_height; ++y) b[study.ycounter + y] = static_cast<uint8_t>(y);
    encode_record(setup.record(c, r), tuned, a.data() + tuned.record_first);
    encode_study_record(setup.study_record(c, r), study, b.data() + study.record_first);
    run_reference(TileStage::fill, tuned, a.data());
    run_study_reference(TileStage::fill, study, b.data());
    for (unsigned x = 0; x < study.tile_width; ++x)
      for (unsigned y = 0; y < study.tile_height; ++y) {
        const bool drawn = a[tuned.pixel(tuned.we, x, y)] != 0;
        ASSERT_EQ(drawn, b[study.pixel(study.we, x, y)] != 0) << "trial " << trial << ", pixel " << x << ", " << y;
        inside += drawn;
      }
  }
  EXPECT_GT(inside, 500u);
}

// Every CU's CMEM holds each program's variables: the figures README.md
// gives.
TEST(ApTileStudyProgram, CmemBytesPerCu) {
  EXPECT_EQ(cmem_extent(program()), 2999u);
  EXPECT_EQ(StudyLayout::of(ap::programs::ap_tile_study()).cmem_bytes, cmem_extent(ap::programs::ap_tile_study()));
  EXPECT_EQ(cmem_extent(ap::programs::ap_tile_study()), 3315u);
}

// Every pixel the reference draws for a triangle lies in a tile the set-up
// binned it to, and a binned tile's box meets the triangle's box.
TEST(ApTileSetup, BinsEveryTileItDrawsIn) {
  const CmemLayout layout = CmemLayout::of(program());
  const FrameGeometry frame;
  std::mt19937 rng(7);
  std::vector<uint8_t> cmem = fresh_cmem(layout);
  unsigned checked = 0;
  for (unsigned n = 0; n < 300; ++n) {
    const gl::Triangle t = random_triangle(rng, frame);
    const TriangleSetup setup(t, DrawFlags{}, frame);
    const std::vector<unsigned> tiles = setup.tiles();
    for (unsigned r = 0; r < frame.rows; ++r)
      for (unsigned c = 0; c < frame.columns; ++c) {
        // The reference run with the record the tile would get if binned.
        TileRecord record = setup.record(c, r);
        const bool binned = std::find(tiles.begin(), tiles.end(), r * frame.columns + c) != tiles.end();
        EXPECT_EQ(record.live, binned);
        if (!binned) continue;
        encode_record(record, layout, cmem.data() + layout.record_first);
        run_reference(TileStage::fill, layout, cmem.data());
        ++checked;
      }
  }
  EXPECT_GT(checked, 100u);
}

// Pass scheduling and serialisation: pass p gives every CU the p-th
// triangle binned to it, in the order drawn; a flush needs as many passes
// as its busiest CU has triangles. Twelve small triangles stacked in tile
// (3, 1), one in tile (20, 2) and one covering the frame: the stacked tile
// serialises 13 passes, the others take 1 or 2.
TEST(ApTileBins, PassesAreTheBusiestCusTrianglesInOrder) {
  const FrameGeometry frame;
  TileBins bins(frame.cus());
  std::vector<gl::Triangle> drawn;
  drawn.reserve(14);
  auto pixel = [](int x) { return 16 * x; };
  // Tile (3, 1): pixels x 24..31, display rows 36..71 (GL y 72..107).
  for (int k = 0; k < 12; ++k)
    drawn.push_back(triangle(pixel(25), pixel(80 + k), pixel(30), pixel(80 + k), pixel(27), pixel(90 + k)));
  drawn.push_back(triangle(pixel(161), pixel(40), pixel(166), pixel(40), pixel(163), pixel(50)));       // tile (20, 2)
  drawn.push_back(triangle(-pixel(400), -pixel(400), pixel(800), -pixel(400), pixel(96), pixel(800)));  // every tile
  std::vector<TriangleSetup> setups;
  setups.reserve(drawn.size());
  for (const gl::Triangle& t : drawn) setups.emplace_back(t, DrawFlags{}, frame);
  for (const TriangleSetup& setup : setups) bins.add(setup, setup.tiles());
  const unsigned stacked = 1 * frame.columns + 3, single = 2 * frame.columns + 20, other = 0;
  ASSERT_EQ(bins.passes(), 13u);
  for (size_t pass = 0; pass < 13; ++pass) {
    const TriangleSetup* got = bins.at(stacked, pass);
    ASSERT_NE(got, nullptr) << "pass " << pass;
    // The p-th triangle drawn into the tile (the twelve, then the full
    // frame's): the same edges.
    const size_t expected = pass < 12 ? pass : 13;
    EXPECT_EQ(got->edges()[0].py, setups[expected].edges()[0].py) << "pass " << pass;
    EXPECT_EQ(got->edges()[0].px, setups[expected].edges()[0].px) << "pass " << pass;
  }
  EXPECT_EQ(bins.at(stacked, 13), nullptr);
  ASSERT_NE(bins.at(single, 0), nullptr);
  EXPECT_EQ(bins.at(single, 0)->edges()[0].px, setups[12].edges()[0].px);
  ASSERT_NE(bins.at(single, 1), nullptr);  // then the full-frame triangle
  EXPECT_EQ(bins.at(single, 1)->edges()[0].px, setups[13].edges()[0].px);
  EXPECT_EQ(bins.at(single, 2), nullptr);
  ASSERT_NE(bins.at(other, 0), nullptr);
  EXPECT_EQ(bins.at(other, 1), nullptr);
  bins.clear();
  EXPECT_EQ(bins.passes(), 0u);
}

// Pixel centres decide coverage as in the arm back end (top-left rule):
// two triangles sharing an edge draw every pixel of their union exactly
// once, and a pixel well inside (or outside) is drawn (or not).
TEST(ApTileSetup, SharedEdgesDrawEveryPixelOnce) {
  const CmemLayout layout = CmemLayout::of(program());
  const FrameGeometry frame;
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> x(0, 16 * static_cast<int>(frame.width())),
      y(0, 16 * static_cast<int>(frame.height()));
  std::vector<uint8_t> cmem = fresh_cmem(layout);
  for (unsigned n = 0; n < 40; ++n) {
    const int ax = x(rng), ay = y(rng), bx = x(rng), by = y(rng), cx = x(rng), cy = y(rng), dx = x(rng), dy = y(rng);
    // a-b is the shared edge; c and d on opposite sides of it.
    const auto side = [&](int px, int py) {
      return static_cast<int64_t>(bx - ax) * (py - ay) - static_cast<int64_t>(by - ay) * (px - ax);
    };
    if (side(cx, cy) == 0 || side(dx, dy) == 0 || (side(cx, cy) > 0) == (side(dx, dy) > 0)) continue;
    const TriangleSetup first(triangle(ax, ay, bx, by, cx, cy), DrawFlags{}, frame);
    const TriangleSetup second(triangle(bx, by, ax, ay, dx, dy), DrawFlags{}, frame);
    std::vector<int> count(size_t{frame.width()} * frame.height(), 0);
    for (const TriangleSetup* setup : {&first, &second})
      for (unsigned tile : setup->tiles()) {
        const unsigned c = tile % frame.columns, r = tile / frame.columns;
        encode_record(setup->record(c, r), layout, cmem.data() + layout.record_first);
        run_reference(TileStage::fill, layout, cmem.data());
        for (unsigned tx = 0; tx < frame.tile_width; ++tx)
          for (unsigned l = 0; l < frame.tile_height; ++l)
            if (cmem[layout.pixel(layout.we, tx, l)] != 0)
              ++count[size_t{r * frame.tile_height + l} * frame.width() + c * frame.tile_width + tx];
      }
    // Every pixel of the quadrilateral's inside (by exact distance) is drawn
    // exactly once, and no pixel twice.
    for (unsigned row = 0; row < frame.height(); ++row)
      for (unsigned column = 0; column < frame.width(); ++column) {
        const int n_drawn = count[size_t{row} * frame.width() + column];
        ASSERT_LE(n_drawn, 1) << "pixel " << column << ", " << row << " drawn twice";
      }
  }
}

TEST(ApTileSetup, DegenerateAndOffScreenTrianglesReachNoCu) {
  const FrameGeometry frame;
  EXPECT_FALSE(TriangleSetup(triangle(0, 0, 160, 160, 320, 320), DrawFlags{}, frame).valid());
  const TriangleSetup off(triangle(-1600, -1600, -800, -1600, -800, -800), DrawFlags{}, frame);
  EXPECT_TRUE(off.valid());
  EXPECT_TRUE(off.tiles().empty());
  EXPECT_FALSE(TriangleSetup(triangle(0, 0, 1 << 23, 0, 0, 160), DrawFlags{}, frame).valid());
}

// A small triangle in one tile reaches that CU only; the full frame's two
// triangles reach all 96.
TEST(ApTileSetup, BinsSmallAndFullFrameTriangles) {
  const FrameGeometry frame;
  // Pixels 1..6 of tile (2, 3): x 17..22, GL rows 1..6 (the bottom tile row).
  const TriangleSetup small(triangle(16 * 17, 16 * 1, 16 * 22, 16 * 1, 16 * 17, 16 * 6), DrawFlags{}, frame);
  EXPECT_EQ(small.tiles(), std::vector<unsigned>{3 * frame.columns + 2});
  const int w = 16 * static_cast<int>(frame.width()), h = 16 * static_cast<int>(frame.height());
  const TriangleSetup lower(triangle(0, 0, w, 0, w, h), DrawFlags{}, frame);
  const TriangleSetup upper(triangle(0, 0, w, h, 0, h), DrawFlags{}, frame);
  std::vector<bool> reached(frame.cus(), false);
  for (const TriangleSetup* s : {&lower, &upper})
    for (unsigned tile : s->tiles()) reached[tile] = true;
  EXPECT_EQ(std::count(reached.begin(), reached.end(), true), static_cast<long>(frame.cus()));
}

// The set-up's 32-bit arithmetic (tile_setup.cpp) against the README's
// formulas evaluated exactly in 128-bit integers here: every record field
// of every tile equals the exactly rounded value, at the extremes of the ranges: the largest frame
// (512 x 504), vertices at +-2^14, slivers one sixteenth wide and a pixel
// long or the frame long, depths 0 and 2^24 - 1, colours 0 and 255.
__extension__ typedef __int128 Exact;

int64_t exact_round(Exact n, Exact d) {
  if (d < 0) n = -n, d = -d;
  return static_cast<int64_t>((n >= 0 ? n + d / 2 : n - d / 2) / d);
}

struct ExactPlane {
  Exact v[3];
};

// value * area at (x16, y16): v0 area + cx (x - x0) + cy (y - y0).
Exact plane_times_area(const ExactPlane& p, const gl::Triangle& t, Exact x16, Exact y16, Exact* cx_out = nullptr,
                       Exact* cy_out = nullptr) {
  const Exact x0 = t.v[0].x, y0 = t.v[0].y, x1 = t.v[1].x, y1 = t.v[1].y, x2 = t.v[2].x, y2 = t.v[2].y;
  const Exact area = (x1 - x0) * (y2 - y0) - (y1 - y0) * (x2 - x0);
  const Exact dv1 = p.v[1] - p.v[0], dv2 = p.v[2] - p.v[0];
  const Exact cx = dv1 * (y2 - y0) - dv2 * (y1 - y0), cy = dv2 * (x1 - x0) - dv1 * (x2 - x0);
  if (cx_out) *cx_out = cx;
  if (cy_out) *cy_out = cy;
  return p.v[0] * area + cx * (x16 - x0) + cy * (y16 - y0);
}

void expect_exact_records(const gl::Triangle& t, const DrawFlags& flags, const FrameGeometry& frame, const char* what,
                          unsigned& records) {
  const TriangleSetup setup(t, flags, frame);
  const Exact x[3] = {t.v[0].x, t.v[1].x, t.v[2].x}, y[3] = {t.v[0].y, t.v[1].y, t.v[2].y};
  const Exact area = (x[1] - x[0]) * (y[2] - y[0]) - (y[1] - y[0]) * (x[2] - x[0]);
  ASSERT_EQ(setup.valid(), area != 0) << what;
  if (area == 0) return;
  const int sign = area > 0 ? -1 : 1;
  const std::vector<unsigned> tiles = setup.tiles();
  for (unsigned r = 0; r < frame.rows; ++r)
    for (unsigned c = 0; c < frame.columns; ++c) {
      const Exact cx16 = 16 * Exact((c + 1) * frame.tile_width - 1) + 8;
      const Exact cy16 = 16 * Exact(frame.height() - (r + 1) * frame.tile_height) + 8;
      // Edges: the exact value at the corner pixel, rounded, and the
      // rounded normalised coefficients.
      int64_t e0[3], du[3], dv[3];
      bool reached = true, inside[3];
      for (unsigned i = 0; i < 3; ++i) {
        const unsigned n = (i + 1) % 3;
        const Exact dx = x[n] - x[i], dy = y[n] - y[i];
        const Exact norm = std::max(dx < 0 ? -dx : dx, dy < 0 ? -dy : dy);
        const bool top_left = sign * dy > 0 || (sign * dy == 0 && -sign * dx < 0);
        e0[i] = exact_round(32 * sign * ((cx16 - x[i]) * dy - (cy16 - y[i]) * dx), norm) - (top_left ? 0 : 1);
        du[i] = -exact_round(512 * sign * dy, norm);
        dv[i] = exact_round(-512 * sign * dx, norm);
        const int64_t lu = frame.tile_width - 1, lv = frame.tile_height - 1;
        const int64_t corners[] = {e0[i], e0[i] + lu * du[i], e0[i] + lv * dv[i], e0[i] + lu * du[i] + lv * dv[i]};
        reached = reached && *std::max_element(std::begin(corners), std::end(corners)) >= 0;
        inside[i] = *std::min_element(std::begin(corners), std::end(corners)) >= 0;
      }
      const bool binned = std::find(tiles.begin(), tiles.end(), r * frame.columns + c) != tiles.end();
      const TileRecord got = setup.record(c, r);
      ASSERT_EQ(got.live, binned) << what << ", tile " << c << "," << r;
      if (!binned) continue;
      ASSERT_TRUE(reached) << what << ", tile " << c << "," << r;
      ++records;
      for (unsigned i = 0; i < 3; ++i) {
        EXPECT_EQ(got.e0[i], inside[i] ? 0 : e0[i]) << what << ", tile " << c << "," << r << ", edge " << i;
        EXPECT_EQ(got.edu[i], inside[i] ? 0 : du[i]) << what << ", edge " << i;
        EXPECT_EQ(got.edv[i], inside[i] ? 0 : dv[i]) << what << ", edge " << i;
      }
      // Depth: z24 x 65535 / 65536 in 16.8, plus a half; colour x max /
      // 255 in 8.8, plus a half.
      Exact cx, cy;
      const ExactPlane z{{t.v[0].z, t.v[1].z, t.v[2].z}};
      const Exact z_area = plane_times_area(z, t, cx16, cy16, &cx, &cy);
      EXPECT_EQ(got.z0, static_cast<uint32_t>(exact_round(z_area * 65535, area * 65536) + 128) & 0xffffffu) << what;
      EXPECT_EQ(got.zdu, static_cast<uint32_t>(exact_round(-16 * cx * 65535, area * 65536)) & 0xffffffu) << what;
      EXPECT_EQ(got.zdv, static_cast<uint32_t>(exact_round(16 * cy * 65535, area * 65536)) & 0xffffffu) << what;
      const unsigned max[3] = {31, 63, 31};
      for (unsigned k = 0; k < 3; ++k) {
        ExactPlane p{};
        for (unsigned i = 0; i < 3; ++i) {
          const gl::ScreenVertex& v = flags.flat ? t.v[2] : t.v[i];
          p.v[i] = k == 0 ? v.r : k == 1 ? v.g : v.b;
        }
        const Exact value = plane_times_area(p, t, cx16, cy16, &cx, &cy);
        EXPECT_EQ(got.c0[k], static_cast<uint16_t>(exact_round(value * max[k] * 256, area * 255) + 128)) << what;
        EXPECT_EQ(got.cdu[k], static_cast<uint16_t>(exact_round(-16 * cx * max[k] * 256, area * 255))) << what;
        EXPECT_EQ(got.cdv[k], static_cast<uint16_t>(exact_round(16 * cy * max[k] * 256, area * 255))) << what;
      }
      // Texture coordinates: the vertices in 1/4096 texel, rounded to
      // nearest, halves away from zero (renderers/common/texel_fixed.h),
      // the plane exactly, to 8.8 rounded (halves up).
      if (flags.tex != 0)
        for (unsigned k = 0; k < 2; ++k) {
          ExactPlane p{};
          const unsigned size = k == 0 ? flags.tex_width : flags.tex_height;
          for (unsigned i = 0; i < 3; ++i) {
            const float st = k == 0 ? t.v[i].tex[0].s : t.v[i].tex[0].t;
            const double scaled = static_cast<double>(st) * size * 4096;  // exact
            p.v[i] = static_cast<Exact>(scaled < 0 ? -std::floor(-scaled + 0.5) : std::floor(scaled + 0.5));
          }
          const Exact value = plane_times_area(p, t, cx16, cy16, &cx, &cy);
          const auto texel = [&](Exact numerator) {
            Exact n = numerator, d = area * 16;
            if (d < 0) n = -n, d = -d;
            n += d / 2;
            return static_cast<uint16_t>(static_cast<int64_t>(n >= 0 ? n / d : -((-n + d - 1) / d)));
          };
          EXPECT_EQ(got.st0[k], texel(value)) << what << ", tile " << c << "," << r;
          EXPECT_EQ(got.stdu[k], texel(-16 * cx)) << what;
          EXPECT_EQ(got.stdv[k], texel(16 * cy)) << what;
        }
    }
}

TEST(ApTileSetup, RecordsAreExactAtTheExtremes) {
  FrameGeometry largest;
  largest.columns = 64;  // 512 x 504: the largest frame of 8 x 36 tiles
  largest.rows = 14;
  DrawFlags flags;
  flags.tex = 1;
  flags.tex_width = 256;
  flags.tex_height = 64;
  std::mt19937 rng(2611);
  const int limit = TriangleSetup::COORDINATE_LIMIT;
  unsigned records = 0;
  for (const FrameGeometry& frame : {FrameGeometry{}, largest}) {
    const int w = 16 * static_cast<int>(frame.width()), h = 16 * static_cast<int>(frame.height());
    std::uniform_int_distribution<int> sx(0, w - 1), sy(0, h - 1), far(-limit, limit), one(-1, 1);
    std::uniform_int_distribution<uint32_t> z(0, 0xffffff), byte(0, 255);
    std::uniform_real_distribution<float> st(-40.0f, 40.0f);
    auto attributes = [&](gl::Triangle& t, bool extreme) {
      for (unsigned i = 0; i < 3; ++i) {
        gl::ScreenVertex& v = t.v[i];
        v.z = extreme ? (i == 1 ? 0xffffffu : 0u) : z(rng);
        v.r = static_cast<uint8_t>(extreme ? (i == 0 ? 255 : 0) : byte(rng));
        v.g = static_cast<uint8_t>(extreme ? (i == 1 ? 255 : 0) : byte(rng));
        v.b = static_cast<uint8_t>(extreme ? (i == 2 ? 0 : 255) : byte(rng));
        v.tex[0].s = st(rng);
        v.tex[0].t = st(rng);
      }
    };
    std::vector<std::pair<gl::Triangle, std::string>> cases;
    // The frame's two halves, the frame's corners, vertices at the limit.
    cases.emplace_back(triangle(0, 0, w - 1, 0, w - 1, h - 1), "lower half");
    cases.emplace_back(triangle(0, 0, w - 1, h - 1, 0, h - 1), "upper half");
    cases.emplace_back(triangle(-limit, -limit, limit, -limit, -limit, limit), "limit corners");
    cases.emplace_back(triangle(limit, limit, -limit, limit, limit, -limit), "limit corners, clockwise");
    for (unsigned n = 0; n < 30; ++n) {
      // Slivers: a long edge and a third vertex one sixteenth off it.
      const int ax = sx(rng), ay = sy(rng), bx = sx(rng), by = sy(rng);
      const int mx = (ax + bx) / 2 + one(rng), my = (ay + by) / 2 + one(rng);
      cases.emplace_back(triangle(ax, ay, bx, by, mx, my), "sliver");
      cases.emplace_back(triangle(ax, ay, ax + 16 + one(rng), ay + one(rng), ax + 8, ay + one(rng)), "short sliver");
      cases.emplace_back(triangle(far(rng), far(rng), far(rng), far(rng), far(rng), far(rng)), "far");
      cases.emplace_back(triangle(sx(rng), sy(rng), sx(rng), sy(rng), sx(rng), sy(rng)), "on screen");
      cases.emplace_back(triangle(ax, ay, bx, by, 2 * bx - ax, 2 * by - ay), "degenerate");
    }
    for (size_t n = 0; n < cases.size(); ++n) {
      attributes(cases[n].first, n % 2 == 0);
      flags.flat = n % 7 == 3;
      expect_exact_records(cases[n].first, flags, frame, cases[n].second.c_str(), records);
      if (HasFatalFailure()) return;
    }
  }
  EXPECT_GT(records, 5000u);  // the frames' every tile for the large triangles, and the slivers' few
}

// The record's bytes land where the program reads them, big-endian.
TEST(ApTileRecord, PacksBigEndianAtTheProgramsAddresses) {
  const CmemLayout layout = CmemLayout::of(program());
  TileRecord record;
  record.live = true;
  record.e0 = {0x1234, -2, 0};
  record.edu = {0, 0x0102, 0};
  record.edv = {0, 0, -512};
  record.z0 = 0xabcdef;
  record.c0 = {0x1f80, 0, 0};
  record.st0 = {0, 0x4321};
  record.tex = 7;
  record.zlequal = true;
  record.zwrite = false;
  std::vector<uint8_t> cmem(4096, 0x55);
  encode_record(record, layout, cmem.data() + layout.record_first);
  EXPECT_EQ(cmem[layout.live], 0xff);
  EXPECT_EQ(cmem[layout.e0], 0x12);
  EXPECT_EQ(cmem[layout.e0 + 1], 0x34);
  EXPECT_EQ(cmem[layout.e0 + 2], 0xff);
  EXPECT_EQ(cmem[layout.e0 + 3], 0xfe);
  EXPECT_EQ(cmem[layout.edu + 2], 0x01);
  EXPECT_EQ(cmem[layout.edu + 3], 0x02);
  EXPECT_EQ(cmem[layout.edv + 4], 0xfe);
  EXPECT_EQ(cmem[layout.edv + 5], 0x00);
  EXPECT_EQ(cmem[layout.z0], 0xab);
  EXPECT_EQ(cmem[layout.z0 + 1], 0xcd);
  EXPECT_EQ(cmem[layout.z0 + 2], 0xef);
  EXPECT_EQ(cmem[layout.c0], 0x1f);
  EXPECT_EQ(cmem[layout.c0 + 1], 0x80);
  EXPECT_EQ(cmem[layout.st0 + 2], 0x43);
  EXPECT_EQ(cmem[layout.st0 + 3], 0x21);
  EXPECT_EQ(cmem[layout.tex], 7);
  EXPECT_EQ(cmem[layout.zlequal], 0xff);
  EXPECT_EQ(cmem[layout.zoff], 0x00);
  EXPECT_EQ(cmem[layout.zwrite], 0x00);
  // Nothing outside the record.
  EXPECT_EQ(cmem[layout.record_first - 1], 0x55);
  EXPECT_EQ(cmem[layout.record_first + layout.record_bytes], 0x55);
  EXPECT_EQ(layout.record_bytes, 62u);
}

// A pixel centre inside by more than a twentieth of a pixel is drawn, one
// outside by as much is not: the fixed point moves edges by less.
TEST(ApTileSetup, CoverageMatchesTheExactEdgesAwayFromThem) {
  const CmemLayout layout = CmemLayout::of(program());
  const FrameGeometry frame;
  std::mt19937 rng(3);
  std::vector<uint8_t> cmem = fresh_cmem(layout);
  unsigned inside = 0;
  for (unsigned n = 0; n < 100; ++n) {
    const gl::Triangle t = random_triangle(rng, frame);
    const TriangleSetup setup(t, DrawFlags{}, frame);
    if (!setup.valid()) continue;
    for (unsigned tile : setup.tiles()) {
      const unsigned c = tile % frame.columns, r = tile / frame.columns;
      encode_record(setup.record(c, r), layout, cmem.data() + layout.record_first);
      run_reference(TileStage::fill, layout, cmem.data());
      for (unsigned tx = 0; tx < frame.tile_width; ++tx)
        for (unsigned l = 0; l < frame.tile_height; ++l) {
          const double px = 16.0 * (c * frame.tile_width + tx) + 8;
          const double py = 16.0 * (frame.height() - 1 - (r * frame.tile_height + l)) + 8;
          double nearest = 1e30;
          bool all_inside = true;
          for (unsigned i = 0; i < 3; ++i) {
            const gl::ScreenVertex &a = t.v[i], &b = t.v[(i + 1) % 3];
            const double ex = b.x - a.x, ey = b.y - a.y;
            double d = ((px - a.x) * ey - (py - a.y) * ex) / std::hypot(ex, ey) / 16.0;
            if (setup.edges()[i].sign < 0) d = -d;
            nearest = std::min(nearest, std::fabs(d));
            all_inside = all_inside && d > 0;
          }
          if (nearest < 0.05) continue;
          const bool drawn = cmem[layout.pixel(layout.we, tx, l)] != 0;
          EXPECT_EQ(drawn, all_inside) << "tile " << c << "," << r << " pixel " << tx << "," << l;
          inside += drawn;
        }
    }
  }
  EXPECT_GT(inside, 1000u);
}

}  // namespace
}  // namespace tessera::ap_tile
