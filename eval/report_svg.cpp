#include "eval/report_svg.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <sstream>

namespace isg::eval {

namespace {

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (c == '&')
      out += "&amp;";
    else if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else
      out += c;
  }
  return out;
}

std::string number(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.1f", v);
  return b;
}

}  // namespace

namespace {

// Where everything goes: the plan's extent decides the map's scale; the chart sits below it.
struct Layout {
  explicit Layout(const ReportInput& input) {
    lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
    hi = -lo;
    auto grow = [&](const Eigen::Vector2d& p) {
      lo = lo.cwiseMin(p);
      hi = hi.cwiseMax(p);
    };
    for (const auto& polygon : input.walls) {
      for (const auto& p : polygon) grow(p);
    }
    for (const auto& pose : input.ground_truth) grow(pose.pose.translation().head<2>());
    if (!std::isfinite(lo.x())) lo = hi = Eigen::Vector2d::Zero();
    const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(1.0));
    scale = (width - 2 * margin) / size.x();
    header = 30.0 + 18.0 * double(input.summary.size());
    map_height = size.y() * scale + 2 * margin;
    chart_top = header + map_height + 20.0;
    height = chart_top + chart_height + 50.0;
  }
  std::string X(double x) const { return number(margin + (x - lo.x()) * scale); }
  std::string Y(double y) const { return number(header + margin + (hi.y() - y) * scale); }

  static constexpr double width = 1000.0, margin = 30.0, chart_height = 180.0;
  Eigen::Vector2d lo, hi;
  double scale = 1.0, header = 0.0, map_height = 0.0, chart_top = 0.0, height = 0.0;
};

void drawHeader(std::ostringstream& svg, const ReportInput& input, const Layout& l) {
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << number(l.width) << "\" height=\""
      << number(l.height) << "\" viewBox=\"0 0 " << number(l.width) << " " << number(l.height)
      << "\" font-family=\"sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << l.margin << "\" y=\"22\" font-size=\"18\" font-weight=\"bold\">"
      << escape(input.title) << "</text>\n";
  for (std::size_t i = 0; i < input.summary.size(); ++i) {
    svg << "<text x=\"" << l.margin << "\" y=\"" << number(42 + 18.0 * i) << "\" font-size=\"13\">"
        << escape(input.summary[i]) << "</text>\n";
  }
}

// The plan's walls and room names, the trajectories, the start and the first localized pose.
void drawMap(std::ostringstream& svg, const ReportInput& input, const Layout& l) {
  svg << "<g fill=\"#9a9a9a\" stroke=\"#555\" stroke-width=\"0.5\">\n";
  for (const auto& polygon : input.walls) {
    svg << "<polygon points=\"";
    for (const auto& p : polygon) svg << l.X(p.x()) << "," << l.Y(p.y()) << " ";
    svg << "\"/>\n";
  }
  svg << "</g>\n<g font-size=\"11\" fill=\"#777\" text-anchor=\"middle\">\n";
  for (const auto& [name, p] : input.labels) {
    svg << "<text x=\"" << l.X(p.x()) << "\" y=\"" << l.Y(p.y()) << "\">" << escape(name)
        << "</text>\n";
  }
  svg << "</g>\n";
  auto path = [&](const Trajectory& trajectory, const std::string& style) {
    if (trajectory.empty()) return;
    svg << "<polyline fill=\"none\" " << style << " points=\"";
    // At most ~4000 vertices: enough for the eye, small enough to open quickly.
    const std::size_t step = std::max<std::size_t>(1, trajectory.size() / 4000);
    for (std::size_t i = 0; i < trajectory.size(); i += step) {
      const auto t = trajectory[i].pose.translation();
      svg << l.X(t.x()) << "," << l.Y(t.y()) << " ";
    }
    svg << "\"/>\n";
  };
  path(input.odometry, "stroke=\"#e8a0a0\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"");
  path(input.ground_truth, "stroke=\"black\" stroke-width=\"1.5\"");
  path(input.estimate, "stroke=\"#1f6fd0\" stroke-width=\"1.5\" stroke-opacity=\"0.85\"");
  if (!input.estimate.empty()) {
    const auto p = input.estimate.front().pose.translation();
    svg << "<circle cx=\"" << l.X(p.x()) << "\" cy=\"" << l.Y(p.y())
        << "\" r=\"7\" fill=\"none\" stroke=\"#d02020\" stroke-width=\"2.5\"/>\n";
    svg << "<text x=\"" << l.X(p.x()) << "\" y=\"" << number(std::stod(l.Y(p.y())) - 11)
        << "\" font-size=\"12\" fill=\"#d02020\" text-anchor=\"middle\">localized</text>\n";
  }
  if (!input.ground_truth.empty()) {
    const auto p = input.ground_truth.front().pose.translation();
    svg << "<rect x=\"" << number(std::stod(l.X(p.x())) - 5) << "\" y=\""
        << number(std::stod(l.Y(p.y())) - 5) << "\" width=\"10\" height=\"10\" fill=\"black\"/>\n";
  }
}

void drawLegend(std::ostringstream& svg, const Layout& l) {
  const double legend_y = l.header + l.map_height - 8;
  const std::pair<const char*, const char*> legend[] = {
      {"black", "ground truth"},
      {"#1f6fd0", "estimate in B (once localized)"},
      {"#e8a0a0", "odometry from the true start"},
      {"#d02020", "first localized pose"}};
  double lx = l.margin;
  for (const auto& [colour, text] : legend) {
    svg << "<line x1=\"" << lx << "\" y1=\"" << number(legend_y) << "\" x2=\"" << lx + 20
        << "\" y2=\"" << number(legend_y) << "\" stroke=\"" << colour
        << "\" stroke-width=\"3\"/><text x=\"" << lx + 25 << "\" y=\"" << number(legend_y + 4)
        << "\" font-size=\"12\">" << text << "</text>\n";
    lx += 60 + 7.0 * std::string(text).size();
  }
}

// The APE over time, with the moment of the first localization.
void drawChart(std::ostringstream& svg, const ReportInput& input, const Layout& l) {
  double t0 = input.ground_truth.empty() ? 0.0 : input.ground_truth.front().t;
  double t1 = input.ground_truth.empty() ? 1.0 : input.ground_truth.back().t;
  if (t1 <= t0) t1 = t0 + 1.0;
  double e_max = 0.05;
  for (const auto& [t, e] : input.error_over_time) e_max = std::max(e_max, e);
  e_max = std::ceil(e_max * 20.0) / 20.0;
  const double top = l.chart_top, height = l.chart_height;
  const double cx0 = l.margin + 50, cx1 = l.width - l.margin;
  auto CX = [&](double t) { return number(cx0 + (t - t0) / (t1 - t0) * (cx1 - cx0)); };
  auto CY = [&](double e) { return number(top + height * (1.0 - e / e_max)); };
  svg << "<text x=\"" << l.margin << "\" y=\"" << number(top - 6)
      << "\" font-size=\"13\">APE in B (2D, no alignment), metres, over time</text>\n";
  svg << "<rect x=\"" << number(cx0) << "\" y=\"" << number(top) << "\" width=\""
      << number(cx1 - cx0) << "\" height=\"" << number(height)
      << "\" fill=\"none\" stroke=\"#444\"/>\n";
  for (int i = 0; i <= 4; ++i) {
    const double e = e_max * i / 4.0;
    char label[32];
    std::snprintf(label, sizeof label, "%.3f", e);
    svg << "<text x=\"" << number(cx0 - 5) << "\" y=\"" << number(std::stod(CY(e)) + 4)
        << "\" font-size=\"10\" text-anchor=\"end\">" << label << "</text>\n";
    svg << "<line x1=\"" << number(cx0) << "\" y1=\"" << CY(e) << "\" x2=\"" << number(cx1)
        << "\" y2=\"" << CY(e) << "\" stroke=\"#ddd\"/>\n";
  }
  for (int i = 0; i <= 5; ++i) {
    const double t = t0 + (t1 - t0) * i / 5.0;
    svg << "<text x=\"" << CX(t) << "\" y=\"" << number(top + height + 14)
        << "\" font-size=\"10\" text-anchor=\"middle\">" << number(t - t0) << " s</text>\n";
  }
  if (input.localized_at) {
    svg << "<line x1=\"" << CX(*input.localized_at) << "\" y1=\"" << number(top) << "\" x2=\""
        << CX(*input.localized_at) << "\" y2=\"" << number(top + height)
        << "\" stroke=\"#d02020\" stroke-dasharray=\"3 3\"/>\n";
  }
  if (!input.error_over_time.empty()) {
    svg << "<polyline fill=\"none\" stroke=\"#1f6fd0\" stroke-width=\"1.2\" points=\"";
    for (const auto& [t, e] : input.error_over_time) svg << CX(t) << "," << CY(e) << " ";
    svg << "\"/>\n";
  } else {
    svg << "<text x=\"" << number(0.5 * (cx0 + cx1)) << "\" y=\"" << number(top + height / 2)
        << "\" font-size=\"14\" text-anchor=\"middle\" fill=\"#d02020\">never localized</text>\n";
  }
}

}  // namespace

std::string reportSvg(const ReportInput& input) {
  const Layout layout(input);
  std::ostringstream svg;
  drawHeader(svg, input, layout);
  drawMap(svg, input, layout);
  drawLegend(svg, layout);
  drawChart(svg, input, layout);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace isg::eval
