// A back end's choice parameter by name: the index of `name` in the list of
// its values, as the enum E, or an error naming the key and the allowed
// values ("ap.pixel.program: unknown array program 'x'; allowed: tuned or
// study").
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace tessera::renderers {

template <typename E, size_t N>
E named_choice(const std::string& name, const char* const (&names)[N], const std::string& key, const char* what) {
  std::string allowed;
  for (size_t i = 0; i < N; ++i) {
    if (name == names[i]) return static_cast<E>(i);
    allowed += std::string(i == 0 ? "" : " or ") + names[i];
  }
  throw std::invalid_argument(key + ": unknown " + what + " '" + name + "'; allowed: " + allowed);
}

}  // namespace tessera::renderers
