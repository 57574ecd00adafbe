// Register offsets of a cluster node's host link, from host_link_regs.def.
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::host_link_regs {

#define TESSERA_REGISTER_TABLE "cluster/host_link_regs.def"
#include "common/register_constants.inc"

}  // namespace tessera::host_link_regs
