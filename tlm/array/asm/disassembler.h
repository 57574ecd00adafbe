// The array processor's disassembler: a Program back to assembly text.
#pragma once

#include <string>

#include "array/program.h"

namespace tessera::ap {

// Assembly that assemble() reads back into the same words and entries:
// the program's constants and variables as directives (variables at their
// fixed addresses), a label per entry, a `.stage` line where the stage
// changes, loop variables named i0, i1, i2 by nesting level and CMEM
// operands as numbers. A word decode() refuses becomes a comment saying
// why, so the text then no longer assembles to the same image.
std::string disassemble(const Program& program);

}  // namespace tessera::ap
