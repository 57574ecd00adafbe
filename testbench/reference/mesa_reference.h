// The reference renderer: draws a built-in scene with Mesa (OSMesa, the
// softpipe driver) so that tessera's frames can be compared with what a
// conforming GL implementation renders for the same GL calls.
//
// The scene must come from a library compiled against Mesa's GL
// (testbench_reference_scenes, testbench/reference/CMakeLists.txt). Mesa's
// libOSMesa and tessera's driver export the same gl* symbols, so the two
// never share a process: our frames reach the comparison as PNG files
// written by soc_sim.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "frame_writer.h"
#include "scenes/scene.h"

namespace tessera::reference {

struct ReferenceRequest {
  unsigned width = 320;
  unsigned height = 240;
  // Frames 0..frame are drawn, as the application would, and the last one is
  // returned: a scene may depend on state left by earlier frames.
  int frame = 0;
  std::vector<std::string> args;  // passed to scene.init
  // When set, called after each frame has been drawn and finished
  // (glFinish), with the frame's number: a benchmark times frames with it.
  std::function<void(int frame)> after_frame;
};

struct ReferenceFrame {
  Image image;  // RGBA8, row 0 at the top (as the PNG frames are)
  // GL_COLOR_CLEAR_VALUE after the last frame, as RGBA8: the background that
  // the image comparison uses to tell covered pixels from uncovered ones.
  uint8_t clear_colour[4] = {0, 0, 0, 0};
  // GL_RENDERER, so a test can check that the environment did not override
  // the choice of driver.
  std::string renderer;
};

// Throws std::runtime_error if OSMesa fails or scene.init reports an error.
// Deterministic: the first call pins Mesa to softpipe without dithering or
// GL threading (see mesa_reference.cpp).
ReferenceFrame render_with_mesa(const scenes::Scene& scene, const ReferenceRequest& request);

}  // namespace tessera::reference
