// soc_sim's progress line (tools/soc_sim/progress_line.h) without a terminal:
// it fits every width, says what matters first, and estimates the time left.
#include "progress_line.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace tessera {
namespace {

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

const std::vector<ProgressState> STATES = {
    {0, 3, 0.0, 0.0},                       // before anything ran
    {1, 3, 0.168, 0.002},                   // fast: 84 s simulated per wall second
    {355, 400, 59.7, 1.1},                  // the teapot run that used to hit the time limit
    {400, 400, 67.2, 1.2},                  // done
    {99999, 100000, 3599999.999, 86399.5},  // the longest run --frames allows, a day of wall time
};

TEST(ProgressLine, FitsEveryWidthFrom20To200WithoutReachingTheLastColumn) {
  for (const ProgressState& state : STATES)
    for (unsigned columns = 20; columns <= 200; ++columns) {
      const std::string line = progress_line(state, columns);
      SCOPED_TRACE("columns " + std::to_string(columns) + ": '" + line + "'");
      EXPECT_EQ(line.size(), columns - 1u);
      EXPECT_EQ(line.find_first_of("\r\n\t"), std::string::npos);
      EXPECT_TRUE(contains(line, "frame " + std::to_string(state.frames_done)));
    }
}

TEST(ProgressLine, NarrowAndTinyWidthsAreCutNotWrapped) {
  const ProgressState state{355, 400, 59.7, 1.1};
  EXPECT_EQ(progress_line(state, 0), "");
  EXPECT_EQ(progress_line(state, 1), "");
  EXPECT_EQ(progress_line(state, 2), "f");
  EXPECT_EQ(progress_line(state, 10), "frame 355");
  EXPECT_EQ(progress_line(state, 20), "frame 355/400      ");
}

// The line without the padding that makes it columns - 1 long.
std::string trimmed(const std::string& line) {
  return line.substr(0, line.find_last_not_of(' ') + 1);
}

TEST(ProgressLine, DropsTheBarFirstThenTheRateThenTheSimulatedTime) {
  const ProgressState state{10, 40, 2.016, 5.0};
  EXPECT_EQ(trimmed(progress_line(state, 100)),
            "[#######.......................] frame 10/40  simulated 2.016 s  403.200 ms/s  ETA 0:15");
  // 79 columns less the 54 of text, the space and the brackets: 22 cells, a quarter of them filled.
  EXPECT_EQ(trimmed(progress_line(state, 80)), "[" + std::string(5, '#') + std::string(17, '.') +
                                                   "] frame 10/40  simulated 2.016 s  403.200 ms/s  ETA 0:15");
  EXPECT_EQ(trimmed(progress_line(state, 66)), "frame 10/40  simulated 2.016 s  403.200 ms/s  ETA 0:15");
  EXPECT_EQ(trimmed(progress_line(state, 50)), "frame 10/40  simulated 2.016 s  ETA 0:15");
  EXPECT_EQ(trimmed(progress_line(state, 30)), "frame 10/40  ETA 0:15");
  EXPECT_EQ(trimmed(progress_line(state, 22)), "frame 10/40  ETA 0:15");
  EXPECT_EQ(trimmed(progress_line(state, 21)), "frame 10/40");
}

TEST(ProgressLine, BarFillsWithTheFrames) {
  const std::string empty = progress_line({0, 4, 0, 0}, 120);
  const std::string half = progress_line({2, 4, 0, 1}, 120);
  const std::string full = progress_line({4, 4, 0, 2}, 120);
  EXPECT_EQ(empty.substr(0, 32), "[" + std::string(30, '.') + "]");
  EXPECT_EQ(half.substr(0, 32), "[" + std::string(15, '#') + std::string(15, '.') + "]");
  EXPECT_EQ(full.substr(0, 32), "[" + std::string(30, '#') + "]");
}

TEST(ProgressLine, EtaIsTheAverageWallTimePerFrameTimesTheFramesLeft) {
  EXPECT_EQ(eta_text({0, 40, 0.5, 0.5}), "ETA --:--");
  EXPECT_EQ(eta_text({10, 40, 2.0, 5.0}), "ETA 0:15");
  EXPECT_EQ(eta_text({1, 2, 1.0, 65.4}), "ETA 1:05");
  EXPECT_EQ(eta_text({1, 2, 1.0, 3725.0}), "ETA 1:02:05");
  EXPECT_EQ(eta_text({40, 40, 10.0, 5.0}), "ETA 0:00");
  EXPECT_EQ(eta_text({41, 40, 10.0, 5.0}), "ETA 0:00");
}

TEST(ProgressLine, WidthComesFromTheTerminalThenColumnsThen80) {
  EXPECT_EQ(choose_columns(132, "50"), 132u);
  EXPECT_EQ(choose_columns(0, "50"), 50u);
  EXPECT_EQ(choose_columns(0, nullptr), 80u);
  EXPECT_EQ(choose_columns(0, ""), 80u);
  EXPECT_EQ(choose_columns(0, "wide"), 80u);
  EXPECT_EQ(choose_columns(0, "50x"), 80u);
  EXPECT_EQ(choose_columns(0, "-5"), 80u);
  EXPECT_EQ(choose_columns(0, "0"), 80u);
  EXPECT_EQ(choose_columns(0, "99999999999999999999"), 80u);
}

TEST(ProgressLine, FormatTimePicksTheUnit) {
  EXPECT_EQ(format_duration(2.0164), "2.016 s");
  EXPECT_EQ(format_duration(0.0123456), "12.346 ms");
  EXPECT_EQ(format_duration(0.000219), "219.000 us");
  EXPECT_EQ(format_duration(0), "0.000 us");
}

}  // namespace
}  // namespace tessera
