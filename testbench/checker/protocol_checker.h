// TLM-2.0 base-protocol checker for loosely-timed sockets.
//
// A pass-through module inserted between an initiator socket and a target
// socket. It forwards b_transport, transport_dbg, get_direct_mem_ptr and
// invalidate_direct_mem_ptr unchanged and checks the IEEE 1666-2011 rules
// that apply to them; README.md lists every rule. Our models are loosely
// timed, so nb_transport is not forwarded: a call is reported as unsupported
// and completed with an error response instead of being lost.
//
// A violation is recorded (violations()) and reported with message type
// "tessera/checker", as a warning by default so that tests can provoke
// violations on purpose; construct with sc_core::SC_ERROR (or call
// set_severity) to make each one an error.
#ifndef TESSERA_TLM_CHECKER_PROTOCOL_CHECKER_H
#define TESSERA_TLM_CHECKER_PROTOCOL_CHECKER_H

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <unordered_map>
#include <vector>

#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/simple_target_socket.h>
#include <systemc>
#include <tlm>

namespace tessera {

enum class ProtocolRule {
  // b_transport, on entry
  response_incomplete_on_entry,
  command_valid,
  data_ptr_non_null,
  data_length_non_zero,
  streaming_width_non_zero,
  byte_enable_length_non_zero,
  byte_enable_length_within_data,
  dmi_hint_false_on_entry,
  delay_not_negative,
  payload_not_in_use,
  // b_transport, on return
  response_complete_on_return,
  command_unchanged,
  data_ptr_unchanged,
  data_length_unchanged,
  byte_enable_ptr_unchanged,
  byte_enable_length_unchanged,
  streaming_width_unchanged,
  time_not_backwards,
  // transport_dbg
  dbg_command_valid,
  dbg_data_ptr_non_null,
  dbg_count_within_length,
  dbg_takes_no_time,
  // get_direct_mem_ptr
  dmi_range_ordered,
  dmi_address_in_range,
  dmi_access_granted,
  dmi_ptr_non_null,
  // invalidate_direct_mem_ptr
  invalidate_range_ordered,
  // nb_transport_fw, nb_transport_bw
  nb_transport_unsupported,
};

inline const char* to_string(ProtocolRule rule) {
  switch (rule) {
    case ProtocolRule::response_incomplete_on_entry: return "response_incomplete_on_entry";
    case ProtocolRule::command_valid: return "command_valid";
    case ProtocolRule::data_ptr_non_null: return "data_ptr_non_null";
    case ProtocolRule::data_length_non_zero: return "data_length_non_zero";
    case ProtocolRule::streaming_width_non_zero: return "streaming_width_non_zero";
    case ProtocolRule::byte_enable_length_non_zero: return "byte_enable_length_non_zero";
    case ProtocolRule::byte_enable_length_within_data: return "byte_enable_length_within_data";
    case ProtocolRule::dmi_hint_false_on_entry: return "dmi_hint_false_on_entry";
    case ProtocolRule::delay_not_negative: return "delay_not_negative";
    case ProtocolRule::payload_not_in_use: return "payload_not_in_use";
    case ProtocolRule::response_complete_on_return: return "response_complete_on_return";
    case ProtocolRule::command_unchanged: return "command_unchanged";
    case ProtocolRule::data_ptr_unchanged: return "data_ptr_unchanged";
    case ProtocolRule::data_length_unchanged: return "data_length_unchanged";
    case ProtocolRule::byte_enable_ptr_unchanged: return "byte_enable_ptr_unchanged";
    case ProtocolRule::byte_enable_length_unchanged: return "byte_enable_length_unchanged";
    case ProtocolRule::streaming_width_unchanged: return "streaming_width_unchanged";
    case ProtocolRule::time_not_backwards: return "time_not_backwards";
    case ProtocolRule::dbg_command_valid: return "dbg_command_valid";
    case ProtocolRule::dbg_data_ptr_non_null: return "dbg_data_ptr_non_null";
    case ProtocolRule::dbg_count_within_length: return "dbg_count_within_length";
    case ProtocolRule::dbg_takes_no_time: return "dbg_takes_no_time";
    case ProtocolRule::dmi_range_ordered: return "dmi_range_ordered";
    case ProtocolRule::dmi_address_in_range: return "dmi_address_in_range";
    case ProtocolRule::dmi_access_granted: return "dmi_access_granted";
    case ProtocolRule::dmi_ptr_non_null: return "dmi_ptr_non_null";
    case ProtocolRule::invalidate_range_ordered: return "invalidate_range_ordered";
    case ProtocolRule::nb_transport_unsupported: return "nb_transport_unsupported";
  }
  return "unknown_rule";
}

struct ProtocolViolation {
  ProtocolRule rule;
  std::string message;
};

template <unsigned int BUSWIDTH = 32>
class ProtocolChecker : public sc_core::sc_module {
 public:
  static constexpr const char* MSG_TYPE = "tessera/checker";

  tlm_utils::simple_target_socket<ProtocolChecker, BUSWIDTH> in;
  tlm_utils::simple_initiator_socket<ProtocolChecker, BUSWIDTH> out;

  explicit ProtocolChecker(const sc_core::sc_module_name& name, sc_core::sc_severity severity = sc_core::SC_WARNING)
      : sc_core::sc_module(name), in("in"), out("out"), m_severity(severity) {
    in.register_b_transport(this, &ProtocolChecker::b_transport);
    in.register_transport_dbg(this, &ProtocolChecker::transport_dbg);
    in.register_get_direct_mem_ptr(this, &ProtocolChecker::get_direct_mem_ptr);
    in.register_nb_transport_fw(this, &ProtocolChecker::nb_transport_fw);
    out.register_invalidate_direct_mem_ptr(this, &ProtocolChecker::invalidate_direct_mem_ptr);
    out.register_nb_transport_bw(this, &ProtocolChecker::nb_transport_bw);
  }

  const char* kind() const override { return "tessera::protocol_checker"; }

  void set_severity(sc_core::sc_severity severity) { m_severity = severity; }
  sc_core::sc_severity severity() const { return m_severity; }

  const std::vector<ProtocolViolation>& violations() const { return m_violations; }
  std::size_t violation_count() const { return m_violations.size(); }
  std::size_t violation_count(ProtocolRule rule) const {
    std::size_t count = 0;
    for (const auto& violation : m_violations) count += violation.rule == rule ? 1 : 0;
    return count;
  }
  std::vector<std::string> messages() const {
    std::vector<std::string> result;
    result.reserve(m_violations.size());
    for (const auto& violation : m_violations) result.push_back(violation.message);
    return result;
  }
  void clear_violations() { m_violations.clear(); }

 private:
  // What the initiator handed over, kept to compare against on return.
  struct RequestSnapshot {
    sc_dt::uint64 address;
    tlm::tlm_command command;
    unsigned char* data_ptr;
    unsigned int data_length;
    unsigned char* byte_enable_ptr;
    unsigned int byte_enable_length;
    unsigned int streaming_width;
    sc_core::sc_time start_time;
    sc_core::sc_time delay;
  };

  // Counts the b_transport calls a payload is inside, so a nested call is
  // seen; a destructor because a report may throw out of b_transport.
  class InUseGuard {
   public:
    InUseGuard(std::unordered_map<const tlm::tlm_generic_payload*, unsigned>& in_use,
               const tlm::tlm_generic_payload* trans)
        : m_in_use(in_use), m_trans(trans) {
      ++m_in_use[m_trans];
    }
    ~InUseGuard() {
      if (--m_in_use[m_trans] == 0) m_in_use.erase(m_trans);
    }
    InUseGuard(const InUseGuard&) = delete;
    InUseGuard& operator=(const InUseGuard&) = delete;

   private:
    std::unordered_map<const tlm::tlm_generic_payload*, unsigned>& m_in_use;
    const tlm::tlm_generic_payload* m_trans;
  };

  void b_transport(tlm::tlm_generic_payload& trans, sc_core::sc_time& delay) {
    const RequestSnapshot request{
        trans.get_address(),         trans.get_command(),         trans.get_data_ptr(),
        trans.get_data_length(),     trans.get_byte_enable_ptr(), trans.get_byte_enable_length(),
        trans.get_streaming_width(), sc_core::sc_time_stamp(),    delay};
    check_request(trans, request);
    InUseGuard guard(m_in_use, &trans);
    out->b_transport(trans, delay);
    check_response(trans, delay, request);
  }

  void check_request(const tlm::tlm_generic_payload& trans, const RequestSnapshot& request) {
    const std::string where = describe(request);
    if (trans.get_response_status() != tlm::TLM_INCOMPLETE_RESPONSE)
      report(ProtocolRule::response_incomplete_on_entry,
             "response status is " + trans.get_response_string() + " on entry (" + where + ")");
    const bool moves_data = request.command == tlm::TLM_READ_COMMAND || request.command == tlm::TLM_WRITE_COMMAND;
    if (!moves_data && request.command != tlm::TLM_IGNORE_COMMAND)
      report(ProtocolRule::command_valid, "command is not READ, WRITE or IGNORE (" + where + ")");
    if (moves_data && request.data_ptr == nullptr)
      report(ProtocolRule::data_ptr_non_null, "data pointer is null (" + where + ")");
    if (moves_data && request.data_length == 0)
      report(ProtocolRule::data_length_non_zero, "data length is 0 (" + where + ")");
    if (request.streaming_width == 0)
      report(ProtocolRule::streaming_width_non_zero, "streaming width is 0 (" + where + ")");
    if (request.byte_enable_ptr != nullptr && request.byte_enable_length == 0)
      report(ProtocolRule::byte_enable_length_non_zero,
             "byte enable pointer is set but byte enable length is 0 (" + where + ")");
    if (moves_data && request.byte_enable_ptr != nullptr && request.byte_enable_length > request.data_length)
      report(ProtocolRule::byte_enable_length_within_data, "byte enable length " +
                                                               std::to_string(request.byte_enable_length) +
                                                               " exceeds the data length (" + where + ")");
    if (trans.is_dmi_allowed())
      report(ProtocolRule::dmi_hint_false_on_entry, "DMI allowed hint is true on entry (" + where + ")");
    if (is_wrapped_negative(request.delay))
      report(ProtocolRule::delay_not_negative,
             "delay on entry is a negative value wrapped to " + request.delay.to_string() + " (" + where + ")");
    if (m_in_use.count(&trans) != 0)
      report(ProtocolRule::payload_not_in_use,
             "payload is already inside a b_transport call through this checker (" + where + ")");
  }

  void check_response(const tlm::tlm_generic_payload& trans, const sc_core::sc_time& delay,
                      const RequestSnapshot& request) {
    const std::string where = describe(request);
    if (trans.get_response_status() == tlm::TLM_INCOMPLETE_RESPONSE)
      report(ProtocolRule::response_complete_on_return,
             "response status is still TLM_INCOMPLETE_RESPONSE on return (" + where + ")");
    // The address is left out on purpose: IEEE 1666-2011 lets an
    // interconnect rewrite it and does not ask for it to be restored, and
    // the checker cannot tell an interconnect from a target downstream.
    if (trans.get_command() != request.command)
      report(ProtocolRule::command_unchanged,
             "command changed to " + command_name(trans.get_command()) + " (" + where + ")");
    if (trans.get_data_ptr() != request.data_ptr)
      report(ProtocolRule::data_ptr_unchanged, "data pointer changed (" + where + ")");
    if (trans.get_data_length() != request.data_length)
      report(ProtocolRule::data_length_unchanged,
             "data length changed to " + std::to_string(trans.get_data_length()) + " (" + where + ")");
    if (trans.get_byte_enable_ptr() != request.byte_enable_ptr)
      report(ProtocolRule::byte_enable_ptr_unchanged, "byte enable pointer changed (" + where + ")");
    if (trans.get_byte_enable_length() != request.byte_enable_length)
      report(ProtocolRule::byte_enable_length_unchanged,
             "byte enable length changed from " + std::to_string(request.byte_enable_length) + " to " +
                 std::to_string(trans.get_byte_enable_length()) + " (" + where + ")");
    if (trans.get_streaming_width() != request.streaming_width)
      report(ProtocolRule::streaming_width_unchanged,
             "streaming width changed from " + std::to_string(request.streaming_width) + " to " +
                 std::to_string(trans.get_streaming_width()) + " (" + where + ")");

    const bool delay_wrapped = is_wrapped_negative(delay);
    if (delay_wrapped)
      report(ProtocolRule::delay_not_negative,
             "delay on return is a negative value wrapped to " + delay.to_string() + " (" + where + ")");
    // A wrapped delay has already been reported, and comparing it would
    // only report the same mistake a second time.
    if (!delay_wrapped && !is_wrapped_negative(request.delay) && went_backwards(request, delay))
      report(ProtocolRule::time_not_backwards, "local time went from " +
                                                   (request.start_time + request.delay).to_string() + " to " +
                                                   (sc_core::sc_time_stamp() + delay).to_string() + " (" + where + ")");
  }

  // start + delay on return must not be earlier than start + delay on entry.
  // sc_time is unsigned, so the sums are compared without forming them.
  static bool went_backwards(const RequestSnapshot& request, const sc_core::sc_time& delay) {
    const sc_dt::uint64 elapsed = sc_core::sc_time_stamp().value() - request.start_time.value();
    const sc_dt::uint64 delay_before = request.delay.value();
    return delay_before > elapsed && delay.value() < delay_before - elapsed;
  }

  // sc_time cannot hold a negative value: subtracting a larger time wraps
  // around to an enormous one. No model delays by half the range of
  // sc_time (over 100 days at a picosecond resolution), so a delay with
  // the top bit set is taken for a negative one.
  static bool is_wrapped_negative(const sc_core::sc_time& delay) {
    constexpr sc_dt::uint64 TOP_BIT = sc_dt::uint64{1} << 63;
    return (delay.value() & TOP_BIT) != 0;
  }

  unsigned int transport_dbg(tlm::tlm_generic_payload& trans) {
    const sc_dt::uint64 address = trans.get_address();
    const tlm::tlm_command command = trans.get_command();
    const unsigned int length = trans.get_data_length();
    const std::string where = describe(address, command, length);
    if (command != tlm::TLM_READ_COMMAND && command != tlm::TLM_WRITE_COMMAND && command != tlm::TLM_IGNORE_COMMAND)
      report(ProtocolRule::dbg_command_valid, "command is not READ, WRITE or IGNORE (" + where + ")");
    if (length > 0 && trans.get_data_ptr() == nullptr)
      report(ProtocolRule::dbg_data_ptr_non_null, "data pointer is null (" + where + ")");

    const sc_core::sc_time time_before = sc_core::sc_time_stamp();
    const sc_dt::uint64 delta_before = sc_core::sc_delta_count();
    const unsigned int count = out->transport_dbg(trans);
    const sc_core::sc_time time_after = sc_core::sc_time_stamp();
    const sc_dt::uint64 delta_after = sc_core::sc_delta_count();

    if (count > length)
      report(ProtocolRule::dbg_count_within_length,
             "returned count " + std::to_string(count) + " exceeds the data length (" + where + ")");
    if (time_after != time_before || delta_after != delta_before)
      report(ProtocolRule::dbg_takes_no_time, "simulation advanced from " + time_before.to_string() + " delta " +
                                                  std::to_string(delta_before) + " to " + time_after.to_string() +
                                                  " delta " + std::to_string(delta_after) + " (" + where + ")");
    return count;
  }

  bool get_direct_mem_ptr(tlm::tlm_generic_payload& trans, tlm::tlm_dmi& dmi) {
    // The address the caller asked for; downstream may rewrite the
    // payload's, but the returned range is in the caller's address space.
    const sc_dt::uint64 address = trans.get_address();
    const std::string where = describe(address, trans.get_command(), trans.get_data_length());
    const bool granted = out->get_direct_mem_ptr(trans, dmi);
    const sc_dt::uint64 start = dmi.get_start_address();
    const sc_dt::uint64 end = dmi.get_end_address();

    if (start > end)
      report(ProtocolRule::dmi_range_ordered,
             "DMI range [" + hex(start) + ", " + hex(end) + "] has start after end (" + where + ")");
    if (!granted) return false;
    if (start <= end && (address < start || address > end))
      report(ProtocolRule::dmi_address_in_range,
             "requested address lies outside the granted range [" + hex(start) + ", " + hex(end) + "] (" + where + ")");
    const tlm::tlm_dmi::dmi_access_e access = dmi.get_granted_access();
    if (access != tlm::tlm_dmi::DMI_ACCESS_READ && access != tlm::tlm_dmi::DMI_ACCESS_WRITE &&
        access != tlm::tlm_dmi::DMI_ACCESS_READ_WRITE)
      report(ProtocolRule::dmi_access_granted, "DMI granted with access " + std::to_string(static_cast<int>(access)) +
                                                   ", not read, write or read-write (" + where + ")");
    if (dmi.get_dmi_ptr() == nullptr)
      report(ProtocolRule::dmi_ptr_non_null, "DMI granted with a null pointer (" + where + ")");
    return true;
  }

  void invalidate_direct_mem_ptr(sc_dt::uint64 start, sc_dt::uint64 end) {
    if (start > end)
      report(ProtocolRule::invalidate_range_ordered,
             "invalidated range [" + hex(start) + ", " + hex(end) + "] has start after end");
    in->invalidate_direct_mem_ptr(start, end);
  }

  tlm::tlm_sync_enum nb_transport_fw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                     sc_core::sc_time& /*delay*/) {
    report(ProtocolRule::nb_transport_unsupported,
           "nb_transport_fw called in phase " + phase_name(phase) +
               "; this checker forwards the loosely-timed interfaces only; completed with an error (" +
               describe(trans.get_address(), trans.get_command(), trans.get_data_length()) + ")");
    trans.set_response_status(tlm::TLM_GENERIC_ERROR_RESPONSE);
    return tlm::TLM_COMPLETED;
  }

  tlm::tlm_sync_enum nb_transport_bw(tlm::tlm_generic_payload& trans, tlm::tlm_phase& phase,
                                     sc_core::sc_time& /*delay*/) {
    report(ProtocolRule::nb_transport_unsupported,
           "nb_transport_bw called in phase " + phase_name(phase) +
               "; this checker forwards the loosely-timed interfaces only (" +
               describe(trans.get_address(), trans.get_command(), trans.get_data_length()) + ")");
    return tlm::TLM_COMPLETED;
  }

  void report(ProtocolRule rule, const std::string& details) {
    std::string message = std::string(name()) + ": " + to_string(rule) + ": " + details;
    // Recorded before reporting: with SC_ERROR the report throws.
    m_violations.push_back({rule, message});
    sc_core::sc_report_handler::report(m_severity, MSG_TYPE, message.c_str(), __FILE__, __LINE__);
  }

  static std::string describe(const RequestSnapshot& request) {
    return describe(request.address, request.command, request.data_length);
  }
  static std::string describe(sc_dt::uint64 address, tlm::tlm_command command, unsigned int length) {
    return "address " + hex(address) + ", command " + command_name(command) + ", length " + std::to_string(length);
  }
  static std::string command_name(tlm::tlm_command command) {
    switch (command) {
      case tlm::TLM_READ_COMMAND: return "READ";
      case tlm::TLM_WRITE_COMMAND: return "WRITE";
      case tlm::TLM_IGNORE_COMMAND: return "IGNORE";
    }
    return std::to_string(static_cast<int>(command));
  }
  static std::string phase_name(const tlm::tlm_phase& phase) {
    std::ostringstream text;
    text << phase;
    return text.str();
  }
  static std::string hex(sc_dt::uint64 value) {
    std::ostringstream text;
    text << "0x" << std::hex << value;
    return text.str();
  }

  sc_core::sc_severity m_severity;
  std::vector<ProtocolViolation> m_violations;
  std::unordered_map<const tlm::tlm_generic_payload*, unsigned> m_in_use;
};

}  // namespace tessera

#endif  // TESSERA_TLM_CHECKER_PROTOCOL_CHECKER_H
