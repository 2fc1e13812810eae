#pragma once

#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace isg::eval {

// Pieces of the SVG pictures (report.svg, isg eval --plot; text is escaped by common::xmlEscape):
// numbers with a fixed precision, round-number axis ticks and a time-series panel.

std::string svgNumber(double value);  // one decimal: enough for pixels

// A round step for an axis spanning `span` with about `target` intervals: 1, 2 or 5 × 10^k.
double niceStep(double span, int target);
// The multiples of niceStep(hi − lo, target) within [lo, hi] (a tick at lo when lo is one).
std::vector<double> niceTicks(double lo, double hi, int target = 5);
// A tick's label with as many decimals as its step needs ("0.05", "20", "2.5").
std::string tickLabel(double value, double step);

// One line of a panel: (x, y) points in data units.
struct ChartSeries {
  std::vector<std::pair<double, double>> points;
  std::string colour;
  std::string label;  // in the panel's legend; none when empty
};

// A panel of time series over [x0, x1] (seconds), y from 0 (or below, if the data go there) to
// a round number above the largest value; round-number ticks on both axes, a dashed vertical line
// at `marker_x` (the first localization) and `empty_text` in the middle when there is no data.
struct ChartPanel {
  std::string title;
  std::string x_unit = "s";
  double x0 = 0.0, x1 = 1.0;
  double y_floor = 0.0;  // the smallest top of the y axis
  std::vector<ChartSeries> series;
  std::optional<double> marker_x;
  std::string empty_text;
};
void drawChartPanel(std::ostringstream& svg, const ChartPanel& panel, double left, double top,
                    double width, double height);

}  // namespace isg::eval
