// A wall's status is decided in one place, row by row as docs/deviations.md's status table says.
#include "slam/deviations/wall_status.hpp"

#include <gtest/gtest.h>

namespace isg::slam {
namespace {

// A wall seen over half its 4 m, on evidence seen from 5 keyframes, neither turned nor shifted.
StatusEvidence seenWell() {
  StatusEvidence e;
  e.has_evidence = true;
  e.observed_share = 0.5;
  e.most_observed = 5;
  e.planned_length = 4.0;
  return e;
}

TEST(WallStatusDecision, SeenOverTheJudgedShareAndNotOffIsAsPlanned) {
  EXPECT_EQ(decideWallStatus(seenWell(), {}), WallStatus::kAsPlanned);
}

TEST(WallStatusDecision, TurnedIsRotatedEvenWhenAlsoShifted) {
  StatusEvidence e = seenWell();
  e.turned = e.shifted = true;
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kRotated);
  e.turned = false;
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kShifted);
}

TEST(WallStatusDecision, ADeviationSeenFromTooFewKeyframesIsNotBelieved) {
  StatusEvidence e = seenWell();
  e.shifted = true;
  e.most_observed = 2;  // under min_deviation_observations (3)
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kNotSeen);
  e.shifted = false;  // as planned needs no such count: the plan is the prior
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kAsPlanned);
}

TEST(WallStatusDecision, ADeviationNotClearOfItsUncertaintyIsNotEnoughData) {
  StatusEvidence e = seenWell();
  e.undecided = true;  // beyond its threshold, within clear_factor σ of zero
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kNotSeen);
  e.shifted = true;  // the other measure is clear: judged by it
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kShifted);
}

TEST(WallStatusDecision, SeenTooLittleIsMissingOnlyWhenInViewAndLongEnough) {
  StatusEvidence e = seenWell();
  e.observed_share = 0.19;  // under judged_share (0.2): not judged, whatever the offset
  e.shifted = true;
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kNotSeen);
  e.observed_share = 0.04;  // under missing_seen_share (0.05)
  e.in_view_share = 0.6;    // missing_view_share
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kMissing);
  e.in_view_share = 0.59;
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kNotSeen);
  e.with_sight = true;  // sight lines recorded: 40 % seen past is enough
  e.in_view_share = 0.4;
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kMissing);
  e.planned_length = 0.99;  // a wall under min_missing_length is never missing
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kNotSeen);
  e.planned_length = 4.0;
  e.in_view_share.reset();  // not measured: not missing
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kNotSeen);
}

TEST(WallStatusDecision, NoEvidenceIsNeverJudged) {
  StatusEvidence e;
  e.planned_length = 4.0;
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kNotSeen);
  e.in_view_share = 0.9;
  EXPECT_EQ(decideWallStatus(e, {}), WallStatus::kMissing);
}

}  // namespace
}  // namespace isg::slam
