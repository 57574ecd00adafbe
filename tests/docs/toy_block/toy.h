// A toy block built by following docs/how_to_add_a_block.md step by step, so
// that a test shows the walk-through is right: a peripheral (section 2) with
// a parameter group (3) and a register table declared as members with
// handlers (4), activity counters, busy statistics and their descriptions,
// a summary row. Software enables it (CTRL.ENABLE) and writes START = 1: a
// job then runs toy.job_cycles cycles of the block's clock from the
// access's time, STATUS.BUSY shows it, and IRQ DONE rises at its end. A
// START while a job runs or while disabled is refused (a command error).
// Sections 5 and 6 (the memory and interrupt maps, the binding in the SoC)
// edit the SoC's own tables and are not followed here.
#pragma once

#include <cstdint>

#include <systemc>

#include <nlohmann/json.hpp>

#include "common/peripheral.h"
#include "config/config.h"

namespace tessera {

struct ToyParams {
  unsigned job_cycles = 0;
  sc_core::sc_time clock_period;  // set by the SoC (the bus clock) in a real block; here toy.clock_mhz

  // The parameters this block owns, the one place their defaults live.
  static ParamGroup parameters();
  static ToyParams from_config(const Config& config);  // reads its own keys only
  static ToyParams defaults();
};

class Toy : public Peripheral {
 public:
  SC_HAS_PROCESS(Toy);

#define TESSERA_REGISTER_TABLE "toy_regs.def"
#include "common/register_members.inc"

  Toy(sc_core::sc_module_name name, const ToyParams& params);

  nlohmann::json stats_json(const sc_core::sc_time& elapsed) const override;
  void describe_stats(StatsSchema& schema) const override;
  SummaryRow summary_row(const sc_core::sc_time& elapsed) const override;

 private:
  const char* write_refusal(const tlm::tlm_generic_payload& gp) const override;
  uint32_t read_STATUS() const;
  void write_START(uint32_t value);
  void job_done();  // SC_METHOD on m_done

  ToyParams m_params;
  ActivityCounter& m_jobs;
  sc_core::sc_time m_busy_until;
  sc_core::sc_time m_busy_time;
  sc_core::sc_event m_done;
};

}  // namespace tessera
