// Thin adapter over the Verilated texture_env.sv, speaking the types of
// tlm/raster/datapath/texture_env.h.
#pragma once

#include <array>
#include <memory>

#include "raster/datapath/texture_env.h"

class VerilatedContext;
class Vtexture_env;

namespace tessera::raster {

class TextureEnvRtl {
 public:
  TextureEnvRtl();
  ~TextureEnvRtl();
  TextureEnvRtl(const TextureEnvRtl&) = delete;
  TextureEnvRtl& operator=(const TextureEnvRtl&) = delete;

  TextureEnvResult run(TexEnv mode, const std::array<Rgba8, 4>& texels, uint8_t weight_s, uint8_t weight_t,
                       Rgba8 fragment);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vtexture_env> m_model;
};

}  // namespace tessera::raster
