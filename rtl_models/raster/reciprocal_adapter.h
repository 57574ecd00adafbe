// Thin adapter over the Verilated reciprocal.sv (Method 3): takes the 10.4
// operand and returns tlm/raster/datapath/reciprocal.h's ReciprocalResult, so
// the co-simulation compares the RTL with the functional core field by field.
// The Verilator headers stay in the .cpp; users see only the core's types.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>

#include "raster/datapath/reciprocal.h"

class VerilatedContext;
class Vreciprocal;

namespace tessera::raster {

class ReciprocalRtl {
 public:
  // Cycles from valid_i to valid_o (the result is registered once).
  static constexpr unsigned LATENCY_CYCLES = 1;

  // Builds the model and applies reset.
  ReciprocalRtl();
  ~ReciprocalRtl();
  ReciprocalRtl(const ReciprocalRtl&) = delete;
  ReciprocalRtl& operator=(const ReciprocalRtl&) = delete;

  // One operand through the unit: drive it with valid_i, clock once, read
  // the registered outputs. The port is 16 bits wide, as the core's operand:
  // every operand reaches the RTL, 0 and those above RECIP_OPERAND_MAX
  // included, and the RTL flags the invalid ones itself.
  ReciprocalResult evaluate(uint16_t x_q10_4);
  uint32_t evaluate_q5_16(uint16_t x_q10_4) { return evaluate(x_q10_4).q5_16; }

  // One rising clock edge with the given inputs; returns the outputs when
  // valid_o is set after the edge. For tests of the handshake and latency.
  std::optional<ReciprocalResult> clock(bool valid, uint16_t x_q10_4);

  void reset();

 private:
  ReciprocalResult read_outputs() const;

  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vreciprocal> m_model;
};

}  // namespace tessera::raster
