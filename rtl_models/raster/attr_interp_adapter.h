// Thin adapter over the Verilated attr_interp.sv, speaking the types of
// tlm/raster/datapath/attribute_interpolator.h.
#pragma once

#include <memory>

#include "raster/datapath/attribute_interpolator.h"

class VerilatedContext;
class Vattr_interp;

namespace tessera::raster {

class attr_interp_rtl {
public:
    attr_interp_rtl();
    ~attr_interp_rtl();
    attr_interp_rtl(const attr_interp_rtl&) = delete;
    attr_interp_rtl& operator=(const attr_interp_rtl&) = delete;

    // dx and dy in -512..511 (10-bit two's complement ports).
    attribute_evaluation evaluate(const attribute_plane& plane, int dx, int dy);

private:
    std::unique_ptr<VerilatedContext> m_context;
    std::unique_ptr<Vattr_interp> m_model;
};

} // namespace tessera::raster
