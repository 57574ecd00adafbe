#include "transaction_writer.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace tessera {

using sc_core::sc_time;

namespace {

uint64_t parse_address(const std::string& text, const std::string& term) {
  size_t used = 0;
  uint64_t value = 0;
  try {
    value = std::stoull(text, &used, 0);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || text[0] == '-')
    throw std::invalid_argument("bad address '" + text + "' in '" + term + "': give a number, e.g. 0x1000");
  return value;
}

sc_time parse_time(const std::string& text, const std::string& term) {
  static const std::pair<const char*, sc_core::sc_time_unit> units[] = {{"ps", sc_core::SC_PS},
                                                                        {"ns", sc_core::SC_NS},
                                                                        {"us", sc_core::SC_US},
                                                                        {"ms", sc_core::SC_MS},
                                                                        {"s", sc_core::SC_SEC}};
  for (const auto& [suffix, unit] : units) {
    const std::string s(suffix);
    if (text.size() <= s.size() || text.compare(text.size() - s.size(), s.size(), s) != 0) continue;
    const std::string number = text.substr(0, text.size() - s.size());
    size_t used = 0;
    double value = -1;
    try {
      value = std::stod(number, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == number.size() && value >= 0 && std::isfinite(value)) return sc_time(value, unit);
    break;
  }
  throw std::invalid_argument("bad time '" + text + "' in '" + term + "': give a number and a unit, e.g. 1.5ms");
}

// "A-B" split at its dash.
std::pair<std::string, std::string> range_of(const std::string& value, const std::string& term) {
  const size_t dash = value.find('-');
  if (dash == std::string::npos || dash == 0 || dash + 1 == value.size())
    throw std::invalid_argument("bad range in '" + term + "': write FROM-TO");
  return {value.substr(0, dash), value.substr(dash + 1)};
}

}  // namespace

bool TransactionFilter::matches(const Transaction& t) const {
  if (initiator && *initiator != t.initiator) return false;
  if (target && *target != t.target) return false;
  if (write && *write != t.write) return false;
  if (address && (t.address < address->first || t.address >= address->second)) return false;
  if (time && (t.request < time->first || t.request >= time->second)) return false;
  return true;
}

TransactionTraceSpec parse_transaction_trace(const std::string& text) {
  TransactionTraceSpec spec;
  const size_t colon = text.find(':');
  spec.path = text.substr(0, colon);
  if (spec.path.empty()) throw std::invalid_argument("no file before the filter in '" + text + "'");
  if (colon == std::string::npos) return spec;
  const std::string filter = text.substr(colon + 1);
  size_t at = 0;
  while (at <= filter.size()) {
    const size_t comma = std::min(filter.find(',', at), filter.size());
    const std::string term = filter.substr(at, comma - at);
    at = comma + 1;
    const size_t equals = term.find('=');
    if (equals == std::string::npos || equals + 1 == term.size())
      throw std::invalid_argument("bad filter term '" + term +
                                  "': write key=value (initiator, target, command, "
                                  "addr or time)");
    const std::string key = term.substr(0, equals), value = term.substr(equals + 1);
    if (key == "initiator") {
      spec.filter.initiator = value;
    } else if (key == "target") {
      spec.filter.target = value;
    } else if (key == "command") {
      if (value != "read" && value != "write")
        throw std::invalid_argument("bad command '" + value + "' in '" + term + "': read or write");
      spec.filter.write = value == "write";
    } else if (key == "addr") {
      const auto [lo, hi] = range_of(value, term);
      spec.filter.address = {{parse_address(lo, term), parse_address(hi, term)}};
    } else if (key == "time") {
      const auto [from, to] = range_of(value, term);
      spec.filter.time = {{parse_time(from, term), parse_time(to, term)}};
    } else {
      throw std::invalid_argument("unknown filter key '" + key + "' in '" + term +
                                  "': initiator, target, command, addr or time");
    }
  }
  return spec;
}

TransactionWriter::TransactionWriter(const TransactionTraceSpec& spec)
    : m_filter(spec.filter),
      m_file(std::make_unique<OutputFile>(spec.path)),
      m_picoseconds_per_unit(sc_core::sc_get_time_resolution().to_seconds() * 1e12) {
  m_buffer = "initiator,target,command,address,bytes,start_ps,wait_ps,service_ps,end_ps\n";
}

void TransactionWriter::transaction(const Transaction& t) {
  if (!m_filter.matches(t)) return;
  const auto ps = [this](const sc_time& time) {
    return static_cast<uint64_t>(std::llround(static_cast<double>(time.value()) * m_picoseconds_per_unit));
  };
  const uint64_t request = ps(t.request), start = ps(t.start), end = ps(t.end);
  char row[256];
  std::snprintf(row, sizeof row,
                "%s,%s,%s,0x%08" PRIx64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64 "\n",
                t.initiator.c_str(), t.target.c_str(), t.write ? "write" : "read", t.address, t.bytes, request,
                start - request, end - start, end);
  m_buffer += row;
  ++m_rows;
  if (m_buffer.size() >= (1u << 20)) flush();
}

void TransactionWriter::flush() {
  write_streamed(m_file.get(), m_buffer, m_error);
  m_buffer.clear();
}

std::string TransactionWriter::finish() {
  flush();
  m_error = commit_streamed(m_file, m_error);
  return m_error;
}

}  // namespace tessera
