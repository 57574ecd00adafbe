// What the cluster network carries between network interfaces, and the
// interface a node's NI offers the network to receive it (README.md).
#pragma once

#include <cstdint>
#include <vector>

namespace tessera {

struct NetworkMessage {
  unsigned source = 0;
  unsigned destination = 0;
  uint32_t tag = 0;       // the software's message type, from the send descriptor
  uint32_t sequence = 0;  // the n-th message from source to destination, from 0
  std::vector<uint8_t> payload;
};

// A node's side of the network: the network calls deliver() at the
// message's arrival time (the kernel's time), from a method process, so it
// must not wait.
class NetworkEndpoint {
 public:
  virtual void deliver(NetworkMessage&& message) = 0;

 protected:
  ~NetworkEndpoint() = default;
};

}  // namespace tessera
