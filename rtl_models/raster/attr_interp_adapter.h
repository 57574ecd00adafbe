// Thin adapter over the Verilated attr_interp.sv, speaking the types of
// tlm/raster/datapath/attribute_interpolator.h.
#pragma once

#include <memory>

#include "raster/datapath/attribute_interpolator.h"

class VerilatedContext;
class Vattr_interp;

namespace tessera::raster {

class AttrInterpRtl {
 public:
  AttrInterpRtl();
  ~AttrInterpRtl();
  AttrInterpRtl(const AttrInterpRtl&) = delete;
  AttrInterpRtl& operator=(const AttrInterpRtl&) = delete;

  // dx and dy in -512..511 (10-bit two's complement ports).
  AttributeEvaluation evaluate(const AttributePlane& plane, int dx, int dy);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vattr_interp> m_model;
};

}  // namespace tessera::raster
