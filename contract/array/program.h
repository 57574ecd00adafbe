// An assembled array program: the image the AC runs and the names the host
// needs around it. The assembler (assembler.h) makes one from source; a
// program embedded in the build (tessera_add_array_programs) is one of these
// returned by a generated accessor.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
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

// The address of `program`'s variable `name`, which the host expects to be
// `size` bytes; throws std::invalid_argument naming the program, the
// variable and the sizes otherwise.
inline uint16_t variable_address(const Program& program, const std::string& name, unsigned size) {
  const auto it = program.variables.find(name);
  if (it == program.variables.end())
    throw std::invalid_argument(program.source_name + ": the program has no CMEM variable '" + name + "'");
  if (it->second.size != size)
    throw std::invalid_argument(program.source_name + ": CMEM variable '" + name + "' is " +
                                std::to_string(it->second.size) + " bytes, the host expects " + std::to_string(size));
  return it->second.address;
}

// The value of `program`'s constant `name`; throws std::invalid_argument if
// it has none.
inline int constant_value(const Program& program, const std::string& name) {
  const auto it = program.constants.find(name);
  if (it == program.constants.end())
    throw std::invalid_argument(program.source_name + ": the program has no constant '" + name + "'");
  return it->second;
}

// The word of `program`'s entry point `name`; throws std::invalid_argument
// if it has none.
inline unsigned entry_word(const Program& program, const std::string& name) {
  const auto it = program.entries.find(name);
  if (it == program.entries.end())
    throw std::invalid_argument(program.source_name + ": the program has no entry point '" + name + "'");
  return it->second;
}

}  // namespace tessera::ap
