// Debian ships tinyobjloader as a header and a library built for the native
// machine; the ARM build compiles the header's implementation here
// (cmake/Arm922tTarget.cmake). ARM only.
#define TINYOBJLOADER_IMPLEMENTATION
#include <tiny_obj_loader.h>
