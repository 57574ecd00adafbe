// Thin adapter over the Verilated fog_unit.sv, speaking the types of
// tlm/raster/datapath/fog_unit.h.
#pragma once

#include <cstdint>
#include <memory>

#include "raster/datapath/fog_unit.h"

class VerilatedContext;
class Vfog_unit;

namespace tessera::raster {

class FogUnitRtl {
 public:
  FogUnitRtl();
  ~FogUnitRtl();
  FogUnitRtl(const FogUnitRtl&) = delete;
  FogUnitRtl& operator=(const FogUnitRtl&) = delete;

  FogUnitResult run(FogMode mode, int32_t argument, Rgba8 fragment, Rgba8 fog_color);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vfog_unit> m_model;
};

}  // namespace tessera::raster
