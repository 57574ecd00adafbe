#include "fragment_tests_adapter.h"

#include <verilated.h>

#include "Vfragment_tests.h"

namespace tessera::raster {

FragmentTestsRtl::FragmentTestsRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vfragment_tests>(m_context.get(), "fragment_tests")) {}

FragmentTestsRtl::~FragmentTestsRtl() {
  m_model->final();
}

FragmentTestResult FragmentTestsRtl::run(const FragmentTestState& state, const FragmentTestInput& in) {
  Vfragment_tests& m = *m_model;
  m.alpha_enable_i = state.alpha_enable;
  m.alpha_func_i = code_of(state.alpha_func);
  m.alpha_ref_i = static_cast<uint8_t>(state.alpha_ref.raw);
  m.alpha_i = static_cast<uint8_t>(in.alpha.raw);
  m.stencil_enable_i = state.stencil_enable;
  m.stencil_func_i = code_of(state.stencil_func);
  m.stencil_ref_i = static_cast<uint8_t>(state.stencil_ref.raw);
  m.stencil_value_mask_i = state.stencil_value_mask;
  m.stencil_write_mask_i = state.stencil_write_mask;
  m.stencil_sfail_i = code_of(state.sfail);
  m.stencil_dpfail_i = code_of(state.dpfail);
  m.stencil_dppass_i = code_of(state.dppass);
  m.stencil_i = static_cast<uint8_t>(in.stored_stencil.raw);
  m.depth_enable_i = state.depth_enable;
  m.depth_func_i = code_of(state.depth_func);
  m.depth_write_mask_i = state.depth_write_mask;
  m.depth_i = in.depth.raw;
  m.stored_depth_i = in.stored_depth.raw;
  m.eval();

  FragmentTestResult r;
  r.alpha_pass = m.alpha_pass_o != 0;
  r.stencil_pass = m.stencil_pass_o != 0;
  r.depth_pass = m.depth_pass_o != 0;
  r.pass = m.pass_o != 0;
  r.stencil = stencil8::from_raw(m.stencil_o);
  r.depth_write = m.depth_we_o != 0;
  return r;
}

}  // namespace tessera::raster
