#include "eval/report_svg.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "eval/svg_chart.hpp"

namespace isg::eval {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

TEST(NiceTicks, StepsAreOneTwoOrFiveTimesAPowerOfTen) {
  EXPECT_DOUBLE_EQ(niceStep(0.013, 4), 0.005);  // not 0.00325
  EXPECT_DOUBLE_EQ(niceStep(8.4, 5), 2.0);
  EXPECT_DOUBLE_EQ(niceStep(47.9, 8), 10.0);  // 5.99 → 10
  EXPECT_DOUBLE_EQ(niceStep(435.2, 8), 100.0);
  EXPECT_DOUBLE_EQ(niceStep(1.0, 5), 0.2);
  EXPECT_EQ(niceTicks(0.0, 47.9, 8), (std::vector<double>{0, 10, 20, 30, 40}));
  EXPECT_EQ(niceTicks(-0.3, 0.25, 4), (std::vector<double>{-0.2, 0.0, 0.2}));
  EXPECT_EQ(tickLabel(0.05, 0.01), "0.05");
  EXPECT_EQ(tickLabel(20.0, 10.0), "20");
  EXPECT_EQ(tickLabel(2.5, 0.5), "2.5");
}

common::Trajectory straight(double t0, double t1, double y) {
  common::Trajectory out;
  for (double t = t0; t <= t1 + 1e-9; t += 0.5) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() = Eigen::Vector3d(t, y, 0);
    out.push_back({t, pose});
  }
  return out;
}

// The marks of the start and of the first localized pose stand on the first pose of the ground
// truth (here a compact track, as a run holds it) and of the estimate: each path begins there.
TEST(ReportSvg, TheStartAndLocalizedMarksStandWhereTheirPathsBegin) {
  ReportInput input;
  input.walls = {{{0, -0.1}, {12, -0.1}, {12, 0.1}, {0, 0.1}}};
  const common::PoseTrack truth(straight(0, 10, 2));
  const common::Trajectory estimate = straight(3, 10, 2.5);
  input.ground_truth = truth;
  input.estimate = estimate;
  input.localized_at = 3.0;
  const std::string svg = reportSvg(input);
  const auto attribute = [&](std::size_t from, const std::string& name) {
    const std::size_t at = svg.find(name + "=\"", from) + name.size() + 2;
    return svg.substr(at, svg.find('"', at) - at);
  };
  const std::size_t circle = svg.find("<circle cx=");
  ASSERT_NE(circle, std::string::npos);
  const std::string mark = attribute(circle, "cx") + "," + attribute(circle, "cy") + " ";
  EXPECT_THAT(svg, HasSubstr("points=\"" + mark));  // the estimate's path begins at the mark
  const std::size_t start = svg.find("width=\"10\" height=\"10\" fill=\"black\"");
  ASSERT_NE(start, std::string::npos);
  const std::size_t rect = svg.rfind("<rect", start);
  const double x = std::stod(attribute(rect, "x")) + 5, y = std::stod(attribute(rect, "y")) + 5;
  const std::size_t truth_path = svg.find("polyline fill=\"none\" stroke=\"black\"");
  ASSERT_NE(truth_path, std::string::npos);
  const std::string first = attribute(truth_path, "points");
  EXPECT_NEAR(std::stod(first), x, 0.11);
  EXPECT_NEAR(std::stod(first.substr(first.find(',') + 1)), y, 0.11);
}

TEST(ReportSvg, DrawsTheMapTheLegendTheScaleBarAndBothPanels) {
  ReportInput input;
  input.title = "isg run: a & b";
  input.walls = {{{0, -0.1}, {4, -0.1}, {4, 0.1}, {0, 0.1}}, {{5, -0.1}, {10, -0.1}, {10, 0.1}}};
  input.overlays = {{MapOverlay::Kind::kClutter, {{1, 1}, {2, 1}, {2, 2}, {1, 2}}}};
  input.labels = {{"R1", {5, 2}, {{0, 0}, {10, 0}, {10, 4}, {0, 4}}}};
  const common::Trajectory truth = straight(0, 10, 2), estimate = straight(3, 10, 2.02);
  input.ground_truth = truth;
  input.estimate = estimate;
  input.localized_at = 3.0;
  for (double t = 3; t <= 10; t += 0.5) {
    input.error_over_time.emplace_back(t, 0.02);
    input.heading_error_over_time.emplace_back(t, 0.7);
  }
  const std::string svg = reportSvg(input);
  EXPECT_THAT(svg, HasSubstr("isg run: a &amp; b"));
  EXPECT_THAT(svg, HasSubstr(">clutter</text>"));
  EXPECT_THAT(svg, Not(HasSubstr(">closed door</text>")));  // only what is there
  EXPECT_THAT(svg, HasSubstr(">2 m</text>"));               // the scale bar: 10 m / 6 → 2
  EXPECT_THAT(svg, HasSubstr("heading error, degrees"));
  EXPECT_THAT(svg, HasSubstr(">10 s</text>"));  // round time ticks: 0, 2, 4, ... 10
  EXPECT_THAT(svg, HasSubstr(">0.04</text>"));  // round error ticks up to 0.05
  EXPECT_THAT(svg, HasSubstr(">first localized pose</text>"));
  // The room's name keeps off the path along y = 2: not at its centre (5, 2).
  const std::size_t label = svg.find(">R1</text>");
  ASSERT_NE(label, std::string::npos);
  const std::size_t y_at = svg.rfind(" y=\"", label);
  const double y_px = std::stod(svg.substr(y_at + 4));
  const std::size_t path_y = svg.find("polyline fill=\"none\" stroke=\"black\"");
  ASSERT_NE(path_y, std::string::npos);
  const std::size_t first_point = svg.find("points=\"", path_y) + 8;
  const double path_px = std::stod(svg.substr(svg.find(',', first_point) + 1));
  EXPECT_GT(std::abs(y_px - path_px), 20.0);
}

TEST(ReportSvg, AnAlignedSlamEstimateIsNotCalledALocalization) {
  ReportInput input;
  const common::Trajectory truth = straight(0, 10, 2), estimate = straight(0, 10, 2.01);
  input.ground_truth = truth;
  input.estimate = estimate;
  input.estimate_is_localization = false;
  input.estimate_label = "estimate in M, SE(3)-aligned to the ground truth";
  const std::string svg = reportSvg(input);
  EXPECT_THAT(svg, HasSubstr(">estimate in M, SE(3)-aligned to the ground truth</text>"));
  EXPECT_THAT(svg, Not(HasSubstr("first localized pose")));
  EXPECT_THAT(svg, Not(HasSubstr(">localized</text>")));
}

TEST(ReportSvg, AMapThinnedAsTheReportThinsItIsDrawnTheSame) {
  // A long run's map is millions of points; the run keeps only every reportDotStep-th of them,
  // and the picture must be the one drawn from them all, for every count of points.
  const common::Trajectory path = straight(0.0, 10.0, 5.0);
  for (const std::size_t n : {std::size_t(15000), std::size_t(39999), std::size_t(40000),
                              std::size_t(123457), std::size_t(1000003)}) {
    ReportInput all, thinned;
    all.walls = thinned.walls = {{{0, 0}, {10, 0}, {10, 10}, {0, 10}}};
    all.ground_truth = thinned.ground_truth = path;
    const std::size_t step = reportDotStep(n);
    for (std::size_t i = 0; i < n; ++i) {
      const Eigen::Vector3d p(double(i % 997) / 99.7, double(i % 991) / 99.1, 1.0);
      all.map_points.push_back(p);
      if (i % step == 0) thinned.map_points.push_back(p);
    }
    EXPECT_LT(thinned.map_points.size(), 40000u) << n;
    EXPECT_EQ(reportSvg(thinned), reportSvg(all)) << n;
  }
}

}  // namespace
}  // namespace isg::eval
