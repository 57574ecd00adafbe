// Thin adapter over the Verilated texture_env.sv, speaking the types of
// tlm/raster/datapath/texture_env.h.
#pragma once

#include <array>
#include <memory>

#include "raster/datapath/texture_env.h"

class VerilatedContext;
class Vtexture_env;

namespace tessera::raster {

class texture_env_rtl {
public:
    texture_env_rtl();
    ~texture_env_rtl();
    texture_env_rtl(const texture_env_rtl&) = delete;
    texture_env_rtl& operator=(const texture_env_rtl&) = delete;

    texture_env_result run(texture_env_mode mode, const std::array<rgba8, 4>& texels, uint8_t weight_s,
                           uint8_t weight_t, rgba8 fragment);

private:
    std::unique_ptr<VerilatedContext> m_context;
    std::unique_ptr<Vtexture_env> m_model;
};

} // namespace tessera::raster
