#include "gl/frame_phases.h"

namespace tessera::gl {

namespace {
constexpr const char* NAMES[] = {"host_application_ns", "host_geometry_ns", "host_rasterization_ns",
                                 "host_presenting_ns"};
static_assert(std::size(NAMES) == static_cast<size_t>(Phase::count_));
}  // namespace

PhaseClock& phase_clock() {
  static PhaseClock clock;
  return clock;
}

void PhaseClock::start(HostApi* host) {
  m_host = host;
  m_phase = Phase::application;
  m_seconds.fill(0);
  m_since = host != nullptr ? host->now_seconds() : 0;
}

Phase PhaseClock::switch_to(Phase phase) {
  const Phase previous = m_phase;
  if (m_host != nullptr && phase != previous) {
    const double now = m_host->now_seconds();
    m_seconds[static_cast<size_t>(previous)] += now - m_since;
    m_since = now;
  }
  m_phase = phase;
  return previous;
}

std::vector<std::pair<std::string, double>> PhaseClock::take_frame() {
  if (m_host != nullptr) {
    const double now = m_host->now_seconds();
    m_seconds[static_cast<size_t>(m_phase)] += now - m_since;
    m_since = now;
  }
  std::vector<std::pair<std::string, double>> figures;
  for (size_t i = 0; i < m_seconds.size(); ++i) figures.emplace_back(NAMES[i], m_seconds[i] * 1e9);
  m_seconds.fill(0);
  return figures;
}

}  // namespace tessera::gl
