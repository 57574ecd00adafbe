#include "blend_logic_op_adapter.h"

#include <verilated.h>

#include "Vblend_logic_op.h"

namespace tessera::raster {

BlendLogicOpRtl::BlendLogicOpRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vblend_logic_op>(m_context.get(), "blend_logic_op")) {}

BlendLogicOpRtl::~BlendLogicOpRtl() {
  m_model->final();
}

Rgba8 BlendLogicOpRtl::run(const BlendState& state, Rgba8 src, Rgba8 dst) {
  Vblend_logic_op& m = *m_model;
  m.src_i = src.pack();
  m.dst_i = dst.pack();
  m.blend_enable_i = state.blend_enable;
  m.src_factor_i = code_of(state.src_factor);
  m.dst_factor_i = code_of(state.dst_factor);
  m.logic_op_enable_i = state.logic_op_enable;
  m.logic_op_i = code_of(state.op);
  m.color_mask_i = state.color_mask & COLOR_MASK_ALL;
  m.eval();
  return Rgba8::unpack(m.rgba_o);
}

}  // namespace tessera::raster
