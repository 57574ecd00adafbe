// The ISA as markdown (ap_asm --isa-table), generated from the .def tables
// for tlm/array/README.md so that the documentation cannot drift from the
// decoder (the readme_isa_table test compares them).
#pragma once

#include <string>

namespace tessera::ap {

// The instruction table, then the mask conditions and the program stages.
std::string isa_table_markdown();

}  // namespace tessera::ap
