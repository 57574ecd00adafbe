// Thin adapter over the Verilated fragment_tests.sv, speaking the types of
// tlm/raster/datapath/fragment_tests.h.
#pragma once

#include <memory>

#include "raster/datapath/fragment_tests.h"

class VerilatedContext;
class Vfragment_tests;

namespace tessera::raster {

class FragmentTestsRtl {
 public:
  FragmentTestsRtl();
  ~FragmentTestsRtl();
  FragmentTestsRtl(const FragmentTestsRtl&) = delete;
  FragmentTestsRtl& operator=(const FragmentTestsRtl&) = delete;

  FragmentTestResult run(const FragmentTestState& state, const FragmentTestInput& in);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vfragment_tests> m_model;
};

}  // namespace tessera::raster
