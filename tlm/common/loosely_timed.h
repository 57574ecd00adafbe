// What a loosely-timed target answers to a non-blocking call: the blocks
// are b_transport only, so nb_transport_fw completes at once with a command
// error and a warning naming the block (the caller counts its error).
#pragma once

#include <string>

#include <tlm>

#include "common/log.h"

namespace tessera {

inline tlm::tlm_sync_enum refuse_non_blocking(const std::string& block, tlm::tlm_generic_payload& gp) {
  log::warning(block, "nb_transport_fw is not supported (loosely timed: b_transport only)");
  gp.set_response_status(tlm::TLM_COMMAND_ERROR_RESPONSE);
  return tlm::TLM_COMPLETED;
}

}  // namespace tessera
