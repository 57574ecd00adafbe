// The semihosting trap from the ARM side: r0 the operation
// (contract/host/iss/semihosting.def), r1 its parameter, the result in r0.
// Bare-metal ARM only (the runtime).
#pragma once

#include <cstdint>

namespace tessera::runtime {

namespace semihosting {
#define TESSERA_SEMIHOSTING(name, number) inline constexpr uint32_t name = number;
#include "host/iss/semihosting.def"
#undef TESSERA_SEMIHOSTING
inline constexpr uint32_t APPLICATION_EXIT = 0x20026;  // SYS_EXIT's reason for an application's exit
}  // namespace semihosting

inline uint32_t semihosting_call(uint32_t op, const void* parameter) {
  register uint32_t r0 asm("r0") = op;
  register const void* r1 asm("r1") = parameter;
  // On a core with a debugger the trap goes through the SWI vector, which
  // writes the supervisor's LR: hence the clobber.
#if defined(__thumb__)
  asm volatile("svc 0xab" : "+r"(r0) : "r"(r1) : "memory", "lr");
#else
  asm volatile("svc 0x123456" : "+r"(r0) : "r"(r1) : "memory", "lr");
#endif
  return r0;
}

}  // namespace tessera::runtime
