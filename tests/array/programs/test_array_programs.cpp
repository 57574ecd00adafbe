// The programs assembled at build time (tessera_add_array_programs): the
// embedded image is the one the assembler makes of the source today.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "ap_programs/example.h"
#include "array/asm/assembler.h"

namespace tessera::ap {
namespace {

TEST(ArrayPrograms, ExampleIsEmbeddedWhole) {
  const Program& program = programs::example();
  EXPECT_EQ(program.source_name, "tlm/array/programs/example.s");
  EXPECT_EQ(program.entries.count("add16"), 1u);
  EXPECT_EQ(program.variables.at("sum").size, 16);
  EXPECT_EQ(program.constants.at("COUNT"), 8);
  EXPECT_EQ(program.lines.size(), program.words.size());

  const char* source_dir = std::getenv("TESSERA_SOURCE_DIR");
  ASSERT_NE(source_dir, nullptr) << "run through ctest, which sets TESSERA_SOURCE_DIR";
  const Program fresh = assemble_file(std::string(source_dir) + "/" + program.source_name);
  EXPECT_EQ(program.words, fresh.words);
  EXPECT_EQ(program.entries, fresh.entries);
  EXPECT_EQ(program.variables, fresh.variables);
  EXPECT_EQ(program.constants, fresh.constants);
  EXPECT_EQ(program.lines, fresh.lines);
}

}  // namespace
}  // namespace tessera::ap
