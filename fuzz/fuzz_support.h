// What the fuzz targets share: a reader that turns the fuzzer's bytes into
// values (never reading past the end: missing bytes read as zero), a
// scratch file for loaders that take a path, and the report of a broken
// invariant (an abort, which libFuzzer and the replay treat as a crash).
#pragma once

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

namespace tessera::fuzz {

[[noreturn]] inline void fail(const std::string& what) {
  std::fprintf(stderr, "fuzz target: %s\n", what.c_str());
  std::abort();
}

class ByteReader {
 public:
  ByteReader(const uint8_t* data, size_t size) : m_data(data), m_size(size) {}

  bool empty() const { return m_position >= m_size; }
  size_t remaining() const { return empty() ? 0 : m_size - m_position; }

  uint8_t u8() { return empty() ? 0 : m_data[m_position++]; }
  uint16_t u16() { return static_cast<uint16_t>(u8() | u8() << 8); }
  uint32_t u32() { return static_cast<uint32_t>(u16()) | static_cast<uint32_t>(u16()) << 16; }
  int32_t i32() {
    const uint32_t bits = u32();
    int32_t value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  float f32() {
    const uint32_t bits = u32();
    float value;
    std::memcpy(&value, &bits, sizeof value);
    return value;
  }
  bool boolean() { return (u8() & 1) != 0; }
  // One of `count` items (count > 0).
  size_t pick(size_t count) { return u8() % count; }

 private:
  const uint8_t* m_data;
  size_t m_size;
  size_t m_position = 0;
};

// A file in memory (/dev/shm) where there is one, else in the temporary
// directory; one per process, rewritten for every input of the loaders that
// read a path.
class ScratchFile {
 public:
  explicit ScratchFile(const std::string& suffix)
      : m_path(directory() / ("tessera_fuzz_" + std::to_string(::getpid()) + suffix)) {}
  ~ScratchFile() {
    std::error_code ignored;
    std::filesystem::remove(m_path, ignored);
  }
  ScratchFile(const ScratchFile&) = delete;
  ScratchFile& operator=(const ScratchFile&) = delete;

  const std::string& write(const uint8_t* data, size_t size) {
    std::ofstream out(m_path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    out.close();
    if (!out) fail("cannot write the scratch file " + m_path.string());
    m_text = m_path.string();
    return m_text;
  }

 private:
  static std::filesystem::path directory() {
    std::error_code error;
    if (std::filesystem::is_directory("/dev/shm", error) && ::access("/dev/shm", W_OK) == 0) return "/dev/shm";
    return std::filesystem::temp_directory_path();
  }
  std::filesystem::path m_path;
  std::string m_text;
};

}  // namespace tessera::fuzz
