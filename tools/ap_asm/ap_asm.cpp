// ap_asm: the array processor's assembler.
//
//   ap_asm FILE.s [-o image.bin]            assemble; print a summary; write the image
//   ap_asm --disassemble FILE.s [-o F]      assemble, then print (or write) the disassembly
//   ap_asm --emit-cpp NAME FILE.s -o out.cpp [--header ap_programs/NAME.h]
//                                           the program as C++ (tessera_add_array_programs)
//   ap_asm --isa-table [-o F]               the ISA as markdown, for tlm/array/README.md
//   --registers N --cmem-bytes N --program-words N   the array the program must fit
//   -D NAME=VALUE                           a constant defined before the source's first line (for .if)
//
// The image is the program's words, each 8 bytes little-endian, in order.
// An assembly error is printed as "ap_asm: file:line: problem", exit status 1.
#include <CLI/CLI.hpp>

#include <climits>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "array/asm/assembler.h"
#include "array/asm/disassembler.h"
#include "array/asm/isa_table.h"
#include "array/asm/program_embedding.h"
#include "array/isa/ap_isa.h"
#include "guarded_main.h"

namespace {

using namespace tessera::ap;

// Writes `bytes` to `path` whole; a failure is an error, never a short file
// that a later build step would take for a program.
void write_file(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

void write_text(const std::string& path, const std::string& text) {
  if (path.empty())
    std::cout << text << std::flush;
  else
    write_file(path, text);
}

// "NAME=VALUE", VALUE a decimal or 0x hexadecimal int, optionally negative.
std::pair<std::string, int> parse_define(const std::string& text) {
  const size_t equals = text.find('=');
  const std::string bad = "-D " + text + ": expected NAME=VALUE, VALUE a decimal or 0x hexadecimal int";
  if (equals == std::string::npos || equals == 0 || equals + 1 == text.size()) throw std::runtime_error(bad);
  const std::string value = text.substr(equals + 1);
  size_t used = 0;
  long long number = 0;
  try {
    number = std::stoll(value, &used, 0);
  } catch (const std::exception&) {
    throw std::runtime_error(bad);
  }
  if (used != value.size() || number < INT_MIN || number > INT_MAX) throw std::runtime_error(bad);
  return {text.substr(0, equals), static_cast<int>(number)};
}

std::string image_bytes(const Program& program) {
  std::string bytes;
  for (const uint64_t word : program.words)
    for (unsigned i = 0; i < 8; ++i) bytes += static_cast<char>((word >> (8 * i)) & 0xff);
  return bytes;
}

std::string summary(const Program& program) {
  std::string entries;
  for (const auto& [name, index] : program.entries) entries += (entries.empty() ? "" : ", ") + name;
  return program.source_name + ": " + std::to_string(program.words.size()) + " words, " +
         std::to_string(program.entries.size()) + (program.entries.size() == 1 ? " entry" : " entries") +
         (entries.empty() ? "" : " (" + entries + ")") + ", " + std::to_string(program.variables.size()) +
         " variables, " + std::to_string(program.constants.size()) + " constants\n";
}

}  // namespace

static int run_main(int argc, char** argv) {
  CLI::App app{"The array processor's assembler (tlm/array/README.md, \"The assembly language\")"};
  std::string file;
  std::string output;
  std::string emit_name;
  std::string header;
  bool disassemble_program = false;
  bool isa_table = false;
  AsmLimits limits;
  std::vector<std::string> defines;
  app.add_option("file", file, "the assembly source");
  app.add_option("-o,--output", output, "the image (raw little-endian words), the disassembly, the C++ or the table");
  auto* disassemble_flag = app.add_flag("--disassemble", disassemble_program, "print the program's disassembly");
  auto* emit = app.add_option("--emit-cpp", emit_name, "write the program as C++ with the accessor programs::NAME()");
  app.add_option("--header", header, "with --emit-cpp: also write the accessor's declaration here")->needs(emit);
  auto* table = app.add_flag("--isa-table", isa_table, "print the ISA as markdown tables");
  disassemble_flag->excludes(emit)->excludes(table);
  emit->excludes(table);
  app.add_option("--registers", limits.registers, "registers of a CU")->check(CLI::Range(1u, MAX_REGISTERS));
  app.add_option("--cmem-bytes", limits.cmem_bytes, "bytes of CMEM of a CU")->check(CLI::Range(1u, 1u << ADDRESS_BITS));
  app.add_option("--program-words", limits.program_words, "words of program memory")->check(CLI::Range(1u, 1u << 20));
  app.add_option("-D,--define", defines, "NAME=VALUE: a constant defined before the source's first line (for .if)")
      ->allow_extra_args(false);
  CLI11_PARSE(app, argc, argv);

  if (isa_table) {
    if (!file.empty()) throw std::runtime_error("--isa-table takes no source file");
    write_text(output, isa_table_markdown());
    return 0;
  }
  if (file.empty()) throw std::runtime_error("no source file (ap_asm FILE.s; --help lists the options)");
  if (!emit_name.empty() && !is_program_name(emit_name))
    throw std::runtime_error("--emit-cpp " + emit_name + ": the name must be a C++ identifier");
  if (!emit_name.empty() && output.empty()) throw std::runtime_error("--emit-cpp needs -o FILE.cpp");

  AsmDefines defined;
  for (const std::string& define : defines) {
    const auto [name, value] = parse_define(define);
    if (!defined.emplace(name, value).second) throw std::runtime_error("-D " + name + " is given twice");
  }
  const Program program = assemble_file(file, limits, defined);
  if (disassemble_program) {
    write_text(output, disassemble(program));
  } else if (!emit_name.empty()) {
    write_file(output, program_cpp_source(program, emit_name));
    if (!header.empty()) write_file(header, program_cpp_header(program, emit_name));
  } else {
    if (!output.empty()) write_file(output, image_bytes(program));
    std::cout << summary(program) << std::flush;
  }
  return 0;
}

int main(int argc, char** argv) {
  return tessera::guarded_main("ap_asm", [&] { return run_main(argc, argv); });
}
