#include "texture_env_adapter.h"

#include <verilated.h>

#include "Vtexture_env.h"

namespace tessera::raster {

TextureEnvRtl::TextureEnvRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vtexture_env>(m_context.get(), "texture_env")) {}

TextureEnvRtl::~TextureEnvRtl() {
  m_model->final();
}

TextureEnvResult TextureEnvRtl::run(TexEnv mode, const std::array<Rgba8, 4>& texels, uint8_t weight_s, uint8_t weight_t,
                                    Rgba8 fragment) {
  Vtexture_env& m = *m_model;
  m.texel00_i = texels[0].pack();
  m.texel10_i = texels[1].pack();
  m.texel01_i = texels[2].pack();
  m.texel11_i = texels[3].pack();
  m.weight_s_i = weight_s;
  m.weight_t_i = weight_t;
  m.fragment_i = fragment.pack();
  m.env_mode_i = code_of(mode);
  m.eval();
  return TextureEnvResult{Rgba8::unpack(m.texel_o), Rgba8::unpack(m.rgba_o)};
}

}  // namespace tessera::raster
