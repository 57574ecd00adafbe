#include "common/log.h"

#include <cstdio>
#include <iostream>
#include <sstream>
#include <stdexcept>

#include <tlm>

namespace tessera::log {

Level detail::g_level = Level::warning;
using detail::g_level;

namespace {

unsigned g_warnings = 0;
unsigned g_errors = 0;

std::string format_time(const sc_core::sc_time& t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%14.3f us", t.to_seconds() * 1e6);
  return buffer;
}

void handler(const sc_core::sc_report& report, const sc_core::sc_actions& actions) {
  std::string type = report.get_msg_type();
  const std::string prefix = "tessera/";
  std::string module = type.rfind(prefix, 0) == 0 ? type.substr(prefix.size()) : type;
  // SystemC's own informational messages ("simulation stopped by user") are
  // not the model's.
  const bool foreign_info = report.get_severity() == sc_core::SC_INFO && module == type;
  if ((actions & sc_core::SC_DISPLAY) && !foreign_info) {
    const char* severity = "";
    switch (report.get_severity()) {
      case sc_core::SC_WARNING: severity = "warning: "; break;
      case sc_core::SC_ERROR: severity = "error: "; break;
      case sc_core::SC_FATAL: severity = "fatal: "; break;
      default: break;
    }
    std::ostringstream line;
    line << "[" << format_time(sc_core::sc_time_stamp()) << "] " << module << ": " << severity << report.get_msg()
         << "\n";
    std::cerr << line.str() << std::flush;
  }
  // Everything but display and logging is left to SystemC's default handler
  // (throwing, stopping, aborting).
  sc_core::sc_report_handler::default_handler(report, actions & ~(sc_core::SC_DISPLAY | sc_core::SC_LOG));
}

}  // namespace

Level parse_level(const std::string& name) {
  if (name == "quiet") return Level::quiet;
  if (name == "error") return Level::error;
  if (name == "warning") return Level::warning;
  if (name == "info") return Level::info;
  if (name == "debug") return Level::debug;
  throw std::invalid_argument("unknown log level '" + name + "' (expected quiet, error, warning, info or debug)");
}

void install(Level level) {
  g_level = level;
  sc_core::sc_report_handler::set_handler(handler);
  using sc_core::sc_report_handler;
  sc_report_handler::set_actions(sc_core::SC_INFO, level >= Level::info ? sc_core::SC_DISPLAY : sc_core::SC_DO_NOTHING);
  sc_report_handler::set_actions(sc_core::SC_WARNING,
                                 level >= Level::warning ? sc_core::SC_DISPLAY : sc_core::SC_DO_NOTHING);
  sc_report_handler::set_verbosity_level(level >= Level::debug ? sc_core::SC_DEBUG : sc_core::SC_MEDIUM);
  // SystemC's own deprecation chatter is not a guest error.
  sc_report_handler::set_actions("/IEEE_Std_1666/deprecated", sc_core::SC_DO_NOTHING);
}

void info(const std::string& module, const std::string& message) {
  if (g_level >= Level::info) SC_REPORT_INFO_VERB(msg_type(module).c_str(), message.c_str(), sc_core::SC_MEDIUM);
}

void debug(const std::string& module, const std::string& message) {
  if (g_level >= Level::debug) SC_REPORT_INFO_VERB(msg_type(module).c_str(), message.c_str(), sc_core::SC_DEBUG);
}

void warning(const std::string& module, const std::string& message) {
  ++g_warnings;
  SC_REPORT_WARNING(msg_type(module).c_str(), message.c_str());
}

void error(const std::string& module, const std::string& message) {
  ++g_errors;
  const std::string type = msg_type(module);
  // Display it like a warning-level line but flagged as an error, without the
  // throw that SC_REPORT_ERROR would cause inside a process.
  sc_core::sc_report_handler::set_actions(type.c_str(), sc_core::SC_ERROR,
                                          g_level >= Level::error ? sc_core::SC_DISPLAY : sc_core::SC_DO_NOTHING);
  SC_REPORT_ERROR(type.c_str(), message.c_str());
}

unsigned warning_count() {
  return g_warnings;
}
unsigned error_count() {
  return g_errors;
}

std::string response_text(int status) {
  switch (static_cast<tlm::tlm_response_status>(status)) {
    case tlm::TLM_OK_RESPONSE: return "ok";
    case tlm::TLM_INCOMPLETE_RESPONSE: return "incomplete (no target answered)";
    case tlm::TLM_GENERIC_ERROR_RESPONSE: return "generic error";
    case tlm::TLM_ADDRESS_ERROR_RESPONSE: return "address error";
    case tlm::TLM_COMMAND_ERROR_RESPONSE: return "command error";
    case tlm::TLM_BURST_ERROR_RESPONSE: return "burst error";
    case tlm::TLM_BYTE_ENABLE_ERROR_RESPONSE: return "byte-enable error";
  }
  return "unknown response " + std::to_string(status);
}

std::string hex(uint64_t value, int digits) {
  char buffer[24];
  std::snprintf(buffer, sizeof buffer, "0x%0*llx", digits, static_cast<unsigned long long>(value));
  return buffer;
}

}  // namespace tessera::log
