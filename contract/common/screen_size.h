// The largest screen the model draws, in pixels, in either direction.
//
// Screen x and y cross the rasterizer's interface as unsigned 9.4 fixed point
// (docs/spec/rasterizer.md, the paper's format: codes 0..8191, 0 to
// 511 15/16 pixels), and the GL driver hands every back end its vertices in
// that format (sw_driver/gl/geometry.h). A 512-pixel screen is the largest
// whose pixel centres and far edge the format reaches (the driver moves a
// vertex on the far edge, 512.0, to 511 15/16). display.width and
// display.height allow at most this (the rasterizer takes the display's
// size); the rasterizer core draws nothing for a larger screen, the GL driver
// clamps its viewport to it (GL_MAX_VIEWPORT_DIMS).
#pragma once

namespace tessera {

inline constexpr unsigned MAX_SCREEN_SIZE = 512;

}  // namespace tessera
