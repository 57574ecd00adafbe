// A payload extension for a run of single transfers that an initiator issues
// back to back to consecutive addresses (for example a CPU's posted stores of
// a pixel span, which the ARM922T's write buffer sends one by one): the
// payload covers all of them, and the bus and targets charge `transfers`
// separate transfers of data_length / transfers bytes each. One call instead
// of many keeps the simulation fast while the timing and statistics stay
// those of the individual transfers.
#pragma once

#include <tlm>

namespace tessera {

struct TransferTrain : tlm::tlm_extension<TransferTrain> {
  unsigned transfers = 1;

  tlm::tlm_extension_base* clone() const override {
    auto* copy = new TransferTrain;
    copy->transfers = transfers;
    return copy;
  }
  void copy_from(const tlm::tlm_extension_base& other) override {
    transfers = static_cast<const TransferTrain&>(other).transfers;
  }
};

// Transfers a payload stands for (1 without the extension).
inline unsigned transfers_of(const tlm::tlm_generic_payload& gp) {
  const TransferTrain* train = gp.get_extension<TransferTrain>();
  return train && train->transfers > 0 ? train->transfers : 1;
}

}  // namespace tessera
