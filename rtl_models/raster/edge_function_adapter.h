// Thin adapter over the Verilated edge_function.sv: takes and returns the
// functional core's types (tlm/raster/datapath/edge_function.h) so that
// co-simulation tests compare like with like.
#pragma once

#include <memory>

#include "raster/datapath/edge_function.h"

class VerilatedContext;
class Vedge_function;

namespace tessera::raster {

class edge_function_rtl {
public:
    edge_function_rtl();
    ~edge_function_rtl();
    edge_function_rtl(const edge_function_rtl&) = delete;
    edge_function_rtl& operator=(const edge_function_rtl&) = delete;

    // px and py are 9-bit port values (0..511).
    edge_evaluation evaluate(const edge& e, unsigned px, unsigned py, q5_16 recip);

private:
    std::unique_ptr<VerilatedContext> m_context;
    std::unique_ptr<Vedge_function> m_model;
};

} // namespace tessera::raster
