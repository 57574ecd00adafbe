#include "renderers/backends.h"

#include <iterator>
#include <stdexcept>

namespace tessera::backends {

const Backend* find_backend(std::string_view name) {
  for (const Backend& entry : BACKENDS)
    if (name == entry.name) return &entry;
  return nullptr;
}

const Backend& backend(std::string_view name) {
  if (const Backend* found = find_backend(name)) return *found;
  throw std::invalid_argument("unknown renderer back end '" + std::string(name) + "' (known: " + backend_names() + ")");
}

std::string backend_names(const char* separator, const char* last_separator) {
  const size_t count = std::size(BACKENDS);
  std::string names;
  for (size_t i = 0; i < count; ++i) {
    if (i > 0) names += last_separator && i + 1 == count ? last_separator : separator;
    names += BACKENDS[i].name;
  }
  return names;
}

}  // namespace tessera::backends
