#include "common/plural.hpp"

#include <gtest/gtest.h>

namespace isg::common {
namespace {

TEST(Counted, OneIsSingularEveryOtherCountPlural) {
  EXPECT_EQ(counted(1, "door"), "1 door");
  EXPECT_EQ(counted(0, "door"), "0 doors");
  EXPECT_EQ(counted(2, "message"), "2 messages");
  EXPECT_EQ(counted(1, "body", "bodies"), "1 body");
  EXPECT_EQ(counted(7, "body", "bodies"), "7 bodies");
  EXPECT_EQ(counted(18446744073709551615ull, "scan"), "18446744073709551615 scans");
}

TEST(NamedList, NamesTheFirstTenAndCountsTheRest) {
  EXPECT_EQ(namedList({}), "");
  EXPECT_EQ(namedList({"R1"}), "R1");
  EXPECT_EQ(namedList({"C1", "C2", "R1"}), "C1, C2, R1");
  std::vector<std::string> rooms;
  for (int i = 1; i <= 606; ++i) rooms.push_back(std::string("R").append(std::to_string(i)));
  EXPECT_EQ(namedList(rooms), "R1, R2, R3, R4, R5, R6, R7, R8, R9, R10 and 596 more (606 in all)");
  rooms.resize(10);
  EXPECT_EQ(namedList(rooms), "R1, R2, R3, R4, R5, R6, R7, R8, R9, R10");
  EXPECT_EQ(namedList({"A", "B", "C"}, 2), "A, B and 1 more (3 in all)");
}

}  // namespace
}  // namespace isg::common
