// State a back end's algorithm does not have, reported once per frame: a
// warning naming the back end and the state through AppEnvironment::warn
// (soc_sim logs it), or on standard error where there is none.
#pragma once

#include <iostream>
#include <set>
#include <string>
#include <utility>

#include "device/app_environment.h"

namespace tessera::renderers {

class UnsupportedState {
 public:
  explicit UnsupportedState(std::string backend) : m_backend(std::move(backend)) {}

  // `what` names the state and what the back end does instead.
  void report(AppEnvironment& env, const std::string& what) {
    if (!m_reported.insert(what).second) return;
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
