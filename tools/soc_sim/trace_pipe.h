// The VCD trace through a pipe. SystemC's VCD writer writes with stdio and
// never reports a failed write (a full disk left a truncated trace behind a
// run that exited 0). So the SoC traces into a named pipe in a private
// temporary folder, and a thread of this class copies what arrives into the
// trace file through OutputFile, which checks every write and puts the file
// in place only when it is whole. The copier blanks the header's date as the
// SoC does for a file (blank_vcd_date), so the bytes are those a direct
// trace would have.
#pragma once

#include <filesystem>
#include <mutex>
#include <string>
#include <thread>

namespace tessera {

class TracePipe {
 public:
  // Creates the pipe and starts the copier; throws naming what failed.
  explicit TracePipe(std::filesystem::path trace_path);
  ~TracePipe();  // abandons the trace unless finish() was called

  // The path to give SocRecorder::trace_to (without ".vcd").
  std::string systemc_base() const { return (m_folder / "trace").string(); }
  // After SocRecorder::close_trace: waits for the copier and puts the trace in
  // place. Returns the first error ("cannot write 'out/trace.vcd': No space
  // left on device"), or "" when the trace is whole.
  std::string finish();
  // Removes the temporary trace: for a run that ends without closing the
  // trace (a hard stop). Safe from another thread; does not wait.
  void abandon_from_other_thread() noexcept;

 private:
  void copy();
  void release_reader() noexcept;

  std::filesystem::path m_trace_path;
  std::filesystem::path m_folder;  // private temporary folder holding the pipe
  std::filesystem::path m_pipe;
  std::mutex m_mutex;
  std::string m_error;
  std::string m_temporary;   // the OutputFile's temporary path, for abandon
  bool m_opened = false;     // the copier has opened the pipe
  bool m_abandoned = false;  // the trace is not to be put in place
  bool m_finished = false;
  std::thread m_thread;
};

}  // namespace tessera
