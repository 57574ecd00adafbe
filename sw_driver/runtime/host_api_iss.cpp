// HostApi as the ISS build has it (contract/host/host_api.h): what is not inline.
// ARM only.
#include "host/host_api.h"

#include "intc/intc_regs.h"
#include "runtime/runtime.h"
#include "soc/memory_map.h"

namespace tessera {

namespace {

volatile uint32_t& intc_register(uint32_t offset) {
  return *reinterpret_cast<volatile uint32_t*>(memory_map::intc.base + offset);
}

// CP15's wait for interrupt: the core stops until IRQ or FIQ is asserted,
// masked or not.
void wait_for_interrupt() {
  asm volatile("mcr p15, 0, %0, c7, c0, 4" : : "r"(0) : "memory");
}

}  // namespace

// Eight words per LDM and STM, as the host-compiled display driver's cost
// model counts them; the rest one at a time.
void HostApi::read_words(uint32_t address, uint32_t* words, unsigned count) {
  auto from = reinterpret_cast<const volatile uint32_t*>(address);
  unsigned i = 0;
#if !defined(__thumb__)
  for (uint32_t* to = words; i + 8 <= count; i += 8)
    asm volatile("ldmia %[from]!, {r3-r10}\n\tstmia %[to]!, {r3-r10}"
                 : [from] "+r"(from), [to] "+r"(to)
                 :
                 : "r3", "r4", "r5", "r6", "r7", "r8", "r9", "r10", "memory");
#endif
  for (; i < count; ++i) words[i] = *from++;
}

void HostApi::write_words(uint32_t address, const uint32_t* words, unsigned count) {
  auto to = reinterpret_cast<volatile uint32_t*>(address);
  unsigned i = 0;
#if !defined(__thumb__)
  for (const uint32_t* from = words; i + 8 <= count; i += 8)
    asm volatile("ldmia %[from]!, {r3-r10}\n\tstmia %[to]!, {r3-r10}"
                 : [from] "+r"(from), [to] "+r"(to)
                 :
                 : "r3", "r4", "r5", "r6", "r7", "r8", "r9", "r10", "memory");
#endif
  for (; i < count; ++i) *to++ = words[i];
}

// The line enabled at the interrupt controller for as long as the wait
// lasts, so that its rise wakes the core; IRQ stays masked in the CPSR, so
// no exception is taken.
void HostApi::wait_irq(unsigned line) {
  const uint32_t bit = 1u << line;
  volatile uint32_t& enable = intc_register(intc_regs::IRQ_ENABLE);
  enable = enable | bit;
  while ((intc_register(intc_regs::RAW) & bit) == 0) wait_for_interrupt();
  enable = enable & ~bit;
}

bool HostApi::irq_pending(unsigned line) {
  return (intc_register(intc_regs::RAW) & (1u << line)) != 0;
}

double HostApi::now_seconds() const {
  return static_cast<double>(runtime::cycles_since_start()) / clock_hz();
}

uint64_t HostApi::now_cycles() const {
  return runtime::cycles_since_start();
}

double HostApi::clock_hz() const {
  return runtime::clock_hz();
}

}  // namespace tessera
