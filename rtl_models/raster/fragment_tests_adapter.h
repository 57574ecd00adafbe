// Thin adapter over the Verilated fragment_tests.sv, speaking the types of
// tlm/raster/datapath/fragment_tests.h.
#pragma once

#include <memory>

#include "raster/datapath/fragment_tests.h"

class VerilatedContext;
class Vfragment_tests;

namespace tessera::raster {

class fragment_tests_rtl {
public:
    fragment_tests_rtl();
    ~fragment_tests_rtl();
    fragment_tests_rtl(const fragment_tests_rtl&) = delete;
    fragment_tests_rtl& operator=(const fragment_tests_rtl&) = delete;

    fragment_test_result run(const fragment_test_state& state, const fragment_test_input& in);

private:
    std::unique_ptr<VerilatedContext> m_context;
    std::unique_ptr<Vfragment_tests> m_model;
};

} // namespace tessera::raster
