// Thin adapter over the Verilated edge_function.sv: takes and returns the
// functional core's types (tlm/raster/datapath/edge_function.h) so that
// co-simulation tests compare like with like.
#pragma once

#include <memory>

#include "raster/datapath/edge_function.h"

class VerilatedContext;
class Vedge_function;

namespace tessera::raster {

class EdgeFunctionRtl {
 public:
  EdgeFunctionRtl();
  ~EdgeFunctionRtl();
  EdgeFunctionRtl(const EdgeFunctionRtl&) = delete;
  EdgeFunctionRtl& operator=(const EdgeFunctionRtl&) = delete;

  // px and py are 9-bit port values (0..511).
  EdgeEvaluation evaluate(const Edge& e, unsigned px, unsigned py, q5_16 recip);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vedge_function> m_model;
};

}  // namespace tessera::raster
