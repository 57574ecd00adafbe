// Fuzz target: the ARM executable loader (tlm/host/iss/elf_image.h),
// parse_elf over the file's bytes as iss_run and soc_sim's launcher read
// them, then a short run of what it loaded on the bare machine.
//
// Input: the ELF file itself.
//
// Checks: a bad input is an ElfError naming the file (any other exception,
// a crash or a sanitizer report is a fault); an accepted image has
// segments that do not overlap, each within 4 GiB, together at most
// MAX_ELF_BYTES, the entry point in an executable segment, and functions
// sorted without overlaps; check_fits either accepts it or says why with an
// ElfError; one that fits the bare machine's RAM is loaded and runs 2,000
// instructions, where only an IssError (an unpredictable encoding, a hung
// branch) may stop it.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fuzz_support.h"
#include "host/iss/arm_core.h"
#include "host/iss/bare_machine.h"
#include "host/iss/elf_image.h"

namespace {

using tessera::iss::ElfError;
using tessera::iss::ElfImage;
using tessera::iss::ElfSegment;

const std::string PATH = "fuzz.elf";

void check_image(const ElfImage& image) {
  uint64_t total = 0;
  bool entry_covered = false;
  std::vector<const ElfSegment*> by_address;
  for (const ElfSegment& segment : image.segments) {
    const uint64_t end = uint64_t{segment.address} + segment.bytes.size();
    if (segment.bytes.empty()) tessera::fuzz::fail("an empty segment was kept");
    if (end > (1ull << 32)) tessera::fuzz::fail("a segment wraps past 4 GiB");
    total += segment.bytes.size();
    entry_covered |= segment.executable && image.entry >= segment.address && image.entry < end;
    by_address.push_back(&segment);
  }
  if (total > tessera::iss::MAX_ELF_BYTES) tessera::fuzz::fail("the segments take more than MAX_ELF_BYTES");
  if (!entry_covered) tessera::fuzz::fail("the entry point is in no executable segment");
  std::sort(by_address.begin(), by_address.end(),
            [](const ElfSegment* a, const ElfSegment* b) { return a->address < b->address; });
  for (size_t i = 1; i < by_address.size(); ++i)
    if (by_address[i]->address < uint64_t{by_address[i - 1]->address} + by_address[i - 1]->bytes.size())
      tessera::fuzz::fail("two segments overlap");
  for (size_t i = 1; i < image.functions.size(); ++i)
    if (image.functions[i].address < uint64_t{image.functions[i - 1].address} + image.functions[i - 1].size)
      tessera::fuzz::fail("functions out of order or overlapping");
}

bool named(const ElfError& error) {
  return std::string(error.what()).rfind(PATH + ": ", 0) == 0;
}

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::vector<uint8_t> file(data, data + size);
  ElfImage image;
  try {
    image = tessera::iss::parse_elf(file, PATH);
  } catch (const ElfError& error) {
    if (!named(error)) tessera::fuzz::fail(std::string("an error without the file's name: ") + error.what());
    return 0;
  } catch (const std::exception& error) {
    tessera::fuzz::fail(std::string("an exception other than ElfError escaped: ") + error.what());
  }
  check_image(image);
  tessera::iss::BareMachine machine;
  tessera::iss::ArmCore core(machine);
  try {
    machine.load(image, core);
  } catch (const ElfError& error) {
    if (!named(error)) tessera::fuzz::fail(std::string("an error without the file's name: ") + error.what());
    return 0;
  }
  try {
    machine.run(core, 2000);
  } catch (const tessera::iss::IssError&) {
  }
  return 0;
}
