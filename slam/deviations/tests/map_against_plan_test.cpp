// The map against the plan measured from points given directly, by hand on the two-room plan:
// W2's inner face is x = 5.9 from y = 0.1 to 3.9 (looking to −x, into the East room), cut in
// four stretches of 0.95 m. Walls 3 m high, so with the 0.2 m margin a point counts between
// z = 0.2 and 2.8. (run/tests/map_to_plan_levels_test.cpp measures the same through a run's
// placed scans.)
#include "slam/deviations/map_against_plan.hpp"

#include <gtest/gtest.h>

#include "bim/agraph.hpp"
#include "bim/tests/test_plans.hpp"

namespace isg::slam {
namespace {

class MeasureMapAgainstPlan : public ::testing::Test {
 protected:
  MeasureMapAgainstPlan()
      : agraph_(bim::buildAGraph(bim::testing::parsePlanJson(bim::testing::twoRoomPlanJson()))) {
    for (int i = 0; i < 40; ++i) {
      const double y = 0.2 + 0.02 * i;
      points_.emplace_back(5.87, y, 1.0);  // 3 cm in front of W2's face
    }
    points_.emplace_back(4.5, 2.0, 1.0);   // near no face: the level's by its floor
    points_.emplace_back(4.5, 2.0, 0.05);  // the floor: in no band
  }

  MapPointSource source() const {
    return [this](const std::function<void(const Eigen::Vector3d&)>& visit) {
      for (const auto& p : points_) visit(p);
    };
  }

  bim::AGraph agraph_;
  std::vector<Eigen::Vector3d> points_;
};

TEST_F(MeasureMapAgainstPlan, AStretchHoldsTheSignedMeanOfThePointsNearestItsFace) {
  const auto levels = measureMapAgainstPlan(agraph_, {"L0"}, source());
  ASSERT_EQ(levels.size(), 1u);
  EXPECT_EQ(levels[0].points, 41u);
  EXPECT_NEAR(levels[0].near_share, 40.0 / 41.0, 1e-12);
  EXPECT_NEAR(levels[0].median_m, 0.03, 1e-3);
  ASSERT_EQ(levels[0].stretches.size(), 1u);
  const FaceStretch& stretch = levels[0].stretches[0];
  EXPECT_EQ(stretch.surface, "W2:left");
  EXPECT_EQ(stretch.points, 40u);
  EXPECT_NEAR(stretch.mean_m, 0.03, 1e-9);
  EXPECT_NEAR(stretch.start.x(), 5.9, 1e-9);
  EXPECT_NEAR(std::abs(stretch.end.y() - stretch.start.y()), 0.95, 1e-9);
}

TEST_F(MeasureMapAgainstPlan, ItsOptionsDecideWhatIsNearAndWhatIsAStretch) {
  MapAgainstPlanOptions options;
  options.cutoff_m = 0.02;  // 3 cm is no longer near
  const auto far = measureMapAgainstPlan(agraph_, {"L0"}, source(), options);
  ASSERT_EQ(far.size(), 1u);
  EXPECT_EQ(far[0].near_share, 0.0);
  EXPECT_TRUE(far[0].stretches.empty());
  options = {};
  options.min_points = 41;
  EXPECT_TRUE(measureMapAgainstPlan(agraph_, {"L0"}, source(), options)[0].stretches.empty());
  options = {};
  options.stretch_m = 4.0;  // the whole face one stretch
  const auto whole = measureMapAgainstPlan(agraph_, {"L0"}, source(), options);
  ASSERT_EQ(whole[0].stretches.size(), 1u);
  EXPECT_NEAR(std::abs(whole[0].stretches[0].end.y() - whole[0].stretches[0].start.y()), 3.8, 1e-9);
}

TEST_F(MeasureMapAgainstPlan, NoPointOrNoLevelMeasuresNothing) {
  EXPECT_TRUE(measureMapAgainstPlan(agraph_, {}, source()).empty());
  EXPECT_TRUE(measureMapAgainstPlan(agraph_, {"L0"}, [](const auto&) {}).empty());
  const auto other = measureMapAgainstPlan(agraph_, {"L9"}, source());
  ASSERT_EQ(other.size(), 1u);
  EXPECT_EQ(other[0].points, 0u);
}

}  // namespace
}  // namespace isg::slam
