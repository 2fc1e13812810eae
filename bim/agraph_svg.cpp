#include "bim/agraph_svg.hpp"

#include <algorithm>
#include <cstdio>
#include <limits>
#include <sstream>

#include "bim/plan_geometry.hpp"
#include "common/xml_escape.hpp"

namespace isg::bim {

namespace {

// Plan coordinates → SVG pixels: y flipped so that the picture looks like the plan.
struct View {
  Eigen::Vector2d lo, hi;
  double scale;  // pixels per metre
  double margin = 40.0;
  std::string x(double px) const { return fmt(margin + (px - lo.x()) * scale); }
  std::string y(double py) const { return fmt(margin + (hi.y() - py) * scale); }
  static std::string fmt(double v) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f", v);
    return b;
  }
};

// The view around the level's walls and columns, at most 1200 pixels across.
View viewOf(const Level& level, const LevelGeometry& geometry) {
  View view;
  view.lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  view.hi = -view.lo;
  for (const auto& g : geometry.walls) {
    for (const auto& p : g.footprint()) {
      view.lo = view.lo.cwiseMin(p);
      view.hi = view.hi.cwiseMax(p);
    }
  }
  for (const auto& c : level.columns) {
    view.lo = view.lo.cwiseMin(c.center - Eigen::Vector2d::Constant(c.size.norm()));
    view.hi = view.hi.cwiseMax(c.center + Eigen::Vector2d::Constant(c.size.norm()));
  }
  const Eigen::Vector2d size = view.hi - view.lo;
  view.scale = std::clamp(1200.0 / std::max(size.x(), size.y()), 4.0, 80.0);
  return view;
}

// The plan under the graph: rooms first, then walls and columns.
void drawPlan(std::ostream& svg, const View& view, const Level& level,
              const LevelGeometry& geometry, const AGraph& graph) {
  for (const auto& r : graph.rooms) {
    if (r.level != level.id) continue;
    svg << "<polygon points=\"";
    for (const auto& p : r.outline) svg << view.x(p.x()) << ',' << view.y(p.y()) << ' ';
    svg << "\" fill=\"#f3efe4\" stroke=\"none\"/>\n";
  }
  for (std::size_t w = 0; w < geometry.walls.size(); ++w) {
    const WallGeometry& g = geometry.walls[w];
    const bool column = g.column;
    svg << "<polygon points=\"";
    for (const auto& p : g.footprint()) svg << view.x(p.x()) << ',' << view.y(p.y()) << ' ';
    svg << "\" fill=\"" << (column ? "#8c8579" : "#b9b4aa") << "\" stroke=\"none\"><title>"
        << (column ? "column " : "wall ") << common::xmlEscape(g.wall->id)
        << "</title></polygon>\n";
  }
  for (const auto& c : level.columns) {
    if (!c.round()) continue;
    svg << "<circle cx=\"" << view.x(c.center.x()) << "\" cy=\"" << view.y(c.center.y())
        << "\" r=\"" << View::fmt(c.radius() * view.scale)
        << "\" fill=\"#8c8579\" stroke=\"none\"><title>column " << common::xmlEscape(c.id)
        << "</title></circle>\n";
  }
}

// Surfaces, wall centres and doorways with their rooms.
void drawSurfacesWallsDoorways(std::ostream& svg, const View& view, const AGraph& graph,
                               const std::string& level_id) {
  for (const auto& s : graph.surfaces) {
    if (s.level != level_id) continue;
    const char* colour = s.axis == SurfaceAxis::kX ? "#d62728" : "#1f77b4";
    for (const auto& [a, b] : s.segments) {
      svg << "<line x1=\"" << view.x(a.x()) << "\" y1=\"" << view.y(a.y()) << "\" x2=\""
          << view.x(b.x()) << "\" y2=\"" << view.y(b.y()) << "\" stroke=\"" << colour
          << "\" stroke-width=\"2\"><title>" << common::xmlEscape(s.id) << "</title></line>\n";
    }
  }
  for (const auto& w : graph.walls) {
    if (w.level != level_id) continue;
    svg << "<circle cx=\"" << view.x(w.centre.x()) << "\" cy=\"" << view.y(w.centre.y())
        << "\" r=\"3\" fill=\"black\"><title>wall " << common::xmlEscape(w.id)
        << "</title></circle>\n";
  }
  for (const auto& d : graph.doorways) {
    if (d.level != level_id) continue;
    for (int r : d.rooms) {
      const auto& c = graph.rooms[r].centre;
      svg << "<line x1=\"" << view.x(d.position.x()) << "\" y1=\"" << view.y(d.position.y())
          << "\" x2=\"" << view.x(c.x()) << "\" y2=\"" << view.y(c.y())
          << "\" stroke=\"#2ca02c\" stroke-width=\"1.5\" stroke-dasharray=\"5,3\"/>\n";
    }
    svg << "<circle cx=\"" << view.x(d.position.x()) << "\" cy=\"" << view.y(d.position.y())
        << "\" r=\"5\" fill=\"#2ca02c\"><title>doorway " << common::xmlEscape(d.id)
        << "</title></circle>\n";
  }
}

// Rooms by kind (four-wall ■, two-wall ◆, other ●) with their names, and the floor ★.
void drawRoomsAndFloor(std::ostream& svg, const View& view, const AGraph& graph,
                       const std::string& level_id) {
  for (const auto& r : graph.rooms) {
    if (r.level != level_id) continue;
    const std::string cx = view.x(r.centre.x()), cy = view.y(r.centre.y());
    if (r.kind == RoomKind::kFourWall) {
      svg << "<rect x=\"" << View::fmt(std::stod(cx) - 6) << "\" y=\""
          << View::fmt(std::stod(cy) - 6) << "\" width=\"12\" height=\"12\" fill=\"#9467bd\"/>\n";
    } else if (r.kind == RoomKind::kTwoWall) {
      svg << "<polygon points=\"" << cx << ',' << View::fmt(std::stod(cy) - 8) << ' '
          << View::fmt(std::stod(cx) + 8) << ',' << cy << ' ' << cx << ','
          << View::fmt(std::stod(cy) + 8) << ' ' << View::fmt(std::stod(cx) - 8) << ',' << cy
          << "\" fill=\"#9467bd\"/>\n";
    } else {
      svg << "<circle cx=\"" << cx << "\" cy=\"" << cy << "\" r=\"6\" fill=\"#9467bd\"/>\n";
    }
    svg << "<text x=\"" << View::fmt(std::stod(cx) + 9) << "\" y=\"" << View::fmt(std::stod(cy) - 8)
        << "\" font-size=\"13\">" << common::xmlEscape(r.id) << " " << common::xmlEscape(r.name)
        << "</text>\n";
  }
  for (const auto& f : graph.floors) {
    if (f.id != level_id) continue;
    svg << "<text x=\"" << view.x(f.centre.x()) << "\" y=\"" << view.y(f.centre.y())
        << "\" font-size=\"22\" text-anchor=\"middle\" dominant-baseline=\"central\" "
           "fill=\"#ff7f0e\">★<title>floor "
        << common::xmlEscape(f.id) << "</title></text>\n";
  }
}

}  // namespace

std::string agraphToSvg(const Plan& plan, const AGraph& graph, const std::string& level_id) {
  const Level* level = plan.findLevel(level_id);
  const LevelGeometry geometry = computeLevelGeometry(*level);
  const View view = viewOf(*level, geometry);
  const Eigen::Vector2d size = view.hi - view.lo;
  const double width = size.x() * view.scale + 2 * view.margin;
  const double height = size.y() * view.scale + 2 * view.margin + 40;

  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << View::fmt(width) << "\" height=\""
      << View::fmt(height) << "\" viewBox=\"0 0 " << View::fmt(width) << ' ' << View::fmt(height)
      << "\" font-family=\"sans-serif\">\n"
      << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n"
      << "<text x=\"" << view.margin << "\" y=\"" << View::fmt(height - 34)
      << "\" font-size=\"15\">" << common::xmlEscape(plan.name) << " — level "
      << common::xmlEscape(level_id) << " — A-Graph</text>\n"
      << "<text x=\"" << view.margin << "\" y=\"" << View::fmt(height - 14)
      << "\" font-size=\"12\">x-surfaces red, y-surfaces blue, wall centres black; rooms: "
         "four-wall ■, two-wall ◆, other ●; doorways green; floor ★</text>\n";
  drawPlan(svg, view, *level, geometry, graph);
  drawSurfacesWallsDoorways(svg, view, graph, level_id);
  drawRoomsAndFloor(svg, view, graph, level_id);
  svg << "</svg>\n";
  return svg.str();
}

}  // namespace isg::bim
