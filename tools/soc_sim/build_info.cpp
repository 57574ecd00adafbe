#include "build_info.h"

// Written by cmake/write_build_info.cmake into the build tree.
#include "tessera_build_info_values.h"

namespace tessera::build_info {

const char* version() {
  return TESSERA_BUILD_VERSION;
}

const char* commit() {
  return TESSERA_BUILD_COMMIT;
}

}  // namespace tessera::build_info
