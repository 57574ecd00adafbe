// main() of the project's programs: nothing may escape it. An exception
// that reaches it is reported as "<program>: <what>" with exit status
// `failure_status` (1 unless the program says otherwise), instead of
// std::terminate's abort. Standard output is checked at the end: a program
// whose output could not be written (a full disk, a closed pipe) fails with
// "<program>: cannot write to standard output: <reason>" instead of
// exiting 0 with its output lost.
#pragma once

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>

namespace tessera {

template <typename Body>
int guarded_main(const char* program, Body&& body, int failure_status = 1) noexcept {
  int status = failure_status;
  try {
    status = body();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
  } catch (...) {
    std::fprintf(stderr, "%s: unknown exception\n", program);
  }
  // std::cout writes through stdout's buffer (synchronised with stdio), so
  // this covers both; the error flag keeps a failure of an earlier write.
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout) != 0) {
    std::fprintf(stderr, "%s: cannot write to standard output: %s\n", program,
                 errno != 0 ? std::strerror(errno) : "an earlier write failed");
    if (status == 0) status = failure_status;
  }
  return status;
}

}  // namespace tessera
