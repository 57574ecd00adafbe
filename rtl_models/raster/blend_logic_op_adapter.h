// Thin adapter over the Verilated blend_logic_op.sv, speaking the types of
// tlm/raster/datapath/blend_logic_op.h.
#pragma once

#include <memory>

#include "raster/datapath/blend_logic_op.h"

class VerilatedContext;
class Vblend_logic_op;

namespace tessera::raster {

class BlendLogicOpRtl {
 public:
  BlendLogicOpRtl();
  ~BlendLogicOpRtl();
  BlendLogicOpRtl(const BlendLogicOpRtl&) = delete;
  BlendLogicOpRtl& operator=(const BlendLogicOpRtl&) = delete;

  Rgba8 run(const BlendState& state, Rgba8 src, Rgba8 dst);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vblend_logic_op> m_model;
};

}  // namespace tessera::raster
