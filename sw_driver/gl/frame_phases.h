// Where a frame's host time goes, by phase of the driver: the application's
// own code (outside the GL calls below), geometry (the front end's part of
// the draw calls: fetching, transforming, lighting, clipping and setting up
// vertices), rasterization (the back end's part: every call into the
// Renderer but present) and presenting (eglSwapBuffers: flushing and the
// back end's present). The driver switches phases with PhaseScope; time is
// the host's (HostApi::now_seconds), so waiting for hardware counts in the
// phase that waits. eglSwapBuffers hands each frame's split to
// AppEnvironment::frame_statistics as host_<phase>_ns, together with the
// back end's own figures for the frame, so that the two host models
// (native and ISS) can be compared phase by phase
// (docs/calibration.md, "The two host models"). glClear's own time is also
// reported on its own, as host_clear_ns, while it stays in its phase: the
// study's figure for the sequential renderer is its rasterization without the
// clear (docs/spec/study_programs.md, "The study's test cases").
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "host/host_api.h"

namespace tessera::gl {

enum class Phase : uint8_t { application, geometry, rasterization, presenting, count_ };

class PhaseClock {
 public:
  // Starts timing on `host` (null: the clock does nothing) in the
  // application phase.
  void start(HostApi* host);
  // Makes `phase` the current one; returns the previous.
  Phase switch_to(Phase phase);
  // The host time per phase since the last call, in ns, named host_<phase>_ns,
  // then the clears' time, host_clear_ns.
  std::vector<std::pair<std::string, double>> take_frame();
  // Times a clear from begin_clear to end_clear (ClearScope), on top of its phase.
  void begin_clear();
  void end_clear();
  // An entry point begins or ends (CallScope): handed to the host.
  void call(const char* name, bool begins) {
    if (m_host != nullptr) m_host->driver_call(name, begins);
  }

 private:
  HostApi* m_host = nullptr;
  Phase m_phase = Phase::application;
  double m_since = 0;
  std::array<double, static_cast<size_t>(Phase::count_)> m_seconds{};
  double m_clear_since = 0;
  double m_clear_seconds = 0;
};

PhaseClock& phase_clock();

// The phase for the life of the scope (nesting: back to the previous one).
class PhaseScope {
 public:
  explicit PhaseScope(Phase phase) : m_previous(phase_clock().switch_to(phase)) {}
  ~PhaseScope() { phase_clock().switch_to(m_previous); }
  PhaseScope(const PhaseScope&) = delete;
  PhaseScope& operator=(const PhaseScope&) = delete;

 private:
  Phase m_previous;
};

// A clear for the life of the scope (PhaseClock::begin_clear).
class ClearScope {
 public:
  ClearScope() { phase_clock().begin_clear(); }
  ~ClearScope() { phase_clock().end_clear(); }
  ClearScope(const ClearScope&) = delete;
  ClearScope& operator=(const ClearScope&) = delete;
};

// A GL or EGL entry point for the life of the scope (WITH_CONTEXT opens
// one), handed to the host for a timeline (HostApi::driver_call). Nothing
// on the ISS: the program's code stays the board's.
class CallScope {
 public:
#if defined(TESSERA_HOST_ISS)
  explicit CallScope(const char* /*name*/) {}
#else
  explicit CallScope(const char* name) : m_name(name) {
    phase_clock().call(name, true);
  }
  ~CallScope() {
    phase_clock().call(m_name, false);
  }
#endif
  CallScope(const CallScope&) = delete;
  CallScope& operator=(const CallScope&) = delete;

#if !defined(TESSERA_HOST_ISS)
 private:
  const char* m_name;
#endif
};

}  // namespace tessera::gl
