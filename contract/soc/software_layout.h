// Where the software on the host keeps its data in system memory: the boot
// loader's layout, beside the memory map (memory_map.def) that says where
// system memory is. From the bottom: the application's own data, from
// HEAP_BASE the driver's heap (textures, depth buffers, command lists), and
// the two frame buffers at the top, each on a page boundary.
#pragma once

#include <algorithm>
#include <cstdint>

#include "soc/memory_map.h"

namespace tessera::software_layout {

inline constexpr uint32_t HEAP_BASE = 4u << 20;
// A program on the ISS (host.model=iss) lives below HEAP_BASE: its code and
// data from address 0, its C heap after them, and its stacks at the top,
// this many bytes for all of them (sw_driver/runtime/README.md).
inline constexpr uint32_t APPLICATION_STACK_BYTES = 256u << 10;
inline constexpr uint32_t FRAME_BUFFER_ALIGNMENT = 4096;

struct Layout {
  uint32_t frame_buffers[2];
  uint32_t heap_base;
  uint32_t heap_end;  // the first frame buffer
};

// The layout of `memory_bytes` of system memory with frame buffers of
// `frame_bytes` each. A memory too small for HEAP_BASE below the frame
// buffers gets an empty heap starting at the frame buffers.
constexpr Layout layout(uint64_t memory_bytes, uint64_t frame_bytes) {
  const uint64_t frame = (frame_bytes + FRAME_BUFFER_ALIGNMENT - 1) / FRAME_BUFFER_ALIGNMENT * FRAME_BUFFER_ALIGNMENT;
  const auto top = static_cast<uint64_t>(memory_map::sysmem.base) + memory_bytes;
  Layout l{};
  l.frame_buffers[0] = static_cast<uint32_t>(top - 2 * frame);
  l.frame_buffers[1] = static_cast<uint32_t>(top - frame);
  l.heap_end = l.frame_buffers[0];
  l.heap_base = std::min<uint32_t>(memory_map::sysmem.base + HEAP_BASE, l.heap_end);
  return l;
}

}  // namespace tessera::software_layout
