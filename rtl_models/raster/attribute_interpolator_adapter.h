// Thin adapter over the Verilated attribute_interpolator.sv, speaking the types of
// tlm/raster/datapath/attribute_interpolator.h.
#pragma once

#include <memory>

#include "raster/datapath/attribute_interpolator.h"

class VerilatedContext;
class Vattribute_interpolator;

namespace tessera::raster {

class AttributeInterpolatorRtl {
 public:
  AttributeInterpolatorRtl();
  ~AttributeInterpolatorRtl();
  AttributeInterpolatorRtl(const AttributeInterpolatorRtl&) = delete;
  AttributeInterpolatorRtl& operator=(const AttributeInterpolatorRtl&) = delete;

  // dx and dy in -512..511 (10-bit two's complement ports).
  AttributeEvaluation evaluate(const AttributePlane& plane, int dx, int dy);

 private:
  std::unique_ptr<VerilatedContext> m_context;
  std::unique_ptr<Vattribute_interpolator> m_model;
};

}  // namespace tessera::raster
