#include "texture_env_adapter.h"

#include <verilated.h>

#include "Vtexture_env.h"

namespace tessera::raster {

texture_env_rtl::texture_env_rtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vtexture_env>(m_context.get(), "texture_env")) {}

texture_env_rtl::~texture_env_rtl() { m_model->final(); }

texture_env_result texture_env_rtl::run(texture_env_mode mode, const std::array<rgba8, 4>& texels, uint8_t weight_s,
                                        uint8_t weight_t, rgba8 fragment) {
    Vtexture_env& m = *m_model;
    m.texel00_i = texels[0].pack();
    m.texel10_i = texels[1].pack();
    m.texel01_i = texels[2].pack();
    m.texel11_i = texels[3].pack();
    m.weight_s_i = weight_s;
    m.weight_t_i = weight_t;
    m.fragment_i = fragment.pack();
    m.env_mode_i = texture_env_mode_code(mode);
    m.eval();
    return texture_env_result{rgba8::unpack(m.texel_o), rgba8::unpack(m.rgba_o)};
}

} // namespace tessera::raster
