// Unit tests of OutputFile (tools/common/output_file.h): files whole or
// absent, every failed write reported with the file and the reason.
#include "output_file.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include <gtest/gtest.h>

#include "fixtures/scratch_folder_test.h"

namespace {

namespace fs = std::filesystem;
using tessera::OutputFile;
using tessera::write_file_atomically;

std::string read_file(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

class OutputFileTest : public tessera::test::ScratchFolderTest {
 protected:
  // Every name in the folder, to show that no temporary file is left.
  std::string listing() const {
    std::string names;
    for (const auto& entry : fs::directory_iterator(m_dir)) names += entry.path().filename().string() + " ";
    return names;
  }
};

TEST_F(OutputFileTest, WritesTheFileAndLeavesNothingElse) {
  write_file_atomically(m_dir / "stats.json", "{}\n");
  EXPECT_EQ(read_file(m_dir / "stats.json"), "{}\n");
  EXPECT_EQ(listing(), "stats.json ");
}

TEST_F(OutputFileTest, TheEarlierFileStaysUntilTheNewOneIsWhole) {
  write_file_atomically(m_dir / "stats.json", "old");
  {
    OutputFile file(m_dir / "stats.json");
    file.write("new, half");
    EXPECT_EQ(read_file(m_dir / "stats.json"), "old");
    // Abandoned (destroyed without commit): the earlier file is untouched.
  }
  EXPECT_EQ(read_file(m_dir / "stats.json"), "old");
  EXPECT_EQ(listing(), "stats.json ");
  OutputFile file(m_dir / "stats.json");
  file.write("new");
  file.commit();
  EXPECT_EQ(read_file(m_dir / "stats.json"), "new");
}

TEST_F(OutputFileTest, AFullDeviceIsAnErrorNamingTheFileAndTheReason) {
  try {
    write_file_atomically("/dev/full", "bytes");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "cannot write '/dev/full': No space left on device");
  }
  EXPECT_TRUE(fs::is_character_file("/dev/full"));
}

TEST_F(OutputFileTest, ALinkIsWrittenThrough) {
  fs::create_symlink("/dev/full", m_dir / "frame.png");
  EXPECT_THROW(write_file_atomically(m_dir / "frame.png", "png"), std::runtime_error);
  EXPECT_TRUE(fs::is_symlink(m_dir / "frame.png"));
  write_file_atomically(m_dir / "target", "old");
  fs::create_symlink("target", m_dir / "link");
  write_file_atomically(m_dir / "link", "new");
  EXPECT_TRUE(fs::is_symlink(m_dir / "link"));
  EXPECT_EQ(read_file(m_dir / "target"), "new");
}

TEST_F(OutputFileTest, AFolderOrAMissingFolderIsAnError) {
  fs::create_directory(m_dir / "folder");
  EXPECT_THROW(write_file_atomically(m_dir / "folder", "x"), std::runtime_error);
  try {
    write_file_atomically(m_dir / "missing/stats.json", "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("missing/stats.json': No such file or directory"), std::string::npos)
        << e.what();
  }
}

}  // namespace
