#include "edge_function_adapter.h"

#include <verilated.h>

#include "Vedge_function.h"

namespace tessera::raster {

EdgeFunctionRtl::EdgeFunctionRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vedge_function>(m_context.get(), "edge_function")) {}

EdgeFunctionRtl::~EdgeFunctionRtl() {
  m_model->final();
}

EdgeEvaluation EdgeFunctionRtl::evaluate(const Edge& e, unsigned px, unsigned py, q5_16 recip) {
  m_model->x0_i = static_cast<uint16_t>(e.x0.raw);
  m_model->y0_i = static_cast<uint16_t>(e.y0.raw);
  m_model->x1_i = static_cast<uint16_t>(e.x1.raw);
  m_model->y1_i = static_cast<uint16_t>(e.y1.raw);
  m_model->px_i = static_cast<uint16_t>(px & 0x1ff);
  m_model->py_i = static_cast<uint16_t>(py & 0x1ff);
  m_model->recip_i = recip.raw;
  m_model->eval();

  EdgeEvaluation r;
  r.value = edge_value::from_raw(m_model->edge_o);
  r.value_next_x = edge_value::from_raw(m_model->edge_next_x_o);
  r.value_next_y = edge_value::from_raw(m_model->edge_next_y_o);
  r.inside = m_model->inside_o != 0;
  r.l1_length = q10_4::from_raw(m_model->l1_length_o);
  r.distance = edge_distance::from_raw(m_model->distance_o);
  r.coverage = unorm8::from_raw(m_model->coverage_o);
  return r;
}

}  // namespace tessera::raster
