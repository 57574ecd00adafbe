// ElfImage: an ARM executable (ELF32, little-endian, EM_ARM) read and
// checked for the ISS: its loadable segments and entry point. Every
// malformed input is an ElfError naming the file and what is wrong.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera::iss {

class ElfError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ElfSegment {
  uint32_t address = 0;        // physical (load) address
  std::vector<uint8_t> bytes;  // the file's bytes, then zeros up to the segment's memory size
  bool executable = false;
};

// A function of the symbol table (STT_FUNC with a size), for profiles and
// the VCD's function signal.
struct ElfFunction {
  std::string name;      // as the symbol table has it (mangled for C++)
  uint32_t address = 0;  // without the Thumb bit
  uint32_t size = 0;
};

struct ElfImage {
  std::string path;
  uint32_t entry = 0;
  std::vector<ElfSegment> segments;
  // Sorted by address, without overlaps; empty for a stripped executable.
  std::vector<ElfFunction> functions;

  // ElfError unless every segment lies in [base, base + size).
  void check_fits(uint32_t base, uint64_t size, const std::string& what) const;
};

// Files larger than this are refused (an executable for a 64 MiB memory).
constexpr uint64_t MAX_ELF_BYTES = 64ull << 20;

ElfImage read_elf(const std::string& path);
ElfImage parse_elf(const std::vector<uint8_t>& file, const std::string& path);

}  // namespace tessera::iss
