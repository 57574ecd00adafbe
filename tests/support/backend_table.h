// The renderer back ends of sw_driver/renderers/backends.def, for tests that
// loop over every back end (soc_sim runs, help texts) without linking the
// driver: a back end added to the table is tested without editing a test.
#pragma once

#include <string>
#include <vector>

namespace tessera::test {

struct BackendEntry {
  std::string id;
  std::string name;
};

inline std::vector<BackendEntry> backend_table() {
  return {
#define TESSERA_BACKEND(id, name, depth_bits, stencil_bits, description) {#id, name},
#include "renderers/backends.def"
#undef TESSERA_BACKEND
  };
}

// The names soc_sim accepts (--backend), in the table's order.
inline std::vector<std::string> back_end_names() {
  std::vector<std::string> names;
  for (const BackendEntry& entry : backend_table()) names.push_back(entry.name);
  return names;
}

}  // namespace tessera::test
