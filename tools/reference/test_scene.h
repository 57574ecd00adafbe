// A Gouraud-shaded triangle that turns a little each frame: the scene the
// reference machinery is tested with, independent of the built-in scenes
// that sw_driver/scenes is growing. Written like those, against
// gles_compat.h, so it compiles both against tessera's headers and Mesa's.
#pragma once

#include "scenes/scene.h"

namespace tessera::reference {

// Named "reference_triangle".
const scenes::Scene& test_scene();

}  // namespace tessera::reference
