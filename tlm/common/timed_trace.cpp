#include "common/timed_trace.h"

namespace tessera {

namespace {
uint64_t g_edges = 0;
}  // namespace

uint64_t timed_signal_edges() {
  return g_edges;
}

template <class T>
TimedSignal<T>::TimedSignal(sc_core::sc_module_name name) : sc_core::sc_module(name), signal("signal") {
  SC_METHOD(apply);
  sensitive << m_wake;
  dont_initialize();
}

template <class T>
void TimedSignal<T>::set_at(T value, const sc_core::sc_time& when) {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  const sc_core::sc_time at = when < now ? now : when;
  m_pending.emplace(at, value);
  ++g_edges;
  // An event keeps only its earliest pending notification, which is the one we need.
  m_wake.notify(at - now);
}

template <class T>
void TimedSignal<T>::apply() {
  const sc_core::sc_time now = sc_core::sc_time_stamp();
  auto it = m_pending.begin();
  bool have_value = false;
  T value{};
  while (it != m_pending.end() && it->first <= now) {
    value = it->second;
    have_value = true;
    it = m_pending.erase(it);
  }
  if (have_value) signal.write(value);
  if (!m_pending.empty()) m_wake.notify(m_pending.begin()->first - now);
}

template class TimedSignal<bool>;
template class TimedSignal<uint32_t>;

}  // namespace tessera
