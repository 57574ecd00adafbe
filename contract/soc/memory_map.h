// Typed view of memory_map.def.
#pragma once

#include <cstdint>

namespace tessera::memory_map {

struct Region {
  const char* name;
  uint32_t base;
  uint32_t size;
  const char* description;
  constexpr bool contains(uint64_t address) const { return address >= base && address - base < size; }
};

#define TESSERA_REGION(name, base, size, description) inline constexpr Region name{#name, base, size, description};
#include "soc/memory_map.def"
#undef TESSERA_REGION

inline constexpr Region ALL_REGIONS[] = {
#define TESSERA_REGION(name, base, size, description) name,
#include "soc/memory_map.def"
#undef TESSERA_REGION
};

}  // namespace tessera::memory_map
