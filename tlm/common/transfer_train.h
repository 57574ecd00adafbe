// A payload extension for a run of single transfers that an initiator issues
// back to back to consecutive addresses (for example a CPU's posted stores of
// a pixel span, which the ARM922T's write buffer sends one by one): the
// payload covers all of them, and the bus and targets charge `transfers`
// separate transfers of data_length / transfers bytes each. One call instead
// of many keeps the simulation fast while the timing and statistics stay
// those of the individual transfers.
#pragma once

#include <tlm>

#include "common/value_extension.h"

namespace tessera {

struct TransferTrain : ValueExtension<TransferTrain> {
  unsigned transfers = 1;
};

// Transfers a payload stands for (1 without the extension).
inline unsigned transfers_of(const tlm::tlm_generic_payload& gp) {
  const TransferTrain* train = gp.get_extension<TransferTrain>();
  return train && train->transfers > 0 ? train->transfers : 1;
}

}  // namespace tessera
