#include "reciprocal_adapter.h"

#include <stdexcept>

#include "Vreciprocal.h"
#include "verilated.h"

namespace tessera::raster {

namespace {

constexpr unsigned EXPONENT_SIGN_BIT = 1u << (RECIP_EXPONENT_BITS - 1);

// Sign-extends the 5-bit two's complement exponent port.
int8_t exponent_from_field(unsigned field) {
  const int value = static_cast<int>(field & ((1u << RECIP_EXPONENT_BITS) - 1));
  return static_cast<int8_t>((field & EXPONENT_SIGN_BIT) ? value - (1 << RECIP_EXPONENT_BITS) : value);
}

}  // namespace

ReciprocalRtl::ReciprocalRtl()
    : m_context(std::make_unique<VerilatedContext>()),
      m_model(std::make_unique<Vreciprocal>(m_context.get(), "reciprocal")) {
  reset();
}

ReciprocalRtl::~ReciprocalRtl() {
  m_model->final();
}

void ReciprocalRtl::reset() {
  m_model->clk_i = 0;
  m_model->valid_i = 0;
  m_model->x_i = 0;
  m_model->rst_ni = 0;
  m_model->eval();
  m_model->rst_ni = 1;
  m_model->eval();
}

std::optional<ReciprocalResult> ReciprocalRtl::clock(bool valid, uint16_t x_q10_4) {
  m_model->valid_i = valid ? 1 : 0;
  m_model->x_i = x_q10_4;
  // Settle the inputs while the clock is low, so the rising edge samples
  // them as a register in a real design would, free of any input/clock race.
  m_model->eval();
  m_model->clk_i = 1;
  m_model->eval();
  m_model->clk_i = 0;
  m_model->eval();
  if (!m_model->valid_o) {
    return std::nullopt;
  }
  return read_outputs();
}

ReciprocalResult ReciprocalRtl::evaluate(uint16_t x_q10_4) {
  const std::optional<ReciprocalResult> result = clock(true, x_q10_4);
  if (!result) {
    throw std::logic_error("reciprocal: valid_o not set one cycle after valid_i");
  }
  return *result;
}

ReciprocalResult ReciprocalRtl::read_outputs() const {
  ReciprocalResult r;
  r.method = RecipMethod::method3;
  r.q5_16 = m_model->recip_o;
  r.invalid_operand = m_model->invalid_o != 0;
  r.mantissa = m_model->mantissa_o;
  r.exponent = exponent_from_field(m_model->exponent_o);
  return r;
}

}  // namespace tessera::raster
