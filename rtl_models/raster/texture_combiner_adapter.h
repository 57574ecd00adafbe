// Thin adapter over the Verilated texture_combiner.sv, speaking the types of
// tlm/raster/datapath/texture_combiner.h.
#pragma once

#include <memory>

#include "raster/datapath/texture_combiner.h"

class VerilatedContext;
class Vtexture_combiner;

namespace tessera::raster {

class TextureCombinerRtl {
 public:
  TextureCombinerRtl();
  ~TextureCombinerRtl();
  TextureCombinerRtl(const TextureCombinerRtl&) = delete;
  TextureCombinerRtl& operator=(const TextureCombinerRtl&) = delete;

  // The combiner words go to the ports as they are (with their reserved bits).
  Rgba8 run(TexEnv env, TexBaseFormat base_format, Rgba8 primary, Rgba8 previous, Rgba8 texel, Rgba8 env_color,
            uint32_t combine_rgb, uint32_t combine_alpha);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vtexture_combiner> m_model;
};

}  // namespace tessera::raster
