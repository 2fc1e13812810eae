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

}  // namespace
}  // namespace isg::common
