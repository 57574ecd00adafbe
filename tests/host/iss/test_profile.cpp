// The per-function profile's look-up (tlm/host/iss/profile.h): the function
// holding a PC, found by a binary search of the symbol table or by the memo
// of earlier answers, against a linear scan written here.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "host/iss/profile.h"

namespace {

using tessera::iss::ElfFunction;
using tessera::iss::Profile;

// Functions with gaps between them, one of size 0 (a label), sorted by
// address as ElfImage lists them.
std::vector<ElfFunction> functions() {
  return {{"first", 0x8000, 0x40},
          {"label", 0x8040, 0},
          {"second", 0x8040, 0x100},
          {"third", 0x8200, 0x20},
          {"last", 0x9000, 0x1000}};
}

// The index a linear scan finds: the function holding pc, or the count of
// functions for an address outside them all.
uint32_t scanned_index(const std::vector<ElfFunction>& table, uint32_t pc) {
  uint32_t found = static_cast<uint32_t>(table.size());
  for (uint32_t i = 0; i < table.size(); ++i)
    if (pc - table[i].address < table[i].size) found = i;
  return found;
}

TEST(Profile, EveryLookUpAgreesWithALinearScanWhateverTheOrder) {
  const std::vector<ElfFunction> table = functions();
  Profile profile(table);
  std::mt19937 random(7);
  // PCs inside and around the functions, and PCs that share a memo slot
  // (1,024 slots by pc / 2) with them but lie far outside.
  std::vector<uint32_t> pcs;
  for (uint32_t pc = 0x7ff0; pc < 0xa010; pc += 2) pcs.push_back(pc);
  for (uint32_t pc = 0x8000; pc < 0x8300; pc += 2) pcs.push_back(pc + 2 * 1024 * 16);
  for (int round = 0; round < 20000; ++round) {
    const uint32_t pc = pcs[random() % pcs.size()];
    const uint32_t expected = scanned_index(table, pc);
    Profile::Entry& entry = profile.at(pc);
    ASSERT_EQ(profile.last_index(), expected) << "pc 0x" << std::hex << pc;
    ASSERT_TRUE(profile.holds(pc)) << "pc 0x" << std::hex << pc;
    // The entry is the function's own: a count made through it is found
    // again through another PC of the same function.
    ++entry.instructions;
  }
  uint64_t counted = 0;
  for (const Profile::Row& row : profile.rows()) counted += row.entry.instructions;
  EXPECT_EQ(counted, 20000u);
}

TEST(Profile, ARangeOutsideTheFunctionsEndsAtTheNextOne) {
  Profile profile(functions());
  profile.at(0x8100);  // into second
  profile.at(0x8180);  // the gap between second and third
  EXPECT_EQ(profile.last_index(), functions().size());
  EXPECT_TRUE(profile.holds(0x81fe));
  EXPECT_FALSE(profile.holds(0x8200));  // third
  // The same gap's PC again, now from the memo: the same range.
  profile.at(0x8200);
  profile.at(0x8180);
  EXPECT_TRUE(profile.holds(0x81fe));
  EXPECT_FALSE(profile.holds(0x8200));
  EXPECT_FALSE(profile.holds(0x817e));  // the range starts at the PC it was found for
}

}  // namespace
