// What the built-in scenes share: their constructors, for the registry, and
// a few GL ES 1.1 set-up steps that several of them repeat.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scenes/mesh.h"
#include "scenes/scene.h"

namespace tessera::scenes {

Scene triangle_scene();
Scene cubes_scene();
Scene fullscreen_rect_scene();
Scene textured_quad_scene();
Scene teapot_scene();
Scene obj_viewer_scene();
Scene tile_grid_scene();

// The corners of a cube centred at the origin: corner k has x, y, z
// positive where bit 0, 1, 2 of k is set. Each face, in the order +x, -x,
// +y, -y, +z, -z, lists its corners counter-clockwise seen from outside.
extern const std::array<std::array<unsigned short, 4>, 6> CUBE_FACE_CORNERS;

// That cube with half edge `half_edge` as 12 triangles (36 vertices, face by
// face: corners 0, 1, 2 and 0, 2, 3 of its list), each face in its colour
// of `face_rgba`: positions into xyz, colours into rgba.
void flat_cube(float half_edge, const std::array<std::array<float, 4>, 6>& face_rgba, std::array<float, 36 * 3>& xyz,
               std::array<float, 36 * 4>& rgba);

// An RGBA8 checkerboard texture of size x size texels in squares of
// `square` texels: square (sx, sy) with sx + sy even is grey `light`, the
// others colour (sx * colour_step + sy) mod the number of colours; alpha 255.
std::vector<unsigned char> checkerboard_rgba8(int size, int square, unsigned char light,
                                              const std::vector<std::array<unsigned char, 3>>& colours,
                                              int colour_step);

// For scenes that take no arguments: false with a message if there are any.
bool expect_no_arguments(const char* scene, const std::vector<std::string>& args, std::string* error);

// A scene's option with a whole number: the value after args[i] (the
// option's name) into `value`; false with `error` naming the scene and the
// option for a missing value or one that is not a whole number in [low,
// high]. Digit by digit, stopping past `high`: no library conversion that
// overflows a 32-bit long on the ARM.
bool whole_number_option(const char* scene, const std::vector<std::string>& args, std::size_t i, uint32_t low,
                         uint32_t high, uint32_t* value, std::string* error);

// The angle after `frame` frames, reduced to (-360, 360) so that it keeps
// its precision in float however long a scene runs.
float rotation_degrees(int frame, float degrees_per_frame);

// Viewport over the whole window and a symmetric perspective projection with
// the given vertical field of view; leaves GL_MODELVIEW current and identity.
void set_perspective(int width, int height, float fovy_degrees, float near_plane, float far_plane);

// GL state for a mesh lit by one white directional light fixed in eye space,
// depth-tested, with the given diffuse colour as its material.
void set_up_lit_mesh(int width, int height, const float diffuse[4]);

// Clears and draws `mesh`, which must fit the unit sphere, 2.6 units in
// front of the eye, tilted towards the viewer and turned about the vertical
// axis by half a degree per frame.
void draw_lit_mesh(const Mesh& mesh, int frame);

// The same for a model in several meshes (`count` of them from `meshes`):
// one clear, one transform, one glDrawElements a mesh.
void draw_lit_meshes(const Mesh* meshes, std::size_t count, int frame);

}  // namespace tessera::scenes
