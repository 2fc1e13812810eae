#include "eval/report_svg.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "common/xml_escape.hpp"
#include "eval/svg_chart.hpp"

namespace isg::eval {

namespace {

constexpr const char* kEstimateColour = "#1f6fd0";
constexpr const char* kAlignedColour = "#8e44ad";
constexpr const char* kMapPointColour = "#2a9d8f";
constexpr const char* kLocalizedColour = "#d02020";

struct OverlayStyle {
  const char* legend;
  const char* svg;  // fill and stroke
};
OverlayStyle styleOf(MapOverlay::Kind kind) {
  switch (kind) {
    case MapOverlay::Kind::kExtraWall:
      return {"extra wall (as built)", "fill=\"#e67e22\" stroke=\"#a04000\" stroke-width=\"0.5\""};
    case MapOverlay::Kind::kShiftedWall:
      return {"shifted wall (as built)",
              "fill=\"#f5b041\" stroke=\"#a04000\" stroke-width=\"0.5\""};
    case MapOverlay::Kind::kMissingWall:
      return {"wall not built",
              "fill=\"none\" stroke=\"#a04000\" stroke-width=\"1\" stroke-dasharray=\"3 2\""};
    case MapOverlay::Kind::kClosedDoor:
      return {"closed door", "fill=\"#6e2c00\" stroke=\"#6e2c00\" stroke-width=\"1.5\""};
    case MapOverlay::Kind::kClutter:
      return {"clutter",
              "fill=\"#d7bde2\" fill-opacity=\"0.8\" stroke=\"#7d3c98\" "
              "stroke-width=\"0.7\""};
  }
  return {"", ""};
}

// Where everything goes: the map's extent decides its scale; the two charts sit below it.
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
    for (const auto& overlay : input.overlays) {
      for (const auto& p : overlay.polygon) grow(p);
    }
    for (const auto& storey : input.storeys) {
      for (const auto& polygon : storey.walls) {
        for (const auto& p : polygon) grow(p);
      }
    }
    for (const auto* trajectory : {&input.ground_truth, &input.estimate}) {
      for (const auto& pose : *trajectory) grow(pose.pose.translation().head<2>());
    }
    if (!std::isfinite(lo.x())) lo = hi = Eigen::Vector2d::Zero();
    const Eigen::Vector2d size = (hi - lo).cwiseMax(Eigen::Vector2d::Constant(1.0));
    scale = (width - 2 * margin) / size.x();
    header = 30.0 + 18.0 * double(input.summary.size());
    // Storeys: one panel each, under a title line.
    const double panels = input.storeys.empty() ? 1.0 : double(input.storeys.size());
    panel_height = size.y() * scale + 2 * margin + (input.storeys.empty() ? 0.0 : kTitle);
    legend_top = header + panels * panel_height;
    map_height = panels * panel_height + 60.0;  // three legend rows and the scale bar
    chart_top = header + map_height + 30.0;
    heading_top = chart_top + chart_height + 55.0;
    height = heading_top + chart_height + 40.0;
  }
  double px(double x) const { return margin + (x - lo.x()) * scale; }
  double py(double y) const { return header + panel_offset + margin + (hi.y() - y) * scale; }
  std::string X(double x) const { return svgNumber(px(x)); }
  std::string Y(double y) const { return svgNumber(py(y)); }

  static constexpr double width = 1000.0, margin = 30.0, chart_height = 150.0, kTitle = 22.0;
  Eigen::Vector2d lo, hi;
  double scale = 1.0, header = 0.0, legend_top = 0.0, map_height = 0.0, chart_top = 0.0,
         heading_top = 0.0, height = 0.0;
  double panel_height = 0.0;
  double panel_offset = 0.0;  // of the storey panel being drawn, from the map's top
};

void drawHeader(std::ostringstream& svg, const ReportInput& input, const Layout& l) {
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << svgNumber(l.width)
      << "\" height=\"" << svgNumber(l.height) << "\" viewBox=\"0 0 " << svgNumber(l.width) << " "
      << svgNumber(l.height) << "\" font-family=\"sans-serif\">\n";
  svg << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  svg << "<text x=\"" << l.margin << "\" y=\"22\" font-size=\"18\" font-weight=\"bold\">"
      << common::xmlEscape(input.title) << "</text>\n";
  for (std::size_t i = 0; i < input.summary.size(); ++i) {
    svg << "<text x=\"" << l.margin << "\" y=\"" << svgNumber(42 + 18.0 * double(i))
        << "\" font-size=\"13\">" << common::xmlEscape(input.summary[i]) << "</text>\n";
  }
}

void polygon(std::ostringstream& svg, const Layout& l, const std::vector<Eigen::Vector2d>& points,
             const std::string& style) {
  svg << "<polygon " << style << " points=\"";
  for (const auto& p : points) svg << l.X(p.x()) << "," << l.Y(p.y()) << " ";
  svg << "\"/>\n";
}

bool inside(const std::vector<Eigen::Vector2d>& outline, const Eigen::Vector2d& p) {
  bool in = false;
  for (std::size_t i = 0, j = outline.size() - 1; i < outline.size(); j = i++) {
    const Eigen::Vector2d& a = outline[i];
    const Eigen::Vector2d& b = outline[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      in = !in;
    }
  }
  return in;
}

// Where a room's name goes: among points around its centre (rings of 0.5 m, eight directions,
// inside the outline when there is one), the one whose text box keeps farthest from the paths,
// up to 0.6 m of clearance; nearer the centre on a tie.
Eigen::Vector2d placeLabel(const RoomLabel& label, const std::vector<Eigen::Vector2d>& paths,
                           const Layout& l) {
  const double half_width = 0.5 * 6.5 * double(label.text.size()) / l.scale;
  const double half_height = 0.5 * 11.0 / l.scale;
  auto clearance = [&](const Eigen::Vector2d& c) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& p : paths) {
      const double dx = std::max(0.0, std::abs(p.x() - c.x()) - half_width);
      const double dy = std::max(0.0, std::abs(p.y() - (c.y() + half_height)) - half_height);
      best = std::min(best, std::hypot(dx, dy));
    }
    return best;
  };
  Eigen::Vector2d best_point = label.centre;
  double best_score = -1.0;
  for (int ring = 0; ring <= 6; ++ring) {
    const double r = 0.5 * ring;
    for (int k = 0; k < (ring == 0 ? 1 : 8); ++k) {
      const double a = k * std::acos(-1.0) / 4.0;
      const Eigen::Vector2d c = label.centre + r * Eigen::Vector2d(std::cos(a), std::sin(a));
      if (!label.outline.empty() && !inside(label.outline, c)) continue;
      const double score = std::min(0.6, clearance(c)) - 0.001 * r;
      if (score > best_score + 1e-9) {
        best_score = score;
        best_point = c;
      }
    }
  }
  return best_point;
}

// `placement`, when given, places each pose first (the odometry from the true start).
void path(std::ostringstream& svg, const Layout& l, TrajectoryView trajectory,
          const std::string& style,
          const std::optional<Eigen::Isometry3d>& placement = std::nullopt) {
  if (trajectory.empty()) return;
  svg << "<polyline fill=\"none\" " << style << " points=\"";
  // At most ~4000 vertices: enough for the eye, small enough to open quickly.
  const std::size_t step = std::max<std::size_t>(1, trajectory.size() / 4000);
  for (std::size_t i = 0; i < trajectory.size(); i += step) {
    const Eigen::Vector3d t = placement
                                  ? Eigen::Vector3d((*placement * trajectory[i].pose).translation())
                                  : Eigen::Vector3d(trajectory[i].pose.translation());
    svg << l.X(t.x()) << "," << l.Y(t.y()) << " ";
  }
  svg << "\"/>\n";
}

// The plan's walls, the as-built changes, the trajectories, the start, the first localized pose
// and the room names.
void drawMap(std::ostringstream& svg, const ReportInput& input, const Layout& l,
             bool mark_start = true, bool mark_localized = true) {
  svg << "<g>\n";
  for (const auto& wall : input.walls) {
    polygon(svg, l, wall, "fill=\"#9a9a9a\" stroke=\"#555\" stroke-width=\"0.5\"");
  }
  for (const auto& overlay : input.overlays) {
    polygon(svg, l, overlay.polygon, styleOf(overlay.kind).svg);
  }
  svg << "</g>\n";
  if (!input.map_points.empty()) {
    // At most ~20000 dots, each a round-capped stroke of no length: one element for all.
    const std::size_t step = reportDotStep(input.map_points.size());
    svg << "<path fill=\"none\" stroke=\"" << kMapPointColour
        << "\" stroke-width=\"1.6\" stroke-linecap=\"round\" stroke-opacity=\"0.55\" d=\"";
    for (std::size_t i = 0; i < input.map_points.size(); i += step) {
      svg << "M" << l.X(input.map_points[i].x()) << " " << l.Y(input.map_points[i].y()) << "h0";
    }
    svg << "\"/>\n";
  }
  path(svg, l, input.odometry, "stroke=\"#e8a0a0\" stroke-width=\"1.2\" stroke-dasharray=\"4 3\"",
       input.odometry_placement);
  path(svg, l, input.ground_truth, "stroke=\"black\" stroke-width=\"1.5\"");
  const std::string estimate_colour =
      input.estimate_is_localization ? kEstimateColour : kAlignedColour;
  path(svg, l, input.estimate,
       "stroke=\"" + estimate_colour + "\" stroke-width=\"1.5\" stroke-opacity=\"0.85\"");
  if (!input.estimate.empty() && input.estimate_is_localization && mark_localized) {
    const Eigen::Vector3d p = input.estimate.front().pose.translation();
    svg << "<circle cx=\"" << l.X(p.x()) << "\" cy=\"" << l.Y(p.y()) << "\" r=\"7\" fill=\"none\" "
        << "stroke=\"" << kLocalizedColour << "\" stroke-width=\"2.5\"/>\n";
    svg << "<text x=\"" << l.X(p.x()) << "\" y=\"" << svgNumber(l.py(p.y()) - 11)
        << "\" font-size=\"12\" fill=\"" << kLocalizedColour
        << "\" text-anchor=\"middle\">localized</text>\n";
  }
  if (!input.ground_truth.empty() && mark_start) {
    const Eigen::Vector3d p = input.ground_truth.front().pose.translation();
    svg << "<rect x=\"" << svgNumber(l.px(p.x()) - 5) << "\" y=\"" << svgNumber(l.py(p.y()) - 5)
        << "\" width=\"10\" height=\"10\" fill=\"black\"/>\n";
  }
  std::vector<Eigen::Vector2d> paths;
  for (const auto* trajectory : {&input.ground_truth, &input.estimate}) {
    const std::size_t step = std::max<std::size_t>(1, trajectory->size() / 3000);
    for (std::size_t i = 0; i < trajectory->size(); i += step) {
      paths.push_back((*trajectory)[i].pose.translation().head<2>());
    }
  }
  svg << "<g font-size=\"11\" fill=\"#555\" text-anchor=\"middle\">\n";
  for (const auto& label : input.labels) {
    const Eigen::Vector2d at = placeLabel(label, paths, l);
    svg << "<text x=\"" << l.X(at.x()) << "\" y=\"" << l.Y(at.y()) << "\">"
        << common::xmlEscape(label.text) << "</text>\n";
  }
  svg << "</g>\n";
}

// A round number of metres, about a sixth of the map's width.
double scaleBarMetres(const Layout& l) { return niceStep((l.hi.x() - l.lo.x()) / 6.0, 1); }

// The scale bar, bottom right under the map (the legend keeps left of it).
void drawScaleBar(std::ostringstream& svg, const Layout& l) {
  const double metres = scaleBarMetres(l);
  const double length = metres * l.scale;
  const double x1 = l.width - l.margin, x0 = x1 - length;
  const double y = l.legend_top + 20;
  svg << "<g stroke=\"black\" stroke-width=\"2\"><line x1=\"" << svgNumber(x0) << "\" y1=\""
      << svgNumber(y) << "\" x2=\"" << svgNumber(x1) << "\" y2=\"" << svgNumber(y) << "\"/>"
      << "<line x1=\"" << svgNumber(x0) << "\" y1=\"" << svgNumber(y - 5) << "\" x2=\""
      << svgNumber(x0) << "\" y2=\"" << svgNumber(y + 5) << "\"/><line x1=\"" << svgNumber(x1)
      << "\" y1=\"" << svgNumber(y - 5) << "\" x2=\"" << svgNumber(x1) << "\" y2=\""
      << svgNumber(y + 5) << "\"/></g>\n";
  svg << "<text x=\"" << svgNumber(0.5 * (x0 + x1)) << "\" y=\"" << svgNumber(y - 8)
      << "\" font-size=\"12\" text-anchor=\"middle\">" << tickLabel(metres, metres)
      << " m</text>\n";
}

void drawLegend(std::ostringstream& svg, const ReportInput& input, const Layout& l) {
  double y = l.legend_top + 12;
  double x = l.margin;
  const double right = l.width - l.margin - scaleBarMetres(l) * l.scale - 30;
  // The swatch is made once the entry's place is known (it may start a new line).
  auto entry = [&](const auto& swatch, const std::string& text) {
    const double width = 30 + 6.3 * double(text.size());
    if (x + width > right && x > l.margin) {  // a new line, clear of the scale bar
      x = l.margin;
      y += 16;
    }
    svg << swatch() << "<text x=\"" << svgNumber(x + 25) << "\" y=\"" << svgNumber(y + 4)
        << "\" font-size=\"12\">" << common::xmlEscape(text) << "</text>\n";
    x += width + 12;
  };
  auto line = [&](const std::string& colour) {
    return [&x, &y, colour] {
      return "<line x1=\"" + svgNumber(x) + "\" y1=\"" + svgNumber(y) + "\" x2=\"" +
             svgNumber(x + 20) + "\" y2=\"" + svgNumber(y) + "\" stroke=\"" + colour +
             "\" stroke-width=\"3\"/>";
    };
  };
  if (!input.ground_truth.empty()) entry(line("black"), "ground truth");
  if (!input.map_points.empty()) entry(line(kMapPointColour), "the map, placed in B");
  if (!input.estimate.empty() || input.estimate_is_localization) {
    entry(line(input.estimate_is_localization ? kEstimateColour : kAlignedColour),
          input.estimate_label);
  }
  if (!input.odometry.empty()) entry(line("#e8a0a0"), "odometry from the true start");
  if (input.estimate_is_localization) entry(line(kLocalizedColour), "first localized pose");
  for (auto kind : {MapOverlay::Kind::kExtraWall, MapOverlay::Kind::kShiftedWall,
                    MapOverlay::Kind::kMissingWall, MapOverlay::Kind::kClosedDoor,
                    MapOverlay::Kind::kClutter}) {
    auto of_kind = [&](const std::vector<MapOverlay>& overlays) {
      return std::any_of(overlays.begin(), overlays.end(),
                         [&](const MapOverlay& o) { return o.kind == kind; });
    };
    bool present = of_kind(input.overlays);
    for (const auto& storey : input.storeys) present = present || of_kind(storey.overlays);
    if (!present) continue;
    const OverlayStyle style = styleOf(kind);
    entry(
        [&] {
          return "<rect x=\"" + svgNumber(x + 2) + "\" y=\"" + svgNumber(y - 5) +
                 "\" width=\"16\" height=\"10\" " + style.svg + "/>";
        },
        style.legend);
  }
}

}  // namespace

namespace {

// The poses of a trajectory at heights in [z_min, z_max).
// The poses whose height lies in [z_min, z_max), each placed by `placement` first when given.
common::Trajectory between(TrajectoryView trajectory, double z_min, double z_max,
                           const std::optional<Eigen::Isometry3d>& placement = std::nullopt) {
  common::Trajectory out;
  for (const auto& row : trajectory) {
    const common::StampedPose pose{row.t,
                                   placement ? Eigen::Isometry3d(*placement * row.pose) : row.pose};
    const double z = pose.pose.translation().z();
    if (z >= z_min && z < z_max) out.push_back(pose);
  }
  return out;
}

// One panel per storey, each under its title, with the trajectories' parts on it; the start
// and the first localized pose are marked on the storey where they are.
void drawStoreys(std::ostringstream& svg, const ReportInput& input, const Layout& layout) {
  for (std::size_t k = 0; k < input.storeys.size(); ++k) {
    const StoreyPanel& storey = input.storeys[k];
    Layout panel = layout;
    panel.panel_offset = double(k) * layout.panel_height + Layout::kTitle;
    svg << "<text x=\"" << layout.margin << "\" y=\""
        << svgNumber(layout.header + double(k) * layout.panel_height + 16)
        << "\" font-size=\"14\" font-weight=\"bold\">" << common::xmlEscape(storey.title)
        << "</text>\n";
    ReportInput on_storey;
    on_storey.walls = storey.walls;
    on_storey.overlays = storey.overlays;
    on_storey.labels = storey.labels;
    const common::Trajectory ground_truth = between(input.ground_truth, storey.z_min, storey.z_max);
    const common::Trajectory estimate = between(input.estimate, storey.z_min, storey.z_max);
    const common::Trajectory odometry =
        between(input.odometry, storey.z_min, storey.z_max, input.odometry_placement);
    on_storey.ground_truth = ground_truth;
    on_storey.estimate = estimate;
    on_storey.odometry = odometry;
    for (const auto& p : input.map_points) {
      if (p.z() >= storey.z_min && p.z() < storey.z_max) on_storey.map_points.push_back(p);
    }
    on_storey.estimate_is_localization = input.estimate_is_localization;
    auto starts_here = [&](TrajectoryView t) {
      if (t.empty()) return false;
      const double z = t.front().pose.translation().z();
      return z >= storey.z_min && z < storey.z_max;
    };
    drawMap(svg, on_storey, panel, starts_here(input.ground_truth), starts_here(input.estimate));
  }
}

}  // namespace

std::size_t reportDotStep(std::size_t points) { return std::max<std::size_t>(1, points / 20000); }

std::string reportSvg(const ReportInput& input) {
  const Layout layout(input);
  std::ostringstream svg;
  drawHeader(svg, input, layout);
  if (input.storeys.empty()) {
    drawMap(svg, input, layout);
  } else {
    drawStoreys(svg, input, layout);
  }
  drawLegend(svg, input, layout);
  drawScaleBar(svg, layout);
  const double t0 = input.ground_truth.empty() ? 0.0 : input.ground_truth.front().t;
  const double t1 = input.ground_truth.empty() ? 1.0 : input.ground_truth.back().t;
  const std::string colour = input.estimate_is_localization ? kEstimateColour : kAlignedColour;
  ChartPanel position;
  position.title = input.error_title + ": position error, metres";
  position.x0 = t0;
  position.x1 = t1;
  position.y_floor = 0.05;
  position.series = {{input.error_over_time, colour, ""}};
  position.marker_x = input.localized_at;
  position.empty_text = input.empty_chart_text;
  drawChartPanel(svg, position, layout.margin, layout.chart_top, layout.width - 2 * layout.margin,
                 layout.chart_height);
  ChartPanel heading = position;
  heading.title = input.error_title + ": heading error, degrees";
  heading.y_floor = 1.0;
  heading.series = {{input.heading_error_over_time, colour, ""}};
  drawChartPanel(svg, heading, layout.margin, layout.heading_top, layout.width - 2 * layout.margin,
                 layout.chart_height);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace isg::eval
