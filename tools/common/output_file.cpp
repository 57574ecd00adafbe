#include "output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace fs = std::filesystem;

namespace tessera {

namespace {

std::string error_text(int error) {
  return std::error_code(error, std::generic_category()).message();
}

// The file `path` names: a symbolic link followed (a relative link taken
// from the link's folder), anything else as it is.
fs::path resolve_link(const fs::path& path) {
  std::error_code error;
  fs::path target = path;
  for (int hops = 0; hops < 40 && fs::is_symlink(target, error); ++hops) {
    const fs::path next = fs::read_symlink(target, error);
    if (error) break;
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  return target;
}

}  // namespace

OutputFile::OutputFile(fs::path path) : m_path(std::move(path)), m_target(resolve_link(m_path)) {
  struct stat status {};
  if (::stat(m_target.c_str(), &status) == 0 && !S_ISREG(status.st_mode)) {
    if (S_ISDIR(status.st_mode)) fail("it is a folder");
    m_direct = true;
    m_temporary = m_target;
    m_fd = ::open(m_target.c_str(), O_WRONLY | O_CLOEXEC);
  } else {
    m_temporary = m_target.parent_path() /
                  ("." + m_target.filename().string() + ".tmp-" + std::to_string(static_cast<long>(::getpid())));
    m_fd = ::open(m_temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  }
  if (m_fd < 0) fail(error_text(errno));
}

OutputFile::~OutputFile() {
  abandon();
}

void OutputFile::fail(const std::string& reason) {
  abandon();
  throw std::runtime_error("cannot write '" + m_path.string() + "': " + reason);
}

void OutputFile::write(const void* bytes, size_t count) {
  if (m_fd < 0) fail("the file is closed");
  const auto* next = static_cast<const char*>(bytes);
  while (count > 0) {
    const ssize_t written = ::write(m_fd, next, count);
    if (written < 0 && errno == EINTR) continue;
    // A write that stores nothing without an error would loop forever.
    if (written <= 0) fail(written < 0 ? error_text(errno) : "the write stored nothing");
    next += written;
    count -= static_cast<size_t>(written);
  }
}

void OutputFile::commit() {
  if (m_fd < 0) fail("the file is closed");
  const int fd = m_fd;
  m_fd = -1;
  if (::close(fd) != 0) {
    const int error = errno;
    if (!m_direct) ::unlink(m_temporary.c_str());
    throw std::runtime_error("cannot write '" + m_path.string() + "': " + error_text(error));
  }
  if (m_direct) return;
  if (::rename(m_temporary.c_str(), m_target.c_str()) != 0) {
    const int error = errno;
    ::unlink(m_temporary.c_str());
    throw std::runtime_error("cannot write '" + m_path.string() + "': " + error_text(error));
  }
  m_temporary.clear();
}

void OutputFile::abandon() noexcept {
  if (m_fd >= 0) {
    ::close(m_fd);
    m_fd = -1;
  }
  if (!m_direct && !m_temporary.empty()) ::unlink(m_temporary.c_str());
  m_temporary.clear();
}

void write_file_atomically(const fs::path& path, std::string_view bytes) {
  OutputFile file(path);
  file.write(bytes);
  file.commit();
}

void write_streamed(OutputFile* file, std::string_view bytes, std::string& error) {
  if (!file || !error.empty()) return;
  try {
    file->write(bytes);
  } catch (const std::exception& e) {
    error = e.what();
    file->abandon();
  }
}

std::string commit_streamed(std::unique_ptr<OutputFile>& file, std::string error) {
  if (error.empty() && file) {
    try {
      file->commit();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  file.reset();
  return error;
}

}  // namespace tessera
