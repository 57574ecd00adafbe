// Thin adapter over the Verilated lod_unit.sv, speaking the types of
// tlm/raster/datapath/lod_unit.h.
#pragma once

#include <cstdint>
#include <memory>

#include "raster/datapath/lod_unit.h"

class VerilatedContext;
class Vlod_unit;

namespace tessera::raster {

class LodUnitRtl {
 public:
  LodUnitRtl();
  ~LodUnitRtl();
  LodUnitRtl(const LodUnitRtl&) = delete;
  LodUnitRtl& operator=(const LodUnitRtl&) = delete;

  LodResult run(uint32_t rho, TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap, unsigned last_level);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vlod_unit> m_model;
};

}  // namespace tessera::raster
