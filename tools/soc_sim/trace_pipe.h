// The VCD trace through a pipe. SystemC's VCD writer writes with stdio and
// never reports a failed write (a full disk left a truncated trace behind a
// run that exited 0). So the SoC traces into a named pipe in a private
// temporary folder, and a thread of this class copies what arrives into the
// trace file through OutputFile, which checks every write and puts the file
// in place only when it is whole. The copier blanks the header's date as the
// SoC does for a file (blank_vcd_date), so the bytes are those a direct
// trace would have. With an FST trace (--fst), the copier also feeds what
// arrives to VcdToFst, which writes the FST under a temporary name beside
// it, put in place when whole: the VCD file is then optional, and no VCD
// lands on disk unless asked for.
#pragma once

#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

namespace tessera {

class TracePipe {
 public:
  // Creates the pipe and starts the copier, for a VCD at `vcd_path`, an FST
  // at `fst_path`, or both (an empty path: none of that kind); throws
  // naming what failed.
  TracePipe(std::filesystem::path vcd_path, std::filesystem::path fst_path);
  ~TracePipe();  // abandons the trace unless finish() was called

  // The path to give SocRecorder::trace_to (without ".vcd").
  std::string systemc_base() const { return (m_folder / "trace").string(); }
  // After SocRecorder::close_trace: waits for the copier and puts the trace in
  // place. Returns the first error ("cannot write 'out/trace.vcd': No space
  // left on device"), or "" when the traces are whole.
  std::string finish();
  // Removes the temporary trace: for a run that ends without closing the
  // trace (a hard stop). Safe from another thread; does not wait.
  void abandon_from_other_thread() noexcept;

 private:
  void copy();
  void release_reader() noexcept;
  void remove_fst_temporary() noexcept;

  std::filesystem::path m_trace_path;  // the VCD's (empty: none)
  std::filesystem::path m_fst_path;    // empty: none
  std::string m_fst_temporary;         // where the FST is written until whole
  std::filesystem::path m_folder;      // private temporary folder holding the pipe
  std::filesystem::path m_pipe;
  std::mutex m_mutex;
  std::string m_error;
  std::string m_temporary;   // the VCD OutputFile's temporary path, for abandon
  bool m_opened = false;     // the copier has opened the pipe
  bool m_abandoned = false;  // the trace is not to be put in place
  bool m_finished = false;
  std::thread m_thread;
};

}  // namespace tessera
