// The array processor's calibration micro-benchmarks (docs/spec/
// calibration.md): a 16-bit addition and a signed 16 x 8 multiplication at
// register level, and the same two on CMEM operands with the result stored
// back, one pass of every CU. Each runs the real programs of
// kernels/ap_calibration.s on the model: the host writes the operands
// through the CIU with the study's packing, runs a long and a short
// version of the program and takes the difference of their AC cycle counts
// (so loads, stores and loop set-up cancel), reads every result back and
// checks it in every CU, and prints the model's figure beside the board's.
//
// calib_ciu times the host's 32-bit writes and reads through the CIU,
// including the ARM's address computation, beside the board's 488 ns and
// 830 ns.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <string>

#include "ap_programs/ap_calibration.h"
#include "apps/apps.h"
#include "array/program.h"
#include "costs/host_cost.h"
#include "device/array_driver.h"
#include "renderers/common/host_time.h"

namespace tessera {

namespace {

constexpr unsigned RECORDS = 128, RECORD = 6;

// calib_ciu: CMEM addresses 0 .. CIU_ADDRESSES - 1 of every group (3072
// words with the default 24 groups); the value written changes by
// VALUE_STEP from one word to the next. The inner loops' own single-cycle
// instructions per access besides their taken branch, in GCC's code for
// the ARM922T (natively charged; the driver charges its call): the
// write loop's four argument moves, the fifth argument's store, the
// value's step, the counter and the compare; the read loop's four moves,
// the sum, the counter and the compare.
constexpr unsigned CIU_ADDRESSES = 128;
constexpr uint32_t VALUE_STEP = 2654435761u;

const ap::Program& program() {
  return ap::programs::ap_calibration();
}

unsigned address_of(const char* name) {
  return program().variables.at(name).address;
}

unsigned entry_of(const std::string& name) {
  return program().entries.at(name);
}

// Deterministic operands per CU and record.
uint16_t operand_a(unsigned cu, unsigned record) {
  return static_cast<uint16_t>(cu * 677 + record * 3001 + 17);
}
uint16_t operand_b(unsigned cu, unsigned record) {
  return static_cast<uint16_t>(cu * 1291 + record * 97 + 40000);
}

void report(const char* what, double model, double measured, const char* unit, const std::string& extra = "") {
  std::printf("array calibration: %s: model %.2f %s%s, measured %.2f %s (%+.1f%%)\n", what, model, unit, extra.c_str(),
              measured, unit, (model / measured - 1) * 100);
}

int mismatch(const char* what, unsigned cu, unsigned record, long got, long expected) {
  std::fprintf(stderr, "array calibration: %s: CU %u record %u holds %ld, expected %ld\n", what, cu, record, got,
               expected);
  return 1;
}

int register_level(AppEnvironment& env, bool multiply) {
  ArrayDriver array(env);
  array.load(program());
  const unsigned n = array.cus();
  std::vector<uint16_t> first(n), second(n);
  std::vector<uint8_t> multipliers(n);
  for (unsigned cu = 0; cu < n; ++cu) {
    first[cu] = operand_a(cu, 0);
    second[cu] = operand_b(cu, 0);
    multipliers[cu] = static_cast<uint8_t>(cu * 37 + 128);
  }
  if (multiply) {
    array.write_all16(address_of("multiplicand"), first);
    array.write_all8(address_of("multiplier"), multipliers);
  } else {
    array.write_all16(address_of("sum"), first);
    array.write_all16(address_of("increment"), second);
  }
  const std::string name = multiply ? "mul_registers_" : "add_registers_";
  const uint32_t short_run = array.run(entry_of(name + "1000"));
  const uint32_t long_run = array.run(entry_of(name + "2000"));
  const double cycles = (long_run - short_run) / 1000.0;

  // Every CU's result, byte for byte through the CIU.
  if (multiply) {
    const std::vector<uint16_t> high_middle = array.read_all16(address_of("product"));
    const std::vector<uint8_t> low = array.read_all8(address_of("product") + 2);
    for (unsigned cu = 0; cu < n; ++cu) {
      const int32_t expected = int32_t{static_cast<int16_t>(first[cu])} * static_cast<int8_t>(multipliers[cu]);
      const uint32_t got = (uint32_t{high_middle[cu]} << 8) | low[cu];
      if (got != (static_cast<uint32_t>(expected) & 0xffffffu))
        return mismatch("register multiply", cu, 0, static_cast<long>(got), expected);
    }
    report("signed 16 x 8-bit multiplication, register level", cycles, 40, "cycles");
  } else {
    const std::vector<uint16_t> sums = array.read_all16(address_of("sum"));
    for (unsigned cu = 0; cu < n; ++cu) {
      // 1000 additions, then 2000 more from that result.
      const auto expected = static_cast<uint16_t>(first[cu] + 3000u * second[cu]);
      if (sums[cu] != expected) return mismatch("register addition", cu, 0, sums[cu], expected);
    }
    report("16-bit addition, register level", cycles, 4, "cycles");
  }
  return 0;
}

int cmem_level(AppEnvironment& env, bool multiply) {
  ArrayDriver array(env);
  array.load(program());
  const unsigned n = array.cus();
  const unsigned records = address_of("records");
  std::vector<uint16_t> values(n);
  std::vector<uint8_t> bytes(n);
  for (unsigned r = 0; r < RECORDS; ++r) {
    for (unsigned cu = 0; cu < n; ++cu) values[cu] = operand_a(cu, r);
    array.write_all16(records + RECORD * r, values);
    if (multiply) {
      for (unsigned cu = 0; cu < n; ++cu) bytes[cu] = static_cast<uint8_t>(operand_b(cu, r));
      array.write_all8(records + RECORD * r + 2, bytes);
    } else {
      for (unsigned cu = 0; cu < n; ++cu) values[cu] = operand_b(cu, r);
      array.write_all16(records + RECORD * r + 2, values);
    }
  }
  const std::string name = multiply ? "mul_cmem_" : "add_cmem_";
  const uint32_t half = array.run(entry_of(name + "half"));
  const uint32_t all = array.run(entry_of(name + "all"));
  // "all" makes RECORDS passes, "half" RECORDS / 2 (RECORDS is even).
  static_assert(RECORDS % 2 == 0);
  const unsigned passes = RECORDS / 2;
  const double cycles = static_cast<double>(all - half) / passes;
  const double ns = cycles / array.clock_hz() * 1e9;

  for (unsigned r = 0; r < RECORDS; ++r) {
    if (multiply) {
      const std::vector<uint16_t> high_middle = array.read_all16(records + RECORD * r + 3);
      const std::vector<uint8_t> low = array.read_all8(records + RECORD * r + 5);
      for (unsigned cu = 0; cu < n; ++cu) {
        const int32_t expected = int32_t{static_cast<int16_t>(operand_a(cu, r))} *
                                 static_cast<int8_t>(static_cast<uint8_t>(operand_b(cu, r)));
        const uint32_t got = (uint32_t{high_middle[cu]} << 8) | low[cu];
        if (got != (static_cast<uint32_t>(expected) & 0xffffffu))
          return mismatch("CMEM multiply", cu, r, static_cast<long>(got), expected);
      }
    } else {
      const std::vector<uint16_t> sums = array.read_all16(records + RECORD * r + 4);
      for (unsigned cu = 0; cu < n; ++cu) {
        const auto expected = static_cast<uint16_t>(operand_a(cu, r) + operand_b(cu, r));
        if (sums[cu] != expected) return mismatch("CMEM addition", cu, r, sums[cu], expected);
      }
    }
  }
  char extra[64];
  std::snprintf(extra, sizeof extra, " (%.2f cycles)", cycles);
  if (multiply)
    report("signed 16 x 8-bit multiplication of CMEM operands stored back, one pass of all CUs", ns, 1093.44, "ns",
           extra);
  else
    report("16-bit addition of two CMEM operands stored back, one pass of all CUs", ns, 64.0, "ns", extra);
  return 0;
}

}  // namespace

int calib_array_add_app(AppEnvironment& env) {
  return register_level(env, false);
}
int calib_array_mul_app(AppEnvironment& env) {
  return register_level(env, true);
}
int calib_array_add_cmem_app(AppEnvironment& env) {
  return cmem_level(env, false);
}
int calib_array_mul_cmem_app(AppEnvironment& env) {
  return cmem_level(env, true);
}

int calib_ciu_app(AppEnvironment& env) {
  HostApi& host = *env.host;
  ArrayDriver array(env);
  // The study's loop: WriteMem32 to every group of every row at each
  // address in turn (as the driver fills a value into every CU), then
  // ReadMem32 of the same words. The arguments are checked once, before
  // the loops; each access is the driver's call alone.
  const unsigned groups = array.groups_per_row(), rows = array.rows();
  array.check_access(groups - 1, rows - 1, CIU_ADDRESSES - 1);
  const unsigned accesses = CIU_ADDRESSES * rows * groups;
  uint32_t value = 0;
  // Each loop's units of the measured cost table counted in the host
  // split's write and read buckets, published with the loops' times
  // (calib_ciu.units_<split>_<row>, calib_ciu.<split>_ns) for
  // scripts/measure_host_costs.py.
  renderers::HostTime time;
  costs::reset_cost_meter();
  double start = host.now_seconds();
  {
    const renderers::TimedScope timed(host, time, renderers::HostSplit::array_write);
    for (unsigned a = 0; a < CIU_ADDRESSES; ++a)
      for (unsigned j = 0; j < rows; ++j)
        for (unsigned i = 0; i < groups; ++i) {
          value += VALUE_STEP;
          array.write32(i, j, a, value);
          costs::charge(host, costs::HostCost::ciu_calibration_write);
        }
  }
  // The last write has left the host's write buffer when a read can pass.
  const double write_ns = (host.now_seconds() - start) / accesses * 1e9;
  start = host.now_seconds();
  uint32_t checksum = 0;
  {
    const renderers::TimedScope timed(host, time, renderers::HostSplit::array_read);
    for (unsigned a = 0; a < CIU_ADDRESSES; ++a)
      for (unsigned j = 0; j < rows; ++j)
        for (unsigned i = 0; i < groups; ++i) {
          checksum += array.read32(i, j, a);
          costs::charge(host, costs::HostCost::ciu_calibration_read);
        }
  }
  const double read_ns = (host.now_seconds() - start) / accesses * 1e9;
  if (env.counters != nullptr) {
    env.counters->counter("calib_ciu.write_ns", "host time of the write loop").value =
        static_cast<uint64_t>(std::llround(renderers::host_ns(host, time.array_write)));
    env.counters->counter("calib_ciu.read_ns", "host time of the read loop").value =
        static_cast<uint64_t>(std::llround(renderers::host_ns(host, time.array_read)));
    for (const auto& [name, units] : costs::take_cost_units())
      if (name.compare(0, 12, "units_write_") == 0 || name.compare(0, 11, "units_read_") == 0)
        env.counters->counter("calib_ciu." + name, "units of a row of the measured cost table charged in the loop")
            .value = static_cast<uint64_t>(units);
  }
  report("one 32-bit CIU write from the ARM, address computation included", write_ns, 488, "ns");
  report("one 32-bit CIU read from the ARM, address computation included", read_ns, 830, "ns");
  // value is the sum of 1 .. accesses steps, the checksum their sum.
  uint32_t expected = 0;
  for (uint32_t k = 1; k <= accesses; ++k) expected += k * VALUE_STEP;
  if (checksum != expected) {
    std::fprintf(stderr, "calib_ciu: read back checksum %" PRIu32 ", expected %" PRIu32 "\n", checksum, expected);
    return 1;
  }
  return 0;
}

}  // namespace tessera
