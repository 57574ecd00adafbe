#include "dma/core/dma_engine.h"

#include <algorithm>
#include <cstring>

namespace tessera::dma {

unsigned Reshuffle::row_elements(uint64_t r) const {
  const uint64_t first = r * lanes;
  return static_cast<unsigned>(std::min<uint64_t>(lanes, elements - first));
}

Reshuffle reshuffle_of(const Descriptor& d, unsigned lanes) {
  Reshuffle r;
  r.element = d.element_bytes();
  r.lanes = lanes;
  r.elements = d.length / r.element;
  const bool to_cmem = d.kind() == Kind::mem_to_cmem;
  const uint32_t mem = to_cmem ? d.src : d.dst;
  const uint32_t mem_stride = to_cmem ? d.src_stride : d.dst_stride;
  const uint32_t cmem = to_cmem ? d.dst : d.src;
  const uint32_t cmem_stride = to_cmem ? d.dst_stride : d.src_stride;
  r.memory = mem;
  r.memory_stride = mem_stride == 0 ? lanes * r.element : mem_stride;
  r.cmem = cmem;
  r.cmem_stride = cmem_stride == 0 ? r.element : cmem_stride;
  return r;
}

namespace {

// [first, end) within memory? The offending address otherwise: the first
// byte below memory or the last byte beyond it.
bool in_memory(uint64_t first, uint64_t end, const Limits& limits, uint64_t& offending) {
  const uint64_t limit = limits.memory_base + limits.memory_bytes;
  if (first < limits.memory_base) {
    offending = first;
    return false;
  }
  if (end > limit) {
    offending = end - 1;
    return false;
  }
  return true;
}

// [first, end) wholly within the readable device window (Limits)?
bool in_readable_window(uint64_t first, uint64_t end, const Limits& limits) {
  return limits.readable_bytes != 0 && first >= limits.readable_base &&
         end <= limits.readable_base + limits.readable_bytes;
}

Fault check_reshuffle(const Descriptor& d, const Limits& limits) {
  const unsigned e = d.element_bytes();
  const bool to_cmem = d.kind() == Kind::mem_to_cmem;
  const Reshuffle r = reshuffle_of(d, limits.lanes);
  if (d.length % e != 0) return {Error::misaligned_length, d.length};
  if (r.memory % e != 0 || r.memory_stride % e != 0) return {Error::misaligned_length, r.memory};
  const uint64_t rows = r.rows();
  const unsigned last = r.row_elements(rows - 1);
  // The memory side's highest byte: the end of a full row before the last, or of the last.
  uint64_t end = r.memory + (rows - 1) * uint64_t{r.memory_stride} + uint64_t{last} * e;
  if (rows > 1) end = std::max(end, r.memory + (rows - 2) * uint64_t{r.memory_stride} + uint64_t{r.lanes} * e);
  uint64_t offending = 0;
  if (!in_memory(r.memory, end, limits, offending))
    return {to_cmem ? Error::src_outside_memory : Error::dst_outside_memory, offending};
  const uint64_t cmem_last = r.cmem + (rows - 1) * uint64_t{r.cmem_stride} + e - 1;
  if (cmem_last >= limits.cmem_bytes) return {to_cmem ? Error::dst_outside_cmem : Error::src_outside_cmem, cmem_last};
  return {};
}

}  // namespace

Fault validate(const Descriptor& d, const Limits& limits) {
  if (d.kind_code() > static_cast<uint32_t>(Kind::broadcast) || (d.ctrl & CTRL_RESERVED_MASK) != 0)
    return {Error::bad_descriptor, d.ctrl};
  if (d.kind() != Kind::broadcast && d.mask != 0) return {Error::bad_descriptor, d.ctrl};
  if (d.kind() == Kind::broadcast && d.src_stride != 0) return {Error::bad_descriptor, d.ctrl};
  if (d.length == 0) return {Error::zero_length, 0};
  uint64_t offending = 0;
  switch (d.kind()) {
    case Kind::mem_to_cmem:
    case Kind::cmem_to_mem: {
      const unsigned field = (d.ctrl & CTRL_ELEMENT_MASK) >> CTRL_ELEMENT_SHIFT;
      if (field > 2) return {Error::bad_descriptor, d.ctrl};
      if (limits.lanes == 0 || limits.cmem_bytes == 0)
        return {Error::no_array, d.kind() == Kind::mem_to_cmem ? d.dst : d.src};
      return check_reshuffle(d, limits);
    }
    case Kind::mem_to_mem:
      if (d.src_stride != 0 || d.dst_stride != 0) return {Error::bad_descriptor, d.ctrl};
      if (d.length % 4 != 0) return {Error::misaligned_length, d.length};
      if (d.src % 4 != 0) return {Error::misaligned_length, d.src};
      if (d.dst % 4 != 0) return {Error::misaligned_length, d.dst};
      if (!in_memory(d.src, uint64_t{d.src} + d.length, limits, offending) &&
          !in_readable_window(d.src, uint64_t{d.src} + d.length, limits))
        return {Error::src_outside_memory, offending};
      if (!in_memory(d.dst, uint64_t{d.dst} + d.length, limits, offending))
        return {Error::dst_outside_memory, offending};
      return {};
    case Kind::broadcast: {
      if (limits.lanes == 0 || limits.cmem_bytes == 0) return {Error::no_array, d.dst};
      if (!in_memory(d.src, uint64_t{d.src} + d.length, limits, offending))
        return {Error::src_outside_memory, offending};
      const uint64_t cmem_last = d.dst + uint64_t{d.length - 1} * broadcast_step(d);
      if (cmem_last >= limits.cmem_bytes) return {Error::dst_outside_cmem, cmem_last};
      if (d.mask != 0 && !in_memory(d.mask, uint64_t{d.mask} + mask_bytes(limits.lanes), limits, offending))
        return {Error::mask_outside_memory, offending};
      return {};
    }
  }
  return {Error::bad_descriptor, d.ctrl};
}

Fault validate_descriptor_address(uint32_t address, const Limits& limits) {
  uint64_t offending = 0;
  if (address % 4 != 0) return {Error::descriptor_outside_memory, address};
  if (!in_memory(address, uint64_t{address} + DESCRIPTOR_BYTES, limits, offending))
    return {Error::descriptor_outside_memory, offending};
  return {};
}

Fault execute(const Descriptor& d, const Limits& limits, unsigned buffer_bytes, DmaPort& port, uint64_t& moved) {
  moved = 0;
  std::vector<uint8_t> buffer(buffer_bytes);
  switch (d.kind()) {
    case Kind::mem_to_cmem:
    case Kind::cmem_to_mem: {
      const Reshuffle r = reshuffle_of(d, limits.lanes);
      for (uint64_t row = 0; row < r.rows(); ++row) {
        const uint64_t k = row * r.lanes;
        const unsigned count = r.row_elements(row);
        const unsigned bytes = count * r.element;
        const auto mem = static_cast<uint32_t>(r.memory_address(k));
        const auto cmem = static_cast<uint32_t>(r.cmem_address(k));
        if (d.kind() == Kind::mem_to_cmem) {
          if (!port.read_memory(mem, buffer.data(), bytes)) return {Error::bus_error, mem};
          port.write_cmem_row(count, cmem, r.element, buffer.data());
        } else {
          port.read_cmem_row(count, cmem, r.element, buffer.data());
          if (!port.write_memory(mem, buffer.data(), bytes)) return {Error::bus_error, mem};
        }
        moved += bytes;
      }
      return {};
    }
    case Kind::mem_to_mem: {
      // A destination above an overlapping source: chunk by chunk from the
      // end, so no chunk reads bytes an earlier one has written (memmove).
      // The chunks are the same ones either way, so is the time.
      const bool backwards = d.dst > d.src && d.dst < uint64_t{d.src} + d.length;
      const uint32_t chunks = (d.length + buffer_bytes - 1) / buffer_bytes;
      for (uint32_t i = 0; i < chunks; ++i) {
        const uint32_t done = (backwards ? chunks - 1 - i : i) * buffer_bytes;
        const unsigned bytes = std::min<uint32_t>(buffer_bytes, d.length - done);
        if (!port.read_memory(d.src + done, buffer.data(), bytes)) return {Error::bus_error, d.src + done};
        if (!port.write_memory(d.dst + done, buffer.data(), bytes)) return {Error::bus_error, d.dst + done};
        moved += bytes;
      }
      return {};
    }
    case Kind::broadcast: {
      std::vector<uint8_t> mask;
      if (d.mask != 0) {
        mask.resize(mask_bytes(limits.lanes));
        if (!port.read_memory(d.mask, mask.data(), static_cast<unsigned>(mask.size())))
          return {Error::bus_error, d.mask};
      }
      const uint32_t step = broadcast_step(d);
      for (uint32_t done = 0; done < d.length;) {
        const unsigned bytes = std::min<uint32_t>(buffer_bytes, d.length - done);
        if (!port.read_memory(d.src + done, buffer.data(), bytes)) return {Error::bus_error, d.src + done};
        port.broadcast_cmem(mask, d.dst + done * step, step, buffer.data(), bytes);
        done += bytes;
        moved += bytes;
      }
      return {};
    }
  }
  return {Error::bad_descriptor, d.ctrl};
}

}  // namespace tessera::dma
