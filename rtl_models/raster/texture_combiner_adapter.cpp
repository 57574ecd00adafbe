#include "texture_combiner_adapter.h"

#include <verilated.h>

#include "Vtexture_combiner.h"

namespace tessera::raster {

TextureCombinerRtl::TextureCombinerRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vtexture_combiner>(m_context.get(), "texture_combiner")) {}

TextureCombinerRtl::~TextureCombinerRtl() {
  m_model->final();
}

Rgba8 TextureCombinerRtl::run(TexEnv env, TexBaseFormat base_format, Rgba8 primary, Rgba8 previous, Rgba8 texel,
                              Rgba8 env_color, uint32_t combine_rgb, uint32_t combine_alpha) {
  Vtexture_combiner& m = *m_model;
  m.env_i = code_of(env);
  m.base_format_i = code_of(base_format);
  m.primary_i = primary.pack();
  m.previous_i = previous.pack();
  m.texel_i = texel.pack();
  m.env_color_i = env_color.pack();
  m.combine_rgb_i = combine_rgb;
  m.combine_alpha_i = combine_alpha;
  m.eval();
  return Rgba8::unpack(m.rgba_o);
}

}  // namespace tessera::raster
