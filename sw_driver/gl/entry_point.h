// How every C entry point of the GL (gl_api.cpp, gl_fixed.cpp) begins: it
// takes the current context as `c`, or returns at once (with the value
// given, for a query) when there is none, a case the GL leaves undefined;
// then the call is on the host's timeline for its life (CallScope).
#pragma once

#include "gl/context.h"
#include "gl/frame_phases.h"

#define WITH_CONTEXT(...)                                   \
  tessera::gl::Context* c = tessera::gl::current_context(); \
  if (!c) return __VA_ARGS__;                               \
  const tessera::gl::CallScope tessera_gl_call_(__func__);
