// See run_context.h.
#include "raster/core/run_context.h"

namespace tessera::raster {

void RunContext::fail(RasterError error, uint32_t address) {
  if (failed()) return;
  m_result.error = error;
  m_result.error_address = address;
}

bool RunContext::read(uint32_t address, void* data, unsigned bytes, RasterError error) {
  if (!m_port.read(address, data, bytes)) {
    fail(error, address);
    return false;
  }
  m_result.bytes_read += bytes;
  return true;
}

bool RunContext::write(uint32_t address, const void* data, unsigned bytes) {
  if (!m_port.write(address, data, bytes)) {
    fail(RasterError::bus_error, address);
    return false;
  }
  m_result.bytes_written += bytes;
  return true;
}

void RunContext::report_cycles() {
  if (m_pending_cycles != 0) m_port.cycles(m_pending_cycles);
  m_pending_cycles = 0;
}

}  // namespace tessera::raster
