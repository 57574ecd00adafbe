// The Newell teapot as an indexed triangle mesh, tessellated from Martin
// Newell's 32 bicubic Bezier patches (1975; the data as distributed in the
// University of Utah "teaset", 306 control points, with Crow's four bottom
// patches). Plain C++, no GL.
#pragma once

#include <cstddef>
#include <vector>

#include "scenes/mesh.h"

namespace tessera::scenes {

constexpr int TEAPOT_PATCHES = 32;
// Each patch becomes its own (n + 1)^2 vertices, which must fit 16-bit indices.
constexpr int TEAPOT_MAX_SUBDIVISIONS = 44;

// Each patch is cut into subdivisions x subdivisions quads, two triangles
// each. The eight patches that close to a point (four at the lid's knob, four
// at the bottom's centre) lose the degenerate half of their first row, so the
// mesh has 32 * 2 * n^2 - 8 * n triangles: 992 for n = 4.
//
// Coordinates are the data's own: z is up, the base at z = 0, the lid's knob
// at z = 3.15, the spout towards +x and the handle towards -x. Normals come
// from the patch derivatives and point outwards; the triangles are
// counter-clockwise seen from outside. Throws std::invalid_argument unless
// 1 <= subdivisions <= TEAPOT_MAX_SUBDIVISIONS.
Mesh teapot_mesh(int subdivisions);

// Finer tessellations than one mesh's 16-bit indices hold: patch (n + 1)^2
// vertices <= 65536.
constexpr int TEAPOT_MAX_PART_SUBDIVISIONS = 255;

// The same tessellation as teapot_mesh(subdivisions), patch by patch in the
// same order, cut into meshes of whole patches of at most MAX_MESH_VERTICES
// vertices each (one glDrawElements a part). Throws std::invalid_argument
// unless 1 <= subdivisions <= TEAPOT_MAX_PART_SUBDIVISIONS.
std::vector<Mesh> teapot_mesh_parts(int subdivisions);

// 32 * 2 * n^2 - 8 * n: the triangles of either function from n = 2 on.
std::size_t teapot_triangle_count(int subdivisions);

}  // namespace tessera::scenes
