// deviations.json read back by its reader: what the writer wrote, read and written again, is the
// same document; a document that is not one fails naming the file and the JSON pointer.
#include "run/deviation_report_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "common/input_error.hpp"
#include "run/deviation_report.hpp"

namespace isg::run {
namespace {

using Json = nlohmann::json;

// Every field the writer writes, with values no default has.
slam::DeviationReport everyField() {
  slam::DeviationReport report;
  report.options.shift_m = 0.07;
  report.options.min_views = 4;
  report.levels = {"L0", "L1"};
  report.placements.push_back({"L0", Eigen::Vector3d(0.01, -0.02, 0.003), 9});
  slam::WallDeviation wall;
  wall.wall = "W3";
  wall.level = "L0";
  wall.status = slam::WallStatus::kRotated;
  wall.offset_m = 0.081;
  wall.angle_deg = 2.25;
  wall.pivot_along_m = 1.5;
  wall.turned_about = "its start";
  wall.observed_share = 0.75;
  wall.shift_threshold_m = 0.06;
  wall.angle_threshold_deg = 1.5;
  wall.local_offset_noise_m = 0.004;
  wall.placement_sigma_m = 0.011;
  wall.planned_start = {0.0, 1.0};
  wall.planned_end = {4.0, 1.0};
  slam::WallEvidence evidence;
  evidence.plane = 12;
  evidence.side = -1;
  evidence.length_m = 3.5;
  evidence.observations = 17;
  evidence.offset_m = 0.08;
  evidence.angle_deg = 2.2;
  evidence.consistent = false;
  evidence.start_B = {0.1, 1.08};
  evidence.end_B = {3.6, 1.2};
  wall.evidence.push_back(evidence);
  wall.progress.status = slam::ProgressStatus::kPartlyBuilt;
  wall.progress.planned_m = 4.0;
  wall.progress.built_m = 2.5;
  wall.progress.not_built_m = 1.0;
  wall.progress.not_seen_m = 0.5;
  wall.progress.built = {{0.0, 1.0}, {2.5, 4.0}};
  report.walls.push_back(wall);
  slam::WallDeviation unseen;
  unseen.wall = "W4";
  unseen.level = "L1";
  unseen.in_view_share = 0.125;
  report.walls.push_back(unseen);
  slam::ExtraWall extra;
  extra.level = "L1";
  extra.start = {1, 1};
  extra.end = {1, 3.5};
  extra.planes = {3, 8};
  report.extra_walls.push_back(extra);
  slam::ColumnDeviation moved;
  moved.column = "C2";
  moved.level = "L0";
  moved.round = true;
  moved.status = slam::ColumnStatus::kMoved;
  moved.planned_centre = {6, 2};
  moved.points = 140;
  moved.offset_m = Eigen::Vector2d(-0.12, 0.05);
  moved.directions_measured = 2;
  moved.seen_past = 1;
  report.columns.push_back(moved);
  slam::ColumnDeviation missing = moved;
  missing.column = "C3";
  missing.round = false;
  missing.status = slam::ColumnStatus::kMissing;
  missing.offset_m.reset();
  report.columns.push_back(missing);
  report.column_options.min_points = 40;
  slam::LevelAgainstPlan level;
  level.level = "L0";
  level.points = 5000;
  level.near_share = 0.97;
  level.cutoff_m = 0.3;
  level.median_m = 0.017;
  level.p95_m = 0.057;
  level.stretches.push_back({"W3:left", {0, 1.1}, {1, 1.1}, 42, -0.031, 0.036});
  report.against_plan.push_back(level);
  return report;
}

slam::DeviationReport readBack(const Json& document) {
  const common::JsonSource source{"deviations.json", nullptr};
  return readDeviationReport(common::JsonNode(document, "", source));
}

// Equal documents, numbers to 1e-12 relative (a placement's yaw goes through degrees and back).
void expectSame(const Json& a, const Json& b, const std::string& where = "") {
  if (a.is_number() && b.is_number()) {
    const double x = a.get<double>(), y = b.get<double>();
    EXPECT_NEAR(x, y, 1e-12 * std::max(1.0, std::abs(x))) << where;
    return;
  }
  ASSERT_EQ(a.type(), b.type()) << where;
  if (a.is_object()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (const auto& [key, value] : a.items()) {
      ASSERT_TRUE(b.contains(key)) << where << "/" << key;
      expectSame(value, b.at(key), where + "/" + key);
    }
  } else if (a.is_array()) {
    ASSERT_EQ(a.size(), b.size()) << where;
    for (std::size_t i = 0; i < a.size(); ++i) {
      expectSame(a[i], b[i], where + "/" + std::to_string(i));
    }
  } else {
    EXPECT_EQ(a, b) << where;
  }
}

TEST(DeviationReportReader, WhatTheWriterWroteReadsBackToTheSameDocument) {
  const Json written = deviationReportJson(everyField());
  const slam::DeviationReport read = readBack(written);
  expectSame(written, deviationReportJson(read));
  // And the typed fields themselves.
  ASSERT_EQ(read.walls.size(), 2u);
  EXPECT_EQ(read.walls[0].status, slam::WallStatus::kRotated);
  EXPECT_EQ(read.walls[0].evidence[0].side, -1);
  EXPECT_EQ(*read.walls[0].pivot_along_m, 1.5);
  EXPECT_FALSE(read.walls[1].offset_m.has_value());
  EXPECT_EQ(*read.walls[1].in_view_share, 0.125);
  EXPECT_EQ(read.columns[1].status, slam::ColumnStatus::kMissing);
  EXPECT_FALSE(read.columns[1].offset_m.has_value());
  EXPECT_EQ(read.column_options.min_points, 40u);
  EXPECT_EQ(read.options.min_views, 4);
  EXPECT_NEAR(read.placements[0].correction.z(), 0.003, 1e-15);
}

TEST(DeviationReportReader, AReportWithoutColumnsOrMapReadsWithout) {
  slam::DeviationReport bare = everyField();
  bare.columns.clear();
  bare.against_plan.clear();
  const Json written = deviationReportJson(bare);
  ASSERT_FALSE(written.contains("columns"));
  expectSame(written, deviationReportJson(readBack(written)));
}

TEST(DeviationReportReader, ADocumentThatIsNotOneFailsNamingTheFileAndPointer) {
  Json document = deviationReportJson(everyField());
  document["walls"][0]["status"] = "leaning";
  try {
    readBack(document);
    FAIL() << "an unknown status was read";
  } catch (const common::InputError& e) {
    EXPECT_EQ(e.file(), "deviations.json");
    EXPECT_EQ(e.pointer(), "/walls/0/status");
    EXPECT_EQ(e.reason(),
              "unknown status \"leaning\" (expected one of as_planned, shifted, rotated, missing, "
              "not_seen)");
  }
  document = deviationReportJson(everyField());
  document["columns"][0].erase("planned_centre");
  EXPECT_THROW(readBack(document), common::InputError);
  document = deviationReportJson(everyField());
  document["format"] = "isg.plan";
  EXPECT_THROW(readBack(document), common::InputError);
}

}  // namespace
}  // namespace isg::run
