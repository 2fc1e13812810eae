#include "eval/floor_plan_score_svg.hpp"

#include <algorithm>
#include <sstream>

#include "common/xml_escape.hpp"
#include "eval/svg_chart.hpp"

namespace isg::eval {

std::string floorPlanScoreSvg(const FloorPlanScore& score, const std::string& title,
                              const std::vector<std::string>& summary) {
  constexpr double kWidth = 900.0, kMargin = 40.0, kPanel = 240.0, kGap = 50.0;
  const double top = 40.0 + 18.0 * double(summary.size());
  const double height = top + 2 * kPanel + 2 * kGap;
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << svgNumber(kWidth) << "\" height=\""
      << svgNumber(height) << "\" viewBox=\"0 0 " << svgNumber(kWidth) << " " << svgNumber(height)
      << "\" font-family=\"sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << kMargin << "\" y=\"22\" font-size=\"18\" font-weight=\"bold\">"
      << common::xmlEscape(title) << "</text>\n";
  for (std::size_t i = 0; i < summary.size(); ++i) {
    svg << "<text x=\"" << kMargin << "\" y=\"" << svgNumber(44.0 + 18.0 * double(i))
        << "\" font-size=\"13\">" << common::xmlEscape(summary[i]) << "</text>\n";
  }
  ChartSeries points{{}, "#1f6fd0", ""}, errors{{}, "#d02020", ""};
  for (const PoseScore& pose : score.per_pose) {
    points.points.emplace_back(pose.t, pose.score);
    errors.points.emplace_back(pose.t, pose.error);
  }
  ChartPanel panel;
  panel.title = "score of each associated pose (100 · e^(−0.4605 · error))";
  panel.x0 = score.run_start;
  panel.x1 = score.per_pose.empty() ? score.run_start + 1.0
                                    : std::max(score.per_pose.back().t, score.run_start + 1.0);
  panel.y_floor = 100.0;
  panel.series = {points};
  panel.marker_x = score.per_pose.empty() ? score.run_start : score.per_pose.front().t;
  panel.empty_text = "no pose of the estimate is associated with the reference";
  drawChartPanel(svg, panel, kMargin, top + kGap * 0.5, kWidth - 2 * kMargin, kPanel);
  panel.title = "error in the plane, metres";
  panel.y_floor = 0.05;
  panel.series = {errors};
  drawChartPanel(svg, panel, kMargin, top + kPanel + kGap * 1.5, kWidth - 2 * kMargin, kPanel);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace isg::eval
