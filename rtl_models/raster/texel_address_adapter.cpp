#include "texel_address_adapter.h"

#include <verilated.h>

#include "Vtexel_address.h"

namespace tessera::raster {

texel_address_rtl::texel_address_rtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vtexel_address>(m_context.get(), "texel_address")) {}

texel_address_rtl::~texel_address_rtl() { m_model->final(); }

texel_footprint texel_address_rtl::lookup(const texture_state& state, q15_16 s, q15_16 t) {
    Vtexel_address& m = *m_model;
    m.s_i = static_cast<uint32_t>(s.raw);
    m.t_i = static_cast<uint32_t>(t.raw);
    m.log2_width_i = state.log2_width & 0xf;
    m.log2_height_i = state.log2_height & 0xf;
    m.wrap_s_i = state.wrap_s == texture_wrap::CLAMP_TO_EDGE;
    m.wrap_t_i = state.wrap_t == texture_wrap::CLAMP_TO_EDGE;
    m.linear_i = state.filter == texture_filter::LINEAR;
    m.base_i = state.base;
    m.eval();

    texel_footprint f;
    f.s = texel_axis{m.i0_o, m.i1_o, m.weight_s_o};
    f.t = texel_axis{m.j0_o, m.j1_o, m.weight_t_o};
    f.address = {m.addr00_o, m.addr10_o, m.addr01_o, m.addr11_o};
    return f;
}

} // namespace tessera::raster
