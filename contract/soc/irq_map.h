// Interrupt line numbers of the host, from irq_map.def, and the checks of
// that table, generated from it.
#pragma once

namespace tessera::irq_map {

#define TESSERA_IRQ(source, line) inline constexpr unsigned source = line;
#include "soc/irq_map.def"
#undef TESSERA_IRQ

// The host's interrupt inputs (host.irq_lines): at least enough for every
// source below, at most what the interrupt controller's 32-bit registers
// hold.
inline constexpr unsigned MIN_HOST_LINES = 4;
inline constexpr unsigned MAX_HOST_LINES = 32;

#define TESSERA_IRQ(source, line) \
  static_assert((line) < MIN_HOST_LINES, "irq_map.def: " #source "'s line must exist on the smallest host");
#include "soc/irq_map.def"
#undef TESSERA_IRQ

namespace detail {
constexpr bool lines_distinct() {
  unsigned used = 0;
#define TESSERA_IRQ(source, line)                 \
  if ((used & (1u << (line))) != 0) return false; \
  used |= 1u << (line);
#include "soc/irq_map.def"
#undef TESSERA_IRQ
  return true;
}
}  // namespace detail
static_assert(detail::lines_distinct(), "irq_map.def: two sources share a line");

}  // namespace tessera::irq_map
