#include "run_outputs.h"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>

#include <nlohmann/json.hpp>

#include "fstapi.h"

namespace fs = std::filesystem;

namespace tessera {

namespace {

constexpr size_t TRACE_HEADER_BYTES = 4096;  // SystemC's header and the first scopes fit easily

bool is_empty_file(const fs::path& path) {
  std::error_code error;
  return fs::is_regular_file(path, error) && fs::file_size(path, error) == 0 && !error;
}

bool same_file(const fs::path& a, const fs::path& b) {
  std::error_code error;
  return fs::equivalent(a, b, error) && !error;
}

bool listed(const EarlierOutputs& outputs, const fs::path& path) {
  const auto is_it = [&](const fs::path& other) { return same_file(other, path); };
  return std::any_of(outputs.files.begin(), outputs.files.end(), is_it) ||
         std::any_of(outputs.foreign.begin(), outputs.foreign.end(), is_it);
}

// One of this run's own paths: soc_sim's file of that kind is an earlier
// output, an empty file is nothing, anything else is foreign.
void check_own_path(const fs::path& path, bool (*written_by_soc_sim)(const fs::path&), EarlierOutputs& outputs) {
  std::error_code error;
  if (path.empty() || !fs::is_regular_file(path, error) || listed(outputs, path) || is_empty_file(path)) return;
  (written_by_soc_sim(path) ? outputs.files : outputs.foreign).push_back(path);
}

}  // namespace

std::string frame_file_name(unsigned index) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04u.png", index);
  return name;
}

bool is_frame_file_name(const std::string& name) {
  const std::string prefix = "frame_", suffix = ".png";
  if (name.size() < prefix.size() + 4 + suffix.size()) return false;
  if (name.compare(0, prefix.size(), prefix) != 0) return false;
  if (name.compare(name.size() - suffix.size(), suffix.size(), suffix) != 0) return false;
  return std::all_of(name.begin() + static_cast<std::ptrdiff_t>(prefix.size()),
                     name.end() - static_cast<std::ptrdiff_t>(suffix.size()),
                     [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; });
}

bool is_soc_sim_stats(const fs::path& path) {
  std::ifstream in(path);
  if (!in) return false;
  const nlohmann::json document = nlohmann::json::parse(in, nullptr, false);
  return document.is_object() && document.contains("config") && document.contains("stats") &&
         document.contains("exit_status");
}

bool is_soc_sim_trace(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string head(TRACE_HEADER_BYTES, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  const auto version = head.find("$version");
  const auto top = head.find("$scope module SystemC $end");
  const auto soc = head.find("$scope module soc $end");
  return head.rfind("$date", 0) == 0 && version != std::string::npos &&
         head.find("SystemC", version) != std::string::npos && top != std::string::npos && soc != std::string::npos &&
         top < soc && head.find_first_not_of(" \t\r\n", top + 26) == soc;
}

bool is_soc_sim_fst(const fs::path& path) {
  void* reader = fstReaderOpen(path.c_str());
  if (reader == nullptr) return false;
  const char* version = fstReaderGetVersionString(reader);
  const bool systemc = version != nullptr && std::strstr(version, "SystemC") != nullptr;
  fstReaderClose(reader);
  return systemc;
}

bool is_soc_sim_report(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::string head(TRACE_HEADER_BYTES, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head.find(std::string("<meta name=\"generator\" content=\"") + RUN_REPORT_GENERATOR + "\">") !=
         std::string::npos;
}

EarlierOutputs find_earlier_outputs(const OutputPaths& paths) {
  EarlierOutputs outputs;
  std::error_code error;
  if (fs::is_directory(paths.out_dir, error)) {
    for (const auto& entry : fs::directory_iterator(paths.out_dir, error)) {
      if (!entry.is_regular_file(error)) continue;
      const fs::path& path = entry.path();
      const std::string name = path.filename().string();
      if (is_frame_file_name(name))
        outputs.frames.push_back(path);
      else if ((name == "stats.json" && is_soc_sim_stats(path)) ||
               (path.extension() == ".vcd" && is_soc_sim_trace(path)) ||
               (path.extension() == ".fst" && is_soc_sim_fst(path)))
        outputs.files.push_back(path);
    }
  }
  std::sort(outputs.frames.begin(), outputs.frames.end());
  std::sort(outputs.files.begin(), outputs.files.end());
  check_own_path(paths.stats, is_soc_sim_stats, outputs);
  check_own_path(paths.trace, is_soc_sim_trace, outputs);
  check_own_path(paths.fst, is_soc_sim_fst, outputs);
  check_own_path(paths.report, is_soc_sim_report, outputs);
  return outputs;
}

std::string describe_outputs(const EarlierOutputs& outputs, const fs::path& out_dir) {
  const auto shown = [&](const fs::path& path) {
    const fs::path relative = path.lexically_relative(out_dir);
    return !relative.empty() && *relative.begin() != ".." ? relative.string() : path.string();
  };
  std::string text;
  if (!outputs.frames.empty()) {
    const size_t count = outputs.frames.size();
    text = std::to_string(count) + (count == 1 ? " frame (" : " frames (") + shown(outputs.frames.front());
    if (count > 1) text += (count == 2 ? ", " : " ... ") + shown(outputs.frames.back());
    text += ")";
  }
  for (const auto& file : outputs.files) text += (text.empty() ? "" : ", ") + shown(file);
  return text;
}

void remove_earlier_outputs(const EarlierOutputs& outputs) {
  for (const auto* list : {&outputs.frames, &outputs.files})
    for (const auto& path : *list) {
      std::error_code error;
      if (!fs::remove(path, error) && error)
        throw std::runtime_error("cannot remove '" + path.string() + "' of an earlier run: " + error.message());
    }
}

OutputFolderClaim::OutputFolderClaim(const fs::path& out_dir) : m_path(out_dir / OUTPUT_FOLDER_LOCK) {
  // A run that ends unlinks the file it locked: a run that opened that file
  // just before then holds a lock on a file no longer in the folder, so it
  // checks that the path still names the file it locked, and tries again if
  // not. A few rounds settle it; the bound only keeps a pathological folder
  // from looping.
  for (int round = 0; round < 100; ++round) {
    const int fd = ::open(m_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0)
      throw std::runtime_error("output folder '" + out_dir.string() + "': cannot create '" + m_path.string() +
                               "': " + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      char holder[32] = {};
      const ssize_t got = ::pread(fd, holder, sizeof holder - 1, 0);
      ::close(fd);
      if (error != EWOULDBLOCK)
        throw std::runtime_error("output folder '" + out_dir.string() + "': cannot lock '" + m_path.string() +
                                 "': " + std::strerror(error));
      std::string pid(holder, got > 0 ? static_cast<size_t>(got) : 0);
      while (!pid.empty() && !std::isdigit(static_cast<unsigned char>(pid.back()))) pid.pop_back();
      throw std::runtime_error("output folder '" + out_dir.string() + "' is in use by another run of soc_sim" +
                               (pid.empty() ? std::string() : " (process " + pid + ")") +
                               ": wait until it has finished, or choose another folder with --out");
    }
    struct stat locked {};
    struct stat named {};
    if (::fstat(fd, &locked) == 0 && ::stat(m_path.c_str(), &named) == 0 && locked.st_dev == named.st_dev &&
        locked.st_ino == named.st_ino) {
      m_fd = fd;
      const std::string pid = std::to_string(::getpid()) + "\n";
      if (::ftruncate(fd, 0) == 0) {
        [[maybe_unused]] const ssize_t written = ::pwrite(fd, pid.data(), pid.size(), 0);
      }
      return;
    }
    ::close(fd);
  }
  throw std::runtime_error("output folder '" + out_dir.string() + "': cannot claim '" + m_path.string() +
                           "': it keeps being replaced");
}

void OutputFolderClaim::unlink_from_other_thread() const noexcept {
  if (m_fd >= 0) ::unlink(m_path.c_str());
}

OutputFolderClaim::~OutputFolderClaim() {
  if (m_fd < 0) return;
  // Unlinked while still locked: a run waiting on this file sees it gone
  // and takes a new one.
  ::unlink(m_path.c_str());
  ::close(m_fd);
}

}  // namespace tessera
