// System tests of soc_sim's back-end choice: every back end of
// sw_driver/renderers/backends.def runs a GL application, is named in the
// help, and is listed when an unknown name is rejected. The list comes from
// the table, so a back end added there is run here without editing this file.
//
// Usage: test_soc_sim_backends <path to soc_sim> [GoogleTest options]
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include "fixtures/backend_table.h"
#include "fixtures/soc_sim_test.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using tessera::test::contains;
using tessera::test::describe;
using tessera::test::SimResult;

constexpr int EXIT_USAGE = 2;

using SocSimBackends = tessera::test::SocSimTest;

TEST_F(SocSimBackends, EveryBackEndDrawsAFrameAndIsRecorded) {
  for (const tessera::test::BackendEntry& backend : tessera::test::backend_table()) {
    SCOPED_TRACE(backend.name);
    const SimResult result =
        run({"--backend", backend.name, "--app", "triangle", "--frames", "1", "--out", backend.id});
    ASSERT_EQ(result.status, 0) << describe(result);
    EXPECT_TRUE(fs::is_regular_file(m_dir / backend.id / "frame_0000.png"));
    std::ifstream in(m_dir / backend.id / "stats.json");
    const json document = json::parse(in, nullptr, false);
    ASSERT_FALSE(document.is_discarded()) << "stats.json is not valid JSON";
    EXPECT_EQ(document["config"]["driver"]["backend"], backend.name);
    EXPECT_EQ(document["stats"]["display"]["frames_shown"], 1);
  }
}

TEST_F(SocSimBackends, HelpNamesEveryBackEnd) {
  const SimResult result = run({"--help"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const size_t line_start = result.out.find("--backend");
  ASSERT_NE(line_start, std::string::npos) << result.out;
  const std::string line = result.out.substr(line_start, result.out.find('\n', line_start) - line_start);
  for (const tessera::test::BackendEntry& backend : tessera::test::backend_table())
    EXPECT_TRUE(contains(line, backend.name)) << "'" << backend.name << "' not in: " << line;
}

TEST_F(SocSimBackends, UnknownBackEndIsRejectedListingEveryOne) {
  const SimResult result = run({"--backend", "no-such-backend", "--out", "out"});
  EXPECT_EQ(result.status, EXIT_USAGE) << describe(result);
  EXPECT_TRUE(contains(result.err, "driver.backend")) << describe(result);
  EXPECT_TRUE(contains(result.err, "no-such-backend")) << describe(result);
  for (const tessera::test::BackendEntry& backend : tessera::test::backend_table())
    EXPECT_TRUE(contains(result.err, backend.name)) << describe(result);
  EXPECT_FALSE(fs::exists(m_dir / "out/stats.json"));
}

TEST_F(SocSimBackends, ConfigurationNamesEveryBackEnd) {
  const SimResult result = run({"--config-reference"});
  ASSERT_EQ(result.status, 0) << describe(result);
  const size_t row = result.out.find("`driver.backend`");
  ASSERT_NE(row, std::string::npos) << result.out;
  const std::string line = result.out.substr(row, result.out.find('\n', row) - row);
  for (const tessera::test::BackendEntry& backend : tessera::test::backend_table())
    EXPECT_TRUE(contains(line, backend.name)) << "'" << backend.name << "' not in: " << line;
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
