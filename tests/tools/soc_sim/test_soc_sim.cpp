// System tests of soc_sim: every test runs the simulator as a subprocess in a
// fresh temporary folder and checks what a user sees -- exit status, messages
// on stdout and stderr, frames, statistics and the VCD trace.
//
// Frames are checked against the pattern application's definition (eight
// colour bars, a grey ramp, a white square moving 16 pixels per frame),
// computed here independently of the application's code. A failing test
// keeps its folder, with the expected image beside ours, and prints where.
//
// Usage: test_soc_sim <path to soc_sim> [GoogleTest options]
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "fixtures/backend_table.h"
#include "fixtures/soc_sim_test.h"

#include "frame_writer.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr int EXIT_USAGE = 2;    // bad option, configuration or input
constexpr int EXIT_FAILED = 1;   // the simulation itself failed
constexpr unsigned WIDTH = 320;  // display.width and display.height defaults
constexpr unsigned HEIGHT = 240;

using tessera::test::contains;
using tessera::test::describe;
using tessera::test::read_file;
using tessera::test::SimResult;

// A bad input must be reported, not crash the simulator.
void expect_no_crash(const SimResult& run) {
  EXPECT_LT(run.status, 128) << describe(run);
  EXPECT_FALSE(contains(run.err, "Aborted")) << describe(run);
  EXPECT_FALSE(contains(run.err, "terminate called")) << describe(run);
  EXPECT_FALSE(contains(run.err, "Segmentation")) << describe(run);
}

// Asserts status and that stderr names every one of `words`.
void expect_rejected(const SimResult& run, int status, const std::vector<std::string>& words) {
  expect_no_crash(run);
  EXPECT_EQ(run.status, status) << describe(run);
  for (const auto& word : words)
    EXPECT_TRUE(contains(run.err, word)) << "stderr lacks '" << word << "'\n" << describe(run);
}

struct Rgb {
  unsigned r, g, b;
  bool operator==(const Rgb& o) const { return r == o.r && g == o.g && b == o.b; }
};
std::ostream& operator<<(std::ostream& out, const Rgb& c) {
  return out << "(" << c.r << ", " << c.g << ", " << c.b << ")";
}

// The pattern application as documented: bars in the top three quarters,
// grey ramp below, white square of side height/4 vertically centred at
// x = (frame * 16) % (width - side).
Rgb pattern_colour(unsigned x, unsigned y, unsigned frame) {
  const Rgb white{255, 255, 255}, yellow{255, 255, 0}, cyan{0, 255, 255}, green{0, 255, 0}, magenta{255, 0, 255},
      red{255, 0, 0}, blue{0, 0, 255}, black{0, 0, 0};
  const Rgb bars[8] = {white, yellow, cyan, green, magenta, red, blue, black};
  const unsigned side = HEIGHT / 4;
  const unsigned left = (frame * 16) % (WIDTH - side);
  const unsigned top = HEIGHT / 2 - side / 2;
  if (x >= left && x < left + side && y >= top && y < top + side) return white;
  if (y < HEIGHT * 3 / 4) return bars[x * 8 / WIDTH];
  const unsigned grey = x * 255 / (WIDTH - 1);
  return {grey, grey, grey};
}

// What an RGB565 frame buffer gives back as 8 bits per channel: rounded to
// the nearest of the 2^n codes (GL's conversion), the code widened again by
// repeating its top bits below it.
unsigned through_bits(unsigned c, unsigned bits) {
  const auto code = static_cast<unsigned>(std::lround(c * double((1u << bits) - 1) / 255.0));
  return (code << (8 - bits)) | (code >> (2 * bits - 8));
}
Rgb through_rgb565(Rgb c) {
  return {through_bits(c.r, 5), through_bits(c.g, 6), through_bits(c.b, 5)};
}

Rgb expected_colour(unsigned x, unsigned y, unsigned frame, bool rgb565) {
  const Rgb c = pattern_colour(x, y, frame);
  return rgb565 ? through_rgb565(c) : c;
}

Rgb pixel(const tessera::Image& image, unsigned x, unsigned y) {
  const uint8_t* p = &image.rgba[(size_t{y} * image.width + x) * 4];
  return {p[0], p[1], p[2]};
}

unsigned alpha(const tessera::Image& image, unsigned x, unsigned y) {
  return image.rgba[(size_t{y} * image.width + x) * 4 + 3];
}

class SocSim : public tessera::test::SocSimTest {
 protected:
  // Writes the expected frame beside ours, for a person to compare.
  void keep_expected(const fs::path& folder, unsigned frame, bool rgb565) {
    std::vector<uint8_t> rgba(size_t{WIDTH} * HEIGHT * 4);
    for (unsigned y = 0; y < HEIGHT; ++y)
      for (unsigned x = 0; x < WIDTH; ++x) {
        const Rgb c = expected_colour(x, y, frame, rgb565);
        uint8_t* p = &rgba[(size_t{y} * WIDTH + x) * 4];
        p[0] = static_cast<uint8_t>(c.r), p[1] = static_cast<uint8_t>(c.g), p[2] = static_cast<uint8_t>(c.b);
        p[3] = 255;
      }
    char name[40];
    std::snprintf(name, sizeof name, "expected_%04u.png", frame);
    tessera::write_png((folder / name).string(), WIDTH, HEIGHT, rgba);
  }

  // Checks frame_0000.png ... in `folder` against the pattern definition:
  // named points first (so a failure says which feature is wrong), then
  // every pixel.
  void expect_pattern_frames(const fs::path& folder, unsigned frames, bool rgb565) {
    for (unsigned frame = 0; frame < frames; ++frame) {
      SCOPED_TRACE("frame " + std::to_string(frame));
      char name[32];
      std::snprintf(name, sizeof name, "frame_%04u.png", frame);
      const fs::path path = folder / name;
      ASSERT_TRUE(fs::is_regular_file(path)) << path;
      const tessera::Image image = tessera::read_image(path.string());
      ASSERT_EQ(image.width, WIDTH);
      ASSERT_EQ(image.height, HEIGHT);

      // Bars: centre of each, near the top and just above the ramp.
      for (unsigned bar = 0; bar < 8; ++bar) {
        const unsigned x = bar * WIDTH / 8 + WIDTH / 16;
        for (unsigned y : {10u, HEIGHT * 3 / 4 - 5}) {
          EXPECT_EQ(pixel(image, x, y), expected_colour(x, y, frame, rgb565))
              << "bar " << bar << " at " << x << "," << y;
        }
      }
      // Grey ramp: both ends and in between, on its first and last line.
      for (unsigned x : {0u, 1u, 100u, WIDTH / 2, WIDTH - 2, WIDTH - 1}) {
        for (unsigned y : {HEIGHT * 3 / 4, HEIGHT - 1}) {
          EXPECT_EQ(pixel(image, x, y), expected_colour(x, y, frame, rgb565)) << "ramp at " << x << "," << y;
        }
      }
      EXPECT_EQ(pixel(image, 0, HEIGHT - 1), (Rgb{0, 0, 0}));
      EXPECT_EQ(pixel(image, WIDTH - 1, HEIGHT - 1), (Rgb{255, 255, 255}));
      // The square: its edges at this frame's position, over the yellow bar.
      const unsigned side = HEIGHT / 4, left = frame * 16, top = HEIGHT / 2 - side / 2;
      EXPECT_EQ(pixel(image, left + side - 1, HEIGHT / 2), (Rgb{255, 255, 255})) << "square's right column";
      EXPECT_EQ(pixel(image, left + side, HEIGHT / 2), expected_colour(left + side, HEIGHT / 2, frame, rgb565))
          << "right of the square";
      EXPECT_EQ(pixel(image, 50, top), (Rgb{255, 255, 255})) << "square's top row";
      EXPECT_EQ(pixel(image, 50, top - 1), expected_colour(50, top - 1, frame, rgb565)) << "above the square";
      EXPECT_EQ(pixel(image, 50, top + side - 1), (Rgb{255, 255, 255})) << "square's bottom row";
      EXPECT_EQ(pixel(image, 50, top + side), expected_colour(50, top + side, frame, rgb565)) << "below the square";

      unsigned wrong = 0;
      std::string first_wrong;
      for (unsigned y = 0; y < HEIGHT; ++y)
        for (unsigned x = 0; x < WIDTH; ++x) {
          const Rgb expected = expected_colour(x, y, frame, rgb565);
          if (pixel(image, x, y) == expected && alpha(image, x, y) == 255) continue;
          if (wrong++ == 0) {
            std::ostringstream text;
            text << "(" << x << ", " << y << "): got " << pixel(image, x, y) << " alpha " << alpha(image, x, y)
                 << ", expected " << expected;
            first_wrong = text.str();
          }
        }
      EXPECT_EQ(wrong, 0u) << "pixels differing from the pattern definition; first at " << first_wrong;
      if (wrong) keep_expected(folder, frame, rgb565);
    }
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04u.png", frames);
    EXPECT_FALSE(fs::exists(folder / name)) << "more frames than asked for";
  }

  json read_stats(const fs::path& path) {
    std::ifstream in(path);
    EXPECT_TRUE(in) << path;
    try {
      return json::parse(in);
    } catch (const json::exception& e) {
      ADD_FAILURE() << path << " is not valid JSON: " << e.what();
      return json::object();
    }
  }
};

// The square moves by 16 pixels a frame: at x = 70 (yellow bar) the square
// covers the pixel in frame 1 (x 16..75) but not in frame 0 (x 0..59).
TEST(PatternDefinition, SquareMovesBetweenTheSampledFrames) {
  EXPECT_EQ(pattern_colour(70, HEIGHT / 2, 0), (Rgb{255, 255, 0}));
  EXPECT_EQ(pattern_colour(70, HEIGHT / 2, 1), (Rgb{255, 255, 255}));
}

TEST_F(SocSim, DefaultRunInRgba8888DrawsThePattern) {
  const SimResult result =
      run({"--app", "pattern", "--frames", "2", "--set", "display.format=rgba8888", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  expect_pattern_frames(m_dir / "out", 2, false);
  {
    const tessera::Image frame0 = tessera::read_image((m_dir / "out/frame_0000.png").string());
    const tessera::Image frame1 = tessera::read_image((m_dir / "out/frame_0001.png").string());
    EXPECT_EQ(pixel(frame0, 70, HEIGHT / 2), (Rgb{255, 255, 0})) << "frame 0: square not yet at x = 70";
    EXPECT_EQ(pixel(frame1, 70, HEIGHT / 2), (Rgb{255, 255, 255})) << "frame 1: square moved over x = 70";
  }

  const json document = read_stats(m_dir / "out/stats.json");
  ASSERT_TRUE(document.contains("stats")) << document.dump(2);
  const json& stats = document["stats"];
  for (const char* section : {"host", "bus", "memory", "display"})
    EXPECT_TRUE(stats.contains(section) && stats[section].is_object()) << "no section " << section;
  EXPECT_EQ(stats["display"]["frames_shown"], 2);
  EXPECT_EQ(stats["display"]["format"], "rgba8888");
  EXPECT_GT(stats["host"]["busy_ns"].get<double>(), 0);
  EXPECT_GT(stats["bus"]["initiators"]["host"]["bytes"].get<double>(), 0);
  EXPECT_EQ(document["frames_written"], 2);
  EXPECT_EQ(document["exit_status"], 0);
  EXPECT_EQ(document["application"], "pattern");

  // The summary names what was written.
  EXPECT_TRUE(contains(result.out, "2 frame(s)")) << result.out;
  EXPECT_TRUE(contains(result.out, "out/frame_0000.png")) << result.out;
  EXPECT_TRUE(contains(result.out, "out/stats.json")) << result.out;
  EXPECT_TRUE(contains(result.out, "pattern")) << result.out;
}

// --version: the program, the project's version and the commit it was built
// from ("unknown" outside a git checkout); stats.json records the same and
// the command line, so a result can be traced to the binary and the run.
TEST_F(SocSim, VersionNamesTheProgramTheVersionAndTheCommit) {
  const SimResult version = run({"--version"});
  ASSERT_EQ(version.status, 0) << describe(version);
  std::smatch match;
  ASSERT_TRUE(std::regex_match(version.out, match,
                               std::regex(R"(soc_sim \(tessera\) ([0-9.]+), commit ([0-9A-Za-z._/+-]+)\n)")))
      << version.out;
  EXPECT_EQ(match[1], TESSERA_PROJECT_VERSION);
  const std::string commit = match[2];
  EXPECT_TRUE(commit == "unknown" || std::regex_match(commit, std::regex(R"(.*[0-9a-f]{7,}(-dirty)?)"))) << commit;

  const std::vector<std::string> args = {"--app", "pattern", "--frames", "1", "--out", "out", "--quiet"};
  const SimResult result = run(args);
  ASSERT_EQ(result.status, 0) << describe(result);
  const json document = read_stats(m_dir / "out/stats.json");
  EXPECT_EQ(document["version"], TESSERA_PROJECT_VERSION);
  EXPECT_EQ(document["commit"], commit);
  std::vector<std::string> command_line{soc_sim()};
  command_line.insert(command_line.end(), args.begin(), args.end());
  EXPECT_EQ(document["command_line"], json(command_line));
}

TEST_F(SocSim, DefaultRgb565FramesAreQuantised) {
  const SimResult result = run({"--app", "pattern", "--frames", "2", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  expect_pattern_frames(m_dir / "out", 2, true);
  // Quantisation shows on the ramp: grey 127 at x = 160 keeps 5 bits of red
  // and blue (01111 -> 0x7b) and 6 of green (011111 -> 0x7d).
  const tessera::Image frame = tessera::read_image((m_dir / "out/frame_0000.png").string());
  EXPECT_EQ(pixel(frame, WIDTH / 2, HEIGHT - 1), (Rgb{0x7b, 0x7d, 0x7b}));
  const json document = read_stats(m_dir / "out/stats.json");
  EXPECT_EQ(document["stats"]["display"]["format"], "rgb565");
  EXPECT_EQ(document["stats"]["display"]["frames_shown"], 2);
}

TEST_F(SocSim, DisplayDmaShowsTheSameFramesOverTheBus) {
  const SimResult result = run({"--app", "pattern", "--set", "display.dma=true", "--frames", "2", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  expect_pattern_frames(m_dir / "out", 2, true);
  const json stats = read_stats(m_dir / "out/stats.json")["stats"];
  EXPECT_EQ(stats["display"]["mode"], "dma");
  EXPECT_EQ(stats["display"]["frames_shown"], 2);
  const json& dma = stats["bus"]["initiators"]["display_dma"];
  EXPECT_GT(dma["transactions"].get<double>(), 0) << dma.dump(2);
  // At least the two frames shown were fetched: 320 x 240 x 2 bytes each.
  EXPECT_GE(dma["bytes"].get<double>(), 2.0 * WIDTH * HEIGHT * 2) << dma.dump(2);
  EXPECT_GT(stats["host"]["busy_ns"].get<double>(), 0);
  // The display DMA's own statistics count the same traffic, a whole
  // number of frames of HEIGHT lines, none of them late.
  const json& engine = stats["display_dma"];
  EXPECT_EQ(engine["bus"]["bytes_read"], dma["bytes"]) << engine.dump(2);
  EXPECT_EQ(engine["bus"]["transactions"], dma["transactions"]) << engine.dump(2);
  EXPECT_EQ(engine["lines_fetched"].get<unsigned>(), engine["frames_fetched"].get<unsigned>() * HEIGHT);
  EXPECT_EQ(engine["underrun_lines"], 0) << engine.dump(2);
}

// The summary's block table is printed from the blocks' own rows: every
// section of the statistics but the run's own has its row, with the busy
// time the block reports, and the bus adds its traffic table, one row per
// initiator it counted.
TEST_F(SocSim, SummaryHasARowForEveryBlockAndTheBusTraffic) {
  const SimResult result = run({"--app", "pattern", "--set", "display.dma=true", "--frames", "1", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const json stats = read_stats(m_dir / "out/stats.json")["stats"];
  std::map<std::string, std::vector<std::string>> rows;
  std::istringstream lines(result.out);
  bool in_blocks = false, in_traffic = false;
  std::set<std::string> initiators;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
    if (w.empty()) {
      in_blocks = in_traffic = false;
      continue;
    }
    if (w[0] == "block") in_blocks = true;
    if (w[0] == "initiator") in_traffic = true;
    // A row starts in the first column after the indent; its notes go on
    // indented below it.
    if (in_blocks && w[0] != "block" && line.rfind("  ", 0) == 0 && line[2] != ' ') rows[w[0]] = w;
    if (in_traffic && w[0] != "initiator") initiators.insert(w[0]);
  }
  // The blocks that did nothing are named on one line instead of a row each.
  std::set<std::string> idle;
  if (rows.count("did")) {
    for (size_t i = 2; i < rows["did"].size(); ++i) {
      std::string name = rows["did"][i];
      if (!name.empty() && name.back() == ',') name.pop_back();
      idle.insert(name);
    }
  }
  for (const auto& [section, value] : stats.items()) {
    if (!value.is_object() || section == "driver" || section == "energy") continue;
    EXPECT_EQ(rows.count(section) + idle.count(section), 1u)
        << "no summary row for " << section << ", nor named as idle\n"
        << result.out;
  }
  ASSERT_EQ(rows.count("host"), 1u) << result.out;
  // "host  4.625 ms  27.8%  stalled on bus ...": the busy time in stats.json.
  ASSERT_GE(rows["host"].size(), 3u) << result.out;
  const double busy_ns = stats["host"]["busy_ns"].get<double>();
  const double scale = rows["host"][2] == "s" ? 1e9 : rows["host"][2] == "ms" ? 1e6 : 1e3;
  EXPECT_NEAR(std::stod(rows["host"][1]) * scale, busy_ns, scale * 0.0005) << result.out;
  EXPECT_TRUE(contains(result.out, "stalled on bus")) << result.out;
  // A traffic row for every initiator but the idle blocks (a row of zeros).
  for (const auto& [name, counts] : stats["bus"]["initiators"].items())
    EXPECT_EQ(initiators.count(name), idle.count(name) ? 0u : 1u) << "traffic row for " << name << "\n" << result.out;
}

// The summary fits a terminal of 80 columns (long notes wrap under the
// notes column), and the blocks that did nothing (no busy time, every
// counter 0: the pattern application on the host leaves the rasterizer and
// the array idle) are named on one line instead of a row each; on ap-tile
// the array and its CIU have rows.
TEST_F(SocSim, SummaryFitsEightyColumnsAndNamesTheIdleBlocksOnOneLine) {
  const SimResult pattern = run({"--app", "pattern", "--frames", "1", "--out", "p"});
  ASSERT_EQ(pattern.status, 0) << describe(pattern);
  const SimResult tile = run({"--backend", "ap-tile", "--app", "triangle", "--frames", "1", "--out", "t"});
  ASSERT_EQ(tile.status, 0) << describe(tile);
  for (const SimResult* result : {&pattern, &tile}) {
    std::istringstream lines(result->out);
    for (std::string line; std::getline(lines, line);) EXPECT_LE(line.size(), 80u) << line;
  }
  const std::regex idle_line(R"(\n  did nothing: ([a-z_, ]+)\n)");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(pattern.out, match, idle_line)) << pattern.out;
  // The block table: from its heading to the first empty line (the energy
  // table below lists energy units, the idle ones' leakage too).
  const auto block_table = [](const std::string& out) {
    const size_t start = out.find("\n  block ");
    return out.substr(start, out.find("\n\n", start) - start);
  };
  for (const char* name : {"raster", "array", "ciu"}) {
    EXPECT_NE(match[1].str().find(name), std::string::npos) << name << " not named idle\n" << pattern.out;
    EXPECT_FALSE(std::regex_search(block_table(pattern.out), std::regex(std::string("\n  ") + name + " +[0-9-]")))
        << name << " has a row though idle\n"
        << pattern.out;
  }
  for (const char* name : {"array", "ciu"})
    EXPECT_TRUE(std::regex_search(block_table(tile.out), std::regex(std::string("\n  ") + name + " +[0-9]")))
        << name << " has no row on ap-tile\n"
        << tile.out;
  // The energy table: units that spent nothing (pattern: the rasterizer, the
  // array's controller and CIU) are named on one line, not listed as rows of
  // zeros; on ap-tile they spent energy and have their rows.
  // (The list wraps at 80 columns onto indented lines.)
  const std::regex no_energy_line(R"(\n  no energy: ([a-z_, \n]+?)\n\n)");
  ASSERT_TRUE(std::regex_search(pattern.out, match, no_energy_line)) << pattern.out;
  for (const char* name : {"raster", "array_controller", "ciu"}) {
    EXPECT_NE(match[1].str().find(name), std::string::npos) << name << " not named as spending nothing\n"
                                                            << pattern.out;
    EXPECT_FALSE(std::regex_search(pattern.out, std::regex(std::string("\n  ") + name + " +0\\.000 uJ")))
        << name << " has an energy row of zeros\n"
        << pattern.out;
  }
  for (const char* name : {"array_controller", "ciu"})
    EXPECT_TRUE(std::regex_search(tile.out, std::regex(std::string("\n  ") + name + " +[0-9.]+ [mun]?J")))
        << name << " has no energy row on ap-tile\n"
        << tile.out;
}

// The arm back end clears each frame with long trains of posted stores
// while the display DMA scans the other buffer out. The host's write buffer
// leaves a train a buffer's worth at a time, so the DMA, first in priority,
// gets in between and no line is late. (When a clear was one bus request of
// up to 4 ms, this run had 98 underrun lines.)
TEST_F(SocSim, DisplayDmaMeetsItsDeadlinesWhileTheHostClears) {
  const SimResult result = run({"--app", "cubes", "--frames", "2", "--set", "display.dma=true", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const json stats = read_stats(m_dir / "out/stats.json")["stats"];
  EXPECT_EQ(stats["display_dma"]["underrun_lines"], 0) << stats["display_dma"].dump(2);
  EXPECT_GT(stats["display_dma"]["lines_fetched"].get<double>(), 2.0 * HEIGHT);
  EXPECT_EQ(stats["display"]["frames_shown"], 2);
}

// stats.json has a record per frame shown: its time, when software
// requested it (PRESENT or SWAP) and its render time from the previous
// request, with the host's busy time and the bus bytes over that render
// time. In port mode a frame is shown when it is requested; with the
// display DMA it is shown at the end of the refresh period after the
// vertical blank that took it, so its time moves in whole periods while its
// render time is the host's.
TEST_F(SocSim, StatisticsPerFrameInBothDisplayModes) {
  constexpr double PERIOD_NS = 1e9 / 60;  // display.refresh_hz
  constexpr double FRAME_BYTES = WIDTH * HEIGHT * 2;
  for (const bool dma : {false, true}) {
    SCOPED_TRACE(dma ? "display DMA" : "port");
    const std::string folder = dma ? "dma" : "port";
    const SimResult result = run({"--app", "pattern", "--frames", "3", "--set",
                                  std::string("display.dma=") + (dma ? "true" : "false"), "--out", folder, "--quiet"});
    ASSERT_EQ(result.status, 0) << describe(result);
    const json stats = read_stats(m_dir / folder / "stats.json")["stats"];
    const json& frames = stats["frames"];
    ASSERT_TRUE(frames.is_array()) << stats.dump(2);
    ASSERT_EQ(frames.size(), stats["display"]["frames_shown"].get<size_t>());
    ASSERT_EQ(frames.size(), 3u);
    double previous_time = 0, previous_request = 0, host_busy = 0, bus_bytes = 0;
    for (size_t i = 0; i < frames.size(); ++i) {
      SCOPED_TRACE("frame " + std::to_string(i));
      const json& f = frames[i];
      EXPECT_EQ(f["index"], i);
      const double time = f["time_ns"].get<double>(), requested = f["requested_ns"].get<double>();
      EXPECT_GT(time, previous_time);
      EXPECT_NEAR(f["interval_ns"].get<double>(), time - previous_time, 1e-3);
      EXPECT_NEAR(f["render_ns"].get<double>(), requested - previous_request, 1e-3);
      EXPECT_GT(f["host_busy_ns"].get<double>(), 0);
      EXPECT_LE(f["host_busy_ns"].get<double>(), f["render_ns"].get<double>());
      if (dma) {
        // Shown at a period boundary, one to two periods after the request;
        // the bus carried at least the drawing of the frame (the pattern
        // stores every pixel).
        EXPECT_NEAR(std::remainder(time, PERIOD_NS), 0, 1e-3 * (i + 2));
        EXPECT_GE(time - requested, PERIOD_NS - 1e-3);
        EXPECT_LE(time - requested, 2 * PERIOD_NS);
        EXPECT_GE(f["bus_bytes"].get<double>(), FRAME_BYTES);
      } else {
        EXPECT_DOUBLE_EQ(requested, time);
        // The host read the frame and copied it to the port.
        EXPECT_GE(f["bus_bytes"].get<double>(), 2 * FRAME_BYTES);
      }
      previous_time = time;
      previous_request = requested;
      host_busy += f["host_busy_ns"].get<double>();
      bus_bytes += f["bus_bytes"].get<double>();
    }
    EXPECT_LE(host_busy, stats["host"]["busy_ns"].get<double>());
    double total_bytes = 0;
    for (const auto& [name, initiator] : stats["bus"]["initiators"].items())
      total_bytes += initiator["bytes"].get<double>();
    EXPECT_LE(bus_bytes, total_bytes);
  }
}

TEST_F(SocSim, IdenticalRunsGiveIdenticalFiles) {
  // The same arguments, run in two folders.
  for (const char* folder : {"a", "b"}) {
    fs::create_directory(m_dir / folder);
    const SimResult result = run_in(m_dir / folder, {"--frames", "2", "--set", "display.dma=true", "--out", "out",
                                                     "--vcd", "out/trace.vcd", "--quiet"});
    ASSERT_EQ(result.status, 0) << describe(result);
  }
  for (const char* file : {"frame_0000.png", "frame_0001.png", "trace.vcd", "stats.json"}) {
    SCOPED_TRACE(file);
    const std::string a = read_file(m_dir / "a/out" / file);
    const std::string b = read_file(m_dir / "b/out" / file);
    EXPECT_FALSE(a.empty());
    EXPECT_TRUE(a == b) << "files differ between identical runs";
  }
}

// The host skips a synchronisation only when no other process has anything
// scheduled (tlm/host/README.md), so running ahead must change nothing the
// model reports: the same frames and statistics as a plain quantum keeper,
// in port mode (where the host runs ahead all the time), with the display
// DMA (only in the blanking interval), and with the rasterizer working
// beside the host.
TEST_F(SocSim, RunAheadChangesNoResult) {
  struct Case {
    std::string name;
    std::string backend;
    std::string dma;
    bool mostly_ahead;
  };
  // Every back end in port mode, the first of the table with the DMA too.
  std::vector<Case> cases;
  for (const tessera::test::BackendEntry& backend : tessera::test::backend_table())
    cases.push_back({backend.id + "_port", backend.name, "false", true});
  cases.push_back(
      {tessera::test::backend_table().front().id + "_dma", tessera::test::backend_table().front().name, "true", false});
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    json stats[2];
    for (int run_ahead = 0; run_ahead < 2; ++run_ahead) {
      const fs::path folder = m_dir / (std::string(c.name) + "_ra" + std::to_string(run_ahead));
      fs::create_directory(folder);
      const SimResult result = run_in(
          folder, {"--frames", "2", "--backend", c.backend, "--set", std::string("display.dma=") + c.dma, "--set",
                   run_ahead ? "sim.run_ahead_us=1000" : "sim.run_ahead_us=0", "--out", "out", "--quiet"});
      ASSERT_EQ(result.status, 0) << describe(result);
      stats[run_ahead] = read_stats(folder / "out/stats.json");
    }
    json& host_without = stats[0]["stats"]["host"];
    json& host_with = stats[1]["stats"]["host"];
    EXPECT_EQ(host_without["run_aheads"], 0);
    if (c.mostly_ahead) {
      EXPECT_GT(host_with["run_aheads"].get<double>(), 0) << host_with.dump(2);
      EXPECT_LT(host_with["synchronisations"].get<double>() * 10, host_without["synchronisations"].get<double>())
          << "running ahead should save most synchronisations";
    }
    for (json* s : {&stats[0], &stats[1]}) {
      (*s)["stats"]["host"].erase("run_aheads");
      (*s)["stats"]["host"].erase("synchronisations");
      (*s)["config"]["sim"].erase("run_ahead_us");
      s->erase("command_line");
    }
    EXPECT_EQ(stats[0], stats[1]) << "statistics differ with and without run-ahead";
    for (const char* file : {"frame_0000.png", "frame_0001.png"}) {
      const std::string prefix = m_dir / (std::string(c.name) + "_ra");
      EXPECT_TRUE(read_file(prefix + "0/out/" + file) == read_file(prefix + "1/out/" + file))
          << file << " differs with and without run-ahead";
    }
  }
}

// A second run into a folder that holds an earlier run's outputs would mix
// the two (a new stats.json beside the frames of the older, longer run): it
// is refused, naming the folder and what is there, and changes nothing.
TEST_F(SocSim, SecondRunIntoTheSameFolderIsRefusedNamingWhatIsThere) {
  ASSERT_EQ(run({"--app", "pattern", "--frames", "3", "--out", "out", "--vcd", "out/trace.vcd", "--quiet"}).status, 0);
  const std::string stats_before = read_file(m_dir / "out/stats.json");
  const std::string frame_before = read_file(m_dir / "out/frame_0002.png");
  const SimResult again = run({"--app", "pattern", "--frames", "1", "--out", "out", "--quiet"});
  expect_rejected(again, EXIT_USAGE,
                  {"output folder 'out'", "earlier run", "3 frames (frame_0000.png ... frame_0002.png)", "stats.json",
                   "trace.vcd", "--force", "--out"});
  EXPECT_EQ(read_file(m_dir / "out/stats.json"), stats_before);
  EXPECT_EQ(read_file(m_dir / "out/frame_0002.png"), frame_before);
  // The same with --no-frames: old frames would still sit beside new statistics.
  expect_rejected(run({"--app", "pattern", "--frames", "1", "--out", "out", "--no-frames", "--quiet"}), EXIT_USAGE,
                  {"earlier run", "frame_0000.png"});
}

// Two runs started together into the same folder: the check that the folder
// is free and its claim are one step, so exactly one runs and the other is
// refused naming the folder, and the outputs are the one run's, whole. (Both
// used to pass the check before either had written anything, both exited 0
// and one run's outputs were lost.) Each run has its own working folder for
// its stdout and stderr; --out is the same absolute folder.
TEST_F(SocSim, TwoRunsStartedTogetherIntoTheSameFolderOneIsRefused) {
  const fs::path shared = m_dir / "shared";
  for (int attempt = 0; attempt < 3; ++attempt) {
    SCOPED_TRACE("attempt " + std::to_string(attempt));
    fs::remove_all(shared);
    const fs::path a = m_dir / ("a" + std::to_string(attempt)), b = m_dir / ("b" + std::to_string(attempt));
    fs::create_directories(a);
    fs::create_directories(b);
    // Different frame counts, so the statistics tell which run they are from.
    tessera::test::ChildProcess first =
        start_in(a, {"--app", "pattern", "--frames", "3", "--out", shared.string(), "--quiet"});
    tessera::test::ChildProcess second =
        start_in(b, {"--app", "pattern", "--frames", "2", "--out", shared.string(), "--quiet"});
    const SimResult one = first.wait();
    const SimResult two = second.wait();
    ASSERT_EQ((one.status == 0) + (two.status == 0), 1) << "exactly one run must run\n"
                                                        << describe(one) << describe(two);
    const SimResult& refused = one.status == 0 ? two : one;
    expect_rejected(refused, EXIT_USAGE, {"output folder '" + shared.string() + "'", "another run"});
    const unsigned frames = one.status == 0 ? 3 : 2;
    EXPECT_EQ(read_stats(shared / "stats.json")["frames_written"], frames);
    expect_pattern_frames(shared, frames, true);
  }
}

// --force removes exactly what soc_sim wrote there before -- frames,
// statistics, traces -- and nothing else in the folder.
TEST_F(SocSim, ForceRemovesExactlyTheEarlierOutputs) {
  ASSERT_EQ(run({"--app", "pattern", "--frames", "3", "--out", "out", "--vcd", "out/trace.vcd", "--quiet"}).status, 0);
  const std::map<std::string, std::string> unrelated = {
      {"notes.txt", "my notes\n"},
      {"frame_final.png", "not a frame soc_sim names\n"},
      {"results.json", "{\"mine\": true}\n"},
      {"other.vcd", "$date\n today\n$end\n$version\n another simulator\n$end\n"},
      {"sub/frame_0000.png", "a folder below is not the output folder\n"}};
  fs::create_directory(m_dir / "out/sub");
  for (const auto& [name, text] : unrelated) std::ofstream(m_dir / "out" / name) << text;

  const SimResult result = run({"--app", "pattern", "--frames", "1", "--out", "out", "--force", "--quiet"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_TRUE(fs::exists(m_dir / "out/frame_0000.png"));
  EXPECT_FALSE(fs::exists(m_dir / "out/frame_0001.png"));
  EXPECT_FALSE(fs::exists(m_dir / "out/frame_0002.png"));
  EXPECT_FALSE(fs::exists(m_dir / "out/trace.vcd"));
  EXPECT_EQ(read_stats(m_dir / "out/stats.json")["frames_written"], 1);
  for (const auto& [name, text] : unrelated) EXPECT_EQ(read_file(m_dir / "out" / name), text) << name;
}

// A file soc_sim did not write, where this run would write its statistics or
// trace, is never overwritten, even with --force.
TEST_F(SocSim, FilesSocSimDidNotWriteAreNeverOverwritten) {
  fs::create_directory(m_dir / "out");
  std::ofstream(m_dir / "out/stats.json") << "my own statistics\n";
  expect_rejected(run({"--frames", "1", "--out", "out", "--force"}), EXIT_USAGE,
                  {"'out/stats.json'", "not written by soc_sim", "--stats"});
  EXPECT_EQ(read_file(m_dir / "out/stats.json"), "my own statistics\n");
  EXPECT_FALSE(fs::exists(m_dir / "out/frame_0000.png"));

  std::ofstream(m_dir / "README.md") << "# my notes\n";
  expect_rejected(run({"--frames", "1", "--out", "b", "--stats", "README.md", "--force"}), EXIT_USAGE,
                  {"'README.md'", "not written by soc_sim"});
  std::ofstream(m_dir / "mine.vcd") << "$date\n today\n$end\n";
  expect_rejected(run({"--frames", "1", "--out", "b", "--vcd", "mine.vcd", "--force"}), EXIT_USAGE,
                  {"'mine.vcd'", "VCD trace", "--vcd"});
  EXPECT_EQ(read_file(m_dir / "README.md"), "# my notes\n");
  EXPECT_EQ(read_file(m_dir / "mine.vcd"), "$date\n today\n$end\n");
  std::ofstream(m_dir / "mine.fst") << "not an FST\n";
  expect_rejected(run({"--frames", "1", "--out", "b", "--fst", "mine.fst", "--force"}), EXIT_USAGE,
                  {"'mine.fst'", "FST trace", "--fst"});
  EXPECT_EQ(read_file(m_dir / "mine.fst"), "not an FST\n");
  std::ofstream(m_dir / "mine.html") << "<p>my page</p>\n";
  expect_rejected(run({"--frames", "1", "--out", "b", "--report", "mine.html", "--force"}), EXIT_USAGE,
                  {"'mine.html'", "run report", "--report"});
  EXPECT_EQ(read_file(m_dir / "mine.html"), "<p>my page</p>\n");
}

// --report without the Python that renders it: the error names the Python,
// the run's other outputs stay, and the status says an output is missing.
TEST_F(SocSim, AReportWithoutItsPythonKeepsTheOtherOutputs) {
  tessera::test::ChildCommand command = tessera::test::soc_sim_command(
      soc_sim(), m_dir, {"--app", "pattern", "--frames", "1", "--out", "out", "--report", "out/run.html"});
  command.environment.push_back("TESSERA_PYTHON=/no/such/python3");
  const SimResult result = tessera::test::ChildProcess(std::move(command)).wait();
  expect_rejected(result, EXIT_FAILED,
                  {"cannot run Python '/no/such/python3' for the run report", "the run's other outputs are kept"});
  EXPECT_TRUE(contains(result.out, "run report: none")) << result.out;
  EXPECT_TRUE(fs::exists(m_dir / "out/frame_0000.png"));
  EXPECT_EQ(read_stats(m_dir / "out/stats.json")["frames_written"], 1);
  EXPECT_FALSE(fs::exists(m_dir / "out/run.html"));
}

// The trace's format is the option's: a name that says the other format,
// or no .fst for --fst (no .html for --report), and a path that cannot be
// written are refused before the run, saying why.
TEST_F(SocSim, TraceAndReportNamesAreCheckedBeforeTheRun) {
  expect_rejected(run({"--frames", "1", "--out", "out", "--vcd", "trace.fst"}), EXIT_USAGE,
                  {"--vcd writes a VCD", "'trace.fst'", "--fst trace.fst"});
  expect_rejected(run({"--frames", "1", "--out", "out", "--fst", "trace.vcd"}), EXIT_USAGE,
                  {"--fst writes an FST", "must end in .fst", "--vcd trace.vcd"});
  expect_rejected(run({"--frames", "1", "--out", "out", "--fst", "trace.wave"}), EXIT_USAGE,
                  {"must end in .fst", "'trace.wave'"});
  expect_rejected(run({"--frames", "1", "--out", "out", "--report", "report.pdf"}), EXIT_USAGE,
                  {"must end in .html", "'report.pdf'"});
  expect_rejected(run({"--frames", "1", "--out", "out", "--fst", "no_such_folder/trace.fst"}), EXIT_USAGE,
                  {"cannot write 'no_such_folder/trace.fst'", "does not exist"});
  expect_rejected(run({"--frames", "1", "--out", "out", "--report", "no_such_folder/run.html"}), EXIT_USAGE,
                  {"cannot write 'no_such_folder/run.html'", "does not exist"});
  EXPECT_FALSE(fs::exists(m_dir / "out/frame_0000.png"));
}

// The frames' records are streamed to side files in the output folder while
// the run goes on and merged into stats.json at the end: the file is the
// whole document as nlohmann's dump(2) writes it (byte for byte: parsed and
// dumped again it is the same), with every frame's record and the driver's
// figures and --wall-clock times joined to it, and no side file is left.
TEST_F(SocSim, StreamedFrameStatisticsMergeIntoTheWholeDocument) {
  const SimResult result = run({"--backend", "ap-tile", "--app", "triangle", "--frames", "4", "--out", "out",
                                "--no-frames", "--wall-clock", "--quiet"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const std::string text = read_file(m_dir / "out/stats.json");
  const json document = json::parse(text);
  EXPECT_EQ(document.dump(2) + "\n", text);
  const json& frames = document["stats"]["frames"];
  ASSERT_EQ(frames.size(), 4u);
  for (size_t i = 0; i < frames.size(); ++i) {
    EXPECT_EQ(frames[i]["index"], i);
    EXPECT_TRUE(frames[i].contains("energy") && frames[i].contains("driver") && frames[i].contains("wall_ns") &&
                frames[i].contains("cpu_ns"))
        << frames[i].dump(2);
    if (i > 0) {
      EXPECT_GT(frames[i]["wall_ns"].get<double>(), frames[i - 1]["wall_ns"].get<double>());
    }
  }
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(m_dir / "out")) names.push_back(entry.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"stats.json"});
  // A run stopped by the time limit before its first frame: an empty list.
  run({"--app", "teapot", "--frames", "1", "--out", "none", "--no-frames", "--quiet", "--set", "sim.time_limit_ms=1"});
  const json stopped = json::parse(read_file(m_dir / "none/stats.json"));
  ASSERT_EQ(stopped["frames_shown"], 0) << stopped.dump(2);
  EXPECT_EQ(stopped["stats"]["frames"], json::array());
  EXPECT_EQ(stopped.dump(2) + "\n", read_file(m_dir / "none/stats.json"));
}

// --no-frames for sweeps: no PNG, the frames still counted.
TEST_F(SocSim, NoFramesWritesNoPngButCountsTheFrames) {
  const SimResult result = run({"--app", "pattern", "--frames", "3", "--out", "out", "--no-frames"});
  ASSERT_EQ(result.status, 0) << describe(result);
  for (const auto& entry : fs::directory_iterator(m_dir / "out"))
    EXPECT_NE(entry.path().extension(), ".png") << entry.path();
  const json document = read_stats(m_dir / "out/stats.json");
  EXPECT_EQ(document["frames_written"], 0);
  EXPECT_EQ(document["frames_shown"], 3);
  EXPECT_EQ(document["stats"]["display"]["frames_shown"], 3);
  EXPECT_TRUE(contains(result.out, "3 frame(s) shown, none written (--no-frames)")) << result.out;
}

// --wall-clock: each frame's wall-clock and CPU time in stats.json (for benchmarks),
// rising from frame to frame; without it the file has none, so that
// identical runs write identical files.
TEST_F(SocSim, WallClockPerFrameOnlyWhenAskedFor) {
  SimResult result = run({"--app", "pattern", "--frames", "3", "--out", "a", "--no-frames", "--quiet", "--wall-clock"});
  ASSERT_EQ(result.status, 0) << describe(result);
  json frames = read_stats(m_dir / "a/stats.json")["stats"]["frames"];
  ASSERT_EQ(frames.size(), 3u);
  double previous = 0, previous_cpu = 0;
  for (const json& frame : frames) {
    ASSERT_TRUE(frame.contains("wall_ns")) << frame.dump();
    EXPECT_GT(frame["wall_ns"].get<double>(), previous);
    previous = frame["wall_ns"].get<double>();
    // The process's CPU time so far: it includes start-up, and simulating
    // a frame takes some, so it only grows (never equal: a clock of ns).
    ASSERT_TRUE(frame.contains("cpu_ns")) << frame.dump();
    EXPECT_GT(frame["cpu_ns"].get<double>(), previous_cpu);
    previous_cpu = frame["cpu_ns"].get<double>();
  }
  result = run({"--app", "pattern", "--frames", "3", "--out", "b", "--no-frames", "--quiet"});
  ASSERT_EQ(result.status, 0) << describe(result);
  frames = read_stats(m_dir / "b/stats.json")["stats"]["frames"];
  ASSERT_EQ(frames.size(), 3u);
  for (const json& frame : frames) {
    EXPECT_FALSE(frame.contains("wall_ns")) << frame.dump();
    EXPECT_FALSE(frame.contains("cpu_ns")) << frame.dump();
  }
}

// 1000 teapot frames take 172 s of simulated time in port mode (a few
// seconds of wall time without PNGs): the automatic limit, 60 s + 10 s per frame, lets them
// finish, where the fixed 60 s default would stop them.
TEST_F(SocSim, LongRunIsNotCutByTheAutomaticTimeLimit) {
  const SimResult result = run({"--app", "teapot", "--frames", "1000", "--no-frames", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const json document = read_stats(m_dir / "out/stats.json");
  EXPECT_EQ(document["frames_shown"], 1000);
  EXPECT_GT(document["stats"]["simulated_ns"].get<double>(), 60e9);
  EXPECT_EQ(document["time_limit_ms"], 10060000);
  EXPECT_EQ(document["time_limit_automatic"], true);
  EXPECT_TRUE(contains(result.out, "time limit      10060.000 s (automatic: 60 s + 10 s x 1000 frames)")) << result.out;
}

// A limit the user gives is kept, and reaching it is an error that names the key, the limit and
// the frames reached.
TEST_F(SocSim, GivenTimeLimitIsKeptAndReachingItIsAnError) {
  SimResult result = run({"--app", "pattern", "--set", "display.dma=true", "--frames", "3", "--set",
                          "sim.time_limit_ms=20", "--out", "a"});
  expect_rejected(result, EXIT_FAILED, {"sim.time_limit_ms = 20 ms", "after 0 of 3 frames"});
  EXPECT_TRUE(contains(result.out, "time limit      20.000 ms (sim.time_limit_ms)")) << result.out;
  json document = read_stats(m_dir / "a/stats.json");
  EXPECT_EQ(document["exit_status"], EXIT_FAILED);
  EXPECT_EQ(document["time_limit_ms"], 20);
  EXPECT_EQ(document["time_limit_automatic"], false);

  std::ofstream(m_dir / "limit.json") << R"({"sim": {"time_limit_ms": 20}})";
  result = run({"--app", "pattern", "--set", "display.dma=true", "--frames", "3", "--config", "limit.json", "--out",
                "b", "--quiet"});
  expect_rejected(result, EXIT_FAILED, {"sim.time_limit_ms = 20 ms"});

  result = run({"--app", "teapot", "--frames", "1000", "--set", "sim.time_limit_ms=60000", "--no-frames", "--out", "c",
                "--quiet"});
  expect_rejected(result, EXIT_FAILED, {"sim.time_limit_ms = 60000 ms", "of 1000 frames"});
  document = read_stats(m_dir / "c/stats.json");
  EXPECT_LT(document["frames_shown"].get<unsigned>(), 1000u);
  EXPECT_EQ(document["time_limit_automatic"], false);
}

// What soc_sim drew on the terminal: each redraw starts with "\r", and the
// lines between "\r" and "\n" are what the terminal showed.
struct TerminalOutput {
  unsigned redraws = 0;
  size_t longest_line = 0;
  std::string last_line;
};

TerminalOutput read_terminal(const std::string& text) {
  TerminalOutput output;
  std::string line;
  for (const char c : text) {
    if (c == '\r' || c == '\n') {
      output.redraws += c == '\r';
      if (!line.empty()) output.last_line = line;
      line.clear();
    } else {
      line += c;
      output.longest_line = std::max(output.longest_line, line.size());
    }
  }
  return output;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// On a terminal 60 columns wide, 100 teapot frames (16.8 s simulated, about
// half a second of wall time) redraw the progress line at most 4 times per
// wall second plus the first and the last drawing -- not once per simulated
// millisecond (16,800 lines in a terminal's scrollback) -- and never reach
// the last column.
TEST_F(SocSim, ProgressOnATerminalFitsTheWidthAndRedrawsAtMostFourTimesASecond) {
  const auto start = std::chrono::steady_clock::now();
  const SimResult result = run_on_terminal({"--frames", "100", "--out", "out"}, 60);
  const double wall = seconds_since(start);
  ASSERT_EQ(result.status, 0) << describe(result);
  const TerminalOutput terminal = read_terminal(result.err);
  EXPECT_GE(terminal.redraws, 1u) << result.err;
  EXPECT_LE(terminal.redraws, static_cast<unsigned>(4 * wall) + 2) << "in " << wall << " s:\n" << result.err;
  EXPECT_LE(terminal.longest_line, 59u) << result.err;
  EXPECT_TRUE(contains(terminal.last_line, "frame 100/100")) << terminal.last_line;
  EXPECT_TRUE(contains(terminal.last_line, "ETA 0:00")) << terminal.last_line;
  EXPECT_TRUE(contains(result.out, "100 frame(s)")) << result.out;
}

// A terminal that reports no size: $COLUMNS, then 80.
TEST_F(SocSim, ProgressUsesColumnsWhenTheTerminalReportsNoWidth) {
  SimResult result = run_on_terminal({"--frames", "1", "--out", "a"}, 0, {"COLUMNS=45"});
  ASSERT_EQ(result.status, 0) << describe(result);
  TerminalOutput terminal = read_terminal(result.err);
  EXPECT_EQ(terminal.longest_line, 44u) << result.err;
  EXPECT_TRUE(contains(terminal.last_line, "frame 1/1")) << result.err;

  result = run_on_terminal({"--frames", "1", "--out", "b"}, 0, {"COLUMNS=not a number"});
  ASSERT_EQ(result.status, 0) << describe(result);
  terminal = read_terminal(result.err);
  EXPECT_EQ(terminal.longest_line, 79u) << result.err;
}

// --quiet, or stderr that is not a terminal: no progress line at all.
TEST_F(SocSim, NoProgressWhenQuietOrNotOnATerminal) {
  const SimResult quiet = run_on_terminal({"--frames", "1", "--out", "a", "--quiet"}, 80);
  ASSERT_EQ(quiet.status, 0) << describe(quiet);
  EXPECT_EQ(quiet.err, "");
  const SimResult piped = run({"--frames", "1", "--out", "b"});
  ASSERT_EQ(piped.status, 0) << describe(piped);
  EXPECT_FALSE(contains(piped.err, "\r")) << piped.err;
  EXPECT_FALSE(contains(piped.err, "ETA")) << piped.err;
}

// Declared signals by hierarchical name ("soc.bus.host_request") -> VCD id,
// and how many value changes each id has after time 0.
struct Vcd {
  std::map<std::string, std::string> ids;
  std::map<std::string, unsigned> changes;
  unsigned timestamps = 0;
};

Vcd parse_vcd(const std::string& text) {
  Vcd vcd;
  std::istringstream in(text);
  std::vector<std::string> scopes;
  std::string line;
  bool definitions = true, after_zero = false;
  while (std::getline(in, line)) {
    std::istringstream words(line);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
    if (w.empty()) continue;
    if (definitions) {
      if (w[0] == "$scope" && w.size() >= 3)
        scopes.push_back(w[2]);
      else if (w[0] == "$upscope")
        scopes.pop_back();
      else if (w[0] == "$var" && w.size() >= 5) {
        std::string name;
        for (const auto& scope : scopes) name += scope + ".";
        vcd.ids[name + w[4]] = w[3];
      } else if (w[0] == "$enddefinitions")
        definitions = false;
      continue;
    }
    if (w[0][0] == '#') {
      ++vcd.timestamps;
      after_zero = std::stoull(w[0].substr(1)) > 0;
    } else if (after_zero && (w[0][0] == '0' || w[0][0] == '1')) {
      ++vcd.changes[w[0].substr(1)];
    } else if (after_zero && w[0][0] == 'r' && w.size() >= 2) {
      ++vcd.changes[w[1]];
    }
  }
  return vcd;
}

TEST_F(SocSim, VcdTraceDeclaresAndChangesTheSignals) {
  const SimResult result =
      run({"--frames", "1", "--set", "display.dma=true", "--out", "out", "--vcd", "out/trace.vcd"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_TRUE(contains(result.out, "out/trace.vcd")) << result.out;
  const std::string text = read_file(m_dir / "out/trace.vcd");
  ASSERT_EQ(text.rfind("$date", 0), 0u) << text.substr(0, 200);
  EXPECT_TRUE(contains(text, "$enddefinitions"));

  const Vcd vcd = parse_vcd(text);
  auto id_of = [&](const std::string& suffix) -> std::string {
    for (const auto& [name, id] : vcd.ids)
      if (name.size() >= suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
        return id;
    return {};
  };
  std::string declared;
  for (const auto& [name, id] : vcd.ids) declared += " " + name;
  const char* signals[] = {"soc.bus.host_request",      "soc.bus.host_grant", "soc.bus.display_dma_request",
                           "soc.bus.display_dma_grant", "soc.host.busy",      "soc.host.irq_0",
                           "soc.display.vblank"};
  for (const char* signal : signals) EXPECT_FALSE(id_of(signal).empty()) << signal << " not in" << declared;
  unsigned irq_lines = 0;
  for (const auto& [name, id] : vcd.ids) irq_lines += contains(name, "soc.host.irq_");
  EXPECT_EQ(irq_lines, 8u) << "host.irq_lines defaults to 8:" << declared;

  EXPECT_GT(vcd.timestamps, 2u);
  // In display DMA mode every one of these toggles during a frame.
  for (const char* signal :
       {"soc.bus.host_grant", "soc.bus.display_dma_grant", "soc.display.vblank", "soc.host.busy", "soc.host.irq_0"}) {
    const std::string id = id_of(signal);
    EXPECT_GT(vcd.changes.count(id) ? vcd.changes.at(id) : 0u, 0u) << signal << " never changes";
  }
  // The power trace (power.trace_window_us): one real per energy unit and
  // the total, each changing at the end of every window with activity.
  for (const char* unit :
       {"host", "bus", "memory", "array_controller", "cu_array", "ciu", "display_dma", "display", "raster", "total"}) {
    const std::string id = id_of(std::string("soc.power.") + unit);
    EXPECT_FALSE(id.empty()) << "soc.power." << unit << " not in" << declared;
    if (std::string(unit) == "host" || std::string(unit) == "bus" || std::string(unit) == "total") {
      EXPECT_GT(vcd.changes.count(id) ? vcd.changes.at(id) : 0u, 0u) << unit << "'s power never changes";
    }
  }
  EXPECT_TRUE(contains(text, "$var real")) << "the powers are real-valued";
}

// The power trace spreads the host's cycles charged ahead of the kernel over
// its windows (Host::attribute_activity_in_time); the frames' and the run's
// energies, taken where nothing is ahead, stay what they are without a VCD,
// to the last bit.
TEST_F(SocSim, AVcdChangesNoEnergy) {
  const SimResult plain = run({"--scene", "teapot", "--frames", "2", "--no-frames", "--out", "plain"});
  const SimResult traced =
      run({"--scene", "teapot", "--frames", "2", "--no-frames", "--out", "traced", "--vcd", "traced/t.vcd"});
  ASSERT_EQ(plain.status, 0) << describe(plain);
  ASSERT_EQ(traced.status, 0) << describe(traced);
  const json a = read_stats(m_dir / "plain/stats.json")["stats"];
  const json b = read_stats(m_dir / "traced/stats.json")["stats"];
  EXPECT_EQ(a["energy"], b["energy"]);
  ASSERT_EQ(a["frames"].size(), 2u);
  for (size_t i = 0; i < a["frames"].size(); ++i) EXPECT_EQ(a["frames"][i]["energy"], b["frames"][i]["energy"]) << i;
}

// power.trace_window_us=0 leaves the power signals out.
// --vcd FILE writes exactly FILE, whatever its extension: SystemC appends
// ".vcd" to the name it is given, and "t.VCD" used to become "t.VCD.vcd".
TEST_F(SocSim, VcdTraceIsWrittenUnderExactlyTheNameGiven) {
  for (const std::string name : {"t.VCD", "trace", "w.vcd.txt", "plain.vcd"}) {
    SCOPED_TRACE(name);
    const std::string out = "out_" + name;
    const SimResult result = run({"--app", "pattern", "--frames", "1", "--out", out, "--vcd", out + "/" + name});
    ASSERT_EQ(result.status, 0) << describe(result);
    EXPECT_TRUE(contains(result.out, "VCD trace: " + out + "/" + name + "\n")) << result.out;
    std::vector<std::string> files;
    for (const auto& entry : fs::directory_iterator(m_dir / out)) files.push_back(entry.path().filename().string());
    std::sort(files.begin(), files.end());
    std::vector<std::string> expected = {"frame_0000.png", name, "stats.json"};
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(files, expected);
    EXPECT_EQ(read_file(m_dir / out / name).rfind("$date", 0), 0u) << "not a VCD";
  }
}

TEST_F(SocSim, NoPowerSignalsWithAZeroWindow) {
  const SimResult result =
      run({"--frames", "1", "--set", "power.trace_window_us=0", "--out", "out", "--vcd", "out/trace.vcd", "--quiet"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_FALSE(contains(read_file(m_dir / "out/trace.vcd"), "power")) << "power signals traced";
}

// The interrupt lines drive these runs, and the trace shows every pulse:
// the display raises swap-done at each vertical blank that takes a frame
// (line 0), the rasterizer raises done at the end of each run (line 1), and
// the driver's write to IRQ_STATUS drops the line at that write's time, a
// little later. (The clear used to take effect at the kernel's time, in
// the very time step of the rise, so the lines never changed in the VCD.)
TEST_F(SocSim, InterruptLinesToggleInTheVcd) {
  const SimResult result = run({"--backend", "raster", "--app", "triangle", "--frames", "2", "--set",
                                "display.dma=true", "--out", "out", "--vcd", "out/trace.vcd", "--quiet"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const json stats = read_stats(m_dir / "out/stats.json")["stats"];
  const Vcd vcd = parse_vcd(read_file(m_dir / "out/trace.vcd"));
  auto changes = [&](const std::string& name) -> unsigned {
    for (const auto& [declared, id] : vcd.ids)
      if (declared.size() >= name.size() && declared.compare(declared.size() - name.size(), name.size(), name) == 0)
        return vcd.changes.count(id) ? vcd.changes.at(id) : 0;
    ADD_FAILURE() << name << " is not declared";
    return 0;
  };
  // A rise and a fall per interrupt.
  EXPECT_EQ(changes("soc.host.irq_0"), 2 * stats["display"]["frames_shown"].get<unsigned>());
  EXPECT_EQ(changes("soc.host.irq_1"), 2 * stats["raster"]["runs"].get<unsigned>());
  EXPECT_EQ(stats["raster"]["runs"], 2);
  for (unsigned line = 2; line < 8; ++line) EXPECT_EQ(changes("soc.host.irq_" + std::to_string(line)), 0u);
}

TEST_F(SocSim, MalformedJsonConfigIsRejected) {
  std::ofstream(m_dir / "broken.json") << "{\"bus\": {\"arbitration\": \"round_robin\",\n";
  expect_rejected(run({"--config", "broken.json", "--out", "out"}), EXIT_USAGE, {"broken.json", "not valid JSON"});
}

TEST_F(SocSim, UnknownKeyIsRejectedWithASuggestion) {
  expect_rejected(run({"--set", "bus.arbitraton=round_robin", "--out", "out"}), EXIT_USAGE,
                  {"bus.arbitraton", "bus.arbitration"});
}

TEST_F(SocSim, UnknownKeyInAConfigFileIsRejected) {
  std::ofstream(m_dir / "typo.json") << R"({"display": {"widht": 640}})";
  expect_rejected(run({"--config", "typo.json", "--out", "out"}), EXIT_USAGE,
                  {"display.widht", "display.width", "typo.json"});
}

TEST_F(SocSim, WrongTypeIsRejected) {
  expect_rejected(run({"--set", "sim.frames=many", "--out", "out"}), EXIT_USAGE, {"sim.frames", "integer", "many"});
}

TEST_F(SocSim, OutOfRangeValueIsRejected) {
  expect_rejected(run({"--set", "mem.size_mib=100000", "--out", "out"}), EXIT_USAGE, {"mem.size_mib", "256"});
}

TEST_F(SocSim, ImpossibleCombinationIsRejected) {
  expect_rejected(run({"--set", "display.width=512", "--set", "display.height=512", "--set", "display.format=rgba8888",
                       "--set", "mem.size_mib=1", "--out", "out"}),
                  EXIT_USAGE, {"impossible combination", "display.width", "display.format", "mem.size_mib"});
  EXPECT_FALSE(fs::exists(m_dir / "out/stats.json"));
}

// dma.broadcast is a write of the DMA: asked for without the DMA in the SoC
// it would change nothing, silently. An error naming both keys, from --set
// and from a file alike; with dma.enabled=true it runs.
TEST_F(SocSim, DmaBroadcastWithoutTheDmaIsRejectedNamingBothKeys) {
  expect_rejected(run({"--set", "dma.broadcast=true", "--frames", "1", "--out", "out"}), EXIT_USAGE,
                  {"impossible combination", "dma.broadcast=true", "dma.enabled=true"});
  EXPECT_FALSE(fs::exists(m_dir / "out/stats.json"));
  std::ofstream(m_dir / "broadcast.json") << R"({"dma": {"broadcast": true, "enabled": false}})";
  expect_rejected(run({"--config", "broadcast.json", "--frames", "1", "--out", "out"}), EXIT_USAGE,
                  {"dma.broadcast", "dma.enabled"});
  const SimResult both = run({"--set", "dma.broadcast=true", "--set", "dma.enabled=true", "--app", "pattern",
                              "--frames", "1", "--out", "both", "--quiet"});
  EXPECT_EQ(both.status, 0) << describe(both);
}

TEST_F(SocSim, MissingConfigFileIsRejected) {
  expect_rejected(run({"--config", "no_such_config.json", "--out", "out"}), EXIT_USAGE, {"no_such_config.json"});
}

TEST_F(SocSim, UnknownOptionIsRejected) {
  expect_rejected(run({"--frobnicate", "--out", "out"}), EXIT_USAGE, {"--frobnicate"});
}

// "soc_sim cubes": a word before "--" is not passed to the application, it
// is rejected with what to write instead.
TEST_F(SocSim, StrayWordBeforeDoubleDashIsRejectedWithAdvice) {
  expect_rejected(run({"cubes", "--out", "out"}), EXIT_USAGE,
                  {"unexpected argument 'cubes'", "--app cubes", "after '--'"});
  EXPECT_FALSE(fs::exists(m_dir / "out/stats.json"));
  expect_rejected(run({"--frames", "1", "model.obj", "--out", "out"}), EXIT_USAGE,
                  {"unexpected argument 'model.obj'", "--app NAME", "after '--'"});
}

// Everything after "--" is the application's, even what looks like one of
// soc_sim's options: obj_viewer gets it as the file to open.
TEST_F(SocSim, ArgumentsAfterDoubleDashGoToTheApplication) {
  const SimResult result = run({"--app", "obj_viewer", "--frames", "1", "--out", "out", "--", "--frames.obj"});
  expect_rejected(result, EXIT_USAGE, {"obj_viewer: --frames.obj: cannot open"});
  EXPECT_FALSE(contains(result.err, "unexpected argument")) << describe(result);
}

// random_triangles' options, on both host models: every bad value named
// (a value past 32 bits too, which a library conversion overflows on the ARM).
TEST_F(SocSim, RandomTrianglesRefusesBadOptionsNamingThem) {
  const std::vector<std::vector<std::string>> cases = {
      {"--triangles", "9999999999"}, {"--triangles", "0"}, {"--size", "x"}, {"--seed"}, {"--shade", "1"}};
  for (const char* model : {"native", "iss"})
    for (const std::vector<std::string>& bad : cases) {
      std::vector<std::string> args = {"--app",
                                       "random_triangles",
                                       "--frames",
                                       "1",
                                       "--force",
                                       "--out",
                                       "out",
                                       "--set",
                                       std::string("host.model=") + model,
                                       "--"};
      args.insert(args.end(), bad.begin(), bad.end());
      expect_rejected(run(args), EXIT_USAGE, {"random_triangles: ", bad[0]});
    }
}

// dense_teapot's options, on both host models: every bad value named.
TEST_F(SocSim, DenseTeapotRefusesBadOptionsNamingThem) {
  const std::vector<std::vector<std::string>> cases = {
      {"--triangles", "4000001"}, {"--triangles", "0"}, {"--stand-in", "dragon"}, {"--stand-in"}, {"--size", "1"}};
  for (const char* model : {"native", "iss"})
    for (const std::vector<std::string>& bad : cases) {
      std::vector<std::string> args = {"--app", "dense_teapot", "--frames",
                                       "1",     "--force",      "--out",
                                       "out",   "--set",        std::string("host.model=") + model,
                                       "--"};
      args.insert(args.end(), bad.begin(), bad.end());
      expect_rejected(run(args), EXIT_USAGE, {"dense_teapot: ", bad[0]});
    }
}

// dense_teapot draws exactly the triangles asked for, the bunny's count from
// its stand-in name (each triangle's three indices go through the vertex
// cache once: hits + misses = 3 x triangles).
TEST_F(SocSim, DenseTeapotDrawsTheTrianglesAskedFor) {
  for (const std::vector<std::string>& scene_args :
       std::vector<std::vector<std::string>>{{"--triangles", "5000"}, {"--stand-in", "bunny"}}) {
    std::vector<std::string> args = {"--app", "dense_teapot", "--frames", "1", "--force", "--out", "out", "--"};
    args.insert(args.end(), scene_args.begin(), scene_args.end());
    const SimResult result = run(args);
    ASSERT_EQ(result.status, 0) << describe(result);
    const json cache = read_stats(m_dir / "out/stats.json")["stats"]["driver"]["vertex_cache"];
    const long triangles = scene_args[0] == "--triangles" ? 5000 : 69451;
    EXPECT_EQ(cache["hits"].get<long>() + cache["misses"].get<long>(), 3 * triangles) << scene_args[1];
  }
}

TEST_F(SocSim, UnknownApplicationIsRejectedListingTheKnownOnes) {
  expect_rejected(run({"--app", "no_such_app", "--out", "out"}), EXIT_USAGE, {"no_such_app", "pattern"});
}

TEST_F(SocSim, UnknownBackEndIsRejected) {
  expect_rejected(run({"--backend", "foo", "--out", "out"}), EXIT_USAGE, {"driver.backend", "foo", "arm"});
}

TEST_F(SocSim, UnwritableOutputFolderIsRejected) {
  expect_rejected(run({"--frames", "1", "--out", "/proc/forbidden"}), EXIT_USAGE, {"/proc/forbidden"});
  std::ofstream(m_dir / "plain_file") << "not a folder\n";
  expect_rejected(run({"--frames", "1", "--out", "plain_file/out"}), EXIT_USAGE, {"plain_file/out"});
}

TEST_F(SocSim, UnwritableStatsPathIsRejected) {
  std::ofstream(m_dir / "plain_file") << "not a folder\n";
  expect_rejected(run({"--frames", "1", "--out", "out", "--stats", "plain_file/stats.json"}), EXIT_USAGE,
                  {"plain_file/stats.json"});
  expect_rejected(run({"--frames", "1", "--out", "out", "--stats", "missing_folder/stats.json"}), EXIT_USAGE,
                  {"missing_folder/stats.json"});
  fs::create_directory(m_dir / "a_folder");
  expect_rejected(run({"--frames", "1", "--out", "out", "--stats", "a_folder"}), EXIT_USAGE, {"a_folder"});
}

TEST_F(SocSim, UnwritableVcdPathIsRejected) {
  std::ofstream(m_dir / "plain_file") << "not a folder\n";
  expect_rejected(run({"--frames", "1", "--out", "out", "--vcd", "plain_file/trace.vcd"}), EXIT_USAGE,
                  {"plain_file/trace.vcd"});
}

TEST_F(SocSim, UnmappedAccessFailsTheSimulationNamingTheAddress) {
  const SimResult result = run({"--app", "unmapped_access", "--out", "out"});
  expect_no_crash(result);
  EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
  // soc_sim's own report names the bus error and the address...
  bool reported = false, logged = false;
  std::istringstream lines(result.err);
  for (std::string line; std::getline(lines, line);) {
    if (contains(line, "soc_sim") && contains(line, "bus error") && contains(line, "0x80000000")) reported = true;
    // ...and the bus warns, naming the initiator and the address.
    if (contains(line, "bus") && contains(line, "warning") && contains(line, "host") && contains(line, "0x80000000"))
      logged = true;
  }
  EXPECT_TRUE(reported) << describe(result);
  EXPECT_TRUE(logged) << describe(result);
  // The failed run still leaves its statistics, with the error counted.
  const json document = read_stats(m_dir / "out/stats.json");
  EXPECT_EQ(document["exit_status"], EXIT_FAILED);
  EXPECT_EQ(document["stats"]["bus"]["initiators"]["host"]["errors"], 1);
}

TEST_F(SocSim, ListAppsDescribesTheDiagnostic) {
  const SimResult result = run({"--list-apps"});
  EXPECT_EQ(result.status, 0) << describe(result);
  for (const char* app : {"pattern", "calib_add", "calib_mul", "calib_display_port", "unmapped_access"})
    EXPECT_TRUE(contains(result.out, app)) << result.out;
  EXPECT_TRUE(contains(result.out, "diagnostic: reads an unmapped address to show the bus error path")) << result.out;
}

// docs/spec/calibration.md's figures, each reproduced by its scenario
// within CALIBRATION_TOLERANCE on both host models: the host-compiled one
// (the default) and the ISS running the driver cross-compiled for the
// ARM922T (host.model=iss, the reference; docs/calibration.md). Each ISS run
// takes well under a second.
namespace {

constexpr double CALIBRATION_TOLERANCE = 0.03;

const std::vector<std::string> ON_THE_ISS = {"--set", "host.model=iss"};

std::vector<std::string> with(std::vector<std::string> args, const std::vector<std::string>& more) {
  args.insert(args.end(), more.begin(), more.end());
  return args;
}

// The board measured 13.9 million loop iterations per second for both loops.
void expect_calibrated(const SimResult& result) {
  ASSERT_EQ(result.status, 0) << describe(result);
  std::smatch match;
  ASSERT_TRUE(std::regex_search(result.out, match, std::regex(R"(model ([0-9]+(\.[0-9]+)?) million/s)"))) << result.out;
  const double rate = std::stod(match[1]);
  EXPECT_NEAR(rate, 13.9, 13.9 * CALIBRATION_TOLERANCE) << result.out;
}

}  // namespace

TEST_F(SocSim, AdditionLoopMatchesTheMeasuredRate) {
  expect_calibrated(run({"--app", "calib_add", "--out", "out"}));
}

TEST_F(SocSim, AdditionLoopMatchesTheMeasuredRateOnTheIss) {
  expect_calibrated(run(with({"--app", "calib_add", "--out", "out"}, ON_THE_ISS)));
}

TEST_F(SocSim, MultiplicationLoopMatchesTheMeasuredRate) {
  expect_calibrated(run({"--app", "calib_mul", "--out", "out"}));
}

TEST_F(SocSim, MultiplicationLoopMatchesTheMeasuredRateOnTheIss) {
  expect_calibrated(run(with({"--app", "calib_mul", "--out", "out"}, ON_THE_ISS)));
}

// docs/spec/calibration.md: the board's host copies one finished 192x144
// 16-bit frame to the display port in 36 ms; display.port_cycles is
// calibrated to it (docs/calibration.md).
namespace {

void expect_display_port_calibrated(const SimResult& result) {
  ASSERT_EQ(result.status, 0) << describe(result);
  std::smatch match;
  ASSERT_TRUE(std::regex_search(result.out, match, std::regex(R"(model ([0-9]+\.[0-9]+) ms, measured 36 ms)")))
      << result.out;
  EXPECT_NEAR(std::stod(match[1]), 36.0, 36.0 * CALIBRATION_TOLERANCE) << result.out;
}

const std::vector<std::string> STUDY_DISPLAY = {"--set", "display.width=192", "--set", "display.height=144"};

}  // namespace

TEST_F(SocSim, DisplayPortCopyMatchesTheMeasuredTime) {
  expect_display_port_calibrated(run(with({"--app", "calib_display_port", "--out", "out"}, STUDY_DISPLAY)));
  EXPECT_TRUE(fs::is_regular_file(m_dir / "out/frame_0000.png"));
}

TEST_F(SocSim, DisplayPortCopyMatchesTheMeasuredTimeOnTheIss) {
  expect_display_port_calibrated(
      run(with(with({"--app", "calib_display_port", "--no-frames", "--out", "out"}, STUDY_DISPLAY), ON_THE_ISS)));
}

// docs/spec/calibration.md's array figures. Each scenario runs real array
// programs and checks every CU's result itself (exit status 1 otherwise);
// the model's figure must be within `tolerance` of the board's.
namespace {

void expect_array_figure(const SimResult& result, const std::string& what, double measured, double tolerance) {
  ASSERT_EQ(result.status, 0) << describe(result);
  std::smatch match;
  ASSERT_TRUE(std::regex_search(result.out, match, std::regex(what + R"(: model ([0-9]+\.[0-9]+) )"))) << result.out;
  EXPECT_NEAR(std::stod(match[1]), measured, measured * tolerance) << result.out;
}

// calib_ciu: the study's loop of WriteMem32 and ReadMem32 calls; the CIU's
// latencies were fitted on the ISS, and the host-compiled driver charges
// the ISS's cycles per call (docs/calibration.md, "The CIU").
void expect_ciu_figures(const SimResult& result) {
  expect_array_figure(result, "one 32-bit CIU write from the ARM, address computation included", 488,
                      CALIBRATION_TOLERANCE);
  expect_array_figure(result, "one 32-bit CIU read from the ARM, address computation included", 830,
                      CALIBRATION_TOLERANCE);
}

}  // namespace

// The array's own figures: the host only sets them up, so both hosts give
// them, within 1 % but for the CMEM addition (64.0 ns is 6.144 array
// cycles: the whole cycles of the ISA give 62.5 ns).
TEST_F(SocSim, ArrayRegisterAdditionTakesTheMeasuredCycles) {
  expect_array_figure(run({"--app", "calib_array_add", "--out", "out"}), "16-bit addition, register level", 4, 0.01);
}

TEST_F(SocSim, ArrayRegisterAdditionTakesTheMeasuredCyclesOnTheIss) {
  expect_array_figure(run(with({"--app", "calib_array_add", "--no-frames", "--out", "out"}, ON_THE_ISS)),
                      "16-bit addition, register level", 4, 0.01);
}

TEST_F(SocSim, ArrayRegisterMultiplicationTakesTheMeasuredCycles) {
  expect_array_figure(run({"--app", "calib_array_mul", "--out", "out"}),
                      "signed 16 x 8-bit multiplication, register level", 40, 0.01);
}

TEST_F(SocSim, ArrayRegisterMultiplicationTakesTheMeasuredCyclesOnTheIss) {
  expect_array_figure(run(with({"--app", "calib_array_mul", "--no-frames", "--out", "out"}, ON_THE_ISS)),
                      "signed 16 x 8-bit multiplication, register level", 40, 0.01);
}

TEST_F(SocSim, ArrayCmemAdditionPassMatchesTheMeasuredTime) {
  expect_array_figure(run({"--app", "calib_array_add_cmem", "--out", "out"}),
                      "16-bit addition of two CMEM operands stored back, one pass of all CUs", 64.0,
                      CALIBRATION_TOLERANCE);
}

TEST_F(SocSim, ArrayCmemAdditionPassMatchesTheMeasuredTimeOnTheIss) {
  expect_array_figure(run(with({"--app", "calib_array_add_cmem", "--no-frames", "--out", "out"}, ON_THE_ISS)),
                      "16-bit addition of two CMEM operands stored back, one pass of all CUs", 64.0,
                      CALIBRATION_TOLERANCE);
}

TEST_F(SocSim, ArrayCmemMultiplicationPassMatchesTheMeasuredTime) {
  expect_array_figure(run({"--app", "calib_array_mul_cmem", "--out", "out"}),
                      "signed 16 x 8-bit multiplication of CMEM operands stored back, one pass of all CUs", 1093.44,
                      0.01);
}

TEST_F(SocSim, ArrayCmemMultiplicationPassMatchesTheMeasuredTimeOnTheIss) {
  expect_array_figure(run(with({"--app", "calib_array_mul_cmem", "--no-frames", "--out", "out"}, ON_THE_ISS)),
                      "signed 16 x 8-bit multiplication of CMEM operands stored back, one pass of all CUs", 1093.44,
                      0.01);
}

TEST_F(SocSim, CiuWritesAndReadsMatchTheMeasuredTimes) {
  expect_ciu_figures(run({"--app", "calib_ciu", "--out", "out"}));
}

TEST_F(SocSim, CiuWritesAndReadsMatchTheMeasuredTimesOnTheIss) {
  expect_ciu_figures(run(with({"--app", "calib_ciu", "--no-frames", "--out", "out"}, ON_THE_ISS)));
}

// The driver checks a loop's arguments once, before the loop: calib_ciu's
// 128 addresses do not fit a CMEM of 64 bytes, and the run says so on
// either host instead of writing into the next group's CMEM.
TEST_F(SocSim, CiuLoopBeyondTheCmemIsRefusedNamingTheAccess) {
  for (const std::string host : {"native", "iss"}) {
    const SimResult result = run(
        {"--app", "calib_ciu", "--set", "array.cmem_bytes=64", "--set", "host.model=" + host, "--out", "out_" + host});
    expect_no_crash(result);
    EXPECT_EQ(result.status, EXIT_FAILED) << describe(result);
    EXPECT_TRUE(contains(result.err, "address 127 is outside the array (6x4 groups, 64 bytes)")) << describe(result);
  }
}

// stats.energy: every unit's total is its static energy plus its events',
// the total is the units' sum, and the frames' energies add up to the
// energy from the start to the last frame's request.
TEST_F(SocSim, EnergyStatisticsAddUp) {
  const SimResult result = run({"--scene", "triangle", "--frames", "3", "--no-frames", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const json stats = read_stats(m_dir / "out/stats.json")["stats"];
  const json& energy = stats["energy"];
  double sum = 0;
  for (const auto& [name, unit] : energy["units"].items()) {
    double events = 0;
    for (const auto& [event, e] : unit["events"].items()) events += e["j"].get<double>();
    EXPECT_NEAR(unit["dynamic_j"].get<double>(), events, 1e-15) << name;
    EXPECT_NEAR(unit["total_j"].get<double>(), events + unit["static_j"].get<double>(), 1e-15) << name;
    sum += unit["total_j"].get<double>();
  }
  EXPECT_NEAR(energy["total_j"].get<double>(), sum, 1e-12);
  EXPECT_GT(energy["units"]["host"]["total_j"].get<double>(), 0);
  const double simulated = stats["simulated_ns"].get<double>() * 1e-9;
  EXPECT_NEAR(energy["average_w"].get<double>(), sum / simulated, 1e-9);
  ASSERT_EQ(stats["frames"].size(), 3u);
  double frames = 0;
  for (const json& frame : stats["frames"]) frames += frame["energy"]["total_j"].get<double>();
  EXPECT_GT(frames, 0);
  EXPECT_LE(frames, sum * (1 + 1e-9));
  EXPECT_NE(result.out.find("energy (1.2 V)"), std::string::npos) << result.out;
}

// power.sleep_unused: an arm run never uses the array, which sleeps (no
// static power, as the board measured with unused blocks asleep); with the
// switch off it is clocked from reset and charged its static power for the
// whole run. Nothing else changes.
TEST_F(SocSim, AnUnusedArraySleepsUnlessSleepIsSwitchedOff) {
  const SimResult asleep = run({"--scene", "triangle", "--frames", "2", "--no-frames", "--out", "asleep"});
  const SimResult clocked = run(
      {"--scene", "triangle", "--frames", "2", "--no-frames", "--out", "clocked", "--set", "power.sleep_unused=false"});
  ASSERT_EQ(asleep.status, 0) << describe(asleep);
  ASSERT_EQ(clocked.status, 0) << describe(clocked);
  const json a = read_stats(m_dir / "asleep/stats.json");
  const json c = read_stats(m_dir / "clocked/stats.json");
  const double static_mw = c["config"]["power"]["cu_array"]["static_mw"].get<double>();
  ASSERT_GT(static_mw, 0);
  const double simulated = c["stats"]["simulated_ns"].get<double>() * 1e-9;
  EXPECT_EQ(a["stats"]["energy"]["units"]["cu_array"]["static_j"].get<double>(), 0.0);
  EXPECT_NEAR(c["stats"]["energy"]["units"]["cu_array"]["static_j"].get<double>(), static_mw * 1e-3 * simulated, 1e-12);
  for (const char* unit : {"host", "bus", "memory", "display"})
    EXPECT_EQ(a["stats"]["energy"]["units"][unit], c["stats"]["energy"]["units"][unit]) << unit;
  EXPECT_EQ(a["stats"]["host"], c["stats"]["host"]);
}

TEST_F(SocSim, NegativeEnergyParameterIsAConfigurationError) {
  const SimResult result = run({"--set", "power.cu_array.cu_cycles_pj=-1", "--out", "out"});
  EXPECT_EQ(result.status, 2) << describe(result);
  EXPECT_NE(result.err.find("power.cu_array.cu_cycles_pj"), std::string::npos) << describe(result);
}

TEST_F(SocSim, ArrayStatisticsProfileAndTraceOfACalibrationRun) {
  const SimResult result = run({"--app", "calib_array_add", "--vcd", "out/trace.vcd", "--out", "out"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const json stats = read_stats(m_dir / "out/stats.json")["stats"];
  const json& array = stats["array"];
  EXPECT_EQ(array["programs"], 2);
  EXPECT_EQ(array["failed_programs"], 0);
  // 1000 and 2000 iterations of add and adc in the "shade" stage, 2 cycles each.
  EXPECT_EQ(array["cycles"]["shade"], 3000 * 4 + 2);
  EXPECT_EQ(array["mix"]["adc"], 3000);
  EXPECT_GT(array["cu_utilisation"].get<double>(), 0.99);
  bool found_add = false;
  for (const json& line : array["profile"])
    if (line["instruction"] == "add r1, r1, r3") {
      found_add = true;
      EXPECT_EQ(line["stage"], "shade");
      EXPECT_EQ(line["cycles"].get<uint64_t>(), 2 * line["executions"].get<uint64_t>());
    }
  EXPECT_TRUE(found_add) << array["profile"].dump();
  const json& ciu = stats["ciu"];
  EXPECT_GT(ciu["writes"].get<uint64_t>(), 0u);
  EXPECT_GT(ciu["host_wait_ns"].get<double>(), 0.0);
  EXPECT_NE(result.out.find("array "), std::string::npos) << result.out;
  const std::string vcd = tessera::test::read_file(m_dir / "out/trace.vcd");
  // The VCD nests signals in a scope per block.
  const size_t array_scope = vcd.find("$scope module array $end");
  const size_t ciu_scope = vcd.find("$scope module ciu $end");
  ASSERT_NE(array_scope, std::string::npos);
  ASSERT_NE(ciu_scope, std::string::npos);
  const std::string array_vars = vcd.substr(array_scope, vcd.find("$upscope", array_scope) - array_scope);
  for (const char* signal : {" busy ", " program [31:0] ", " stage [31:0] ", " irq "})
    EXPECT_NE(array_vars.find(signal), std::string::npos) << signal << "\n" << array_vars;
  EXPECT_NE(vcd.find(" access ", ciu_scope), std::string::npos);
}

TEST_F(SocSim, DisplayPortCalibrationOnAnotherDisplayIsRejected) {
  expect_rejected(run({"--app", "calib_display_port", "--out", "out"}), EXIT_USAGE,
                  {"calib_display_port", "192x144", "display.width=192", "display.height=144"});
  expect_rejected(run({"--app", "calib_display_port", "--set", "display.width=192", "--set", "display.height=144",
                       "--set", "display.dma=true", "--out", "out_dma"}),
                  EXIT_USAGE, {"DMA mode"});
}

TEST_F(SocSim, PrintConfigShowsTheEffectiveConfiguration) {
  SimResult result = run({"--print-config"});
  ASSERT_EQ(result.status, 0) << describe(result);
  json config = json::parse(result.out, nullptr, false);
  ASSERT_FALSE(config.is_discarded()) << result.out;
  EXPECT_EQ(config["bus"]["arbitration"], "fixed_priority");

  result = run({"--print-config", "--set", "bus.arbitration=round_robin"});
  ASSERT_EQ(result.status, 0) << describe(result);
  config = json::parse(result.out, nullptr, false);
  ASSERT_FALSE(config.is_discarded()) << result.out;
  EXPECT_EQ(config["bus"]["arbitration"], "round_robin");
}

void collect_keys(const json& node, const std::string& prefix, std::vector<std::string>& keys) {
  for (auto it = node.begin(); it != node.end(); ++it) {
    const std::string key = prefix.empty() ? it.key() : prefix + "." + it.key();
    if (it->is_object())
      collect_keys(*it, key, keys);
    else
      keys.push_back(key);
  }
}

TEST_F(SocSim, ConfigReferenceHasARowForEveryKey) {
  const SimResult printed = run({"--print-config"});
  ASSERT_EQ(printed.status, 0) << describe(printed);
  std::vector<std::string> keys;
  collect_keys(json::parse(printed.out), "", keys);
  ASSERT_GT(keys.size(), 20u);

  const SimResult result = run({"--config-reference"});
  ASSERT_EQ(result.status, 0) << describe(result);
  EXPECT_EQ(result.out.rfind("| key |", 0), 0u) << result.out.substr(0, 100);
  EXPECT_TRUE(contains(result.out, "| --- |"));
  std::set<std::string> rows;
  std::istringstream lines(result.out);
  for (std::string line; std::getline(lines, line);) {
    const auto open = line.find("| `");
    if (open != 0) continue;
    rows.insert(line.substr(3, line.find('`', 3) - 3));
  }
  for (const auto& key : keys) EXPECT_EQ(rows.count(key), 1u) << key << " has no row";
  EXPECT_EQ(rows.size(), keys.size());
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
