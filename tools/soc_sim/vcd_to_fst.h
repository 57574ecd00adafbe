// A VCD stream translated into an FST file as it arrives, through GTKWave's
// own FST writer (fstapi, as Verilator bundles it): soc_sim --fst. The VCD
// SystemC writes into the trace pipe is fed in pieces of any size; every
// scope, variable (wire or real, aliases kept), time and value change goes
// to the writer, so the FST holds the same signals as the VCD and no VCD
// lands on disk. The VCD is the subset SystemC and GTKWave's fst2vcd write:
// $date, $version, $timescale, $scope/$upscope, $var, $comment, $dumpvars
// and the body's #time, scalar (0!), vector (b101 !) and real (r1.5 !)
// changes. The FST writer reports no failed write of its own, so finish()
// reads the file back and checks its variables and end time.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace tessera {

class VcdToFst {
 public:
  // Creates the FST file at `path` (and, while writing, fstapi's
  // "<path>.hier" beside it). Throws std::runtime_error naming the path.
  explicit VcdToFst(std::filesystem::path path);
  ~VcdToFst();  // closes the writer if finish() was not called
  VcdToFst(const VcdToFst&) = delete;
  VcdToFst& operator=(const VcdToFst&) = delete;

  // The next bytes of the VCD. Throws std::runtime_error on a VCD it cannot
  // translate ("VCD line 12: unknown variable id 'aaz'").
  void feed(std::string_view bytes);
  // The VCD has ended: closes the FST and checks that it reads back with
  // every variable and the last time. Throws naming what is wrong.
  void finish();

 private:
  struct Variable {
    uint32_t handle;
    uint32_t width;
    bool real;
  };
  void token(std::string_view text);
  void header_token(std::string_view text);
  void declaration_done();
  void body_token(std::string_view text);
  void emit(const std::string& id, std::string_view value);
  [[noreturn]] void fail(const std::string& reason) const;

  std::filesystem::path m_path;
  void* m_writer = nullptr;
  std::string m_partial;  // a token split between two feeds
  uint64_t m_line = 1;
  bool m_body = false;                   // after $enddefinitions
  std::string m_section;                 // the $keyword whose tokens are being gathered
  std::vector<std::string> m_arguments;  // its tokens so far
  std::string m_pending_value;           // "b101" or "r1.5", waiting for its id
  std::unordered_map<std::string, Variable> m_variables;
  uint64_t m_declared = 0;  // $var declarations, aliases included
  std::string m_bits;       // a vector's value widened to its variable
  uint64_t m_time = 0;
  bool m_has_time = false;
};

}  // namespace tessera
