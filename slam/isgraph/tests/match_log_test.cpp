// The matching's log (MatchLog): status changes once each, attempts and their times, and its part
// of sgraph.json.
#include "slam/isgraph/match_log.hpp"

#include <gtest/gtest.h>

namespace isg::slam {
namespace {

TEST(MatchLog, AStatusIsRecordedWhenItChanges) {
  MatchLog log;
  EXPECT_EQ(log.status(), MatchStatus::kNotYet);
  log.record(0.5, 0, MatchStatus::kNotYet, "first attempt");  // the first is always recorded
  log.record(1.0, 1, MatchStatus::kNotYet, "again");
  log.record(2.0, 3, MatchStatus::kMatched, "unique");
  log.record(3.0, 4, MatchStatus::kMatched, "still");
  log.record(4.0, 6, MatchStatus::kLost, "the scans no longer agree with the plan");
  ASSERT_EQ(log.events().size(), 3u);
  EXPECT_EQ(log.events()[1].stamp, 2.0);
  EXPECT_EQ(log.events()[1].keyframe, 3);
  EXPECT_EQ(log.events()[2].reason, "the scans no longer agree with the plan");
  EXPECT_EQ(log.status(), MatchStatus::kLost);
}

TEST(MatchLog, ItsPartOfTheGraphJson) {
  MatchLog log;
  MatchResult result;
  result.status = MatchStatus::kAmbiguous;
  result.seconds = 0.25;
  log.attempted(result);
  log.attempted(result);
  log.record(1.0, 2, MatchStatus::kMatched, "unique");
  log.contradicted();
  log.lost();
  log.lost();
  log.moved({5.0, 0.5, 10.0, 14.0});
  EXPECT_EQ(log.matchingTimes(), (std::vector<double>{0.25, 0.25}));
  ASSERT_TRUE(log.lastMatch().has_value());
  nlohmann::json matching;
  log.addTo(matching);
  EXPECT_EQ(matching["status"], "matched");
  EXPECT_EQ(matching["contradictions"], 1);
  EXPECT_EQ(matching["times_lost"], 2);
  EXPECT_EQ(matching["answer_moves"][0]["moved_m"], 0.5);
  EXPECT_EQ(matching["answer_moves"][0]["walls_agreeing_after"], 14.0);
  EXPECT_EQ(matching["events"][0]["keyframe"], 2);
  EXPECT_TRUE(matching.contains("last_match"));
}

}  // namespace
}  // namespace isg::slam
