// Semihosting: the ARM convention by which a program asks its host for
// console output, files, the time and its exit (semihosting.def lists the
// operations served). The ISS serves a call when the program executes the
// semihosting SWI (SVC 0x123456 in ARM state, 0xAB in Thumb state), as a
// debugger would with the core halted: the call itself takes no simulated
// time beyond the SWI's own cycles, and no bus traffic (memory is reached
// through debug access). The bare-metal runtime's system calls
// (sw_driver/runtime) are built on it; so is the launcher's hand-over of the
// boot information and of the driver's statistics (named files, below).
//
// Plain C++, no SystemC: the memory and the clock are a small port.
#pragma once

#include <cstdint>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace tessera::iss {

namespace semihosting {
#define TESSERA_SEMIHOSTING(name, number) inline constexpr uint32_t name = number;
#include "host/iss/semihosting.def"
#undef TESSERA_SEMIHOSTING
// The SWI comments that mean a semihosting call.
inline constexpr uint32_t ARM_SWI = 0x123456, THUMB_SWI = 0xab;
// SYS_EXIT's reason for an application's exit (ADP_Stopped_ApplicationExit).
inline constexpr uint32_t APPLICATION_EXIT = 0x20026;
// The name of the console in SYS_OPEN; modes 0-3 read it (stdin), 4-7
// write it (stdout), 8-11 append to it (stderr).
inline constexpr const char* CONSOLE = ":tt";
// SYS_ERRNO's values: newlib's numbers, which the runtime's errno uses.
inline constexpr int ERROR_NO_ENTRY = 2, ERROR_BAD_HANDLE = 9, ERROR_ACCESS = 13, ERROR_FAULT = 14, ERROR_INVALID = 22,
                     ERROR_NOT_IMPLEMENTED = 88;
}  // namespace semihosting

class SemihostingPort {
 public:
  virtual ~SemihostingPort() = default;
  // Memory without time (false: nothing there).
  virtual bool read_memory(uint32_t address, uint8_t* data, unsigned bytes) = 0;
  virtual bool write_memory(uint32_t address, const uint8_t* data, unsigned bytes) = 0;
  // The core's cycles since the program started, and its clock.
  virtual uint64_t elapsed_cycles() = 0;
  virtual uint32_t clock_hz() = 0;
};

class Semihosting {
 public:
  explicit Semihosting(SemihostingPort& port) : m_port(port) {}

  // True if `instruction` (32 bits in ARM state, 16 in Thumb) is the
  // semihosting SWI.
  static bool is_call(uint32_t instruction, bool thumb);

  // Serves operation `op` with parameter `parameter` (the program's r0 and
  // r1); returns the value for r0. An unknown operation returns -1 with
  // errno ENOSYS and is reported once through `warn`.
  uint32_t serve(uint32_t op, uint32_t parameter);

  // Where the console goes: stream 1 (stdout) or 2 (stderr), text as written.
  std::function<void(int stream, const std::string& text)> console;
  // Problems worth a warning that are not the program's failure.
  std::function<void(const std::string& message)> warn;
  // The command line SYS_GET_CMDLINE returns.
  std::string command_line;
  // Whether SYS_OPEN may open the host's files for reading (never for
  // writing: a simulated program does not change the host's files).
  bool host_files = true;

  // A file the program may open for reading by `name` (e.g. ":tessera/boot").
  void offer_file(const std::string& name, std::string content);
  // A file the program may open for writing by `name`; every write is handed to `sink`.
  void offer_sink(const std::string& name, std::function<void(const std::string& data)> sink);

  bool exited() const { return m_exited; }
  int exit_status() const { return m_exit_status; }

 private:
  struct Handle {
    enum class Kind { console_in, console_out, console_error, content, host_file, sink } kind;
    std::string content;  // kind content
    size_t position = 0;  // kind content
    std::unique_ptr<std::ifstream> file;
    uint64_t file_length = 0;
    std::function<void(const std::string&)> sink;
  };
  uint32_t fail(int error);
  bool words(uint32_t address, uint32_t* out, unsigned count);
  Handle* handle(uint32_t number);
  uint32_t open(uint32_t block);
  uint32_t write(uint32_t block);
  uint32_t read(uint32_t block);
  uint32_t seek(uint32_t block);
  uint32_t length(uint32_t block);
  uint32_t get_command_line(uint32_t block);
  bool read_string(uint32_t address, uint32_t length, std::string& out);

  SemihostingPort& m_port;
  std::map<std::string, std::string> m_files;
  std::map<std::string, std::function<void(const std::string&)>> m_sinks;
  std::vector<std::unique_ptr<Handle>> m_handles;  // index + 1 is the handle's number
  int m_errno = 0;
  bool m_exited = false;
  int m_exit_status = 0;
  std::vector<uint32_t> m_warned;
};

}  // namespace tessera::iss
