#include "host/iss/elf_image.h"

#include <algorithm>
#include <cstring>
#include <fstream>
#include <iterator>

#include "host/iss/arm_core.h"

namespace tessera::iss {

namespace {

constexpr unsigned HEADER_BYTES = 52, PROGRAM_HEADER_BYTES = 32;
constexpr uint16_t EXECUTABLE = 2, MACHINE_ARM = 40;
constexpr uint32_t LOAD = 1, FLAG_EXECUTE = 1;

uint32_t u32(const std::vector<uint8_t>& b, uint64_t at) {
  return uint32_t{b[at]} | uint32_t{b[at + 1]} << 8 | uint32_t{b[at + 2]} << 16 | uint32_t{b[at + 3]} << 24;
}
uint16_t u16(const std::vector<uint8_t>& b, uint64_t at) {
  return static_cast<uint16_t>(b[at] | b[at + 1] << 8);
}

constexpr uint32_t SYMBOL_TABLE = 2;
constexpr unsigned SECTION_HEADER_BYTES = 40, SYMBOL_BYTES = 16;
constexpr uint8_t FUNCTION = 2;

// The symbol table's functions. A malformed table is left out rather than
// refused: the program runs without it, and only its profile is poorer.
void read_functions(const std::vector<uint8_t>& file, ElfImage& image) {
  const uint64_t sections = u32(file, 32);
  const unsigned entry_size = u16(file, 46), count = u16(file, 48);
  if (sections == 0 || entry_size < SECTION_HEADER_BYTES || sections + uint64_t{entry_size} * count > file.size())
    return;
  for (unsigned i = 0; i < count; ++i) {
    const uint64_t at = sections + uint64_t{entry_size} * i;
    if (u32(file, at + 4) != SYMBOL_TABLE) continue;
    const uint64_t table = u32(file, at + 16), table_size = u32(file, at + 20);
    const unsigned link = u32(file, at + 24);
    if (link >= count || table + table_size > file.size()) return;
    const uint64_t strings_at = sections + uint64_t{entry_size} * link;
    const uint64_t strings = u32(file, strings_at + 16), strings_size = u32(file, strings_at + 20);
    if (strings + strings_size > file.size()) return;
    for (uint64_t s = table; s + SYMBOL_BYTES <= table + table_size; s += SYMBOL_BYTES) {
      const uint32_t name = u32(file, s), value = u32(file, s + 4), size = u32(file, s + 8);
      if ((file[s + 12] & 0xf) != FUNCTION || size == 0 || name >= strings_size) continue;
      const auto* text = reinterpret_cast<const char*>(file.data() + strings + name);
      const size_t length = strnlen(text, strings_size - name);
      image.functions.push_back({std::string(text, length), value & ~1u, size});
    }
  }
  std::sort(image.functions.begin(), image.functions.end(),
            [](const ElfFunction& a, const ElfFunction& b) { return a.address < b.address; });
  // Aliases and overlaps: the first function at an address keeps it.
  std::vector<ElfFunction> kept;
  for (ElfFunction& f : image.functions)
    if (kept.empty() || f.address >= kept.back().address + kept.back().size) kept.push_back(std::move(f));
  image.functions = std::move(kept);
}

}  // namespace

ElfImage read_elf(const std::string& path) {
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw ElfError(path + ": cannot open the ARM executable");
  const auto size = static_cast<uint64_t>(in.tellg());
  if (size > MAX_ELF_BYTES)
    throw ElfError(path + ": " + std::to_string(size) + " bytes, more than an executable for the SoC can be (" +
                   std::to_string(MAX_ELF_BYTES) + ")");
  in.seekg(0);
  std::vector<uint8_t> file(size);
  if (!in.read(reinterpret_cast<char*>(file.data()), static_cast<std::streamsize>(size)))
    throw ElfError(path + ": read failed");
  return parse_elf(file, path);
}

ElfImage parse_elf(const std::vector<uint8_t>& file, const std::string& path) {
  auto fail = [&](const std::string& what) { throw ElfError(path + ": not an ARM executable: " + what); };
  if (file.size() < HEADER_BYTES || file[0] != 0x7f || file[1] != 'E' || file[2] != 'L' || file[3] != 'F')
    fail("no ELF header");
  if (file[4] != 1) fail("not a 32-bit ELF");
  if (file[5] != 1) fail("not little-endian");
  if (u16(file, 16) != EXECUTABLE) fail("ELF type " + std::to_string(u16(file, 16)) + ", not an executable (2)");
  if (u16(file, 18) != MACHINE_ARM) fail("machine " + std::to_string(u16(file, 18)) + ", not ARM (40)");
  ElfImage image;
  image.path = path;
  image.entry = u32(file, 24);
  const uint64_t table = u32(file, 28);
  const unsigned entry_size = u16(file, 42), count = u16(file, 44);
  if (count == 0) fail("no program headers");
  if (entry_size < PROGRAM_HEADER_BYTES || table + uint64_t{entry_size} * count > file.size())
    fail("program headers outside the file");
  // Every header is checked, and the segments' total and overlaps, before
  // a byte is allocated: a small file must not make the loader take
  // gigabytes (many large segments) nor leave two segments claiming the
  // same memory (which copy would run, which would GDB show?).
  struct Loadable {
    unsigned index;
    uint64_t offset, address, file_size, memory_size;
    bool executable;
  };
  std::vector<Loadable> loadable;
  uint64_t total = 0;
  for (unsigned i = 0; i < count; ++i) {
    const uint64_t at = table + uint64_t{entry_size} * i;
    if (u32(file, at) != LOAD) continue;
    const uint64_t offset = u32(file, at + 4), address = u32(file, at + 12);
    const uint64_t file_size = u32(file, at + 16), memory_size = u32(file, at + 20);
    if (file_size > memory_size) fail("segment " + std::to_string(i) + " has more file bytes than memory bytes");
    if (offset + file_size > file.size()) fail("segment " + std::to_string(i) + " extends past the end of the file");
    if (address + memory_size > (1ull << 32))
      fail("segment " + std::to_string(i) + " at " + address_text(address) + " wraps past 4 GiB");
    if (memory_size == 0) continue;
    total += memory_size;
    if (total > MAX_ELF_BYTES)
      fail("its loadable segments take " + std::to_string(total) + " bytes or more (up to segment " +
           std::to_string(i) + "), more than an executable for the SoC can (" + std::to_string(MAX_ELF_BYTES) + ")");
    loadable.push_back({i, offset, address, file_size, memory_size, (u32(file, at + 24) & FLAG_EXECUTE) != 0});
  }
  std::vector<const Loadable*> by_address;
  by_address.reserve(loadable.size());
  for (const Loadable& segment : loadable) by_address.push_back(&segment);
  std::sort(by_address.begin(), by_address.end(),
            [](const Loadable* a, const Loadable* b) { return a->address < b->address; });
  const auto range = [](const Loadable& s) {
    return address_text(static_cast<uint32_t>(s.address)) + ".." + address_text(s.address + s.memory_size);
  };
  for (size_t k = 1; k < by_address.size(); ++k) {
    const Loadable& before = *by_address[k - 1];
    const Loadable& after = *by_address[k];
    if (after.address < before.address + before.memory_size)
      fail("segments " + std::to_string(before.index) + " (" + range(before) + ") and " + std::to_string(after.index) +
           " (" + range(after) + ") overlap");
  }
  bool entry_covered = false;
  for (const Loadable& s : loadable) {
    ElfSegment segment;
    segment.address = static_cast<uint32_t>(s.address);
    segment.executable = s.executable;
    segment.bytes.assign(file.begin() + static_cast<std::ptrdiff_t>(s.offset),
                         file.begin() + static_cast<std::ptrdiff_t>(s.offset + s.file_size));
    segment.bytes.resize(s.memory_size, 0);
    entry_covered |= s.executable && image.entry >= s.address && image.entry < s.address + s.memory_size;
    image.segments.push_back(std::move(segment));
  }
  if (image.segments.empty()) fail("no loadable segment");
  read_functions(file, image);
  if (!entry_covered) fail("entry point " + address_text(image.entry) + " is not in an executable segment");
  return image;
}

void ElfImage::check_fits(uint32_t base, uint64_t size, const std::string& what) const {
  for (const ElfSegment& segment : segments) {
    const uint64_t end = uint64_t{segment.address} + segment.bytes.size();
    if (segment.address < base || end > base + size)
      throw ElfError(path + ": segment " + address_text(segment.address) + ".." + address_text(end) +
                     " falls outside " + what + " (" + address_text(base) + ".." + address_text(base + size) + ")");
  }
}

}  // namespace tessera::iss
