#include "gl/frame_phases.h"

#include "costs/host_cost.h"

namespace tessera::gl {

namespace {
constexpr const char* NAMES[] = {"host_application_ns", "host_geometry_ns", "host_rasterization_ns",
                                 "host_presenting_ns"};
static_assert(std::size(NAMES) == static_cast<size_t>(Phase::count_));
// The same phases on a timeline (HostApi::driver_phase).
constexpr const char* TIMELINE_NAMES[] = {"application", "geometry", "rasterization", "presenting"};
static_assert(std::size(TIMELINE_NAMES) == static_cast<size_t>(Phase::count_));
// The meter's first buckets are the phases, in this order (the array back
// ends' host split follows: costs::COST_BUCKET_NAMES).
static_assert(static_cast<size_t>(Phase::count_) == costs::PHASE_BUCKETS);
}  // namespace

PhaseClock& phase_clock() {
  static PhaseClock clock;
  return clock;
}

void PhaseClock::start(HostApi* host) {
  m_host = host;
  m_phase = Phase::application;
  m_seconds.fill(0);
  m_clear_seconds = 0;
  m_since = host != nullptr ? host->now_seconds() : 0;
  if (host != nullptr) host->driver_phase(TIMELINE_NAMES[static_cast<size_t>(Phase::application)]);
  costs::reset_cost_meter();
}

Phase PhaseClock::switch_to(Phase phase) {
  const Phase previous = m_phase;
  if (m_host != nullptr && phase != previous) {
    const double now = m_host->now_seconds();
    m_seconds[static_cast<size_t>(previous)] += now - m_since;
    m_since = now;
    m_host->driver_phase(TIMELINE_NAMES[static_cast<size_t>(phase)]);
  }
  m_phase = phase;
  costs::set_cost_bucket(static_cast<unsigned>(phase));
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
  figures.emplace_back("host_clear_ns", m_clear_seconds * 1e9);
  m_seconds.fill(0);
  m_clear_seconds = 0;
  for (auto& units : costs::take_cost_units()) figures.push_back(std::move(units));
  return figures;
}

void PhaseClock::begin_clear() {
  if (m_host != nullptr) m_clear_since = m_host->now_seconds();
}

void PhaseClock::end_clear() {
  if (m_host != nullptr) m_clear_seconds += m_host->now_seconds() - m_clear_since;
}

}  // namespace tessera::gl
