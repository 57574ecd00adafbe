// Unit tests of VcdToFst (tools/soc_sim/vcd_to_fst.h): a small hand-written
// VCD, fed whole and a byte at a time, read back through GTKWave's own FST
// reader; and the VCD it cannot translate, refused with the line and why.
#include "vcd_to_fst.h"

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fixtures/scratch_folder_test.h"
#include "fstapi.h"

namespace {

namespace fs = std::filesystem;
using tessera::VcdToFst;

// Scalars, a 4-bit vector given short (leading zeros left out, as VCD
// allows, and an x to widen), a real, an alias in another scope, a
// comment and $dumpvars.
const std::string VCD = R"($date today $end
$version a hand-written VCD $end
$timescale 1 ns $end
$scope module top $end
$var wire 1 ! clk $end
$var wire 4 " bus [3:0] $end
$var real 1 # power $end
$scope module sub $end
$var wire 1 ! clk_again $end
$upscope $end
$upscope $end
$enddefinitions $end
$comment the values at the start $end
$dumpvars
0!
b0 "
r0 #
$end
#10
1!
b101 "
r1.5 #
#20
0!
bx "
#35
b1111 "
)";

struct Change {
  uint64_t time;
  fstHandle handle;
  std::string value;
  bool operator==(const Change& other) const {
    return time == other.time && handle == other.handle && value == other.value;
  }
};

std::ostream& operator<<(std::ostream& out, const Change& change) {
  return out << "(" << change.time << ", " << change.handle << ", " << change.value << ")";
}

struct ReadBack {
  uint64_t variables = 0, handles = 0, end_time = 0;
  signed char timescale = 0;  // the exponent of ten of the time unit, as fstapi gives it
  std::vector<Change> changes;
};

ReadBack read_fst(const fs::path& path) {
  void* reader = fstReaderOpen(path.c_str());
  if (reader == nullptr) throw std::runtime_error("fstReaderOpen failed on " + path.string());
  ReadBack back;
  back.variables = fstReaderGetVarCount(reader);
  back.handles = fstReaderGetMaxHandle(reader);
  back.end_time = fstReaderGetEndTime(reader);
  back.timescale = fstReaderGetTimescale(reader);
  fstReaderSetFacProcessMaskAll(reader);
  fstReaderIterBlocks(
      reader,
      [](void* data, uint64_t time, fstHandle handle, const unsigned char* value) {
        static_cast<ReadBack*>(data)->changes.push_back({time, handle, reinterpret_cast<const char*>(value)});
      },
      &back, nullptr);
  fstReaderClose(reader);
  // The reader gives a time's changes in no set order.
  std::sort(back.changes.begin(), back.changes.end(),
            [](const Change& a, const Change& b) { return a.time != b.time ? a.time < b.time : a.handle < b.handle; });
  return back;
}

class VcdToFstTest : public tessera::test::ScratchFolderTest {};

void expect_translated(const ReadBack& back) {
  EXPECT_EQ(back.variables, 4u);  // the alias counts as a variable, not a handle
  EXPECT_EQ(back.handles, 3u);
  EXPECT_EQ(back.timescale, static_cast<signed char>(-9));  // ns
  EXPECT_EQ(back.end_time, 35u);
  // Handles in the order of declaration: clk 1, bus 2, power 3.
  const std::vector<Change> expected = {{0, 1, "0"},  {0, 2, "0000"},  {0, 3, "0"},
                                        {10, 1, "1"}, {10, 2, "0101"}, {10, 3, "1.5"},
                                        {20, 1, "0"}, {20, 2, "xxxx"}, {35, 2, "1111"}};
  EXPECT_EQ(back.changes, expected);
}

TEST_F(VcdToFstTest, TranslatesAWholeVcd) {
  VcdToFst fst(m_dir / "whole.fst");
  fst.feed(VCD);
  fst.finish();
  expect_translated(read_fst(m_dir / "whole.fst"));
  EXPECT_FALSE(fs::exists(m_dir / "whole.fst.hier"));
}

TEST_F(VcdToFstTest, TranslatesAVcdFedAByteAtATime) {
  VcdToFst fst(m_dir / "bytes.fst");
  for (char c : VCD) fst.feed(std::string(1, c));
  fst.finish();
  expect_translated(read_fst(m_dir / "bytes.fst"));
}

// The message of what VcdToFst throws for `vcd`, fed whole then finished.
std::string error_for(const fs::path& path, const std::string& vcd) {
  try {
    VcdToFst fst(path);
    fst.feed(vcd);
    fst.finish();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST_F(VcdToFstTest, RefusesWhatItCannotTranslateNamingTheLine) {
  const std::string header =
      "$timescale 1 ps $end $scope module m $end $var wire 1 ! a $end $upscope $end\n"
      "$enddefinitions $end\n";
  const fs::path path = m_dir / "bad.fst";
  EXPECT_NE(error_for(path, header + "#5\n1?\n").find("VCD line 4: unknown variable id '?'"), std::string::npos);
  EXPECT_NE(error_for(path, header + "#5\n#4\n").find("time 4 goes back from 5"), std::string::npos);
  EXPECT_NE(error_for(path, header + "#5\nr1.5 !\n").find("a real value for the bit variable '!'"), std::string::npos);
  EXPECT_NE(error_for(path, header + "#5\nb102 !\n").find("bad value 'b102'"), std::string::npos);
  EXPECT_NE(error_for(path, header + "#5\nb1\n").find("ended after the value 'b1' without its id"), std::string::npos);
  EXPECT_NE(error_for(path, "$timescale 1 ps $end $var wire 1 ! a $end").find("ended before its $enddefinitions"),
            std::string::npos);
  EXPECT_NE(error_for(path, "$var wire wide ! a $end").find("bad width in $var 'wire wide ! a'"), std::string::npos);
  EXPECT_NE(error_for(path, "$timescale 1 ps").find("ended inside $timescale"), std::string::npos);
}

TEST_F(VcdToFstTest, AnUnwritablePathIsAnErrorNamingIt) {
  const fs::path path = m_dir / "no such folder" / "trace.fst";
  try {
    VcdToFst fst(path);
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot create the FST trace '" + path.string() + "'"), std::string::npos)
        << e.what();
  }
}

}  // namespace
