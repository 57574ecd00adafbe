// A direct path into every CU's CMEM for a block beside the array (the
// system/array DMA, tlm/dma), not through the host's CIU window: no WriteMem32
// layout, no CIU latency. The caller charges its own transfer rate. Like the
// CIU it must respect a running program: the CUs own CMEM until
// cmem_free_from() (ArrayProcessor: the end of the running program).
#pragma once

#include <cstdint>

#include <systemc>

#include "array/core/cu_array.h"

namespace tessera {

class CmemAccess {
 public:
  virtual ~CmemAccess() = default;
  virtual const ap::ArrayGeometry& cmem_geometry() const = 0;
  // The earliest time at or after `arrival` at which CMEM may be accessed.
  virtual sc_core::sc_time cmem_free_from(const sc_core::sc_time& arrival) const = 0;
  // One byte of lane `lane` (row x columns + column) at CMEM address `address`.
  virtual uint8_t read_cmem(unsigned lane, unsigned address) const = 0;
  virtual void write_cmem(unsigned lane, unsigned address, uint8_t value) = 0;
};

}  // namespace tessera
