#include "toy.h"

#include <cstring>

#include "toy_regs.h"

namespace tessera {

ParamGroup ToyParams::parameters() {
  return {"toy",
          {param::integer("toy.job_cycles", 16, 1, 1024, "cycles", "cycles of the block's clock a job takes"),
           param::real("toy.clock_mhz", 100.0, 1.0, 1000.0, "MHz", "the block's clock")},
          {}};
}

ToyParams ToyParams::from_config(const Config& config) {
  ToyParams p;
  p.job_cycles = static_cast<unsigned>(config.get_uint("toy.job_cycles"));
  p.clock_period = sc_core::sc_time(1e3 / config.get_real("toy.clock_mhz"), sc_core::SC_NS);
  return p;
}

ToyParams ToyParams::defaults() {
  return from_config(Config({parameters()}));
}

Toy::Toy(sc_core::sc_module_name name, const ToyParams& params)
    : Peripheral(name, params.clock_period), m_params(params), m_jobs(counter("jobs", "jobs completed")) {
  STATUS.on_read(this, &Toy::read_STATUS);
  START.on_write(this, &Toy::write_START);
  bind_irq_registers(IRQ_STATUS, IRQ_ENABLE);
  SC_METHOD(job_done);
  sensitive << m_done;
  dont_initialize();
}

const char* Toy::write_refusal(const tlm::tlm_generic_payload& gp) const {
  if (!gp.is_write() || gp.get_address() != toy_regs::START || gp.get_data_length() != 4 || !gp.get_data_ptr())
    return nullptr;
  uint32_t value = 0;
  std::memcpy(&value, gp.get_data_ptr(), sizeof value);
  if (value != 1) return "START takes 1";
  if ((CTRL.get() & toy_regs::CTRL_ENABLE) == 0) return "START while CTRL.ENABLE is clear";
  if (access_time() < m_busy_until) return "START while a job runs";
  return nullptr;
}

uint32_t Toy::read_STATUS() const {
  return access_time() < m_busy_until ? toy_regs::STATUS_BUSY : 0;
}

void Toy::write_START(uint32_t /*value*/) {
  const sc_core::sc_time job = clock_period() * static_cast<double>(m_params.job_cycles);
  m_busy_until = access_time() + job;
  m_busy_time += job;
  m_done.notify(m_busy_until - sc_core::sc_time_stamp());
}

void Toy::job_done() {
  ++m_jobs;
  raise_irq(toy_regs::IRQ_DONE);
}

nlohmann::json Toy::stats_json(const sc_core::sc_time& elapsed) const {
  nlohmann::json stats = Peripheral::stats_json(elapsed);
  stats["job_cycles"] = m_params.job_cycles;
  add_busy_stats(stats, m_busy_time, elapsed);
  return stats;
}

void Toy::describe_stats(StatsSchema& schema) const {
  Peripheral::describe_stats(schema);
  schema.add_setting("job_cycles", "cycles", "cycles a job takes (toy.job_cycles)");
  describe_busy_stats(schema, "time the block ran jobs");
}

SummaryRow Toy::summary_row(const sc_core::sc_time& elapsed) const {
  return busy_row(m_busy_time, elapsed, std::to_string(m_jobs.value) + " jobs");
}

}  // namespace tessera
