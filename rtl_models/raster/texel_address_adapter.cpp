#include "texel_address_adapter.h"

#include <verilated.h>

#include "Vtexel_address.h"

namespace tessera::raster {

TexelAddressRtl::TexelAddressRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vtexel_address>(m_context.get(), "texel_address")) {}

TexelAddressRtl::~TexelAddressRtl() {
  m_model->final();
}

TexelFootprint TexelAddressRtl::lookup(const TextureState& state, q15_16 s, q15_16 t) {
  Vtexel_address& m = *m_model;
  m.s_i = static_cast<uint32_t>(s.raw);
  m.t_i = static_cast<uint32_t>(t.raw);
  m.log2_width_i = state.log2_width & 0xf;
  m.log2_height_i = state.log2_height & 0xf;
  m.wrap_s_i = code_of(state.wrap_s);
  m.wrap_t_i = code_of(state.wrap_t);
  m.filter_i = code_of(state.filter);
  m.base_i = state.base;
  m.eval();

  TexelFootprint f;
  f.s = TexelAxis{m.i0_o, m.i1_o, m.weight_s_o};
  f.t = TexelAxis{m.j0_o, m.j1_o, m.weight_t_o};
  f.address = {m.addr00_o, m.addr10_o, m.addr01_o, m.addr11_o};
  return f;
}

}  // namespace tessera::raster
