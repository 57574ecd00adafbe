#include "lod_unit_adapter.h"

#include <verilated.h>

#include "Vlod_unit.h"

namespace tessera::raster {

LodUnitRtl::LodUnitRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vlod_unit>(m_context.get(), "lod_unit")) {}

LodUnitRtl::~LodUnitRtl() {
  m_model->final();
}

LodResult LodUnitRtl::run(uint32_t rho, TexFilter min_filter, TexFilter mag_filter, TexMipmap mipmap,
                          unsigned last_level) {
  Vlod_unit& m = *m_model;
  m.rho_i = rho;
  m.min_filter_i = code_of(min_filter);
  m.mag_filter_i = code_of(mag_filter);
  m.mipmap_i = code_of(mipmap);
  m.last_level_i = last_level & 15;
  m.eval();
  LodResult r;
  // lambda_o is 14 bits, two's complement.
  r.lambda = static_cast<int32_t>(static_cast<uint32_t>(m.lambda_o) << 18) >> 18;
  r.minified = m.minified_o != 0;
  r.linear = m.linear_o != 0;
  r.level[0] = static_cast<uint8_t>(m.level0_o);
  r.level[1] = static_cast<uint8_t>(m.level1_o);
  r.two_levels = m.two_levels_o != 0;
  r.weight = static_cast<uint8_t>(m.weight_o);
  return r;
}

}  // namespace tessera::raster
