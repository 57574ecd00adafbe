// The renderer back ends soc_sim offers (--backend), for tests that must
// hold on every one of them. A hand list until the back-end registry
// exists; then it comes from there, and a new back end is covered without
// touching the tests.
#pragma once

#include <string>
#include <vector>

namespace tessera::test {

inline const std::vector<std::string>& back_end_names() {
  static const std::vector<std::string> names = {"arm", "raster"};
  return names;
}

}  // namespace tessera::test
