// Register offsets and field masks of a cluster node's network interface,
// from ni_regs.def; the send descriptor and receive header layouts; the
// error codes (ni_errors.def).
#pragma once

#include <cstdint>

#include "common/register_table.h"

namespace tessera::ni_regs {

#define TESSERA_REGISTER_TABLE "network/ni_regs.def"
#include "common/register_constants.inc"

// A send descriptor: four little-endian words.
inline constexpr uint32_t DESCRIPTOR_BYTES = 16;
inline constexpr uint32_t DESC_DESTINATION = 0x0, DESC_PAYLOAD = 0x4, DESC_LENGTH = 0x8, DESC_TAG = 0xC;
// The header the NI writes at the start of a receive slot, the payload after it.
inline constexpr uint32_t HEADER_BYTES = 16;
inline constexpr uint32_t HDR_SOURCE = 0x0, HDR_LENGTH = 0x4, HDR_TAG = 0x8, HDR_SEQUENCE = 0xC;
// Ring alignment.
inline constexpr uint32_t TX_BASE_ALIGN = 16;
inline constexpr uint32_t RX_BASE_ALIGN = 4;
inline constexpr uint32_t MIN_RX_COUNT = 2;

enum class Error : uint32_t {
#define TESSERA_NI_ERROR(name, code, stops, text) name = code,
#include "network/ni_errors.def"
#undef TESSERA_NI_ERROR
};

inline constexpr const char* error_text(Error error) {
  switch (error) {
#define TESSERA_NI_ERROR(name, code, stops, text) \
  case Error::name:                               \
    return text;
#include "network/ni_errors.def"
#undef TESSERA_NI_ERROR
  }
  return "unknown error";
}

// Whether the error clears CTRL.ENABLE.
inline constexpr bool error_stops(Error error) {
  switch (error) {
#define TESSERA_NI_ERROR(name, code, stops, text) \
  case Error::name:                               \
    return stops;
#include "network/ni_errors.def"
#undef TESSERA_NI_ERROR
  }
  return true;
}

}  // namespace tessera::ni_regs
