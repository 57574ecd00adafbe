// Thin adapter over the Verilated blend_logic_op.sv, speaking the types of
// tlm/raster/datapath/blend_logic_op.h.
#pragma once

#include <memory>

#include "raster/datapath/blend_logic_op.h"

class VerilatedContext;
class Vblend_logic_op;

namespace tessera::raster {

class blend_logic_op_rtl {
public:
    blend_logic_op_rtl();
    ~blend_logic_op_rtl();
    blend_logic_op_rtl(const blend_logic_op_rtl&) = delete;
    blend_logic_op_rtl& operator=(const blend_logic_op_rtl&) = delete;

    rgba8 run(const blend_state& state, rgba8 src, rgba8 dst);

private:
    std::unique_ptr<VerilatedContext> m_context;
    std::unique_ptr<Vblend_logic_op> m_model;
};

} // namespace tessera::raster
