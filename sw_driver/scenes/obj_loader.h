// Loading a Wavefront OBJ model into a Mesh, with validation. Plain C++, no GL.
#pragma once

#include <cstddef>
#include <string>

#include "scenes/mesh.h"

namespace tessera::scenes {

// Largest coordinate accepted in a 'v' statement: anything bigger is taken to
// be a broken export rather than a model, and would wreck the fit to view.
constexpr double MAX_OBJ_COORDINATE = 1e6;

// Largest file read: far above any model that fits MAX_MESH_VERTICES (a
// model of 65536 vertices with normals and 130000 faces is about 12 MB);
// a bigger file, or a device such as /dev/zero, is refused.
constexpr std::size_t MAX_OBJ_FILE_BYTES = 64u * 1024 * 1024;

// Most corners in one 'f', 'l' or 'p' statement. tinyobjloader triangulates
// a polygon by ear clipping, whose time grows with the square of the corners
// or worse, so a giant polygon would hang rather than fail.
constexpr std::size_t MAX_OBJ_FACE_CORNERS = 256;

// Reads `path`, triangulates its polygons and fills *mesh with one vertex per
// distinct (position, normal) pair. If the file has a normal for every face
// corner they are used; otherwise smooth normals are computed from the
// triangles and any normals in the file are ignored. Texture coordinates,
// materials, lines and points are ignored.
//
// On failure returns false, leaves *mesh alone and sets *error to
// "<path>:<line>: <problem>", or "<path>: <problem>" when no line is to blame.
// Failures: the file cannot be read or is larger than MAX_OBJ_FILE_BYTES; a
// control character (a NUL byte, a carriage return inside a line); a
// statement that is not OBJ; a 'v', 'vn' or 'vt' with too few, unparsable or
// non-finite numbers, a number that is not plain decimal (0x10, which
// tinyobjloader would read differently), or a position beyond
// MAX_OBJ_COORDINATE; a face with fewer than three or more than
// MAX_OBJ_FACE_CORNERS corners; a malformed corner; an index that is zero or
// refers to an element not defined before it; no faces at all; more than
// MAX_MESH_VERTICES distinct vertices. Models that large are
// rejected rather than split into several draw calls: the built-in scenes
// are test loads for a simulated GPU, where a model that size is already
// minutes of simulation.
bool load_obj(const std::string& path, Mesh* mesh, std::string* error);

}  // namespace tessera::scenes
