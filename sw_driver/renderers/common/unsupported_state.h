// State a back end's algorithm does not have, reported once per frame: a
// warning naming the back end and the state through AppEnvironment::warn
// (soc_sim logs it), or on standard error where there is none.
#pragma once

#include <iostream>
#include <set>
#include <string>
#include <utility>

#include "costs/host_cost.h"
#include "device/app_environment.h"

namespace tessera::renderers {

class UnsupportedState {
 public:
  explicit UnsupportedState(std::string backend) : m_backend(std::move(backend)) {}

  // `what` names the state and what the back end does instead. The look-up
  // and the warning are the driver's work on the ISS too: rows of the
  // measured cost table.
  void report(AppEnvironment& env, const std::string& what) {
    if (env.host != nullptr) costs::charge(*env.host, costs::HostCost::unsupported_check);
    if (!m_reported.insert(what).second) return;
    if (env.host != nullptr) costs::charge(*env.host, costs::HostCost::unsupported_warning);
    const std::string message = m_backend + " does not support " + what + " (reported once per frame)";
    if (env.warn)
      env.warn(m_backend, message);
    else
      std::cerr << "warning: " << message << "\n";
  }
  // At the end of a frame: the next frame reports again.
  void new_frame() { m_reported.clear(); }

 private:
  std::string m_backend;
  std::set<std::string> m_reported;
};

}  // namespace tessera::renderers
