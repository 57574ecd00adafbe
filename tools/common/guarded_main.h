// main() of the project's programs: nothing may escape it. An exception
// that reaches it is reported as "<program>: <what>" with exit status
// `failure_status` (1 unless the program says otherwise), instead of
// std::terminate's abort.
#pragma once

#include <cstdio>
#include <exception>

namespace tessera {

template <typename Body>
int guarded_main(const char* program, Body&& body, int failure_status = 1) noexcept {
  try {
    return body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown exception\n", program);
  }
  return failure_status;
}

}  // namespace tessera
