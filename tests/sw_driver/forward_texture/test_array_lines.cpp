// resample_lines.s, Eq. 6 on the array with one line per CU, run on the
// array's functional core (tlm/array/core): the factors computed with the
// J2210's own instructions (resample_lines), and looked up in the shared
// table (resample_lines_lut, array.features.lut, lockstep and under delayed
// execution) for the box and the tent: every output pixel bit for bit what
// step_borders and resample_line compute, on random lines and on the lines
// of whole warps; the lines and filters it refuses.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

#include "ap_programs/resample_lines.h"
#include "ap_programs/resample_lines_lut.h"
#include "array/core/array_controller.h"
#include "forward_texture/array_lines.h"
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
  std::vector<bool> flagged;              // the CU flagged an error
  uint64_t cycles = 0;
  uint64_t lut_stall_cycles = 0;
  uint64_t lookups = 0;  // lut instructions run
};

// The array a batch runs on: the J2210 computing the factors, or with the
// lookup table (2048 entries: every width up to 8) looking them up,
// lockstep or under delayed execution (array.issue_skew = lane, K = 1).
enum class Factors { computed, table, table_skewed };

constexpr unsigned TABLE_ENTRIES = PHASES * MAX_FILTER_WIDTH;

// Runs `lines` (at most one per CU, all of the same length) through the
// program on a J2210 array, or one with the lookup table.
Batch run_on_array(const std::vector<Line>& lines, const FilterTable& table, int pixel_count,
                   Factors factors = Factors::computed) {
  const bool looked_up = factors != Factors::computed;
  const ap::Program& program = looked_up ? ap::programs::resample_lines_lut() : ap::programs::resample_lines();
  const ArrayLineLayout layout = ArrayLineLayout::of(program);
  const int n = static_cast<int>(lines.front().texels.size());
  EXPECT_EQ(array_line_error(layout, table, n, looked_up ? TABLE_ENTRIES : 0), "");
  ap::ArrayController controller{ap::ArrayGeometry{}, ap::CycleTable::defaults(), 4096, uint64_t{1} << 40};
  EXPECT_TRUE(controller.load(0, program_for_lines(program, n, table.width)));
  ap::CuArray& array = controller.array();
  if (looked_up) {
    ap::EnabledOps enabled = ap::j2210_ops();
    enabled[static_cast<unsigned>(ap::Opcode::op_lut)] = true;
    controller.enable_ops(enabled);
    controller.set_issue_skew(factors == Factors::table_skewed ? 1 : 0);
    array.set_lut_entries(TABLE_ENTRIES);
    const std::vector<uint16_t> entries = lut_entries(table);
    for (std::size_t i = 0; i < entries.size(); ++i) {
      array.set_lut_entry(static_cast<unsigned>(i), entries[i]);
    }
  }
  EXPECT_LE(lines.size(), array.lanes());
  for (unsigned lane = 0; lane < array.lanes(); ++lane) {
    for (const CmemBlock& block : filter_blocks(layout, table.width)) {
      for (std::size_t k = 0; k < block.bytes.size(); ++k) {
        array.set_cmem(lane, block.address + static_cast<unsigned>(k), block.bytes[k]);
      }
    }
  }
  std::vector<std::vector<q8_8>> texels;
  std::vector<ArrayLine> oriented(lines.size());
  for (std::size_t k = 0; k < lines.size(); ++k) {
    texels.push_back(lines[k].texels);
    EXPECT_TRUE(orient_line(lines[k].mapping, {texels.back().data(), n, 1}, oriented[k]));
  }
  for (const CmemRow& row : line_rows(layout, oriented, array.lanes())) {
    for (unsigned lane = 0; lane < array.lanes(); ++lane) {
      array.set_cmem(lane, row.address, row.per_cu[lane]);
    }
  }
  const ap::RunResult result = controller.run(ap::entry_word(program, "resample"));
  EXPECT_TRUE(result.ok) << result.error;
  Batch batch;
  batch.cycles = result.cycles;
  batch.lut_stall_cycles = controller.activity().lut_stall_cycles;
  batch.lookups = controller.activity().instruction_mix[static_cast<unsigned>(ap::Opcode::op_lut)];
  std::vector<CmemRow> results;
  for (const uint16_t address : result_addresses(layout, n, table.width)) {
    CmemRow row{address, std::vector<uint8_t>(array.lanes())};
    for (unsigned lane = 0; lane < array.lanes(); ++lane) {
      row.per_cu[lane] = array.cmem(lane, address);
    }
    results.push_back(row);
  }
  for (unsigned lane = 0; lane < lines.size(); ++lane) {
    std::vector<q8_8> pixels(static_cast<std::size_t>(pixel_count), -1);
    batch.flagged.push_back(!scatter_line(n, table.width, results, lane, {pixels.data(), pixel_count, 1}));
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

// Random lines like ResampleLine.Eq6InFixedPointAgreesWithEq3WithinTheBound's:
// either direction, mild perspective, some starting left of the image or
// running past its end; texels unorm8 << 8 (a row pass) or any q8_8 (a
// column pass's intermediate values).
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

TEST(ArrayLines, RandomLinesBitExactForEveryBoxWidth) {
  std::mt19937 random(32210);
  const int pixel_count = 64;
  int compared = 0;
  for (int width = 1; width <= MAX_FILTER_WIDTH; ++width) {
    const FilterTable table = make_filter_table(FilterKind::box, width);
    const int n = 20 + 7 * width;
    const std::vector<Line> lines = random_lines(random, n, 96, pixel_count);
    const Batch batch = run_on_array(lines, table, pixel_count);
    for (std::size_t k = 0; k < lines.size(); ++k) {
      const std::vector<q8_8> expected = on_host(lines[k], table, pixel_count);
      ASSERT_EQ(batch.flagged[k], expected.empty()) << "F = " << width << " line " << k;
      if (!expected.empty()) {
        ASSERT_EQ(batch.pixels[k], expected) << "F = " << width << " line " << k;
        ++compared;
      }
    }
  }
  // Most lines are minified and compared; the magnified ones are flagged.
  EXPECT_GE(compared, 400);
}

TEST(ArrayLines, ExtremeTexelsAndClampedSums) {
  // Alternating black and white under a 2:1 and a 1:1 map: the largest
  // differences, sums that the clamp must hold at 0 and 255 << 8.
  const int n = 48;
  std::vector<Line> lines;
  for (const double scale : {1.0, 0.5, -1.0, -0.75, 0.999}) {
    Line line{{to_fixed(scale > 0 ? 2.25 : 60.25, 20), to_fixed(scale, 20), 1 << 30, 0},
              std::vector<q8_8>(static_cast<std::size_t>(n))};
    for (int t = 0; t < n; ++t) {
      line.texels[static_cast<std::size_t>(t)] = (t % 2 == 0) ? 255 << 8 : 0;
    }
    lines.push_back(line);
  }
  for (int width = 1; width <= 4; ++width) {
    const FilterTable table = make_filter_table(FilterKind::box, width);
    const Batch batch = run_on_array(lines, table, 64);
    for (std::size_t k = 0; k < lines.size(); ++k) {
      EXPECT_FALSE(batch.flagged[k]);
      EXPECT_EQ(batch.pixels[k], on_host(lines[k], table, 64)) << "F = " << width << " line " << k;
    }
  }
}

TEST(ArrayLines, TheRowsAndColumnsOfAPerspectiveWarp) {
  // The lines warp.cpp resamples for a tilted plane: the row pass's rows,
  // then columns of the column pass over random intermediate values.
  const PerspectiveMatrix m = testing::fixed_matrix(0.9, 0.15, 20.0, -0.1, 0.7, 12.0, 0.0008, 0.0012, 1.0);
  const int size = 64;
  ASSERT_EQ(matrix_error(m, size, size), "");
  std::mt19937 random(7);
  std::uniform_int_distribution<int> colour(0, 255);
  for (const int width : {1, 2, 3, 4}) {
    const FilterTable table = make_filter_table(FilterKind::box, width);
    std::vector<Line> rows;
    for (int row = 0; row < size; ++row) {
      Line line{{}, std::vector<q8_8>(size)};
      ASSERT_EQ(row_pass_line(m, row, size, line.mapping), "");
      for (q8_8& texel : line.texels) {
        texel = colour(random) << 8;
      }
      rows.push_back(line);
    }
    const Batch row_batch = run_on_array(rows, table, 96);
    for (int row = 0; row < size; ++row) {
      ASSERT_EQ(row_batch.pixels[static_cast<std::size_t>(row)],
                on_host(rows[static_cast<std::size_t>(row)], table, 96))
          << "F = " << width << " row " << row;
    }
    ColumnPassSetup setup;
    ASSERT_EQ(column_pass_setup(m, setup), "");
    std::vector<Line> columns;
    for (int column = 10; column < 10 + 90; ++column) {
      Line line{{}, std::vector<q8_8>(size)};
      ASSERT_EQ(column_pass_line(setup, column, size, line.mapping), "");
      for (q8_8& texel : line.texels) {
        texel = colour(random) * 256 + colour(random);
      }
      columns.push_back(line);
    }
    const Batch column_batch = run_on_array(columns, table, 96);
    for (std::size_t k = 0; k < columns.size(); ++k) {
      ASSERT_EQ(column_batch.pixels[k], on_host(columns[k], table, 96)) << "F = " << width << " column " << k;
    }
  }
}

TEST(ArrayLines, FlagsWhatStepBordersRefuses) {
  // A texel wider than a pixel (x = 3 + 1.25 t), and a border beyond 2^14
  // pixels (x = 16380 + 0.5 t, passing 16384 at t = 8).
  const int n = 16;
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

// The table program: the box and the tent, every width, bit for bit the
// host's, lockstep and under delayed execution; F lookups a border.
TEST(ArrayLines, TableFactorsBitExactForBoxAndTentAtEveryWidth) {
  std::mt19937 random(2210);
  const int pixel_count = 64;
  int compared = 0;
  for (const FilterKind kind : {FilterKind::box, FilterKind::tent}) {
    for (int width = 1; width <= MAX_FILTER_WIDTH; ++width) {
      const FilterTable table = make_filter_table(kind, width);
      const int n = 20 + 5 * width;
      const std::vector<Line> lines = random_lines(random, n, 96, pixel_count);
      for (const Factors factors : {Factors::table, Factors::table_skewed}) {
        const Batch batch = run_on_array(lines, table, pixel_count, factors);
        const bool skewed = factors == Factors::table_skewed;
        // One lut a factor: F a border, n + 1 borders.
        EXPECT_EQ(batch.lookups, static_cast<uint64_t>(width) * static_cast<uint64_t>(n + 1));
        if (!skewed) {
          // Lockstep, one port: every lut waits for 95 more CUs.
          EXPECT_EQ(batch.lut_stall_cycles, 95 * batch.lookups);
        }
        for (std::size_t k = 0; k < lines.size(); ++k) {
          const std::vector<q8_8> expected = on_host(lines[k], table, pixel_count);
          ASSERT_EQ(batch.flagged[k], expected.empty())
              << filter_name(kind) << " F = " << width << (skewed ? " skewed" : "") << " line " << k;
          if (!expected.empty()) {
            ASSERT_EQ(batch.pixels[k], expected)
                << filter_name(kind) << " F = " << width << (skewed ? " skewed" : "") << " line " << k;
            ++compared;
          }
        }
      }
    }
  }
  EXPECT_GE(compared, 1600);
}

TEST(ArrayLines, TableFactorsOnTheRowsAndColumnsOfAWarp) {
  // The perspective warp's lines, as TheRowsAndColumnsOfAPerspectiveWarp,
  // with the tent looked up.
  const PerspectiveMatrix m = testing::fixed_matrix(0.9, 0.15, 20.0, -0.1, 0.7, 12.0, 0.0008, 0.0012, 1.0);
  const int size = 64;
  std::mt19937 random(11);
  std::uniform_int_distribution<int> colour(0, 255);
  ColumnPassSetup setup;
  ASSERT_EQ(column_pass_setup(m, setup), "");
  for (const int width : {2, 3}) {
    const FilterTable table = make_filter_table(FilterKind::tent, width);
    std::vector<Line> rows;
    std::vector<Line> columns;
    for (int row = 0; row < size; ++row) {
      Line line{{}, std::vector<q8_8>(size)};
      ASSERT_EQ(row_pass_line(m, row, size, line.mapping), "");
      for (q8_8& texel : line.texels) {
        texel = colour(random) << 8;
      }
      rows.push_back(line);
    }
    for (int column = 10; column < 10 + 90; ++column) {
      Line line{{}, std::vector<q8_8>(size)};
      ASSERT_EQ(column_pass_line(setup, column, size, line.mapping), "");
      for (q8_8& texel : line.texels) {
        texel = colour(random) * 256 + colour(random);
      }
      columns.push_back(line);
    }
    for (const Factors factors : {Factors::table, Factors::table_skewed}) {
      for (const std::vector<Line>* lines : {&rows, &columns}) {
        const Batch batch = run_on_array(*lines, table, 96, factors);
        for (std::size_t k = 0; k < lines->size(); ++k) {
          ASSERT_EQ(batch.pixels[k], on_host((*lines)[k], table, 96)) << "F = " << width << " line " << k;
        }
      }
    }
  }
}

TEST(ArrayLines, TheTableIsTheFiltersPrimitive) {
  // Entry 256 (F - 1 - j) + phase is the table's (phase, j); for the box
  // of width 2 the entries rise by 64 (2^15 / 512) from 0.
  const FilterTable box = make_filter_table(FilterKind::box, 2);
  const std::vector<uint16_t> entries = lut_entries(box);
  ASSERT_EQ(entries.size(), 512u);
  for (int n = 0; n < 512; ++n) {
    EXPECT_EQ(entries[static_cast<std::size_t>(n)], 64 * n) << n;
  }
  const FilterTable tent = make_filter_table(FilterKind::tent, 3);
  const std::vector<uint16_t> tent_entries = lut_entries(tent);
  for (int phase = 0; phase < PHASES; ++phase) {
    for (int j = 0; j < 3; ++j) {
      EXPECT_EQ(tent_entries[static_cast<std::size_t>(PHASES * (2 - j) + phase)], tent.at(phase, j));
    }
  }
}

TEST(ArrayLines, TheTableProgramRefusesWhatItsTableCannotHold) {
  const ArrayLineLayout layout = ArrayLineLayout::of(ap::programs::resample_lines_lut());
  EXPECT_TRUE(layout.table_factors);
  EXPECT_FALSE(ArrayLineLayout::of(ap::programs::resample_lines()).table_factors);
  const FilterTable tent4 = make_filter_table(FilterKind::tent, 4);
  EXPECT_EQ(array_line_error(layout, tent4, 64, 1024), "");
  EXPECT_EQ(array_line_error(layout, tent4, 64, 1023),
            "filter width F = 4 needs 1024 lookup table entries (256 phases x F), more than array.lut.entries = "
            "1023");
  EXPECT_NE(array_line_error(layout, tent4, 64, 0).find("array.features.lut = false"), std::string::npos);
  EXPECT_EQ(array_line_error(layout, make_filter_table(FilterKind::box, 1), 64, 256), "");
  EXPECT_NE(array_line_error(layout, make_filter_table(FilterKind::box, 2), 64, 256).find("array.lut.entries = 256"),
            std::string::npos);
  FilterTable too_wide = make_filter_table(FilterKind::box, 2);
  too_wide.width = 9;
  EXPECT_NE(array_line_error(layout, too_wide, 64, 65536).find("F = 9"), std::string::npos);
}

TEST(ArrayLines, RefusesWhatTheProgramCannotRun) {
  const ArrayLineLayout layout = ArrayLineLayout::of(ap::programs::resample_lines());
  EXPECT_EQ(layout.max_texels, 512);
  EXPECT_NE(array_line_error(layout, make_filter_table(FilterKind::tent, 2), 64).find("box filter's factors only"),
            std::string::npos);
  FilterTable too_wide = make_filter_table(FilterKind::box, 2);
  too_wide.width = 9;
  EXPECT_NE(array_line_error(layout, too_wide, 64).find("F = 9"), std::string::npos);
  EXPECT_NE(array_line_error(layout, make_filter_table(FilterKind::box, 2), 513).find("513 texels"), std::string::npos);
  EXPECT_EQ(array_line_error(layout, make_filter_table(FilterKind::box, 8), 512), "");
}

}  // namespace
}  // namespace tessera::forward_texture
