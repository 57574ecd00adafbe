// The cluster platform's gathered frames against Mesa: soc_sim --platform
// cluster draws the random scene and the teapot on several node counts, and
// Mesa (the reference oracle, testbench/reference) draws the same triangles
// (the same world positions, lit vertex colours and view, from the
// GL-free cluster::ClusterScene) with GL's depth test, back-face culling
// and smooth shading. The comparison is the built-in scenes' (coverage
// mismatches only on edges; colours within tolerance).
//
// Usage: test_cluster_mesa <path to soc_sim> [GoogleTest options]
#include <GL/gl.h>

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "cluster/cluster_scene.h"
#include "fixtures/soc_sim_test.h"
#include "frame_writer.h"
#include "reference/image_compare.h"
#include "reference/mesa_reference.h"

namespace {

namespace fs = std::filesystem;
using tessera::test::describe;
using tessera::test::SimResult;

// The scene Mesa draws: the one the nodes draw, set before each render.
std::unique_ptr<tessera::cluster::ClusterScene>& current() {
  static std::unique_ptr<tessera::cluster::ClusterScene> scene;
  return scene;
}

bool init(int /*width*/, int /*height*/, const std::vector<std::string>& /*args*/, std::string* /*error*/) {
  glClearColor(0.0f, 0.0f, 0.0f, 1.0f);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glShadeModel(GL_SMOOTH);
  glDisable(GL_DITHER);
  return true;
}

void draw(int /*frame*/) {
  const tessera::cluster::ClusterScene& scene = *current();
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixf(scene.view().matrix.m);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glBegin(GL_TRIANGLES);
  for (uint32_t i = 0; i < scene.triangles(); ++i) {
    const tessera::cluster::WorldTriangle t = scene.triangle(i);
    for (const tessera::cluster::WorldVertex& v : t.v) {
      glColor3f(v.r, v.g, v.b);
      glVertex3f(v.x, v.y, v.z);
    }
  }
  glEnd();
}

class ClusterMesa : public tessera::test::SocSimTest {
 protected:
  void compare(const std::string& scene_name, unsigned nodes, unsigned width, unsigned height) {
    const std::string out = scene_name + "_" + std::to_string(nodes);
    const SimResult result =
        run({"--platform", "cluster", "--scene", scene_name, "--frames", "1", "--out", out, "--set",
             "cluster.nodes=" + std::to_string(nodes), "--set", "cluster.triangles=3000", "--set",
             "cluster.width=" + std::to_string(width), "--set", "cluster.height=" + std::to_string(height)});
    ASSERT_EQ(result.status, 0) << describe(result);
    const tessera::Image ours = tessera::read_image((m_dir / out / "frame_0000.png").string());

    current() = std::make_unique<tessera::cluster::ClusterScene>(scene_name, 3000, 10, 1, width, height);
    const tessera::scenes::Scene reference_scene{"cluster", "the cluster's scene", init, draw};
    tessera::reference::ReferenceRequest request;
    request.width = width;
    request.height = height;
    const tessera::reference::ReferenceFrame reference = tessera::reference::render_with_mesa(reference_scene, request);

    tessera::reference::CompareOptions options;
    options.format = tessera::PixelFormat::rgba8888;
    options.clear_colour = {reference.clear_colour[0], reference.clear_colour[1], reference.clear_colour[2],
                            reference.clear_colour[3]};
    const tessera::reference::CompareResult compared =
        tessera::reference::compare_images(ours, reference.image, options);
    // The random triangles cross each other in depth everywhere; where two
    // meet, our 24-bit depth and Mesa's order them differently along the
    // line they cut, so colour differences follow those lines and a few
    // pixels of coverage differ off the triangles' edges (slivers).
    tessera::reference::PassRule rule;
    rule.allowed_coverage_mismatches = compared.pixels / 100;
    rule.min_percent_within_tolerance = 98.0;
    EXPECT_LE(compared.coverage_off_edges, compared.pixels / 1000) << compared.summary();
    EXPECT_TRUE(compared.passes(rule)) << scene_name << " on " << nodes << " nodes: " << compared.summary() << "; "
                                       << tessera::reference::write_comparison_images(
                                              m_dir.string(), out, ours, reference.image, compared, options);
    size_t drawn = 0;
    for (size_t i = 0; i < ours.rgba.size(); i += 4)
      drawn += ours.rgba[i] != 0 || ours.rgba[i + 1] != 0 || ours.rgba[i + 2] != 0;
    EXPECT_GT(drawn, compared.pixels / 20) << "too little drawn to compare";
  }
};

TEST_F(ClusterMesa, RandomTrianglesOnOneAndSixteenNodes) {
  compare("random_triangles", 1, 160, 120);
  compare("random_triangles", 16, 160, 120);
}

TEST_F(ClusterMesa, TeapotOnEightNodes) {
  compare("teapot", 8, 160, 120);
}

}  // namespace

int main(int argc, char** argv) {
  return tessera::test::soc_sim_test_main(argc, argv);
}
