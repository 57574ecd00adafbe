// System tests of the GL front end through soc_sim: applications built like
// a user's (tessera_add_app) run on every back end, and the frames and the
// statistics show what the front end did.
//
// Usage: test_gl_front_end <soc_sim> <libcollinear_triangles.so> <libempty_scissor.so> [GoogleTest options]
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "fixtures/backend_table.h"
#include "fixtures/soc_sim_test.h"
#include "frame_writer.h"
#include "scenes/teapot_mesh.h"

namespace {

namespace fs = std::filesystem;

std::string g_collinear_app;
std::string g_empty_scissor_app;

using tessera::test::describe;
using tessera::test::SimResult;

class GlFrontEnd : public tessera::test::SocSimTest {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::is_regular_file(g_collinear_app) && fs::is_regular_file(g_empty_scissor_app))
        << "usage: test_gl_front_end <soc_sim> <libcollinear_triangles.so> <libempty_scissor.so>";
    SocSimTest::SetUp();
  }
};

// Pixels whose colour is not `rgb`.
size_t pixels_other_than(const tessera::Image& image, const uint8_t (&rgb)[3]) {
  size_t count = 0;
  for (size_t i = 0; i + 3 < image.rgba.size(); i += 4)
    if (image.rgba[i] != rgb[0] || image.rgba[i + 1] != rgb[1] || image.rgba[i + 2] != rgb[2]) ++count;
  return count;
}

// Triangles with three collinear vertices have no area: before the front
// end decided that on unsnapped coordinates, each drew a dotted line.
TEST_F(GlFrontEnd, CollinearTrianglesDrawNothingOnEveryBackEnd) {
  const uint8_t clear_blue[3] = {0, 0, 255};
  for (const std::string& backend : tessera::test::back_end_names()) {
    const SimResult result = run({"--backend", backend, "--app", g_collinear_app, "--frames", "1", "--out", backend});
    ASSERT_EQ(result.status, 0) << backend << ": " << describe(result);
    const tessera::Image frame = tessera::read_image((m_dir / backend / "frame_0000.png").string());
    ASSERT_GT(frame.rgba.size(), 0u);
    EXPECT_EQ(pixels_other_than(frame, clear_blue), 0u) << backend << ": pixels drawn by zero-area triangles";
  }
}

// A scissor box of zero width or height lets no pixel through: a clear and
// a full-window quad under it change nothing, on every back end. ap-tile,
// which has no per-pixel scissor, drew the quad over the whole frame.
TEST_F(GlFrontEnd, EmptyScissorBoxDrawsAndClearsNothingOnEveryBackEnd) {
  const uint8_t clear_blue[3] = {0, 0, 255};
  for (const std::string& backend : tessera::test::back_end_names()) {
    const SimResult result =
        run({"--backend", backend, "--app", g_empty_scissor_app, "--frames", "2", "--out", backend});
    ASSERT_EQ(result.status, 0) << backend << ": " << describe(result);
    for (const char* name : {"frame_0000.png", "frame_0001.png"}) {
      const tessera::Image frame = tessera::read_image((m_dir / backend / name).string());
      ASSERT_GT(frame.rgba.size(), 0u) << backend << " " << name;
      EXPECT_EQ(pixels_other_than(frame, clear_blue), 0u)
          << backend << " " << name << ": pixels drawn or cleared through an empty scissor box";
    }
  }
}

// The teapot draws its mesh with one glDrawElements a frame; the vertex
// cache transforms each vertex the mesh uses once and finds it for the
// other indices (stats.json, "driver"), on every back end alike.
TEST_F(GlFrontEnd, TeapotTransformsEachVertexOncePerFrame) {
  const tessera::scenes::Mesh mesh = tessera::scenes::teapot_mesh(4);  // as sw_driver/scenes/teapot.cpp draws it
  const std::set<uint16_t> used(mesh.indices.begin(), mesh.indices.end());
  const uint64_t frames = 2, indices = mesh.indices.size(), vertices = used.size();
  for (const std::string& backend : tessera::test::back_end_names()) {
    const SimResult result = run({"--backend", backend, "--app", "teapot", "--frames", "2", "--out", backend});
    ASSERT_EQ(result.status, 0) << backend << ": " << describe(result);
    std::ifstream in(m_dir / backend / "stats.json");
    const nlohmann::json document = nlohmann::json::parse(in, nullptr, false);
    ASSERT_FALSE(document.is_discarded()) << backend << ": stats.json is not valid JSON";
    const nlohmann::json& driver = document["stats"]["driver"];
    ASSERT_TRUE(driver.contains("vertex_cache")) << backend << ": " << driver.dump(2);
    const uint64_t hits = driver["vertex_cache"]["hits"], misses = driver["vertex_cache"]["misses"];
    EXPECT_EQ(misses, frames * vertices) << backend;
    EXPECT_EQ(hits, frames * (indices - vertices)) << backend;
    EXPECT_EQ(driver["vertices_transformed"].get<uint64_t>(), misses) << backend;
    // 2,976 indices and 792 vertices used: 73% of the look-ups hit.
    EXPECT_GT(static_cast<double>(hits) / static_cast<double>(hits + misses), 0.73) << backend;
  }
}

}  // namespace

int main(int argc, char** argv) {
  tessera::test::init_soc_sim_test(argc, argv);
  if (argc >= 4) {
    g_collinear_app = fs::absolute(argv[2]).string();
    g_empty_scissor_app = fs::absolute(argv[3]).string();
  }
  return RUN_ALL_TESTS();
}
