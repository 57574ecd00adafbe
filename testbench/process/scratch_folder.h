// A fresh folder under the temporary folder (TMPDIR, else /tmp), named
// "<prefix>_XXXXXX" and removed with everything in it when the object goes,
// unless keep() was called so that a person can look. The one temporary-
// folder idiom of the tests, the benchmarks and render_compare;
// ScratchFolderTest (fixtures/scratch_folder_test.h) makes one per test.
#pragma once

#include <filesystem>
#include <string>

namespace tessera::test {

class ScratchFolder {
 public:
  // Throws std::runtime_error if the folder cannot be made.
  explicit ScratchFolder(const std::string& prefix);
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  const std::filesystem::path& path() const { return m_path; }
  void keep() { m_keep = true; }

 private:
  std::filesystem::path m_path;
  bool m_keep = false;
};

}  // namespace tessera::test
