// The sort-middle node program's messages (README.md, "Messages"): what a
// message's tag says. Every message carries the frame it belongs to, so a
// node that sees a message of the next frame knows that the frame it is in
// is complete everywhere (no node starts a frame before the global
// completion of the one before).
#pragma once

#include <cstdint>

namespace tessera::sort_middle {

enum class MessageType : uint32_t {
  trapezoids = 1,               // d trapezoids (or fewer: the last of the frame) for the receiver's stripe
  last_trapezoid = 2,           // LT: the sender sends this frame no more trapezoids to the receiver
  last_trapezoid_complete = 3,  // LTC: the receiver has drawn every trapezoid the LT's sender sent it
  neighbours_complete = 4,      // NC, to node 0: every neighbour has drawn what the sender sent it
  global_completion = 5,        // GC, from node 0: the frame is complete on every node
};

constexpr uint32_t TYPE_BITS = 8;

constexpr uint32_t make_tag(MessageType type, uint32_t frame) {
  return static_cast<uint32_t>(type) | (frame << TYPE_BITS);
}
constexpr MessageType tag_type(uint32_t tag) {
  return static_cast<MessageType>(tag & ((1u << TYPE_BITS) - 1));
}
constexpr uint32_t tag_frame(uint32_t tag) {
  return tag >> TYPE_BITS;
}

}  // namespace tessera::sort_middle
