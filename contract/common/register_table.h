// What a register table (a *_regs.def file) says about each register and
// each bit field, and the generic header that turns a table into
// constants (register_constants.inc). A table lists
//   TESSERA_REG(name, offset, reset, access)        a register
//   TESSERA_BITS(prefix, name, lsb, width)          a field: prefix_name is
//       its mask; prefix is the register's name, or IRQ for the bits that
//       IRQ_STATUS and IRQ_ENABLE share
//   TESSERA_CHANNEL_REG(name, offset, reset, access)  a register repeated
//       per channel (the DMA's), offset from the channel's base
// and its includer defines the three macros. The models declare their
// registers from the same table (tlm/common/register_members.inc).
#pragma once

#include <cstdint>

namespace tessera {

enum class RegAccess {
  rw,   // read and write
  ro,   // read only: a write is a command error
  wo,   // write only: a read is a command error
  w1c,  // read; writing 1 to a bit clears it
};

struct RegisterInfo {
  const char* name;
  uint32_t offset;
  uint32_t reset;
  RegAccess access;
};

// The mask of a field `width` bits wide starting at bit `lsb`.
constexpr uint32_t register_field_mask(unsigned lsb, unsigned width) {
  return (width >= 32 ? ~0u : (1u << width) - 1u) << lsb;
}

}  // namespace tessera
