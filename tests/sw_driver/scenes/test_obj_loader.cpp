// OBJ loading: the valid cubes load with the right counts; each malformed
// file is rejected with an error naming the file, the line and the problem.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "scenes/obj_loader.h"

namespace tessera::scenes {
namespace {

std::string data_file(const std::string& name) {
  return std::string(TESSERA_SCENE_TEST_DATA) + "/" + name;
}

void expect_unit_normals(const Mesh& mesh) {
  ASSERT_EQ(mesh.normals.size(), mesh.positions.size());
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const float* n = &mesh.normals[3 * v];
    EXPECT_NEAR(std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]), 1.0, 1e-5) << "vertex " << v;
  }
}

TEST(ObjLoader, CubeWithoutNormalsGetsSmoothComputedNormals) {
  Mesh mesh;
  std::string error;
  ASSERT_TRUE(load_obj(data_file("cube.obj"), &mesh, &error)) << error;
  EXPECT_EQ(mesh.vertex_count(), 8u);
  EXPECT_EQ(mesh.triangle_count(), 12u);
  expect_unit_normals(mesh);
  // A corner's smooth normal points along its diagonal, away from the centre.
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v)
    for (int axis = 0; axis < 3; ++axis)
      EXPECT_NEAR(mesh.normals[3 * v + axis], std::copysign(1.0 / std::sqrt(3.0), mesh.positions[3 * v + axis]), 1e-5);
  const Bounds bounds = mesh_bounds(mesh);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_FLOAT_EQ(bounds.min[axis], -0.5f);
    EXPECT_FLOAT_EQ(bounds.max[axis], 0.5f);
  }
}

TEST(ObjLoader, CubeWithNormalsKeepsThemPerFace) {
  Mesh mesh;
  std::string error;
  ASSERT_TRUE(load_obj(data_file("cube_normals.obj"), &mesh, &error)) << error;
  EXPECT_EQ(mesh.vertex_count(), 24u);
  EXPECT_EQ(mesh.triangle_count(), 12u);
  expect_unit_normals(mesh);
  // Each face normal is an axis and agrees with the triangle's winding.
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint16_t* c = &mesh.indices[3 * t];
    auto at = [&mesh](std::uint16_t v, int axis) { return double(mesh.positions[3 * v + axis]); };
    const double e1[3] = {at(c[1], 0) - at(c[0], 0), at(c[1], 1) - at(c[0], 1), at(c[1], 2) - at(c[0], 2)};
    const double e2[3] = {at(c[2], 0) - at(c[0], 0), at(c[2], 1) - at(c[0], 1), at(c[2], 2) - at(c[0], 2)};
    const double face[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
    const float* n = &mesh.normals[3 * c[0]];
    EXPECT_GT(face[0] * n[0] + face[1] * n[1] + face[2] * n[2], 0.0) << "triangle " << t;
  }
}

TEST(ObjLoader, FitToUnitSphereCentresAndScales) {
  Mesh mesh;
  std::string error;
  ASSERT_TRUE(load_obj(data_file("cube.obj"), &mesh, &error)) << error;
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) mesh.positions[i] = mesh.positions[i] * 10.0f + 7.0f;
  fit_to_unit_sphere(&mesh);
  for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
    const float* p = &mesh.positions[3 * v];
    EXPECT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 1.0, 1e-5);
  }
}

struct Malformed {
  const char* file;
  // ":<line>:" or, for a fault of the whole file, ": " right after the name.
  const char* location;
  const char* problem;
};

class ObjLoaderRejects : public ::testing::TestWithParam<Malformed> {};

TEST_P(ObjLoaderRejects, WithFileLineAndProblem) {
  const Malformed& bad = GetParam();
  const std::string path = data_file(bad.file);
  Mesh mesh;
  mesh.positions = {1.0f, 2.0f, 3.0f};
  std::string error;
  EXPECT_FALSE(load_obj(path, &mesh, &error));
  EXPECT_EQ(error.rfind(path + bad.location, 0), 0u) << error;
  EXPECT_NE(error.find(bad.problem), std::string::npos) << error;
  EXPECT_EQ(mesh.positions.size(), 3u) << "the mesh must be left alone";
}

INSTANTIATE_TEST_SUITE_P(MalformedFiles, ObjLoaderRejects,
                         ::testing::Values(Malformed{"bad_index.obj", ":8:", "vertex index 9 is out of range"},
                                           Malformed{"nan_coordinate.obj", ":4:", "'nan' is not finite"},
                                           Malformed{"huge_coordinate.obj", ":3:", "1e30 is too large"},
                                           Malformed{"garbage_line.obj", ":5:", "not an OBJ statement: 'this'"},
                                           Malformed{"empty.obj", ": ", "empty"},
                                           Malformed{"short_face.obj", ":6:", "needs at least 3 vertices, has 2"},
                                           Malformed{"no_such_file.obj", ": ", "cannot open"}),
                         [](const ::testing::TestParamInfo<Malformed>& case_info) {
                           std::string name = case_info.param.file;
                           return name.substr(0, name.find('.'));
                         });

class TemporaryObj {
 public:
  explicit TemporaryObj(const std::string& text) {
    std::string name = (std::filesystem::temp_directory_path() / "tessera_test_obj_XXXXXX").string();
    const int fd = mkstemp(name.data());
    if (fd >= 0) close(fd);
    m_path = name;
    std::ofstream(m_path) << text;
  }
  ~TemporaryObj() { std::remove(m_path.c_str()); }
  const std::string& path() const { return m_path; }

 private:
  std::string m_path;
};

TEST(ObjLoader, RejectsMoreVerticesThanSixteenBitIndicesAddress) {
  // A strip of 70000 vertices along x, each triangle using three new ones.
  constexpr int VERTICES = 70002;
  std::string text;
  for (int v = 0; v < VERTICES; ++v) text += "v " + std::to_string(v % 1000) + " " + std::to_string(v / 1000) + " 0\n";
  for (int v = 1; v + 2 <= VERTICES; v += 3)
    text += "f " + std::to_string(v) + " " + std::to_string(v + 1) + " " + std::to_string(v + 2) + "\n";
  const TemporaryObj obj(text);
  Mesh mesh;
  std::string error;
  EXPECT_FALSE(load_obj(obj.path(), &mesh, &error));
  EXPECT_EQ(error.rfind(obj.path() + ": 70002 distinct vertices", 0), 0u) << error;
  EXPECT_NE(error.find("16-bit"), std::string::npos) << error;
}

TEST(ObjLoader, AcceptsNegativeIndicesPolygonsAndCommentsAndRejectsFaceWithoutVertices) {
  const TemporaryObj good("# comment\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\ng quad\nf -4 -3 -2 -1 # trailing\n");
  Mesh mesh;
  std::string error;
  ASSERT_TRUE(load_obj(good.path(), &mesh, &error)) << error;
  EXPECT_EQ(mesh.vertex_count(), 4u);
  EXPECT_EQ(mesh.triangle_count(), 2u);

  const TemporaryObj before("f 1 2 3\nv 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_FALSE(load_obj(before.path(), &mesh, &error));
  EXPECT_NE(error.find(":1: vertex index 1 is out of range: 0 vertices defined before this line"), std::string::npos)
      << error;

  const TemporaryObj zero("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_FALSE(load_obj(zero.path(), &mesh, &error));
  EXPECT_NE(error.find(":4: vertex index 0 is out of range"), std::string::npos) << error;

  const TemporaryObj no_faces("v 0 0 0\nv 1 0 0\nv 0 1 0\n");
  EXPECT_FALSE(load_obj(no_faces.path(), &mesh, &error));
  EXPECT_NE(error.find("no faces"), std::string::npos) << error;
}

}  // namespace
}  // namespace tessera::scenes
