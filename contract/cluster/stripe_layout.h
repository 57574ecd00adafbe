// How the cluster platform's frame is shared among its nodes, and where a
// node keeps its stripe: shared by the node program (sw_driver/cluster),
// which draws into it, and the platform (tlm/cluster), which gathers the
// stripes into the frame.
//
// Node s of p owns the rows [floor(s H / p), floor((s + 1) H / p)) of a
// screen H = `height` rows high, rows counted from the top. When p does not
// divide H, stripes differ by at most one row. Every node owns at least one
// row: the platform refuses more nodes than rows.
#pragma once

#include <cstdint>

namespace tessera::stripes {

constexpr unsigned first_row(unsigned stripe, unsigned height, unsigned nodes) {
  return stripe * height / nodes;  // < 2^16: one 32-bit division
}

constexpr unsigned rows(unsigned stripe, unsigned height, unsigned nodes) {
  return first_row(stripe + 1, height, nodes) - first_row(stripe, height, nodes);
}

// The s with first_row(s) <= row < first_row(s + 1).
constexpr unsigned owner_of_row(unsigned row, unsigned height, unsigned nodes) {
  return ((row + 1) * nodes - 1) / height;
}

// The stripe's colour buffer: RGBA8888 (contract/common/pixel_format.def),
// `width` pixels a row, its first row first, where the node's host link's
// STRIPE_ADDRESS says (host_link_regs.def).
inline constexpr unsigned BYTES_PER_PIXEL = 4;

constexpr uint32_t colour_bytes(unsigned stripe, unsigned width, unsigned height, unsigned nodes) {
  return rows(stripe, height, nodes) * width * BYTES_PER_PIXEL;
}

}  // namespace tessera::stripes
