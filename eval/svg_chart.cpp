#include "eval/svg_chart.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/xml_escape.hpp"

namespace isg::eval {

std::string svgNumber(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

double niceStep(double span, int target) {
  if (!(span > 0.0) || target < 1) return 1.0;
  const double raw = span / target;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0}) {
    if (m * magnitude >= raw * (1.0 - 1e-9)) return m * magnitude;
  }
  return 10.0 * magnitude;
}

std::vector<double> niceTicks(double lo, double hi, int target) {
  const double step = niceStep(hi - lo, target);
  std::vector<double> ticks;
  for (double k = std::ceil(lo / step - 1e-9); k * step <= hi + 1e-9 * step; k += 1.0) {
    ticks.push_back(k * step == 0.0 ? 0.0 : k * step);  // no "-0"
  }
  return ticks;
}

std::string tickLabel(double value, double step) {
  const int decimals = std::max(0, int(std::ceil(-std::log10(step) - 1e-9)));
  char b[32];
  std::snprintf(b, sizeof b, "%.*f", decimals, value);
  return b;
}

void drawChartPanel(std::ostringstream& svg, const ChartPanel& panel, double left, double top,
                    double width, double height) {
  const double x0 = panel.x0, x1 = panel.x1 > panel.x0 ? panel.x1 : panel.x0 + 1.0;
  double y_lo = 0.0, y_hi = panel.y_floor;
  for (const auto& s : panel.series) {
    for (const auto& [x, y] : s.points) {
      y_lo = std::min(y_lo, y);
      y_hi = std::max(y_hi, y);
    }
  }
  // The axis ends on a round tick above the data.
  const double y_step = niceStep(y_hi - y_lo, 4);
  y_hi = std::ceil(y_hi / y_step - 1e-9) * y_step;
  y_lo = std::floor(y_lo / y_step + 1e-9) * y_step;
  if (y_hi <= y_lo) y_hi = y_lo + y_step;
  const double cx0 = left + 50, cx1 = left + width;
  auto CX = [&](double x) { return svgNumber(cx0 + (x - x0) / (x1 - x0) * (cx1 - cx0)); };
  auto CY = [&](double y) { return svgNumber(top + height * (y_hi - y) / (y_hi - y_lo)); };
  svg << "<text x=\"" << svgNumber(left) << "\" y=\"" << svgNumber(top - 6)
      << "\" font-size=\"13\">" << common::xmlEscape(panel.title) << "</text>\n";
  svg << "<rect x=\"" << svgNumber(cx0) << "\" y=\"" << svgNumber(top) << "\" width=\""
      << svgNumber(cx1 - cx0) << "\" height=\"" << svgNumber(height)
      << "\" fill=\"none\" stroke=\"#444\"/>\n";
  const double y_tick_step = niceStep(y_hi - y_lo, 4);
  for (double y : niceTicks(y_lo, y_hi, 4)) {
    svg << "<text x=\"" << svgNumber(cx0 - 5) << "\" y=\"" << svgNumber(std::stod(CY(y)) + 4)
        << "\" font-size=\"10\" text-anchor=\"end\">" << tickLabel(y, y_tick_step) << "</text>\n";
    svg << "<line x1=\"" << svgNumber(cx0) << "\" y1=\"" << CY(y) << "\" x2=\"" << svgNumber(cx1)
        << "\" y2=\"" << CY(y) << "\" stroke=\"#ddd\"/>\n";
  }
  const double x_step = niceStep(x1 - x0, 8);
  for (double x : niceTicks(x0, x1, 8)) {
    svg << "<text x=\"" << CX(x) << "\" y=\"" << svgNumber(top + height + 14)
        << "\" font-size=\"10\" text-anchor=\"middle\">" << tickLabel(x, x_step) << " "
        << common::xmlEscape(panel.x_unit) << "</text>\n";
    svg << "<line x1=\"" << CX(x) << "\" y1=\"" << svgNumber(top + height) << "\" x2=\"" << CX(x)
        << "\" y2=\"" << svgNumber(top + height + 4) << "\" stroke=\"#444\"/>\n";
  }
  if (panel.marker_x) {
    svg << "<line x1=\"" << CX(*panel.marker_x) << "\" y1=\"" << svgNumber(top) << "\" x2=\""
        << CX(*panel.marker_x) << "\" y2=\"" << svgNumber(top + height)
        << "\" stroke=\"#d02020\" stroke-dasharray=\"3 3\"/>\n";
  }
  bool any = false;
  double legend_x = cx1 - 10;
  for (const auto& s : panel.series) {
    if (s.points.empty()) continue;
    any = true;
    svg << "<polyline fill=\"none\" stroke=\"" << s.colour << "\" stroke-width=\"1.2\" points=\"";
    // At most ~2000 vertices: enough for the eye, small enough to open quickly.
    const std::size_t step = std::max<std::size_t>(1, s.points.size() / 2000);
    for (std::size_t i = 0; i < s.points.size(); i += step) {
      svg << CX(s.points[i].first) << "," << CY(s.points[i].second) << " ";
    }
    svg << "\"/>\n";
    if (!s.label.empty()) {
      svg << "<text x=\"" << svgNumber(legend_x) << "\" y=\"" << svgNumber(top + 14)
          << "\" font-size=\"11\" text-anchor=\"end\" fill=\"" << s.colour << "\">"
          << common::xmlEscape(s.label) << "</text>\n";
      legend_x -= 12 + 6.5 * double(s.label.size());
    }
  }
  if (!any && !panel.empty_text.empty()) {
    svg << "<text x=\"" << svgNumber(0.5 * (cx0 + cx1)) << "\" y=\"" << svgNumber(top + height / 2)
        << "\" font-size=\"14\" text-anchor=\"middle\" "
        << "fill=\"#d02020\">" << common::xmlEscape(panel.empty_text) << "</text>\n";
  }
}

}  // namespace isg::eval
