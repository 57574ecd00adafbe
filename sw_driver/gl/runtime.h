// What connects the standard GL ES / EGL entry points (plain C functions
// with no context argument) to the simulated SoC: the application's
// environment on the host model (which carries the factory of the back end
// chosen for this run) and the memory the driver allocates (textures, depth
// buffers) in system memory.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "device/app_environment.h"
#include "gl/renderer.h"

namespace tessera::gl {

// Thrown by eglSwapBuffers when the run's frame count has been presented;
// the application wrapper catches it and ends the program normally.
class FramesComplete {};

// Installs the environment before the application's main runs.
void set_environment(AppEnvironment* env);
AppEnvironment& environment();  // throws std::logic_error when none is set

// Bump allocator over [heap_base, heap_end) of system memory. Throws
// std::runtime_error when the heap is exhausted.
uint32_t allocate(uint32_t bytes, uint32_t alignment = 32);

}  // namespace tessera::gl
