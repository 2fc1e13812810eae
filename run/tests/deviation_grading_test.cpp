// The deviation report graded against the truth, by hand on the two-room plan (W1–W5).
#include "run/deviation_grading.hpp"

#include <gtest/gtest.h>

#include "bim/tests/test_plans.hpp"

namespace isg::run {
namespace {

slam::WallDeviation reported(const std::string& id, slam::WallStatus status, double share,
                             double offset, double angle) {
  slam::WallDeviation w;
  w.wall = id;
  w.level = "L0";
  w.status = status;
  w.observed_share = share;
  if (status != slam::WallStatus::kMissing) w.offset_m = offset, w.angle_deg = angle;
  return w;
}

TEST(DeviationGrading, CountsFoundFalseAndMissedWallsAndTheirErrors) {
  const bim::Plan plan = bim::testing::parsePlanJson(bim::testing::twoRoomPlanJson());
  bim::AsBuilt truth;
  truth.wall_shifts = {{"W1", 0.20}, {"W2", 0.12}};  // W2 is missed below
  truth.wall_rotations = {{"W5", 5.0, bim::WallRotation::About::kCentre}};
  truth.missing_walls = {"W3"};
  bim::ExtraWall extra;
  extra.level = "L0";
  extra.start = {1, 2};
  extra.end = {2, 2};
  truth.extra_walls = {extra};
  bim::Clutter box;
  box.level = "L0";
  box.center = {5, 1, 0.5};
  box.size = {1, 1, 1.6};
  truth.clutter = {box};

  slam::DeviationReport report;
  report.levels = {"L0"};
  report.walls = {
      reported("W1", slam::WallStatus::kShifted, 0.9, 0.21, 0.1),    // found, 1 cm off
      reported("W2", slam::WallStatus::kAsPlanned, 0.8, 0.03, 0.0),  // missed, 9 cm off
      reported("W3", slam::WallStatus::kMissing, 0.0, 0.0, 0.0),     // missing, found
      reported("W4", slam::WallStatus::kShifted, 0.7, 0.08, 0.0),    // a false report
      reported("W5", slam::WallStatus::kRotated, 0.6, 0.0, 4.5),     // found, 0.5° off
  };
  slam::ExtraWall seen_extra;
  seen_extra.level = "L0";
  seen_extra.start = {1.05, 2.04};
  seen_extra.end = {1.95, 2.04};
  slam::ExtraWall on_box = seen_extra;
  on_box.start = {4.6, 1.6};
  on_box.end = {5.4, 1.6};
  slam::ExtraWall stray = seen_extra;
  stray.start = {4, 3};
  stray.end = {4, 3.8};
  report.extra_walls = {seen_extra, on_box, stray};

  const DeviationGrade g = gradeDeviations(report, plan, truth);
  EXPECT_EQ(g.judged, 4);  // W1, W2, W4, W5: seen over at least half their length
  EXPECT_EQ(g.found, 2);
  EXPECT_EQ(g.false_reports, 1);
  EXPECT_EQ(g.missed, 1);
  EXPECT_DOUBLE_EQ(*g.precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(*g.recall, 2.0 / 3.0);
  // Over W1, W2, W5: |0.21 − 0.20|, |0.03 − 0.12|, |0 − 0| and |0.1|, 0, |4.5 − 5|.
  EXPECT_NEAR(*g.offset_error_m, (0.01 + 0.09 + 0.0) / 3.0, 1e-9);
  EXPECT_NEAR(*g.angle_error_deg, (0.1 + 0.0 + 0.5) / 3.0, 1e-9);
  EXPECT_EQ(g.missing_found, 1);
  EXPECT_EQ(g.missing_false_reports, 0);
  EXPECT_EQ(g.extra_found, 1);
  EXPECT_EQ(g.extra_on_clutter, 1);
  EXPECT_EQ(g.extra_false_reports, 1);
  EXPECT_EQ(g.extra_missed, 0);
  EXPECT_DOUBLE_EQ(*g.extra_precision, 0.5);
  EXPECT_DOUBLE_EQ(*g.extra_recall, 1.0);

  // metrics.json keeps it, and reads it back.
  const DeviationMetrics metrics = deviationMetrics(report, &plan, &truth);
  EXPECT_EQ(metrics.shifted, 2);
  EXPECT_EQ(metrics.rotated, 1);
  EXPECT_EQ(metrics.extra_walls, 3);
  const nlohmann::json json = deviationMetricsJson(metrics);
  const common::JsonSource source{"metrics.json", nullptr};
  const DeviationMetrics back =
      deviationMetricsFromJson(common::JsonNode(json, "/deviations", source));
  EXPECT_EQ(deviationMetricsJson(back), json);
}

// Walls built in part: W1 built over [0, 3] m and reported partly built 3.0 m on its exposed
// [0.1, 5.9] (truly 2.9 there: 0.1 m off), seen end to end; W2 built over [0, 1] m and reported
// 1.2 m on [0.1, 3.9] (truly 0.9: 0.3 m off), 1 m of it not seen. The built-length error is
// their mean, 0.2 m; over the walls seen end to end, W1's 0.1 m alone.
TEST(DeviationGrading, BuiltLengthErrorsOverAllAndOverTheWallsSeenEndToEnd) {
  const bim::Plan plan = bim::testing::parsePlanJson(bim::testing::twoRoomPlanJson());
  bim::AsBuilt truth;
  truth.shortened_walls = {{"W1", {{0.0, 3.0}}}, {"W2", {{0.0, 1.0}}}};
  slam::DeviationReport report;
  report.levels = {"L0"};
  auto partly = [](const std::string& id, double from, double to, double built, double unseen) {
    slam::WallDeviation w = reported(id, slam::WallStatus::kAsPlanned, 0.5, 0.0, 0.0);
    w.progress.status = slam::ProgressStatus::kPartlyBuilt;
    w.progress.exposed = {{from, to}};
    w.progress.planned_m = to - from;
    w.progress.built_m = built;
    w.progress.not_seen_m = unseen;
    w.progress.not_built_m = to - from - built - unseen;
    return w;
  };
  report.walls = {partly("W1", 0.1, 5.9, 3.0, 0.0), partly("W2", 0.1, 3.9, 1.2, 1.0)};
  const DeviationGrade g = gradeDeviations(report, plan, truth);
  EXPECT_EQ(g.partly_found, 2);
  EXPECT_NEAR(*g.built_length_error_m, 0.2, 1e-9);
  EXPECT_NEAR(*g.built_length_error_seen_m, 0.1, 1e-9);
  const nlohmann::json json = deviationMetricsJson(deviationMetrics(report, &plan, &truth));
  EXPECT_NEAR(json["graded"]["partly_built"]["built_length_error_seen_end_to_end_m"].get<double>(),
              0.1, 1e-9);
}

// Columns on the column hall: C1 truly moved 10 cm and found moved 2 cm off that; C2 truly moved
// 3 cm (under the 6 cm a report calls moved) and reported moved: a false report; C3 truly missing
// and reported as planned: missed; C4 truly missing and found; C5 not seen: not graded.
TEST(DeviationGrading, ColumnsFoundFalseAndMissed) {
  const bim::Plan plan = bim::testing::parsePlanJson(bim::testing::columnHallPlanJson());
  bim::AsBuilt truth;
  truth.missing_columns = {"C3", "C4", "C5"};
  truth.moved_columns = {{"C1", Eigen::Vector2d(0.1, 0.0)}, {"C2", Eigen::Vector2d(0.0, 0.03)}};
  slam::DeviationReport report;
  report.levels = {"L0"};
  auto column = [](const std::string& id, slam::ColumnStatus status,
                   std::optional<Eigen::Vector2d> offset) {
    slam::ColumnDeviation c;
    c.column = id;
    c.level = "L0";
    c.status = status;
    c.offset_m = offset;
    return c;
  };
  report.columns = {column("C1", slam::ColumnStatus::kMoved, Eigen::Vector2d(0.1, 0.02)),
                    column("C2", slam::ColumnStatus::kMoved, Eigen::Vector2d(0.0, 0.07)),
                    column("C3", slam::ColumnStatus::kAsPlanned, Eigen::Vector2d::Zero()),
                    column("C4", slam::ColumnStatus::kMissing, std::nullopt),
                    column("C5", slam::ColumnStatus::kNotSeen, std::nullopt)};
  const DeviationGrade g = gradeDeviations(report, plan, truth);
  EXPECT_EQ(g.column_found, 2);
  EXPECT_EQ(g.column_false_reports, 1);
  EXPECT_EQ(g.column_missed, 1);
  EXPECT_DOUBLE_EQ(*g.column_precision, 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(*g.column_recall, 2.0 / 3.0);
  EXPECT_NEAR(*g.column_offset_error_m, 0.02, 1e-12);

  const DeviationMetrics metrics = deviationMetrics(report, &plan, &truth);
  EXPECT_TRUE(metrics.hasColumns());
  EXPECT_EQ(metrics.columns_moved, 2);
  EXPECT_EQ(metrics.columns_missing, 1);
  EXPECT_EQ(metrics.columns_not_seen, 1);
  const nlohmann::json json = deviationMetricsJson(metrics);
  EXPECT_EQ(json["columns"]["as_planned"], 1);
  EXPECT_EQ(json["graded"]["columns"]["found"], 2);
  const common::JsonSource source{"metrics.json", nullptr};
  const DeviationMetrics back =
      deviationMetricsFromJson(common::JsonNode(json, "/deviations", source));
  EXPECT_EQ(deviationMetricsJson(back), json);
  // A report without columns writes none.
  report.columns.clear();
  EXPECT_FALSE(deviationMetricsJson(deviationMetrics(report, &plan, &truth)).contains("columns"));
}

}  // namespace
}  // namespace isg::run
