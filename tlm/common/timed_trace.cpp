#include "common/timed_trace.h"

namespace tessera {

TimedTrace::TimedTrace(sc_core::sc_module_name name) : sc_core::sc_module(name), signal("signal") {
  SC_METHOD(apply);
  sensitive << m_wake;
  dont_initialize();
}

void TimedTrace::set_at(bool value, const sc_core::sc_time& when) {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  const sc_core::sc_time at = when < now ? now : when;
  m_pending.emplace(at, value);
  // An event keeps only its earliest pending notification, which is the one we need.
  m_wake.notify(at - now);
}

void TimedTrace::apply() {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  auto it = m_pending.begin();
  bool have_value = false;
  bool value = false;
  while (it != m_pending.end() && it->first <= now) {
    value = it->second;
    have_value = true;
    it = m_pending.erase(it);
  }
  if (have_value) signal.write(value);
  if (!m_pending.empty()) m_wake.notify(m_pending.begin()->first - now);
}

}  // namespace tessera
