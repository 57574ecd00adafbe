// What this soc_sim was built from, for --version and stats.json.
#pragma once

namespace tessera::build_info {

// The project's version: CMake's project(VERSION).
const char* version();
// `git describe --always --dirty` of the source tree at the last build that
// compiled soc_sim (taken at build time, so never older than the binary);
// "unknown" when it was built without git or outside a checkout.
const char* commit();

}  // namespace tessera::build_info
