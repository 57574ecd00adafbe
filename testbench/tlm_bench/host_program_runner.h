// Runs test bodies as the host model's program, one at a time, in benches
// whose host (alone or inside the SoC) must keep running between tests:
// the program waits for a body, runs it on the HostApi, synchronises the
// host's local time and waits for the next one. The simulation is driven
// from sc_main's side with run().
#pragma once

#include <functional>

#include <gtest/gtest.h>
#include <systemc>

#include "host/host_api.h"

namespace tessera::test {

class HostProgramRunner {
 public:
  using Body = std::function<void(HostApi&)>;

  // The program to hand to Host::set_program (or Soc::set_program).
  std::function<int(HostApi&)> program() {
    return [this](HostApi& api) {
      for (;;) {
        sc_core::wait(m_next);
        m_body(api);
        api.irq_pending(0);  // synchronises the host's local time
        m_done = true;
      }
      return 0;
    };
  }

  // Lets `settle` of simulated time pass (the previous body's traffic
  // ends), runs `body` on the host and simulates until it has finished, for
  // at most `limit`. Returns the simulated time the body started.
  sc_core::sc_time run(Body body, sc_core::sc_time settle = sc_core::sc_time(100, sc_core::SC_US),
                       sc_core::sc_time limit = sc_core::sc_time(1, sc_core::SC_SEC)) {
    m_body = std::move(body);
    m_done = false;
    sc_core::sc_start(settle);
    const sc_core::sc_time start = sc_core::sc_time_stamp();
    m_next.notify();
    const sc_core::sc_time slice(1, sc_core::SC_MS);
    while (!m_done && sc_core::sc_time_stamp() - start < limit) sc_core::sc_start(slice);
    EXPECT_TRUE(m_done) << "the test body did not finish within " << limit;
    return start;
  }

 private:
  Body m_body;
  sc_core::sc_event m_next;
  bool m_done = false;
};

}  // namespace tessera::test
