#include "attribute_interpolator_adapter.h"

#include <verilated.h>

#include "Vattribute_interpolator.h"

namespace tessera::raster {

namespace {

constexpr uint64_t WORD40_MASK = (uint64_t{1} << 40) - 1;

}  // namespace

AttributeInterpolatorRtl::AttributeInterpolatorRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vattribute_interpolator>(m_context.get(), "attribute_interpolator")) {}

AttributeInterpolatorRtl::~AttributeInterpolatorRtl() {
  m_model->final();
}

AttributeEvaluation AttributeInterpolatorRtl::evaluate(const AttributePlane& plane, int dx, int dy) {
  m_model->kind_i = static_cast<uint8_t>(plane.kind) & 0x3;
  m_model->start_i = static_cast<uint64_t>(plane.start) & WORD40_MASK;
  m_model->grad_x_i = static_cast<uint64_t>(plane.grad_x) & WORD40_MASK;
  m_model->grad_y_i = static_cast<uint64_t>(plane.grad_y) & WORD40_MASK;
  m_model->offset_x_i = static_cast<uint16_t>(static_cast<unsigned>(dx) & 0x3ff);
  m_model->offset_y_i = static_cast<uint16_t>(static_cast<unsigned>(dy) & 0x3ff);
  m_model->eval();

  AttributeEvaluation r;
  r.value = attribute_sum::from_raw(static_cast<int64_t>(m_model->value_o));
  r.value_next_x = attribute_sum::from_raw(static_cast<int64_t>(m_model->value_next_x_o));
  r.value_next_y = attribute_sum::from_raw(static_cast<int64_t>(m_model->value_next_y_o));
  r.output = m_model->attr_o;
  return r;
}

}  // namespace tessera::raster
