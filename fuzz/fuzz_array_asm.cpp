// Fuzz target: the array processor's assembler (tlm/array/asm, the library
// of tools/ap_asm), the input being a source file's text.
//
// Checks: a bad source is an AsmError naming the source (any other
// exception, a crash or a sanitizer report is a fault); an assembled
// program keeps its promises (assembler.h): every word passes decode() and
// check_limits(), one source line per word, every entry inside the program;
// and its disassembly assembles back to the same words and entries
// (disassembler.h).
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "array/asm/assembler.h"
#include "array/asm/disassembler.h"
#include "array/isa/ap_isa.h"
#include "fuzz_support.h"

namespace {

using tessera::fuzz::fail;
namespace ap = tessera::ap;

// Assembles `source`; false when it is rejected as it should be.
bool assemble(std::string_view source, const std::string& name, const ap::AsmLimits& limits, ap::Program& program) {
  try {
    program = ap::assemble(source, name, limits);
    return true;
  } catch (const ap::AsmError& e) {
    if (e.file() != name) fail("an error that names '" + e.file() + "', not the source: " + e.what());
    return false;
  } catch (const std::exception& e) {
    fail(std::string("an exception other than AsmError escaped: ") + e.what());
  }
}

}  // namespace

// NOLINTNEXTLINE(readability-identifier-naming): the name libFuzzer calls
extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string_view source(reinterpret_cast<const char*>(data), size);
  const ap::AsmLimits limits;  // array.* defaults, as ap_asm without options
  ap::Program program;
  if (!assemble(source, "fuzz.s", limits, program)) return 0;

  if (program.words.size() > limits.program_words) fail("more words than the program memory holds");
  if (program.lines.size() != program.words.size()) fail("not one source line per word");
  for (const uint64_t word : program.words) {
    const ap::Decoded decoded = ap::decode(word);
    if (!decoded.error.empty()) fail("an emitted word decode() refuses: " + decoded.error);
    const std::string limit = ap::check_limits(decoded.instruction, limits.registers, limits.cmem_bytes);
    if (!limit.empty()) fail("an emitted word beyond the limits: " + limit);
  }
  for (const auto& [label, word] : program.entries)
    if (word > program.words.size()) fail("entry '" + label + "' beyond the program");

  const std::string text = ap::disassemble(program);
  ap::Program again;
  if (!assemble(text, "disassembly.s", limits, again)) fail("the disassembly does not assemble:\n" + text);
  if (again.words != program.words) fail("the disassembly assembles to other words:\n" + text);
  if (again.entries != program.entries) fail("the disassembly assembles to other entries:\n" + text);
  return 0;
}
