// Output files that are whole or absent. A file is written under a
// temporary name in its own folder and renamed over its path only when every
// byte was written and the file closed without error, so that a full disk, a
// failed write or a run that stops half way never leaves a truncated file
// where a finished one is expected (a reader sees the earlier file or none).
// Every write and the close are checked; a failure throws
// std::runtime_error naming the file and the reason ("cannot write
// 'out/stats.json': No space left on device").
//
// A path that is a symbolic link is written through: the temporary file
// goes beside the file the link points to. A path that exists and is not a
// regular file (a device such as /dev/null or /dev/full, a pipe) cannot be
// replaced by a rename: it is written directly, still checked.
//
// Limits: the rename makes a file whole against a process that stops or
// crashes, not against a power failure (no fsync). A process killed with
// SIGKILL while writing leaves its temporary file, named
// ".<name>.tmp-<pid>" beside the file.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace tessera {

class OutputFile {
 public:
  // Opens the temporary file (or the device). Throws naming `path`.
  explicit OutputFile(std::filesystem::path path);
  ~OutputFile();  // abandons a file not committed
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Appends `bytes`; throws on the first failed write.
  void write(const void* bytes, size_t count);
  void write(std::string_view text) { write(text.data(), text.size()); }
  // Closes the file and puts it in place. Throws if the close or the rename
  // fails, after removing the temporary file.
  void commit();
  // Closes and removes the temporary file: nothing of it is left.
  void abandon() noexcept;

  const std::filesystem::path& path() const { return m_path; }
  // The temporary file's path (the path itself for a device).
  const std::filesystem::path& temporary_path() const { return m_temporary; }

 private:
  [[noreturn]] void fail(const std::string& reason);

  std::filesystem::path m_path;       // as given, for messages
  std::filesystem::path m_target;     // where the file ends up (a link resolved)
  std::filesystem::path m_temporary;  // what is written
  int m_fd = -1;
  bool m_direct = false;  // a device or pipe: written in place
};

// A write of a file streamed by a writer that keeps its first error rather
// than throwing: appends `bytes` to `file` (when there is one) unless
// `error` holds an earlier error; a failed write goes into `error` and
// abandons the file.
void write_streamed(OutputFile* file, std::string_view bytes, std::string& error);

// The end of a file streamed by a writer that keeps its first error rather
// than throwing (the timeline, the transaction trace): commits `file` when
// there is one and `error` is empty, then releases it (an uncommitted file
// is abandoned); returns the first error, the commit's if it failed.
std::string commit_streamed(std::unique_ptr<OutputFile>& file, std::string error);

// Writes `bytes` to `path` whole or not at all (OutputFile).
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace tessera
