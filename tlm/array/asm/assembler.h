// The array processor's assembler: source text (the language is described in
// tlm/array/README.md, "The assembly language") to a Program. Every word it
// emits has passed decode(), so the AC never refuses an assembled program,
// and every address it emits, with the largest value of the loop variable
// added, lies inside the CMEM of the limits it was given.
#pragma once

#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

#include "array/isa/ap_isa.h"
#include "array/program.h"

namespace tessera::ap {

// The array configuration a program must fit (array.registers,
// array.cmem_bytes, array.program_words); by default the J2210's, as those
// keys default to (ap_isa.h).
struct AsmLimits {
  unsigned registers = J2210::REGISTERS;
  unsigned cmem_bytes = J2210::CMEM_BYTES;
  unsigned program_words = J2210::PROGRAM_WORDS;
};

// A problem in a source, as "file:line: problem" (or "file: problem" when no
// line is to blame, e.g. an unreadable file), so editors and the build jump
// to it.
class AsmError : public std::runtime_error {
 public:
  AsmError(const std::string& file, unsigned line, const std::string& problem);

  const std::string& file() const { return m_file; }
  unsigned line() const { return m_line; }  // 0 when the whole file is to blame
  const std::string& problem() const { return m_problem; }

 private:
  std::string m_file;
  unsigned m_line;
  std::string m_problem;
};

// The largest source assemble_file reads: far above any program that fits
// the largest program memory written out line by line.
constexpr size_t MAX_SOURCE_BYTES = 64u * 1024 * 1024;

// Constants the caller defines before the source's first line (ap_asm -D
// NAME=VALUE), as if by `.const`: one source assembled into variants that
// `.if` tells apart (README.md, "Conditional assembly").
using AsmDefines = std::map<std::string, int>;

// Throws AsmError on the first problem; std::invalid_argument when the
// limits themselves are not an array the ISA can address, or a defined name
// is not a name the language allows.
Program assemble(std::string_view source, const std::string& source_name, const AsmLimits& limits = {},
                 const AsmDefines& defines = {});
Program assemble_file(const std::string& path, const AsmLimits& limits = {}, const AsmDefines& defines = {});

}  // namespace tessera::ap
