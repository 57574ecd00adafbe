// How every C entry point of the GL (gl_api.cpp, gl_fixed.cpp) begins: it
// takes the current context as `c`, or returns at once (with the value
// given, for a query) when there is none, a case the GL leaves undefined.
#pragma once

#include "gl/context.h"

#define WITH_CONTEXT(...)                                   \
  tessera::gl::Context* c = tessera::gl::current_context(); \
  if (!c) return __VA_ARGS__;
