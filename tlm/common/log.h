// Logging through sc_report: one message type per module ("tessera/<module>"),
// one line format "[time] module: message", and a verbosity setting.
#pragma once

#include <string>

#include <systemc>

namespace tessera::log {

enum class Level { quiet, error, warning, info, debug };

// Parses "quiet", "error", "warning", "info" or "debug"; throws
// std::invalid_argument naming the accepted values otherwise.
Level parse_level(const std::string& name);

// Installs the line formatter and filters messages below `level`.
void install(Level level);

// Message type of a module: "tessera/" + module.
inline std::string msg_type(const std::string& module) {
  return "tessera/" + module;
}

namespace detail {
extern Level g_level;  // set by install()
}  // namespace detail

// True when messages of `level` are printed; guards messages that are
// expensive to build. Inline: the bus asks on every access.
inline bool enabled(Level level) {
  return detail::g_level >= level;
}

void info(const std::string& module, const std::string& message);
void debug(const std::string& module, const std::string& message);
void warning(const std::string& module, const std::string& message);
// Reports an error without throwing (SC_ERROR's default action would throw).
void error(const std::string& module, const std::string& message);

// Count of warnings and errors reported since start, for the summary.
unsigned warning_count();
unsigned error_count();

// "address error", "command error", ... for a TLM response status.
std::string response_text(int tlm_response_status);

// "0x0000abcd"
std::string hex(uint64_t value, int digits = 8);

}  // namespace tessera::log
