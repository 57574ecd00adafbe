#include "trace_pipe.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <memory>
#include <stdexcept>
#include <system_error>
#include <vector>

#include "output_file.h"
#include "soc/soc_recorder.h"
#include "vcd_to_fst.h"

namespace fs = std::filesystem;

namespace tessera {

namespace {

constexpr size_t COPY_BYTES = 1 << 16;  // a pipe's buffer

std::string error_text(int error) {
  return std::error_code(error, std::generic_category()).message();
}

}  // namespace

TracePipe::TracePipe(fs::path vcd_path, fs::path fst_path)
    : m_trace_path(std::move(vcd_path)), m_fst_path(std::move(fst_path)) {
  if (!m_fst_path.empty())
    m_fst_temporary =
        (m_fst_path.parent_path() / ("." + m_fst_path.filename().string() + ".tmp-" + std::to_string(::getpid())))
            .string();
  std::string pattern = (fs::temp_directory_path() / "soc_sim_trace_XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr)
    throw std::runtime_error("cannot create a temporary folder for the trace (" + pattern + "): " + error_text(errno));
  m_folder = pattern;
  m_pipe = m_folder / "trace.vcd";
  if (::mkfifo(m_pipe.c_str(), 0600) != 0) {
    const int error = errno;
    std::error_code ignored;
    fs::remove_all(m_folder, ignored);
    throw std::runtime_error("cannot create a pipe for the trace (" + m_pipe.string() + "): " + error_text(error));
  }
  m_thread = std::thread([this] { copy(); });
}

TracePipe::~TracePipe() {
  if (m_finished) return;
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_abandoned = true;
  }
  finish();
}

void TracePipe::copy() {
  const int in = ::open(m_pipe.c_str(), O_RDONLY | O_CLOEXEC);
  const int open_error = errno;
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    m_opened = true;
    if (in < 0) {
      m_error = "cannot read the trace's pipe: " + error_text(open_error);
      return;
    }
  }
  std::string error;
  std::unique_ptr<OutputFile> out;
  std::unique_ptr<VcdToFst> fst;
  try {
    if (!m_trace_path.empty()) {
      out = std::make_unique<OutputFile>(m_trace_path);
      std::lock_guard<std::mutex> lock(m_mutex);
      m_temporary = out->temporary_path().string();
    }
    if (!m_fst_path.empty()) fst = std::make_unique<VcdToFst>(m_fst_temporary);
  } catch (const std::exception& e) {
    error = e.what();
  }
  std::vector<char> buffer(COPY_BYTES);
  std::string head;  // held until the date can be blanked
  bool head_written = false;
  const auto write = [&](const char* bytes, size_t count) {
    if (!error.empty() || count == 0) return;
    try {
      if (out) out->write(bytes, count);
      if (fst) fst->feed(std::string_view(bytes, count));
    } catch (const std::exception& e) {
      error = e.what();
      out.reset();
      fst.reset();
    }
  };
  const auto write_head = [&] {
    blank_vcd_date(head);
    write(head.data(), head.size());
    head_written = true;
  };
  for (;;) {
    const ssize_t count = ::read(in, buffer.data(), buffer.size());
    if (count < 0 && errno == EINTR) continue;
    if (count < 0) {
      if (error.empty()) error = "cannot read the trace's pipe: " + error_text(errno);
      break;
    }
    if (count == 0) break;
    // Every byte is read, even after an error, so that SystemC never blocks.
    const auto bytes = static_cast<size_t>(count);
    if (head_written) {
      write(buffer.data(), bytes);
      continue;
    }
    const size_t taken = std::min(bytes, VCD_DATE_BYTES - head.size());
    head.append(buffer.data(), taken);
    if (head.size() == VCD_DATE_BYTES) {
      write_head();
      write(buffer.data() + taken, bytes - taken);
    }
  }
  ::close(in);
  if (!head_written) write_head();
  bool abandoned = false;
  {
    std::lock_guard<std::mutex> lock(m_mutex);
    abandoned = m_abandoned;
  }
  if (error.empty() && !abandoned) {
    try {
      // The FST first: its check fails the run before the VCD is put in place.
      if (fst) {
        fst->finish();
        fst.reset();
        if (::rename(m_fst_temporary.c_str(), m_fst_path.c_str()) != 0)
          throw std::runtime_error("cannot put the FST trace in place as '" + m_fst_path.string() +
                                   "': " + error_text(errno));
      }
      if (out) out->commit();
    } catch (const std::exception& e) {
      error = e.what();
    }
  }
  out.reset();
  fst.reset();
  std::lock_guard<std::mutex> lock(m_mutex);
  if (!m_fst_temporary.empty()) remove_fst_temporary();
  m_temporary.clear();
  if (m_error.empty()) m_error = error;
}

// What of the FST is left under its temporary names (after it was put in
// place, nothing): the file and fstapi's ".hier" beside it.
void TracePipe::remove_fst_temporary() noexcept {
  ::unlink(m_fst_temporary.c_str());
  ::unlink((m_fst_temporary + ".hier").c_str());
}

void TracePipe::release_reader() noexcept {
  const int fd = ::open(m_pipe.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd >= 0) ::close(fd);
}

std::string TracePipe::finish() {
  if (m_finished) return m_error;
  m_finished = true;
  // A copier still waiting in open() is released by a writer that opens and
  // closes the pipe; before the copier calls open() there is no reader, the
  // writer's open fails, and it is tried again.
  for (;;) {
    {
      std::lock_guard<std::mutex> lock(m_mutex);
      if (m_opened) break;
    }
    release_reader();
    ::usleep(1000);
  }
  m_thread.join();
  std::error_code ignored;
  fs::remove_all(m_folder, ignored);
  std::lock_guard<std::mutex> lock(m_mutex);
  return m_abandoned ? "" : m_error;
}

void TracePipe::abandon_from_other_thread() noexcept {
  std::lock_guard<std::mutex> lock(m_mutex);
  m_abandoned = true;
  if (!m_temporary.empty()) ::unlink(m_temporary.c_str());
  if (!m_fst_temporary.empty()) remove_fst_temporary();
  ::unlink(m_pipe.c_str());
  ::rmdir(m_folder.c_str());
}

}  // namespace tessera
