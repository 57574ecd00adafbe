// Fuzz target: the Wavefront OBJ loader (sw_driver/scenes/obj_loader.cpp),
// the input being the file's bytes.
//
// Checks: a rejected file gives an error that names the file; an accepted
// one gives a mesh the GL can draw as it is: whole triangles, every index
// below the vertex count, one unit-or-zero finite normal per position, every
// coordinate finite and within MAX_OBJ_COORDINATE, at most MAX_MESH_VERTICES
// vertices.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "scenes/obj_loader.h"

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using tessera::fuzz::fail;
  namespace scenes = tessera::scenes;
  static tessera::fuzz::ScratchFile file(".obj");
  const std::string& path = file.write(data, size);

  scenes::Mesh mesh;
  std::string error;
  if (!scenes::load_obj(path, &mesh, &error)) {
    if (error.compare(0, path.size(), path) != 0) fail("the error does not name the file: " + error);
    if (!mesh.positions.empty() || !mesh.indices.empty()) fail("a rejected file changed the mesh");
    return 0;
  }
  if (!error.empty()) fail("an accepted file set an error: " + error);
  if (mesh.positions.size() % 3 != 0 || mesh.indices.size() % 3 != 0) fail("a partial vertex or triangle");
  if (mesh.indices.empty()) fail("an accepted mesh without triangles");
  if (mesh.normals.size() != mesh.positions.size()) fail("not one normal per position");
  if (mesh.vertex_count() > scenes::MAX_MESH_VERTICES) fail("more vertices than MAX_MESH_VERTICES");
  for (const uint16_t index : mesh.indices)
    if (index >= mesh.vertex_count()) fail("an index beyond the vertices");
  for (const float c : mesh.positions)
    if (!std::isfinite(c) || std::fabs(c) > scenes::MAX_OBJ_COORDINATE) fail("a position out of range");
  for (size_t v = 0; v < mesh.vertex_count(); ++v) {
    const float* n = &mesh.normals[3 * v];
    if (!std::isfinite(n[0]) || !std::isfinite(n[1]) || !std::isfinite(n[2])) fail("a normal that is not finite");
    const double length = std::sqrt(double(n[0]) * n[0] + double(n[1]) * n[1] + double(n[2]) * n[2]);
    if (length > 1.001) fail("a normal longer than 1");
  }
  return 0;
}
