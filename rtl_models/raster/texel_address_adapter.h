// Thin adapter over the Verilated texel_address.sv, speaking the types of
// tlm/raster/datapath/texel_address.h.
#pragma once

#include <memory>

#include "raster/datapath/texel_address.h"

class VerilatedContext;
class Vtexel_address;

namespace tessera::raster {

class TexelAddressRtl {
 public:
  TexelAddressRtl();
  ~TexelAddressRtl();
  TexelAddressRtl(const TexelAddressRtl&) = delete;
  TexelAddressRtl& operator=(const TexelAddressRtl&) = delete;

  // log2 sizes are 4-bit port values (0..15).
  TexelFootprint lookup(const TextureState& state, q15_16 s, q15_16 t);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vtexel_address> m_model;
};

}  // namespace tessera::raster
