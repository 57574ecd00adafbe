// Loading a Wavefront OBJ model into a Mesh, with validation. Plain C++, no GL.
#pragma once

#include <string>

#include "scenes/mesh.h"

namespace tessera::scenes {

// Largest coordinate accepted in a 'v' statement: anything bigger is taken to
// be a broken export rather than a model, and would wreck the fit to view.
constexpr double MAX_OBJ_COORDINATE = 1e6;

// Reads `path`, triangulates its polygons and fills *mesh with one vertex per
// distinct (position, normal) pair. If the file has a normal for every face
// corner they are used; otherwise smooth normals are computed from the
// triangles and any normals in the file are ignored. Texture coordinates,
// materials, lines and points are ignored.
//
// On failure returns false, leaves *mesh alone and sets *error to
// "<path>:<line>: <problem>", or "<path>: <problem>" when no line is to blame.
// Failures: the file cannot be read; a statement that is not OBJ; a 'v',
// 'vn' or 'vt' with too few, unparsable or non-finite numbers, or a position
// beyond MAX_OBJ_COORDINATE; a face with fewer than three corners; an index
// that is zero or refers to an element not defined before it; no faces at
// all; more than MAX_MESH_VERTICES distinct vertices. Models that large are
// rejected rather than split into several draw calls: the built-in scenes
// are test loads for a simulated GPU, where a model that size is already
// minutes of simulation.
bool load_obj(const std::string& path, Mesh* mesh, std::string* error);

}  // namespace tessera::scenes
