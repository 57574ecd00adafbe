// Thin adapter over the Verilated texel_address.sv, speaking the types of
// tlm/raster/datapath/texel_address.h.
#pragma once

#include <memory>

#include "raster/datapath/texel_address.h"

class VerilatedContext;
class Vtexel_address;

namespace tessera::raster {

class texel_address_rtl {
public:
    texel_address_rtl();
    ~texel_address_rtl();
    texel_address_rtl(const texel_address_rtl&) = delete;
    texel_address_rtl& operator=(const texel_address_rtl&) = delete;

    // log2 sizes are 4-bit port values (0..15).
    texel_footprint lookup(const texture_state& state, q15_16 s, q15_16 t);

private:
    std::unique_ptr<VerilatedContext> m_context;
    std::unique_ptr<Vtexel_address> m_model;
};

} // namespace tessera::raster
