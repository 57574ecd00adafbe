// Tessellation of the Newell teapot.
//
// A patch is P(u, v) = sum_ij B_i(u) B_j(v) C[4i + j] with the cubic
// Bernstein polynomials B_i, u running along the control rows (i) and v along
// the columns (j). In this data set dP/dv x dP/du points out of the teapot,
// so that is the normal, and the triangles are wound to match it.
//
// Where a row of control points collapses to one point (the pole at the top
// of the knob and at the centre of the bottom), dP/dv vanishes on that edge
// and the cross product is zero. The limit of the normal as the parameter
// leaves the pole is well defined, so it is taken by evaluating the
// derivatives a small step into the patch.
//
// Single precision, by de Casteljau's construction (repeated linear
// interpolation) rather than by summing the Bernstein terms: interpolating
// between equal points gives that point exactly, so a pole evaluates to its
// control point and its dP/dv to exactly zero, and the triangles with two
// corners there have exactly no area, as they had in double precision.
#include "scenes/teapot_mesh.h"

#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera::scenes {

namespace {

constexpr int TEAPOT_CONTROL_POINTS = 306;

// Indices into TEAPOT_CONTROL_POINTS, four rows of four per patch: rim (4),
// body (8), handle (4), spout (4), lid (8), bottom (4).
constexpr std::array<std::array<std::uint16_t, 16>, TEAPOT_PATCHES> TEAPOT_PATCH_INDICES = {{
    {{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}},
    {{3, 16, 17, 18, 7, 19, 20, 21, 11, 22, 23, 24, 15, 25, 26, 27}},
    {{18, 28, 29, 30, 21, 31, 32, 33, 24, 34, 35, 36, 27, 37, 38, 39}},
    {{30, 40, 41, 0, 33, 42, 43, 4, 36, 44, 45, 8, 39, 46, 47, 12}},
    {{12, 13, 14, 15, 48, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59}},
    {{15, 25, 26, 27, 51, 60, 61, 62, 55, 63, 64, 65, 59, 66, 67, 68}},
    {{27, 37, 38, 39, 62, 69, 70, 71, 65, 72, 73, 74, 68, 75, 76, 77}},
    {{39, 46, 47, 12, 71, 78, 79, 48, 74, 80, 81, 52, 77, 82, 83, 56}},
    {{56, 57, 58, 59, 84, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95}},
    {{59, 66, 67, 68, 87, 96, 97, 98, 91, 99, 100, 101, 95, 102, 103, 104}},
    {{68, 75, 76, 77, 98, 105, 106, 107, 101, 108, 109, 110, 104, 111, 112, 113}},
    {{77, 82, 83, 56, 107, 114, 115, 84, 110, 116, 117, 88, 113, 118, 119, 92}},
    {{120, 121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135}},
    {{123, 136, 137, 120, 127, 138, 139, 124, 131, 140, 141, 128, 135, 142, 143, 132}},
    {{132, 133, 134, 135, 144, 145, 146, 147, 148, 149, 150, 151, 68, 152, 153, 154}},
    {{135, 142, 143, 132, 147, 155, 156, 144, 151, 157, 158, 148, 154, 159, 160, 68}},
    {{161, 162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176}},
    {{164, 177, 178, 161, 168, 179, 180, 165, 172, 181, 182, 169, 176, 183, 184, 173}},
    {{173, 174, 175, 176, 185, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196}},
    {{176, 183, 184, 173, 188, 197, 198, 185, 192, 199, 200, 189, 196, 201, 202, 193}},
    {{203, 203, 203, 203, 206, 207, 208, 209, 210, 210, 210, 210, 211, 212, 213, 214}},
    {{203, 203, 203, 203, 209, 216, 217, 218, 210, 210, 210, 210, 214, 219, 220, 221}},
    {{203, 203, 203, 203, 218, 223, 224, 225, 210, 210, 210, 210, 221, 226, 227, 228}},
    {{203, 203, 203, 203, 225, 229, 230, 206, 210, 210, 210, 210, 228, 231, 232, 211}},
    {{211, 212, 213, 214, 233, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244}},
    {{214, 219, 220, 221, 236, 245, 246, 247, 240, 248, 249, 250, 244, 251, 252, 253}},
    {{221, 226, 227, 228, 247, 254, 255, 256, 250, 257, 258, 259, 253, 260, 261, 262}},
    {{228, 231, 232, 211, 256, 263, 264, 233, 259, 265, 266, 237, 262, 267, 268, 241}},
    {{269, 269, 269, 269, 278, 279, 280, 281, 274, 275, 276, 277, 270, 271, 272, 273}},
    {{269, 269, 269, 269, 281, 288, 289, 290, 277, 285, 286, 287, 273, 282, 283, 284}},
    {{269, 269, 269, 269, 290, 297, 298, 299, 287, 294, 295, 296, 284, 291, 292, 293}},
    {{269, 269, 269, 269, 299, 304, 305, 278, 296, 302, 303, 274, 293, 300, 301, 270}},
}};

constexpr float TEAPOT_CONTROL_POINTS_XYZ[TEAPOT_CONTROL_POINTS][3] = {
    {1.4f, 0.0f, 2.4f},
    {1.4f, -0.784f, 2.4f},
    {0.784f, -1.4f, 2.4f},
    {0.0f, -1.4f, 2.4f},
    {1.3375f, 0.0f, 2.53125f},
    {1.3375f, -0.749f, 2.53125f},
    {0.749f, -1.3375f, 2.53125f},
    {0.0f, -1.3375f, 2.53125f},
    {1.4375f, 0.0f, 2.53125f},
    {1.4375f, -0.805f, 2.53125f},
    {0.805f, -1.4375f, 2.53125f},
    {0.0f, -1.4375f, 2.53125f},
    {1.5f, 0.0f, 2.4f},
    {1.5f, -0.84f, 2.4f},
    {0.84f, -1.5f, 2.4f},
    {0.0f, -1.5f, 2.4f},
    {-0.784f, -1.4f, 2.4f},
    {-1.4f, -0.784f, 2.4f},
    {-1.4f, 0.0f, 2.4f},
    {-0.749f, -1.3375f, 2.53125f},
    {-1.3375f, -0.749f, 2.53125f},
    {-1.3375f, 0.0f, 2.53125f},
    {-0.805f, -1.4375f, 2.53125f},
    {-1.4375f, -0.805f, 2.53125f},
    {-1.4375f, 0.0f, 2.53125f},
    {-0.84f, -1.5f, 2.4f},
    {-1.5f, -0.84f, 2.4f},
    {-1.5f, 0.0f, 2.4f},
    {-1.4f, 0.784f, 2.4f},
    {-0.784f, 1.4f, 2.4f},
    {0.0f, 1.4f, 2.4f},
    {-1.3375f, 0.749f, 2.53125f},
    {-0.749f, 1.3375f, 2.53125f},
    {0.0f, 1.3375f, 2.53125f},
    {-1.4375f, 0.805f, 2.53125f},
    {-0.805f, 1.4375f, 2.53125f},
    {0.0f, 1.4375f, 2.53125f},
    {-1.5f, 0.84f, 2.4f},
    {-0.84f, 1.5f, 2.4f},
    {0.0f, 1.5f, 2.4f},
    {0.784f, 1.4f, 2.4f},
    {1.4f, 0.784f, 2.4f},
    {0.749f, 1.3375f, 2.53125f},
    {1.3375f, 0.749f, 2.53125f},
    {0.805f, 1.4375f, 2.53125f},
    {1.4375f, 0.805f, 2.53125f},
    {0.84f, 1.5f, 2.4f},
    {1.5f, 0.84f, 2.4f},
    {1.75f, 0.0f, 1.875f},
    {1.75f, -0.98f, 1.875f},
    {0.98f, -1.75f, 1.875f},
    {0.0f, -1.75f, 1.875f},
    {2.0f, 0.0f, 1.35f},
    {2.0f, -1.12f, 1.35f},
    {1.12f, -2.0f, 1.35f},
    {0.0f, -2.0f, 1.35f},
    {2.0f, 0.0f, 0.9f},
    {2.0f, -1.12f, 0.9f},
    {1.12f, -2.0f, 0.9f},
    {0.0f, -2.0f, 0.9f},
    {-0.98f, -1.75f, 1.875f},
    {-1.75f, -0.98f, 1.875f},
    {-1.75f, 0.0f, 1.875f},
    {-1.12f, -2.0f, 1.35f},
    {-2.0f, -1.12f, 1.35f},
    {-2.0f, 0.0f, 1.35f},
    {-1.12f, -2.0f, 0.9f},
    {-2.0f, -1.12f, 0.9f},
    {-2.0f, 0.0f, 0.9f},
    {-1.75f, 0.98f, 1.875f},
    {-0.98f, 1.75f, 1.875f},
    {0.0f, 1.75f, 1.875f},
    {-2.0f, 1.12f, 1.35f},
    {-1.12f, 2.0f, 1.35f},
    {0.0f, 2.0f, 1.35f},
    {-2.0f, 1.12f, 0.9f},
    {-1.12f, 2.0f, 0.9f},
    {0.0f, 2.0f, 0.9f},
    {0.98f, 1.75f, 1.875f},
    {1.75f, 0.98f, 1.875f},
    {1.12f, 2.0f, 1.35f},
    {2.0f, 1.12f, 1.35f},
    {1.12f, 2.0f, 0.9f},
    {2.0f, 1.12f, 0.9f},
    {2.0f, 0.0f, 0.45f},
    {2.0f, -1.12f, 0.45f},
    {1.12f, -2.0f, 0.45f},
    {0.0f, -2.0f, 0.45f},
    {1.5f, 0.0f, 0.225f},
    {1.5f, -0.84f, 0.225f},
    {0.84f, -1.5f, 0.225f},
    {0.0f, -1.5f, 0.225f},
    {1.5f, 0.0f, 0.15f},
    {1.5f, -0.84f, 0.15f},
    {0.84f, -1.5f, 0.15f},
    {0.0f, -1.5f, 0.15f},
    {-1.12f, -2.0f, 0.45f},
    {-2.0f, -1.12f, 0.45f},
    {-2.0f, 0.0f, 0.45f},
    {-0.84f, -1.5f, 0.225f},
    {-1.5f, -0.84f, 0.225f},
    {-1.5f, 0.0f, 0.225f},
    {-0.84f, -1.5f, 0.15f},
    {-1.5f, -0.84f, 0.15f},
    {-1.5f, 0.0f, 0.15f},
    {-2.0f, 1.12f, 0.45f},
    {-1.12f, 2.0f, 0.45f},
    {0.0f, 2.0f, 0.45f},
    {-1.5f, 0.84f, 0.225f},
    {-0.84f, 1.5f, 0.225f},
    {0.0f, 1.5f, 0.225f},
    {-1.5f, 0.84f, 0.15f},
    {-0.84f, 1.5f, 0.15f},
    {0.0f, 1.5f, 0.15f},
    {1.12f, 2.0f, 0.45f},
    {2.0f, 1.12f, 0.45f},
    {0.84f, 1.5f, 0.225f},
    {1.5f, 0.84f, 0.225f},
    {0.84f, 1.5f, 0.15f},
    {1.5f, 0.84f, 0.15f},
    {-1.6f, 0.0f, 2.025f},
    {-1.6f, -0.3f, 2.025f},
    {-1.5f, -0.3f, 2.25f},
    {-1.5f, 0.0f, 2.25f},
    {-2.3f, 0.0f, 2.025f},
    {-2.3f, -0.3f, 2.025f},
    {-2.5f, -0.3f, 2.25f},
    {-2.5f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 2.025f},
    {-2.7f, -0.3f, 2.025f},
    {-3.0f, -0.3f, 2.25f},
    {-3.0f, 0.0f, 2.25f},
    {-2.7f, 0.0f, 1.8f},
    {-2.7f, -0.3f, 1.8f},
    {-3.0f, -0.3f, 1.8f},
    {-3.0f, 0.0f, 1.8f},
    {-1.5f, 0.3f, 2.25f},
    {-1.6f, 0.3f, 2.025f},
    {-2.5f, 0.3f, 2.25f},
    {-2.3f, 0.3f, 2.025f},
    {-3.0f, 0.3f, 2.25f},
    {-2.7f, 0.3f, 2.025f},
    {-3.0f, 0.3f, 1.8f},
    {-2.7f, 0.3f, 1.8f},
    {-2.7f, 0.0f, 1.575f},
    {-2.7f, -0.3f, 1.575f},
    {-3.0f, -0.3f, 1.35f},
    {-3.0f, 0.0f, 1.35f},
    {-2.5f, 0.0f, 1.125f},
    {-2.5f, -0.3f, 1.125f},
    {-2.65f, -0.3f, 0.9375f},
    {-2.65f, 0.0f, 0.9375f},
    {-2.0f, -0.3f, 0.9f},
    {-1.9f, -0.3f, 0.6f},
    {-1.9f, 0.0f, 0.6f},
    {-3.0f, 0.3f, 1.35f},
    {-2.7f, 0.3f, 1.575f},
    {-2.65f, 0.3f, 0.9375f},
    {-2.5f, 0.3f, 1.125f},
    {-1.9f, 0.3f, 0.6f},
    {-2.0f, 0.3f, 0.9f},
    {1.7f, 0.0f, 1.425f},
    {1.7f, -0.66f, 1.425f},
    {1.7f, -0.66f, 0.6f},
    {1.7f, 0.0f, 0.6f},
    {2.6f, 0.0f, 1.425f},
    {2.6f, -0.66f, 1.425f},
    {3.1f, -0.66f, 0.825f},
    {3.1f, 0.0f, 0.825f},
    {2.3f, 0.0f, 2.1f},
    {2.3f, -0.25f, 2.1f},
    {2.4f, -0.25f, 2.025f},
    {2.4f, 0.0f, 2.025f},
    {2.7f, 0.0f, 2.4f},
    {2.7f, -0.25f, 2.4f},
    {3.3f, -0.25f, 2.4f},
    {3.3f, 0.0f, 2.4f},
    {1.7f, 0.66f, 0.6f},
    {1.7f, 0.66f, 1.425f},
    {3.1f, 0.66f, 0.825f},
    {2.6f, 0.66f, 1.425f},
    {2.4f, 0.25f, 2.025f},
    {2.3f, 0.25f, 2.1f},
    {3.3f, 0.25f, 2.4f},
    {2.7f, 0.25f, 2.4f},
    {2.8f, 0.0f, 2.475f},
    {2.8f, -0.25f, 2.475f},
    {3.525f, -0.25f, 2.49375f},
    {3.525f, 0.0f, 2.49375f},
    {2.9f, 0.0f, 2.475f},
    {2.9f, -0.15f, 2.475f},
    {3.45f, -0.15f, 2.5125f},
    {3.45f, 0.0f, 2.5125f},
    {2.8f, 0.0f, 2.4f},
    {2.8f, -0.15f, 2.4f},
    {3.2f, -0.15f, 2.4f},
    {3.2f, 0.0f, 2.4f},
    {3.525f, 0.25f, 2.49375f},
    {2.8f, 0.25f, 2.475f},
    {3.45f, 0.15f, 2.5125f},
    {2.9f, 0.15f, 2.475f},
    {3.2f, 0.15f, 2.4f},
    {2.8f, 0.15f, 2.4f},
    {0.0f, 0.0f, 3.15f},
    {0.0f, -0.002f, 3.15f},
    {0.002f, 0.0f, 3.15f},
    {0.8f, 0.0f, 3.15f},
    {0.8f, -0.45f, 3.15f},
    {0.45f, -0.8f, 3.15f},
    {0.0f, -0.8f, 3.15f},
    {0.0f, 0.0f, 2.85f},
    {0.2f, 0.0f, 2.7f},
    {0.2f, -0.112f, 2.7f},
    {0.112f, -0.2f, 2.7f},
    {0.0f, -0.2f, 2.7f},
    {-0.002f, 0.0f, 3.15f},
    {-0.45f, -0.8f, 3.15f},
    {-0.8f, -0.45f, 3.15f},
    {-0.8f, 0.0f, 3.15f},
    {-0.112f, -0.2f, 2.7f},
    {-0.2f, -0.112f, 2.7f},
    {-0.2f, 0.0f, 2.7f},
    {0.0f, 0.002f, 3.15f},
    {-0.8f, 0.45f, 3.15f},
    {-0.45f, 0.8f, 3.15f},
    {0.0f, 0.8f, 3.15f},
    {-0.2f, 0.112f, 2.7f},
    {-0.112f, 0.2f, 2.7f},
    {0.0f, 0.2f, 2.7f},
    {0.45f, 0.8f, 3.15f},
    {0.8f, 0.45f, 3.15f},
    {0.112f, 0.2f, 2.7f},
    {0.2f, 0.112f, 2.7f},
    {0.4f, 0.0f, 2.55f},
    {0.4f, -0.224f, 2.55f},
    {0.224f, -0.4f, 2.55f},
    {0.0f, -0.4f, 2.55f},
    {1.3f, 0.0f, 2.55f},
    {1.3f, -0.728f, 2.55f},
    {0.728f, -1.3f, 2.55f},
    {0.0f, -1.3f, 2.55f},
    {1.3f, 0.0f, 2.4f},
    {1.3f, -0.728f, 2.4f},
    {0.728f, -1.3f, 2.4f},
    {0.0f, -1.3f, 2.4f},
    {-0.224f, -0.4f, 2.55f},
    {-0.4f, -0.224f, 2.55f},
    {-0.4f, 0.0f, 2.55f},
    {-0.728f, -1.3f, 2.55f},
    {-1.3f, -0.728f, 2.55f},
    {-1.3f, 0.0f, 2.55f},
    {-0.728f, -1.3f, 2.4f},
    {-1.3f, -0.728f, 2.4f},
    {-1.3f, 0.0f, 2.4f},
    {-0.4f, 0.224f, 2.55f},
    {-0.224f, 0.4f, 2.55f},
    {0.0f, 0.4f, 2.55f},
    {-1.3f, 0.728f, 2.55f},
    {-0.728f, 1.3f, 2.55f},
    {0.0f, 1.3f, 2.55f},
    {-1.3f, 0.728f, 2.4f},
    {-0.728f, 1.3f, 2.4f},
    {0.0f, 1.3f, 2.4f},
    {0.224f, 0.4f, 2.55f},
    {0.4f, 0.224f, 2.55f},
    {0.728f, 1.3f, 2.55f},
    {1.3f, 0.728f, 2.55f},
    {0.728f, 1.3f, 2.4f},
    {1.3f, 0.728f, 2.4f},
    {0.0f, 0.0f, 0.0f},
    {1.5f, 0.0f, 0.15f},
    {1.5f, 0.84f, 0.15f},
    {0.84f, 1.5f, 0.15f},
    {0.0f, 1.5f, 0.15f},
    {1.5f, 0.0f, 0.075f},
    {1.5f, 0.84f, 0.075f},
    {0.84f, 1.5f, 0.075f},
    {0.0f, 1.5f, 0.075f},
    {1.425f, 0.0f, 0.0f},
    {1.425f, 0.798f, 0.0f},
    {0.798f, 1.425f, 0.0f},
    {0.0f, 1.425f, 0.0f},
    {-0.84f, 1.5f, 0.15f},
    {-1.5f, 0.84f, 0.15f},
    {-1.5f, 0.0f, 0.15f},
    {-0.84f, 1.5f, 0.075f},
    {-1.5f, 0.84f, 0.075f},
    {-1.5f, 0.0f, 0.075f},
    {-0.798f, 1.425f, 0.0f},
    {-1.425f, 0.798f, 0.0f},
    {-1.425f, 0.0f, 0.0f},
    {-1.5f, -0.84f, 0.15f},
    {-0.84f, -1.5f, 0.15f},
    {0.0f, -1.5f, 0.15f},
    {-1.5f, -0.84f, 0.075f},
    {-0.84f, -1.5f, 0.075f},
    {0.0f, -1.5f, 0.075f},
    {-1.425f, -0.798f, 0.0f},
    {-0.798f, -1.425f, 0.0f},
    {0.0f, -1.425f, 0.0f},
    {0.84f, -1.5f, 0.15f},
    {1.5f, -0.84f, 0.15f},
    {0.84f, -1.5f, 0.075f},
    {1.5f, -0.84f, 0.075f},
    {0.798f, -1.425f, 0.0f},
    {1.425f, -0.798f, 0.0f},
};

using Vec3 = std::array<float, 3>;

// The point at t along a -> b, from the nearer end: exactly a at t = 0,
// exactly b at t = 1 (1 - t is exact for t >= 1/2), and exactly a when
// b == a. So a patch's edge evaluates to the same floats as its
// neighbour's, which shares those control points: no cracks between them.
float lerp(float a, float b, float t) {
  return t < 0.5f ? a + t * (b - a) : b - (1 - t) * (b - a);
}

Vec3 lerp(const Vec3& a, const Vec3& b, float t) {
  return {lerp(a[0], b[0], t), lerp(a[1], b[1], t), lerp(a[2], b[2], t)};
}

Vec3 sub(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

struct CurvePoint {
  Vec3 point;
  Vec3 derivative;
};

// The cubic Bezier curve of `c` at t, and its derivative 3 (bcd - abc).
CurvePoint de_casteljau(const std::array<Vec3, 4>& c, float t) {
  const Vec3 ab = lerp(c[0], c[1], t), bc = lerp(c[1], c[2], t), cd = lerp(c[2], c[3], t);
  const Vec3 abc = lerp(ab, bc, t), bcd = lerp(bc, cd, t);
  const Vec3 d = sub(bcd, abc);
  return {lerp(abc, bcd, t), {3 * d[0], 3 * d[1], 3 * d[2]}};
}

struct SurfacePoint {
  Vec3 position;
  Vec3 d_du;
  Vec3 d_dv;
};

// Each control row i as a curve in v, then the rows' points (and their
// v-derivatives) as a curve in u.
SurfacePoint evaluate(const std::array<std::uint16_t, 16>& patch, float u, float v) {
  std::array<Vec3, 4> rows, row_derivatives;
  for (int i = 0; i < 4; ++i) {
    std::array<Vec3, 4> row;
    for (int j = 0; j < 4; ++j) {
      const float* control = TEAPOT_CONTROL_POINTS_XYZ[patch[4 * i + j]];
      row[j] = {control[0], control[1], control[2]};
    }
    const CurvePoint along_v = de_casteljau(row, v);
    rows[i] = along_v.point;
    row_derivatives[i] = along_v.derivative;
  }
  const CurvePoint along_u = de_casteljau(rows, u);
  return {along_u.point, along_u.derivative, de_casteljau(row_derivatives, u).point};
}

Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}

float length(const Vec3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// Far below the squared length of any real derivative of this data (the
// smallest patch is about 0.1 across), far above rounding noise at a pole.
constexpr float DEGENERATE_NORMAL = 1e-9f;
// How far into the patch the normal at a pole is taken from.
constexpr float POLE_STEP = 1e-4f;

Vec3 outward_normal(const std::array<std::uint16_t, 16>& patch, float u, float v) {
  SurfacePoint point = evaluate(patch, u, v);
  Vec3 normal = cross(point.d_dv, point.d_du);
  if (length(normal) < DEGENERATE_NORMAL) {
    const float inner_u = u < 0.5f ? u + POLE_STEP : u - POLE_STEP;
    const float inner_v = v < 0.5f ? v + POLE_STEP : v - POLE_STEP;
    point = evaluate(patch, inner_u, inner_v);
    normal = cross(point.d_dv, point.d_du);
  }
  const float n = length(normal);
  return {normal[0] / n, normal[1] / n, normal[2] / n};
}

// Twice the area of triangle abc, from the stored (float) positions.
float doubled_area(const Mesh& mesh, std::uint16_t a, std::uint16_t b, std::uint16_t c) {
  auto at = [&mesh](std::uint16_t vertex) {
    return Vec3{mesh.positions[3 * vertex], mesh.positions[3 * vertex + 1], mesh.positions[3 * vertex + 2]};
  };
  const Vec3 pa = at(a), pb = at(b), pc = at(c);
  return length(cross({pb[0] - pa[0], pb[1] - pa[1], pb[2] - pa[2]}, {pc[0] - pa[0], pc[1] - pa[1], pc[2] - pa[2]}));
}

// A triangle at a pole has two corners at the same point; its area is
// rounding noise, many orders of magnitude below a real triangle's.
constexpr float DEGENERATE_AREA = 1e-9f;

// Appends `patch` cut into n x n quads to `mesh`: its (n + 1)^2 vertices
// (which the caller has checked fit 16-bit indices) and its triangles.
void append_patch(const std::array<std::uint16_t, 16>& patch, int n, Mesh* mesh) {
  const int side = n + 1;
  const auto first = static_cast<std::uint16_t>(mesh->vertex_count());
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const float u = static_cast<float>(i) / static_cast<float>(n);
      const float v = static_cast<float>(j) / static_cast<float>(n);
      const SurfacePoint point = evaluate(patch, u, v);
      const Vec3 normal = outward_normal(patch, u, v);
      for (int axis = 0; axis < 3; ++axis) {
        mesh->positions.push_back(point.position[axis]);
        mesh->normals.push_back(normal[axis]);
      }
    }
  auto vertex = [first, side](int i, int j) { return static_cast<std::uint16_t>(first + i * side + j); };
  auto add_triangle = [mesh](std::uint16_t a, std::uint16_t b, std::uint16_t c) {
    if (doubled_area(*mesh, a, b, c) < DEGENERATE_AREA) return;
    mesh->indices.insert(mesh->indices.end(), {a, b, c});
  };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      // (i, j) -> (i, j + 1) -> (i + 1, j + 1) turns from +v towards +u,
      // which is counter-clockwise about dP/dv x dP/du.
      add_triangle(vertex(i, j), vertex(i, j + 1), vertex(i + 1, j + 1));
      add_triangle(vertex(i, j), vertex(i + 1, j + 1), vertex(i + 1, j));
    }
}

void check_subdivisions(const char* function, int subdivisions, int limit) {
  if (subdivisions < 1 || subdivisions > limit)
    throw std::invalid_argument(std::string(function) + ": subdivisions must be 1.." + std::to_string(limit) +
                                ", not " + std::to_string(subdivisions));
}

}  // namespace

Mesh teapot_mesh(int subdivisions) {
  check_subdivisions("teapot_mesh", subdivisions, TEAPOT_MAX_SUBDIVISIONS);
  const int n = subdivisions;
  const int side = n + 1;
  Mesh mesh;
  mesh.positions.reserve(3 * TEAPOT_PATCHES * side * side);
  mesh.normals.reserve(3 * TEAPOT_PATCHES * side * side);
  mesh.indices.reserve(6 * TEAPOT_PATCHES * n * n);
  for (const auto& patch : TEAPOT_PATCH_INDICES) append_patch(patch, n, &mesh);
  return mesh;
}

std::vector<Mesh> teapot_mesh_parts(int subdivisions) {
  check_subdivisions("teapot_mesh_parts", subdivisions, TEAPOT_MAX_PART_SUBDIVISIONS);
  const std::size_t patch_vertices = static_cast<std::size_t>(subdivisions + 1) * (subdivisions + 1);
  std::vector<Mesh> parts(1);
  for (const auto& patch : TEAPOT_PATCH_INDICES) {
    if (parts.back().vertex_count() + patch_vertices > MAX_MESH_VERTICES) parts.emplace_back();
    append_patch(patch, subdivisions, &parts.back());
  }
  return parts;
}

std::size_t teapot_triangle_count(int subdivisions) {
  const auto n = static_cast<std::size_t>(subdivisions);
  return 64 * n * n - 8 * n;
}

}  // namespace tessera::scenes
