// soc_sim --trace-transactions FILE[:FILTER]: the TransactionSink
// (tlm/common/transaction_trace.h) that writes each bus transaction
// matching the filter as a CSV row, streamed (tools/common/output_file.h:
// whole or not at all). The filter is comma-separated key=value terms, all
// of which a transaction must match:
//   initiator=NAME   the bus initiator (host, dma, raster, display_dma)
//   target=NAME      the target region (sysmem, ciu, array_regs, ...)
//   command=read|write
//   addr=LO-HI       LO <= address < HI (decimal or 0x hex)
//   time=A-B         requested from A to before B; each with a unit: ps, ns, us, ms or s
// e.g. out/tx.csv:initiator=dma,target=memory,time=1ms-2ms.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "common/transaction_trace.h"
#include "output_file.h"

namespace tessera {

struct TransactionFilter {
  std::optional<std::string> initiator, target;
  std::optional<bool> write;
  std::optional<std::pair<uint64_t, uint64_t>> address;               // [lo, hi)
  std::optional<std::pair<sc_core::sc_time, sc_core::sc_time>> time;  // [from, to)
  bool matches(const Transaction& t) const;
};

// The option's value split into the file and its filter; throws
// std::invalid_argument naming the bad term.
struct TransactionTraceSpec {
  std::string path;
  TransactionFilter filter;
};
TransactionTraceSpec parse_transaction_trace(const std::string& text);

class TransactionWriter : public TransactionSink {
 public:
  explicit TransactionWriter(const TransactionTraceSpec& spec);  // throws naming the file
  void transaction(const Transaction& t) override;
  // Puts the file in place; the error that lost it ("" if none).
  std::string finish();
  uint64_t rows() const { return m_rows; }

 private:
  void flush();
  TransactionFilter m_filter;
  std::unique_ptr<OutputFile> m_file;
  std::string m_buffer, m_error;
  uint64_t m_rows = 0;
  double m_picoseconds_per_unit;
};

}  // namespace tessera
