// OBJ loading: the valid cubes load with the right counts; each malformed
// file is rejected with an error naming the file, the line and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "process/scratch_folder.h"
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

// An OBJ file in a folder of its own, removed with it.
class TemporaryObj {
 public:
  explicit TemporaryObj(const std::string& text)
      : m_folder("tessera_test_obj"), m_path((m_folder.path() / "model.obj").string()) {
    std::ofstream(m_path) << text;
  }
  const std::string& path() const { return m_path; }

 private:
  tessera::test::ScratchFolder m_folder;
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

// Issue 14: the check and tinyobjloader must read the same file, and no file
// may take unbounded time or memory. Each case is a one-triangle model with
// one fault; the error names the file, the line and the problem.
struct Disagreement {
  const char* name;
  std::string text;
  const char* location;
  const char* problem;
};

void PrintTo(const Disagreement& bad, std::ostream* out) {
  *out << bad.name;
}

class ObjLoaderRefusesWhatTheParsersReadDifferently : public ::testing::TestWithParam<Disagreement> {};

TEST_P(ObjLoaderRefusesWhatTheParsersReadDifferently, WithFileLineAndProblem) {
  const Disagreement& bad = GetParam();
  const TemporaryObj obj(bad.text);
  Mesh mesh;
  std::string error;
  EXPECT_FALSE(load_obj(obj.path(), &mesh, &error));
  EXPECT_EQ(error.rfind(obj.path() + bad.location, 0), 0u) << error;
  EXPECT_NE(error.find(bad.problem), std::string::npos) << error;
}

const std::string TRIANGLE_TAIL = "v 1 0 0\nv 0 1 0\nf 1 2 3\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, ObjLoaderRefusesWhatTheParsersReadDifferently,
    ::testing::Values(
        // strtod reads 16, tinyobjloader 0.
        Disagreement{"hexadecimal", "v 0x10 0 0\n" + TRIANGLE_TAIL, ":1:", "'0x10' is not a plain decimal number"},
        Disagreement{"hex_float", "v 0 0x1p3 0\n" + TRIANGLE_TAIL, ":1:", "'0x1p3' is not a plain decimal"},
        Disagreement{"empty_exponent", "v 0 0 1.5e\n" + TRIANGLE_TAIL, ":1:", "'1.5e' is not a number"},
        Disagreement{"bare_dot", "v 0 . 0\n" + TRIANGLE_TAIL, ":1:", "'.' is not a number"},
        // Both read 0 as plain text, but tinyobjloader computes 0 x 5^999999
        // = NaN: caught by comparing what the two read.
        Disagreement{"zero_times_huge_exponent", "v 0e999999 0 0\n" + TRIANGLE_TAIL,
                     ":1:", "vertex coordinate 1 is read as"},
        Disagreement{"zero_times_huge_exponent_names_both", "v 0e999999 0 0\n" + TRIANGLE_TAIL,
                     ":1:", "nan by tinyobjloader and as 0 by the check"},
        Disagreement{"normal_read_differently", "vn 0 0 0e999999\nv 0 0 0\n" + TRIANGLE_TAIL,
                     ":1:", "normal coordinate 3 is read as"},
        // A NUL byte after a number: strtod stops there, so did the check.
        Disagreement{"nul_after_number", std::string("v 0 0 0\nv 1 0 0\nv 0 1\0 5 0\nf 1 2 3\n", 29),
                     ":3:", "a NUL byte in column 6: not a text file"},
        Disagreement{"nul_in_comment", std::string("v 0 0 0 # \0\n", 12) + TRIANGLE_TAIL, ":1:", "a NUL byte"},
        // tinyobjloader ends a line at a carriage return; the check did not.
        Disagreement{"carriage_return_inside_line", "v 0 0 0\rv 1 0 0\nv 0 1 0\nv 1 1 0\nf 1 2 3\n",
                     ":1:", "a carriage return inside the line in column 8"},
        // The check split words at any white space, tinyobjloader at spaces
        // and tabs only.
        Disagreement{"vertical_tab", "v 0\v0 0\n" + TRIANGLE_TAIL, ":1:", "control character 0x0B in column 4"},
        Disagreement{"form_feed", "v 0 0 0\n" + TRIANGLE_TAIL + "f 1\f2 3\n", ":5:", "control character 0x0C"},
        // atoi reads a prefix.
        Disagreement{"index_with_suffix", "v 0 0 0\n" + TRIANGLE_TAIL + "f 1x 2 3\n",
                     ":5:", "malformed face corner '1x'"},
        Disagreement{"index_with_plus", "v 0 0 0\n" + TRIANGLE_TAIL + "f +1 2 3\n",
                     ":5:", "malformed face corner '+1'"},
        Disagreement{"trailing_slash", "v 0 0 0\n" + TRIANGLE_TAIL + "f 1/ 2 3\n", ":5:", "malformed face corner '1/'"},
        Disagreement{"empty_normal", "v 0 0 0\n" + TRIANGLE_TAIL + "f 1// 2 3\n",
                     ":5:", "malformed face corner '1//'"}),
    [](const ::testing::TestParamInfo<Disagreement>& case_info) { return std::string(case_info.param.name); });

TEST(ObjLoader, PlainDecimalNumbersInEveryFormAndWindowsLineEndsLoad) {
  const TemporaryObj obj("v .5 -.5 +5.\r\nv 1e-3 2.5E+1 -0\r\nv 10 0 3e0\r\nvn 0 0 1\r\nf 1//1 2//1 3//1\r\n");
  Mesh mesh;
  std::string error;
  ASSERT_TRUE(load_obj(obj.path(), &mesh, &error)) << error;
  ASSERT_EQ(mesh.vertex_count(), 3u);
  const float expected[] = {0.5f, -0.5f, 5.0f, 0.001f, 25.0f, 0.0f, 10.0f, 0.0f, 3.0f};
  for (int i = 0; i < 9; ++i) EXPECT_FLOAT_EQ(mesh.positions[i], expected[i]) << i;
}

TEST(ObjLoader, FileSizeIsLimited) {
  ASSERT_EQ(MAX_OBJ_FILE_BYTES, 64u * 1024 * 1024);
  // A sparse file one byte over the limit is refused by its size, unread.
  const TemporaryObj big("");
  std::filesystem::resize_file(big.path(), MAX_OBJ_FILE_BYTES + 1);
  Mesh mesh;
  std::string error;
  EXPECT_FALSE(load_obj(big.path(), &mesh, &error));
  EXPECT_EQ(error, big.path() + ": 67108865 bytes, more than the limit of 67108864") << error;
  // A device has no size: /dev/zero is refused at its first byte.
  if (std::filesystem::exists("/dev/zero")) {
    EXPECT_FALSE(load_obj("/dev/zero", &mesh, &error));
    EXPECT_EQ(error.rfind("/dev/zero:1: a NUL byte in column 1", 0), 0u) << error;
  }
}

TEST(ObjLoader, MaterialLibraryIsNotRead) {
  // Materials are ignored; an 'mtllib' naming /dev/zero used to be read
  // without end.
  std::string up;
  for (int i = 0; i < 32; ++i) up += "../";
  const TemporaryObj obj("mtllib " + up + "dev/zero\nusemtl red\nv 0 0 0\n" + TRIANGLE_TAIL);
  Mesh mesh;
  std::string error;
  ASSERT_TRUE(load_obj(obj.path(), &mesh, &error)) << error;
  EXPECT_EQ(mesh.triangle_count(), 1u);
}

TEST(ObjLoader, CornersPerFaceAreLimited) {
  ASSERT_EQ(MAX_OBJ_FACE_CORNERS, 256u);
  // A convex polygon of n corners on the unit circle.
  auto polygon = [](std::size_t corners) {
    std::string text;
    for (std::size_t i = 0; i < corners; ++i) {
      const double angle = 2.0 * M_PI * static_cast<double>(i) / static_cast<double>(corners);
      text += "v " + std::to_string(std::cos(angle)) + " " + std::to_string(std::sin(angle)) + " 0\n";
    }
    text += "f";
    for (std::size_t i = 1; i <= corners; ++i) text += " " + std::to_string(i);
    return text + "\n";
  };
  Mesh mesh;
  std::string error;
  const TemporaryObj most(polygon(256));
  ASSERT_TRUE(load_obj(most.path(), &mesh, &error)) << error;
  EXPECT_EQ(mesh.triangle_count(), 254u);
  const TemporaryObj over(polygon(257));
  EXPECT_FALSE(load_obj(over.path(), &mesh, &error));
  EXPECT_EQ(error, over.path() + ":258: 'f' has 257 vertices, more than the limit of 256") << error;
}

}  // namespace
}  // namespace tessera::scenes
