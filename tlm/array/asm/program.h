// An assembled array program: the image the AC runs and the names the host
// needs around it. The assembler (assembler.h) makes one from source; a
// program embedded in the build (tessera_add_array_programs) is one of these
// returned by a generated accessor.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace tessera::ap {

// A named area of CMEM: the host writes a CU's inputs there and reads its
// results back by name, so a program can move its data without the host
// changing.
struct Variable {
  uint16_t address = 0;
  uint16_t size = 0;

  bool operator==(const Variable& other) const { return address == other.address && size == other.size; }
};

struct Program {
  std::string source_name;
  std::vector<uint64_t> words;
  // Every label is an entry point: the host starts the AC at its word.
  std::map<std::string, unsigned> entries;
  std::map<std::string, Variable> variables;
  std::map<std::string, int> constants;
  // The source line of each word, so a profile per word reads per line.
  std::vector<unsigned> lines;
};

}  // namespace tessera::ap
