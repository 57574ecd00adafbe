// A blocking transport reached by one plain virtual call.
//
// tlm_fw_transport_if reaches b_transport through virtual bases: a call
// through it adjusts `this` by an offset read from the vtable, then enters a
// thunk that adjusts it back. On the paths every host access takes (the
// host's socket to the bus, the bus to the memory and the CIU) that is a
// chain of dependent loads per access. A forward interface that also
// derives from DirectTransport (publicly, as it derives from
// tlm_fw_transport_if, so that direct_transport_of finds it) is called here
// instead; its direct_b_transport must do exactly what its b_transport does
// (call it: b_transport is final there, so the call is direct, not a second
// dispatch).
//
// Whoever calls looks the interface up once, after binding (end of
// elaboration), and keeps the plain socket call for an interface without it
// (a protocol checker in between, a test's target).
//
// Beside the payload the direct call carries DirectExtras: the values of the
// two extensions this house's blocks read or set on every access
// (TransferTrain's count, ScheduleUntouched's flag) as plain fields, so that
// neither side calls tlm_generic_payload::get_extension, an out-of-line call
// into the SystemC library, per access. The payload still carries the
// extensions themselves, with the same values, for any target reached
// through a socket; a target sets the flag in DirectExtras when called
// directly and in the extension when called through its socket.
#pragma once

#include <systemc>
#include <tlm>

namespace tessera {

struct DirectExtras {
  unsigned transfers = 1;  // the single transfers the payload stands for (TransferTrain)
  bool untouched = false;  // set by a target whose access scheduled nothing (ScheduleUntouched)
};

class DirectTransport {
 public:
  virtual void direct_b_transport(tlm::tlm_generic_payload& gp, sc_core::sc_time& delay, DirectExtras& extras) = 0;

 protected:
  DirectTransport() = default;
  DirectTransport(const DirectTransport&) = default;
  DirectTransport& operator=(const DirectTransport&) = default;
  ~DirectTransport() = default;
};

// The DirectTransport of a bound forward interface, or null.
inline DirectTransport* direct_transport_of(tlm::tlm_fw_transport_if<>* fw) {
  return dynamic_cast<DirectTransport*>(fw);
}

}  // namespace tessera
