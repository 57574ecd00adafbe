// resample_chain.s, Eq. 6 after van Sinten's own mapping (each CU of a row a
// different border, the window's sums passed down the row's chain, the H
// table in the lookup table), run on the array's functional core with
// delayed execution, the row ring, nadds/nadcs and lut: every output pixel
// bit for bit what step_borders and resample_line compute, for the box and
// the tent of every width, on random lines (one or many rounds, the last
// border in every column) and on the rows and columns of a warp; the lines
// it refuses; the cycles a texel takes.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <random>
#include <vector>

#include "ap_programs/resample_chain.h"
#include "array/core/array_controller.h"
#include "forward_texture/array_chain.h"
#include "forward_texture/matrix.h"
#include "forward_texture/resample_line.h"
#include "forward_texture_test_support.h"

namespace tessera::forward_texture {
namespace {

using testing::to_fixed;

struct Line {
  LineMapping mapping;
  std::vector<q8_8> texels;
};

struct Batch {
  std::vector<std::vector<q8_8>> pixels;  // per line
  std::vector<bool> flagged;              // a CU flagged an error on the line
  uint64_t cycles = 0;
  std::array<uint64_t, ap::STAGE_COUNT> stage_cycles{};
};

constexpr unsigned LUT_ENTRIES = PHASES * MAX_FILTER_WIDTH;

ChainGeometry chain_geometry() {
  const ap::ArrayGeometry grid;
  return {grid.columns, grid.rows, LUT_ENTRIES};
}

// Runs `lines` (at most one per CU row, all of the same length) through the
// program on an array with the Image Blender's features, K = 1.
Batch run_on_array(const std::vector<Line>& lines, const FilterTable& table, int pixel_count,
                   const ap::CycleTable& cycles = ap::CycleTable::defaults()) {
  const ap::Program& program = ap::programs::resample_chain();
  const ArrayChainLayout layout = ArrayChainLayout::of(program);
  const ChainGeometry geometry = chain_geometry();
  const int n = static_cast<int>(lines.front().texels.size());
  EXPECT_EQ(array_chain_error(layout, geometry, table, n), "");
  ap::ArrayController controller{ap::ArrayGeometry{}, cycles, 4096, uint64_t{1} << 40};
  controller.enable_ops(ap::all_enabled_ops());
  controller.set_issue_skew(1);
  ap::CuArray& array = controller.array();
  array.set_row_ring(true);
  array.set_lut_entries(LUT_ENTRIES);
  const std::vector<uint16_t> lut = chain_lut(table);
  for (unsigned index = 0; index < lut.size(); ++index) {
    array.set_lut_entry(index, lut[index]);
  }
  EXPECT_TRUE(controller.load(0, program_for_chain(program, geometry.rounds(n), table.width)));
  EXPECT_LE(lines.size(), geometry.rows);
  for (unsigned cu = 0; cu < array.lanes(); ++cu) {
    for (const CmemBlock& block : chain_filter_blocks(layout, table.width)) {
      for (std::size_t k = 0; k < block.bytes.size(); ++k) {
        array.set_cmem(cu, block.address + static_cast<unsigned>(k), block.bytes[k]);
      }
    }
  }
  std::vector<std::vector<q8_8>> texels;
  texels.reserve(lines.size());
  std::vector<ArrayLine> oriented(lines.size());
  for (std::size_t k = 0; k < lines.size(); ++k) {
    texels.push_back(lines[k].texels);
    EXPECT_TRUE(orient_line(lines[k].mapping, {texels.back().data(), n, 1}, oriented[k]));
  }
  for (const CmemRow& row : chain_rows(layout, geometry, oriented)) {
    for (unsigned cu = 0; cu < array.lanes(); ++cu) {
      array.set_cmem(cu, row.address, row.per_cu[cu]);
    }
  }
  const ap::RunResult result = controller.run(ap::entry_word(program, "resample"));
  EXPECT_TRUE(result.ok) << result.error;
  Batch batch;
  batch.cycles = result.cycles;
  batch.stage_cycles = controller.activity().stage_cycles;
  const auto cmem = [&array](unsigned cu, uint16_t address) { return array.cmem(cu, address); };
  for (unsigned row = 0; row < lines.size(); ++row) {
    std::vector<q8_8> pixels(static_cast<std::size_t>(pixel_count), -1);
    batch.flagged.push_back(
        !gather_chain_line(layout, geometry, n, table.width, row, cmem, {pixels.data(), pixel_count, 1}));
    batch.pixels.push_back(pixels);
  }
  return batch;
}

// step_borders and resample_line; empty when step_borders refuses the line.
std::vector<q8_8> on_host(const Line& line, const FilterTable& table, int pixel_count) {
  const int n = static_cast<int>(line.texels.size());
  std::vector<q16_16> borders(static_cast<std::size_t>(n) + 1);
  if (!step_borders(line.mapping, n, "line", borders.data()).empty()) {
    return {};
  }
  std::vector<q8_8> texels = line.texels;
  std::vector<q8_8> pixels(static_cast<std::size_t>(pixel_count), -1);
  resample_line({texels.data(), n, 1}, borders.data(), table, {pixels.data(), pixel_count, 1});
  return pixels;
}

// As test_array_lines.cpp's: either direction, mild perspective, some
// starting left of the image or running past its end; texels unorm8 << 8
// (a row pass) or any q8_8 (a column pass's intermediate values).
std::vector<Line> random_lines(std::mt19937& random, int n, int count, int pixel_count) {
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_int_distribution<int> colour(0, 255 << 8);
  std::vector<Line> lines;
  while (static_cast<int>(lines.size()) < count) {
    const double scale = (0.1 + 0.9 * unit(random)) * (unit(random) < 0.5 ? -1.0 : 1.0);
    const double denominator = 0.6 + 0.8 * unit(random);
    const double perspective = (unit(random) - 0.5) * 0.4 / n;
    const double start =
        scale > 0 ? -4.0 + (pixel_count / 2.0) * unit(random) : pixel_count + 4.0 - (pixel_count / 2.0) * unit(random);
    Line line{
        {to_fixed(start * denominator, 20), to_fixed(scale, 20), to_fixed(denominator, 30), to_fixed(perspective, 30)},
        std::vector<q8_8>(static_cast<std::size_t>(n))};
    const bool row_pass = lines.size() % 2 == 0;
    for (q8_8& texel : line.texels) {
      texel = row_pass ? (colour(random) & 0xff00) : colour(random);
    }
    lines.push_back(line);
  }
  return lines;
}

// Runs `lines` four at a time and compares each with the host's.
int compare_with_host(const std::vector<Line>& lines, const FilterTable& table, int pixel_count,
                      const std::string& what) {
  int compared = 0;
  for (std::size_t first = 0; first < lines.size(); first += 4) {
    const std::vector<Line> batch_lines(lines.begin() + static_cast<std::ptrdiff_t>(first),
                                        lines.begin() + static_cast<std::ptrdiff_t>(std::min(first + 4, lines.size())));
    const Batch batch = run_on_array(batch_lines, table, pixel_count);
    for (std::size_t k = 0; k < batch_lines.size(); ++k) {
      const std::vector<q8_8> expected = on_host(batch_lines[k], table, pixel_count);
      EXPECT_EQ(batch.flagged[k], expected.empty()) << what << " line " << first + k;
      if (!expected.empty() && !batch.flagged[k]) {
        EXPECT_EQ(batch.pixels[k], expected) << what << " line " << first + k;
        ++compared;
      }
    }
  }
  return compared;
}

TEST(ArrayChain, RandomLinesBitExactForTheBoxAndTheTentOfEveryWidth) {
  std::mt19937 random(2210);
  const int pixel_count = 80;
  int compared = 0;
  for (const FilterKind kind : {FilterKind::box, FilterKind::tent}) {
    for (int width = 1; width <= MAX_FILTER_WIDTH; ++width) {
      const FilterTable table = make_filter_table(kind, width);
      // One round, the last border in the last column, in the first column
      // of a new round, and several rounds.
      for (const int n : {9, 22, 23, 45 + width, 100}) {
        compared += compare_with_host(
            random_lines(random, n, 4, pixel_count), table, pixel_count,
            std::string(filter_name(kind)) + " F = " + std::to_string(width) + " n = " + std::to_string(n));
      }
    }
  }
  // Most lines are minified and compared; the magnified ones are flagged.
  EXPECT_GE(compared, 200);
}

TEST(ArrayChain, ExtremeTexelsAndClampedSums) {
  const int n = 48;
  std::vector<Line> lines;
  for (const double scale : {1.0, 0.5, -1.0, -0.75}) {
    Line line{{to_fixed(scale > 0 ? 2.25 : 60.25, 20), to_fixed(scale, 20), 1 << 30, 0},
              std::vector<q8_8>(static_cast<std::size_t>(n))};
    for (int t = 0; t < n; ++t) {
      line.texels[static_cast<std::size_t>(t)] = (t % 2 == 0) ? 255 << 8 : 0;
    }
    lines.push_back(line);
  }
  for (const FilterKind kind : {FilterKind::box, FilterKind::tent}) {
    for (int width = 1; width <= 4; ++width) {
      const FilterTable table = make_filter_table(kind, width);
      const Batch batch = run_on_array(lines, table, 64);
      for (std::size_t k = 0; k < lines.size(); ++k) {
        EXPECT_FALSE(batch.flagged[k]);
        EXPECT_EQ(batch.pixels[k], on_host(lines[k], table, 64))
            << filter_name(kind) << " F = " << width << " line " << k;
      }
    }
  }
}

TEST(ArrayChain, TheRowsAndColumnsOfAPerspectiveWarp) {
  const PerspectiveMatrix m = testing::fixed_matrix(0.9, 0.15, 20.0, -0.1, 0.7, 12.0, 0.0008, 0.0012, 1.0);
  const int size = 64;
  ASSERT_EQ(matrix_error(m, size, size), "");
  std::mt19937 random(7);
  std::uniform_int_distribution<int> colour(0, 255);
  ColumnPassSetup setup;
  ASSERT_EQ(column_pass_setup(m, setup), "");
  for (const int width : {1, 2, 3, 4}) {
    for (const FilterKind kind : {FilterKind::box, FilterKind::tent}) {
      const FilterTable table = make_filter_table(kind, width);
      const std::string what = std::string(filter_name(kind)) + " F = " + std::to_string(width);
      std::vector<Line> rows;
      for (int row = 0; row < size; row += 3) {
        Line line{{}, std::vector<q8_8>(size)};
        ASSERT_EQ(row_pass_line(m, row, size, line.mapping), "");
        for (q8_8& texel : line.texels) {
          texel = colour(random) << 8;
        }
        rows.push_back(line);
      }
      EXPECT_EQ(compare_with_host(rows, table, 96, what + " rows"), static_cast<int>(rows.size()));
      std::vector<Line> columns;
      for (int column = 10; column < 10 + 90; column += 5) {
        Line line{{}, std::vector<q8_8>(size)};
        ASSERT_EQ(column_pass_line(setup, column, size, line.mapping), "");
        for (q8_8& texel : line.texels) {
          texel = colour(random) * 256 + colour(random);
        }
        columns.push_back(line);
      }
      EXPECT_EQ(compare_with_host(columns, table, 96, what + " columns"), static_cast<int>(columns.size()));
    }
  }
}

TEST(ArrayChain, FlagsWhatStepBordersRefuses) {
  // A texel wider than a pixel (x = 3 + 1.25 t), a border beyond 2^14
  // pixels (passing 16384 at t = 8), and a good line; 30 texels, two rounds.
  const int n = 30;
  std::vector<Line> lines{{{to_fixed(3.0, 20), to_fixed(1.25, 20), 1 << 30, 0}, std::vector<q8_8>(n, 100 << 8)},
                          {{to_fixed(1023.75, 20), to_fixed(0.03125, 20), 1 << 26, 0}, std::vector<q8_8>(n, 100 << 8)},
                          {{to_fixed(3.0, 20), to_fixed(0.75, 20), 1 << 30, 0}, std::vector<q8_8>(n, 100 << 8)}};
  const FilterTable table = make_filter_table(FilterKind::box, 2);
  const Batch batch = run_on_array(lines, table, 32);
  ASSERT_TRUE(on_host(lines[0], table, 32).empty());
  ASSERT_TRUE(on_host(lines[1], table, 32).empty());
  EXPECT_TRUE(batch.flagged[0]);
  EXPECT_TRUE(batch.flagged[1]);
  EXPECT_FALSE(batch.flagged[2]);
  EXPECT_EQ(batch.pixels[2], on_host(lines[2], table, 32));
}

TEST(ArrayChain, RefusesWhatTheProgramCannotRun) {
  const ArrayChainLayout layout = ArrayChainLayout::of(ap::programs::resample_chain());
  const ChainGeometry geometry = chain_geometry();
  EXPECT_EQ(layout.max_rounds, 48);
  FilterTable too_wide = make_filter_table(FilterKind::box, 2);
  too_wide.width = 9;
  EXPECT_NE(array_chain_error(layout, geometry, too_wide, 64).find("F = 9"), std::string::npos);
  ChainGeometry small_table = geometry;
  small_table.lut_entries = 256;
  EXPECT_NE(array_chain_error(layout, small_table, make_filter_table(FilterKind::tent, 2), 64).find("512 entries"),
            std::string::npos);
  EXPECT_EQ(array_chain_error(layout, small_table, make_filter_table(FilterKind::tent, 1), 64), "");
  // 48 rounds of 23 borders: 1103 texels at most.
  EXPECT_EQ(array_chain_error(layout, geometry, make_filter_table(FilterKind::box, 8), 1103), "");
  EXPECT_NE(array_chain_error(layout, geometry, make_filter_table(FilterKind::box, 8), 1104).find("49 rounds"),
            std::string::npos);
}

// The cycles a round takes (every texel CU one border), from two runs that
// differ by rounds only, on this array's cycle counts and on the Image
// Blender preset's (every instruction one cycle, mulm 2): van Sinten's 8 + F
// a texel is his PE's program; here a texel is a round.
TEST(ArrayChain, CyclesPerTexel) {
  std::mt19937 random(5);
  ap::CycleTable one_cycle = ap::CycleTable::defaults();
  for (unsigned& c : one_cycle.cycles) {
    c = c == 0 ? 0 : 1;
  }
  one_cycle.cycles[static_cast<unsigned>(ap::Opcode::op_mulm)] = 2;
  const ChainGeometry geometry = chain_geometry();
  for (const int width : {1, 2, 4, 8}) {
    const FilterTable table = make_filter_table(FilterKind::box, width);
    for (const bool preset : {false, true}) {
      const ap::CycleTable& cycles = preset ? one_cycle : ap::CycleTable::defaults();
      const int short_n = geometry.borders_per_round() - 1, long_n = 11 * geometry.borders_per_round() - 1;
      const Batch one = run_on_array(random_lines(random, short_n, 4, 64), table, 64, cycles);
      const Batch eleven = run_on_array(random_lines(random, long_n, 4, 64), table, 64, cycles);
      const uint64_t round = (eleven.cycles - one.cycles) / 10;
      EXPECT_EQ((eleven.cycles - one.cycles) % 10, 0u);
      const auto per_round = [&](ap::Stage stage) {
        const auto index = static_cast<unsigned>(stage);
        return static_cast<unsigned long long>((eleven.stage_cycles[index] - one.stage_cycles[index]) / 10);
      };
      std::printf(
          "resample_chain F = %d (%s): %llu cycles a round (a texel per CU; texcoord %llu, shade %llu, "
          "transfer %llu), %.1f per border of the array's 92; a one-round run %llu; van Sinten: 8 + F = %d\n",
          width, preset ? "Image Blender preset" : "J2210 cycles", static_cast<unsigned long long>(round),
          per_round(ap::Stage::texcoord), per_round(ap::Stage::shade), per_round(ap::Stage::transfer),
          static_cast<double>(round) / (4.0 * geometry.borders_per_round()),
          static_cast<unsigned long long>(one.cycles), 8 + width);
    }
  }
}

}  // namespace
}  // namespace tessera::forward_texture
