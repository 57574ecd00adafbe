// A payload extension made of plain values (TransferTrain,
// ScheduleUntouched): its clone and copy are its copy constructor and
// assignment, written here once.
#pragma once

#include <tlm>

namespace tessera {

template <class T>
struct ValueExtension : tlm::tlm_extension<T> {
  tlm::tlm_extension_base* clone() const override { return new T(static_cast<const T&>(*this)); }
  void copy_from(const tlm::tlm_extension_base& other) override {
    static_cast<T&>(*this) = static_cast<const T&>(other);
  }
};

}  // namespace tessera
