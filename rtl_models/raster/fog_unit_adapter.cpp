#include "fog_unit_adapter.h"

#include <verilated.h>

#include "Vfog_unit.h"

namespace tessera::raster {

FogUnitRtl::FogUnitRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vfog_unit>(m_context.get(), "fog_unit")) {}

FogUnitRtl::~FogUnitRtl() {
  m_model->final();
}

FogUnitResult FogUnitRtl::run(FogMode mode, int32_t argument, Rgba8 fragment, Rgba8 fog_color) {
  Vfog_unit& m = *m_model;
  m.fog_mode_i = code_of(mode);
  m.argument_i = static_cast<uint32_t>(argument);
  m.fragment_i = fragment.pack();
  m.fog_color_i = fog_color.pack();
  m.eval();
  FogUnitResult r;
  r.factor = static_cast<uint8_t>(m.factor_o);
  r.color = Rgba8::unpack(m.rgba_o);
  return r;
}

}  // namespace tessera::raster
