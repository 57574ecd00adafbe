// Every bus transaction, for a record of them (soc_sim
// --trace-transactions: a CSV with a filter). The bus hands each one to a
// TransactionSink when it has one (AhbBus::trace_transactions_to); without
// one the cost is nothing: the bus tests one flag for its VCD and this
// together. The times are those the bus's arbitration computes: the request
// (the initiator's local time at a clock edge), the start of service (after
// arbitration and contention) and the end.
#pragma once

#include <cstdint>
#include <string>

#include <systemc>

namespace tessera {

struct Transaction {
  const std::string& initiator;  // the bus's name for it (host, dma, raster, display_dma)
  const std::string& target;     // the region's name (sysmem, ciu, array_regs, ...), "unmapped" for none
  bool write;
  uint64_t address;
  uint64_t bytes;
  sc_core::sc_time request, start, end;  // wait = start - request, service = end - start
};

class TransactionSink {
 public:
  virtual ~TransactionSink() = default;
  virtual void transaction(const Transaction& t) = 0;
};

}  // namespace tessera
