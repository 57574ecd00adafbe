// A Program as C++ source, so that a program assembled at build time
// (tessera_add_array_programs in cmake/Tessera.cmake, ap_asm --emit-cpp) is
// linked into the simulator rather than read from a file at run time.
//
// The header convention: the accessor of program NAME is declared in
// `ap_programs/NAME.h` as `const tessera::ap::Program& tessera::ap::programs::NAME()`.
// The accessors share one namespace, so NAME is unique in a link and one
// folder of headers serves every program library.
#pragma once

#include <string>
#include <string_view>

#include "array/program.h"

namespace tessera::ap {

// Whether `name` can name an accessor: a C++ identifier.
bool is_program_name(std::string_view name);

// The definition of programs::<name>() returning `program`.
std::string program_cpp_source(const Program& program, std::string_view name);

// The declaration of programs::<name>(), the contents of ap_programs/<name>.h.
std::string program_cpp_header(const Program& program, std::string_view name);

}  // namespace tessera::ap
